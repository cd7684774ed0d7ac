//! Why a ray is in one tree and not the other: the rule of MODEL that
//! casts it, or keeps it from being cast, with our numbers.

use super::ours::OurRays;
use crate::raylog::{RayPath, Step};
use raystep_engine::record::{LightFate, Node, num, precise};
use raystep_engine::scene::Scene;
use raystep_engine::trace::{PruneRule, RayKind};

/// Why our tree has no ray at `path` (a ray only in yours).
pub(crate) fn why_not_ours(scene: &Scene, ours: &OurRays, path: &RayPath) -> String {
    let Some((parent, step)) = path.parent() else {
        return "MODEL §2: one primary ray per pixel".into();
    };
    let Some(node) = ours.node_at(&parent) else {
        return format!("ours never cast its parent {parent}: it follows from there");
    };
    let Some(hit) = &node.hit else {
        return format!(
            "our {parent} hit nothing, and a ray that misses spawns nothing (MODEL §5)"
        );
    };
    match step {
        Step::Shadow(i) => match node
            .lights
            .iter()
            .find(|l| l.light_index == i)
            .map(|l| (l, LightFate::of(l)))
        {
            Some((light, LightFate::AtPoint)) => format!(
                "MODEL §4: light {i} is within EPS of the hit point (d_L = {}): no shadow ray",
                precise(light.distance.unwrap_or_default())
            ),
            Some((light, LightFate::FacesAway)) => format!(
                "MODEL §4: light {i} is behind the surface (N·L = {} ≤ 0): no shadow ray is cast to it",
                num(light.n_dot_l)
            ),
            _ => format!("MODEL §4: ours cast no shadow ray to light {i} here"),
        },
        Step::Reflected | Step::Transmitted => {
            let kind = if step == Step::Reflected {
                RayKind::Reflected
            } else {
                RayKind::Transmitted
            };
            let reflects = scene.material_of(hit.object_index).reflects;
            secondary_not_cast(ours, node, kind, hit.factors.ks, hit.factors.kt, reflects)
        }
    }
}

/// The depth test as the rules ours was traced by put it: k < max_depth,
/// or k < max_depth − 1 under `depth-off-by-one` (MODEL §5, §8).
fn depth_rule(ours: &OurRays) -> (u32, String) {
    let max_depth = ours.tree.settings.max_depth;
    let limit = ours.rules().spawn_below_depth();
    let rule = if limit == max_depth {
        format!("max_depth {max_depth}")
    } else {
        format!("max_depth − 1 = {limit} (max_depth {max_depth}, under depth-off-by-one, MODEL §8)")
    };
    (limit, rule)
}

fn secondary_not_cast(
    ours: &OurRays,
    node: &Node,
    kind: RayKind,
    ks: f64,
    kt: f64,
    reflects: bool,
) -> String {
    let max_depth = ours.tree.settings.max_depth;
    let (limit, rule) = depth_rule(ours);
    if node.at_depth_limit() || node.depth >= limit {
        if limit == max_depth {
            return format!(
                "MODEL §5: a hit at depth k spawns secondary rays only if k < max_depth; \
                 this hit is at depth {} and max_depth is {max_depth}",
                node.depth
            );
        }
        return format!(
            "MODEL §5: a hit at depth k spawns secondary rays only if k < {rule}; \
             this hit is at depth {}",
            node.depth
        );
    }
    if let Some(not_cast) = node.not_cast.iter().find(|n| n.kind == kind) {
        return match not_cast.rule {
            PruneRule::MinWeight { min_weight } => format!(
                "MODEL §5: its accumulated weight {} is below min_weight {}: not cast",
                precise(not_cast.path_weight),
                precise(min_weight)
            ),
            PruneRule::MaxRays { max_rays } => format!(
                "MODEL §5: the pixel's tree already holds max_rays = {max_rays} rays: not cast"
            ),
        };
    }
    match kind {
        RayKind::Transmitted if node.tir() => {
            let k = node.refraction.map_or(0.0, |r| r.k);
            let moves = if ours.rules().tir_adds_kt() {
                "k_t moves to the reflected ray"
            } else {
                "k_t is lost, not moved to the reflected ray (tir-dropped, MODEL §8)"
            };
            format!(
                "MODEL §5: total internal reflection (k = 1 − η²(1 − cos_i²) = {} < 0): \
                 no transmitted ray; {moves}",
                num(k)
            )
        }
        RayKind::Transmitted if kt == 0.0 => {
            "MODEL §5: the material has k_t = 0: no transmitted ray".into()
        }
        RayKind::Reflected if ks == 0.0 => {
            "MODEL §5: a reflected ray is spawned when k_s > 0 or on total internal \
             reflection; here k_s = 0 and no TIR"
                .into()
        }
        RayKind::Reflected if !reflects => {
            "MODEL §5: the material has reflect = false (MTL illum 0 to 2): k_s gives \
             highlights but no mirror ray"
                .into()
        }
        _ => "MODEL §5: a switch of the scene keeps it from being cast".into(),
    }
}

/// Why our tree casts ray `ray`, which your log does not have.
pub(crate) fn why_ours(scene: &Scene, ours: &OurRays, ray: usize) -> String {
    let path = &ours.rays()[ray].path;
    let (_, max_depth) = depth_rule(ours);
    match path.steps.last() {
        None if ours.viewport(scene).pixel_offset() == 0.0 => {
            "MODEL §2: one primary ray per pixel, through its top-left corner under \
             pixel-corner (§8)"
                .into()
        }
        None => "MODEL §2: one primary ray per pixel, through its centre".into(),
        Some(Step::Shadow(i)) => match ours.light(ray) {
            Some(light) => format!(
                "MODEL §4: a shadow ray to each light in front of the surface; light {i} is \
                 in front (N·L = {} > 0)",
                num(light.n_dot_l)
            ),
            None => format!("MODEL §4: a shadow ray to light {i}"),
        },
        Some(Step::Reflected) => {
            let parent = ours.source(ray);
            let (ks, depth) = parent.map_or((0.0, 0), |p| {
                (p.hit.as_ref().map_or(0.0, |h| h.factors.ks), p.depth)
            });
            if parent.is_some_and(Node::tir) {
                let weight = if ours.rules().tir_adds_kt() {
                    "k_s + k_t"
                } else {
                    "k_s alone (tir-dropped, MODEL §8)"
                };
                format!(
                    "MODEL §5: total internal reflection at depth {depth} < {max_depth} \
                     spawns a reflected ray of weight {weight}"
                )
            } else {
                format!(
                    "MODEL §5: a hit with k_s = {} > 0 at depth {depth} < {max_depth} \
                     spawns a reflected ray",
                    num(ks)
                )
            }
        }
        Some(Step::Transmitted) => {
            let parent = ours.source(ray);
            let depth = parent.map_or(0, |p| p.depth);
            let kt = parent
                .and_then(|p| p.hit.as_ref())
                .map_or(0.0, |h| h.factors.kt);
            let k = parent.and_then(|p| p.refraction).map_or(0.0, |r| r.k);
            format!(
                "MODEL §5: a hit with k_t = {} > 0 at depth {depth} < {max_depth} \
                 spawns a transmitted ray when k = 1 − η²(1 − cos_i²) ≥ 0; here k = {}",
                num(kt),
                num(k)
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use raystep_engine::scene::Settings;
    use raystep_model::mistakes::{Mistake, Mistakes};

    /// A mirror floor (k_s = 0.5) seen from (0, 1, 1), max_depth 2: the
    /// primary ray (depth 1) meets it at the origin and, by MODEL §5
    /// (1 < 2), spawns a reflected ray; under depth-off-by-one (§8) only a
    /// hit at depth k < max_depth − 1 = 1 does, so ours casts no P/R.
    const MIRROR_FLOOR: &str = r#"
        [camera]
        eye = [0, 1, 1]
        look_at = [0, 0, 0]
        [image]
        width = 1
        height = 1
        [settings]
        max_depth = 2
        [materials.mirror]
        ks = 0.5
        [[object]]
        material = "mirror"
        plane = { normal = [0, 1, 0], point = [0, 0, 0] }
    "#;

    #[test]
    fn a_ray_the_depth_limit_kept_under_depth_off_by_one_is_told_by_that_limit() {
        let scene = raystep_engine::scene::parse(Path::new("floor.toml"), MIRROR_FLOOR).unwrap();
        let model = OurRays::record(&scene, &scene.settings, (0, 0));
        let reflected = RayPath::parse("P/R", 0).unwrap();
        assert!(model.find(&reflected).is_some(), "the model casts P/R");
        let settings = Settings {
            mistakes: Mistakes::from_iter([Mistake::DepthOffByOne]),
            ..scene.settings
        };
        let ours = OurRays::record(&scene, &settings, (0, 0));
        assert!(ours.find(&reflected).is_none());
        let why = why_not_ours(&scene, &ours, &reflected);
        assert!(
            why.contains("only if k < max_depth − 1 = 1 (max_depth 2, under depth-off-by-one"),
            "{why}"
        );
        assert!(why.contains("this hit is at depth 1"), "{why}");
    }
}
