//! The ray tree's rows in words, as the debugger's tree pane and the web
//! page list them: a ray's kind and what it met, a light's fate, and a
//! row's share of the pixel.

use raystep_model::math::Color;

use super::{LightFate, LightRecord, Node, NodeId, RayTree, kind_name, light_label, num};

/// A ray row's words after its id: "reflected → hit floor", "primary → miss".
pub fn ray_summary(node: &Node) -> String {
    let what = node
        .hit
        .as_ref()
        .map_or("miss".to_string(), |h| format!("hit {}", h.object));
    format!("{} → {what}", kind_name(node.kind))
}

/// A light row's words: the light and what became of it.
pub fn light_summary(light: &LightRecord) -> String {
    let name = light_label(&light.light);
    match LightFate::of(light) {
        LightFate::AtPoint => format!("{name}: at the point"),
        LightFate::FacesAway => format!("{name}: faces away"),
        LightFate::NotCast => format!("{name}: shadows off"),
        LightFate::Lit(_) => format!("{name}: lit, S = 1"),
        LightFate::Crossed(s) | LightFate::PartlyBlocked(s) | LightFate::Blocked(s) => {
            let mut names: Vec<&str> = s.blockers.iter().map(|b| b.object.as_str()).collect();
            names.dedup();
            format!("{name}: S = {}, blocked by {}", num(s.s), names.join(", "))
        }
    }
}

/// The product of weights and attenuations (and the tints a profile weighs
/// rays by, MODEL §11) from the primary ray down to `id`: what one unit of
/// this ray's colour is worth in the pixel, channel by channel.
pub fn path_factor(tree: &RayTree, id: NodeId) -> Color {
    let mut factor = Color::ONE;
    let mut node = Some(id);
    while let Some(n) = node {
        let ray = &tree.nodes[n];
        factor *= ray.weight * ray.attenuation;
        if let Some(tint) = ray.tint {
            factor *= tint;
        }
        node = ray.parent;
    }
    factor
}

/// `part` (already scaled into the pixel) as a share of the pixel's colour.
pub fn share_of_pixel(tree: &RayTree, part: Color) -> String {
    let total = tree.color().element_sum();
    if total <= 1e-12 {
        "  -".into()
    } else {
        format!("{:>3.0}%", 100.0 * part.element_sum() / total)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_scenes::ball;

    #[test]
    fn a_rays_worth_in_the_pixel_is_the_product_down_its_path() {
        let (_, tree) = ball();
        // r0 counts fully; r1 is weighted by ks = 0.5 (no distance attenuation).
        assert_eq!(path_factor(&tree, 0), Color::ONE);
        assert_eq!(path_factor(&tree, 1), Color::splat(0.5));
    }

    #[test]
    fn light_labels_say_light_once() {
        assert_eq!(light_label("lamp"), "light lamp");
        assert_eq!(light_label("light 0"), "light 0");
    }
}
