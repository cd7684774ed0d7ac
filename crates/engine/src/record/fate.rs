//! What became of a light at a hit (MODEL §4), told once from the
//! recording: every presenter (the `inspect` text, `explain`, the Graphviz
//! tree, the debugger's panes and search, the log comparison's explainers)
//! words the same classification.

use super::ray_tree::{LightRecord, ShadowRecord};

/// A light's fate at a hit, in the order MODEL §4 decides it.
#[derive(Clone, Copy, Debug)]
pub enum LightFate<'a> {
    /// The light is within EPS of the point: no direction, no shadow ray,
    /// it adds nothing (recorded as facing away, with `at_point`).
    AtPoint,
    /// N·L ≤ 0 (as the rules in force count it): no shadow ray, it adds
    /// nothing.
    FacesAway,
    /// Shadows are switched off: no shadow ray is cast, S = 1.
    NotCast,
    /// The shadow ray crosses nothing: S = 1.
    Lit(&'a ShadowRecord),
    /// The shadow ray crosses only surfaces with k_t = 1: S = 1 all the same.
    Crossed(&'a ShadowRecord),
    /// Crossings dim the light without putting it out: 0 < S < 1.
    PartlyBlocked(&'a ShadowRecord),
    /// S = 0: an opaque crossing (or so many transparent ones that the
    /// product is 0).
    Blocked(&'a ShadowRecord),
}

impl LightFate<'_> {
    /// The light's fate as the recording holds it.
    pub fn of(light: &LightRecord) -> LightFate<'_> {
        if light.at_point {
            return LightFate::AtPoint;
        }
        if light.faces_away && !light.lit_from_behind {
            return LightFate::FacesAway;
        }
        match &light.shadow {
            None => LightFate::NotCast,
            Some(shadow) if shadow.blockers.is_empty() => LightFate::Lit(shadow),
            Some(shadow) if shadow.s == 0.0 => LightFate::Blocked(shadow),
            Some(shadow) if shadow.s < 1.0 => LightFate::PartlyBlocked(shadow),
            Some(shadow) => LightFate::Crossed(shadow),
        }
    }

    /// No shadow ray was cast and the light adds nothing.
    pub fn adds_nothing(self) -> bool {
        matches!(self, LightFate::AtPoint | LightFate::FacesAway)
    }

    /// S, the shadow factor: 1 where no shadow ray dims the light (also
    /// where it adds nothing for another reason).
    pub fn s(self) -> f64 {
        match self {
            LightFate::Lit(shadow)
            | LightFate::Crossed(shadow)
            | LightFate::PartlyBlocked(shadow)
            | LightFate::Blocked(shadow) => shadow.s,
            LightFate::AtPoint | LightFate::FacesAway | LightFate::NotCast => 1.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::record_pixel;
    use crate::scene::Scene;

    /// Every light of every hit of a pixel of `scene`.
    fn lights(scene: &Scene, x: u32, y: u32) -> Vec<LightRecord> {
        let tree = record_pixel(scene, &scene.settings, x, y);
        tree.nodes.into_iter().flat_map(|n| n.lights).collect()
    }

    #[test]
    fn a_light_behind_a_glass_ball_is_partly_blocked_and_behind_an_opaque_one_blocked() {
        // A floor lit from straight above; a ball with k_t = 0.5 over the
        // pixel the camera looks at straight down. The shadow ray crosses the
        // ball twice: S = 0.5 × 0.5 = 0.25 (MODEL §4), so partly blocked.
        let scene = |kt: f64| {
            let text = format!(
                r#"
[camera]
eye = [0, 5, 0]
look_at = [0, 0, 0]
up = [0, 0, -1]
fov = 10

[image]
width = 1
height = 1

[materials.floor]
color = [1, 1, 1]
kd = 1

[materials.glass]
color = [1, 1, 1]
kt = {kt}

[[light]]
position = [0, 10, 0]

[[object]]
material = "floor"
plane = {{ normal = [0, 1, 0], point = [0, 0, 0] }}

[[object]]
material = "glass"
sphere = {{ center = [0, 7, 0], radius = 0.5 }}
"#
            );
            crate::scene::parse(std::path::Path::new("fate.toml"), &text).unwrap()
        };
        let glass = lights(&scene(0.5), 0, 0);
        assert!(matches!(
            LightFate::of(&glass[0]),
            LightFate::PartlyBlocked(s) if s.s == 0.25
        ));
        assert_eq!(LightFate::of(&glass[0]).s(), 0.25);
        let opaque = lights(&scene(0.0), 0, 0);
        assert!(matches!(LightFate::of(&opaque[0]), LightFate::Blocked(_)));
        let clear = lights(&scene(1.0), 0, 0);
        assert!(matches!(LightFate::of(&clear[0]), LightFate::Crossed(_)));
    }
}
