//! The kind only a ray's colour has: its local part clamped to 1 before
//! the reflected and transmitted terms were added (`clamp-before-adding`,
//! MODEL §8), which MODEL §6 never does: it clamps the pixel's colour
//! alone, as it becomes a byte.

use glam::DVec3;

use super::{Kind, close, vec3};
use crate::divergence::ours::OurRays;

/// When yours is min(1, local) + k_s I_r + k_t I_t with ours' numbers,
/// where the local colour (ambient plus the lights' terms) passes 1 in
/// some channel: the kind and the words that say so.
pub(super) fn clamped_before_adding(
    ours: &OurRays,
    ray: usize,
    yours: DVec3,
) -> Option<(Kind, String)> {
    let node = ours.node(ray);
    node.hit.as_ref()?;
    let local = node.lights.iter().fold(node.ambient, |sum, light| {
        sum + light.diffuse + light.specular
    });
    if local.max_element() <= 1.0 {
        return None;
    }
    let secondary = [node.reflected, node.transmitted]
        .into_iter()
        .flatten()
        .map(|child| ours.tree.nodes[child].contribution)
        .fold(DVec3::ZERO, |a, b| a + b);
    let clamped = local.min(DVec3::ONE);
    if !close(yours, clamped + secondary) {
        return None;
    }
    let added = if secondary == DVec3::ZERO {
        "(this ray has neither, so yours is the clamped local colour)".to_string()
    } else {
        format!("= {} + {}", vec3(clamped), vec3(secondary))
    };
    Some((
        Kind::Clamped,
        format!(
            "yours is min(1, local) + k_s I_r + k_t I_t {added}: the local colour, ambient + the \
             lights' terms = {}, was clamped to 1 before the reflected and transmitted terms were \
             added (clamp-before-adding); MODEL §6 adds every term first and clamps only the \
             pixel's colour, as it becomes a byte",
            vec3(local)
        ),
    ))
}
