//! The words every presenter of a recording shares (the `inspect` text,
//! `explain`, `inspect --format dot`, the debugger's panes and the log
//! comparison's explainers): a ray's kind, why a rule kept a ray from being
//! cast, a light's label, the specular cosine's name, a ray's first line.

use std::fmt::Write;

use super::numbers::{fraction, num, precise, vector};
use super::ray_tree::{LightRecord, Node};
use crate::scene::SpecularModel;
use crate::trace::{NotCast, PruneRule, RayKind};

/// A secondary ray a rule kept from being cast, and the rule, in one line.
pub(crate) fn not_cast_line(ray: &NotCast) -> String {
    format!(
        "{} ray not cast: {}",
        kind_name(ray.kind),
        not_cast_reason(ray)
    )
}

/// "light key", or just the name when it already says "light" (NFF's "light 0").
pub fn light_label(name: &str) -> String {
    if name.starts_with("light") {
        name.to_string()
    } else {
        format!("light {name}")
    }
}

/// "1 / (0 + 0 d + 1 d²)": the quotient f_att is, with the light's
/// coefficients, as the words of an unclamped f_att give it (MODEL §11).
pub(crate) fn attenuation_formula(light: &LightRecord) -> String {
    let [c1, c2, c3] = light.coefficients;
    format!("1 / ({} + {} d + {} d²)", num(c1), num(c2), num(c3))
}

/// "directional light, L = (0.6, 0.8, 0), not attenuated" for a
/// directional light (MODEL §4: one L everywhere, no d_L, f_att = 1);
/// `None` for a point light.
pub(crate) fn directional_words(light: &LightRecord) -> Option<String> {
    light.directional.then(|| {
        format!(
            "directional light, L = {}, not attenuated",
            vector(light.to_light)
        )
    })
}

/// Why a rule kept a secondary ray from being cast.
pub(crate) fn not_cast_reason(ray: &NotCast) -> String {
    match ray.rule {
        PruneRule::MinWeight { min_weight } => format!(
            "accumulated weight {} < min_weight {}",
            precise(ray.path_weight),
            fraction(min_weight)
        ),
        PruneRule::MaxRays { max_rays } => {
            format!("the pixel's tree already has max_rays = {max_rays} rays")
        }
    }
}

pub fn kind_name(kind: RayKind) -> &'static str {
    match kind {
        RayKind::Primary => "primary",
        RayKind::Reflected => "reflected",
        RayKind::Transmitted => "transmitted",
    }
}

/// "N·H" for Blinn, "R·V" for Phong.
pub(crate) fn cosine_name(model: SpecularModel) -> &'static str {
    match model {
        SpecularModel::Blinn => "N·H",
        SpecularModel::Phong => "R·V",
    }
}

/// "reflected ray, depth 1, weight 0.5": a ray's first line (no weight for
/// the primary ray), in the text form and the details pane.
pub fn ray_header(node: &Node) -> String {
    let mut text = format!("{} ray, depth {}", kind_name(node.kind), node.depth);
    if node.kind != RayKind::Primary {
        let _ = write!(text, ", weight {}", weight_words(node));
    }
    text
}

/// A secondary ray's weight as its parent scales it: "0.5", or with the
/// colour a profile weighs it by, "0.5 × O_s (0.200, 0.400, 0.600)"
/// (cse167's mirror ray, MODEL §11).
pub fn weight_words(node: &Node) -> String {
    match node.tint {
        None => num(node.weight),
        Some(tint) => format!("{} × O_s {}", num(node.weight), super::color(tint)),
    }
}
