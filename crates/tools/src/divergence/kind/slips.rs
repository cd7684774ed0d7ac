//! Common slips a student's tracer makes outside the catalogue, each
//! named from the numbers: the reflection formula with the sign of its
//! 2 (d·N) N term changed, a child's colour added without its weight, a
//! specular term multiplied by the object colour, a shadow ray blocked by
//! its own surface (EPS) or past the light (d_L).

use glam::DVec3;

use super::{Kind, close, vec3};
use crate::divergence::ours::OurRays;
use crate::raylog::Step;
use raystep_engine::record::num;
use raystep_engine::scene::{Scene, Settings};
use raystep_model::math::{EPS, Interval, Ray};
use raystep_model::mistakes::Mistake;

/// A reflected direction d + 2 (d·N) N: MODEL §5's R = d − 2 (d·N) N
/// with the sign of its second term changed.
pub(super) fn reflection_formula(
    ours: &OurRays,
    ray: usize,
    yours: DVec3,
) -> Option<(Kind, String)> {
    if ours.rays()[ray].path.steps.last() != Some(&Step::Reflected) {
        return None;
    }
    let parent = ours.source(ray)?;
    let n = parent.hit.as_ref()?.normal;
    let d = parent.direction;
    let plus = d + 2.0 * d.dot(n) * n;
    close(yours.normalize_or_zero(), plus.normalize_or_zero()).then(|| {
        (
            Kind::ReflectionFormula,
            format!(
                "yours is d + 2 (d·N) N = {}: the reflection formula with + where MODEL §5 has −, \
                 R = d − 2 (d·N) N (d·N = {}, N facing the ray)",
                vec3(plus),
                num(d.dot(n))
            ),
        )
    })
}

/// A colour whose reflected or transmitted part (or both) was added
/// without its weight: yours = ours + (1/w − 1) × (what the child adds).
pub(super) fn weight_missing(ours: &OurRays, ray: usize, yours: DVec3) -> Option<(Kind, String)> {
    let node = ours.node(ray);
    node.hit.as_ref()?;
    let tir = node.tir();
    let children: Vec<(&str, &str, f64, DVec3)> = [
        (
            node.reflected,
            "reflected",
            if tir { "k_s + k_t" } else { "k_s" },
        ),
        (node.transmitted, "transmitted", "k_t"),
    ]
    .into_iter()
    .filter_map(|(child, what, weight)| {
        let child = &ours.tree.nodes[child?];
        (child.weight > 0.0 && child.weight != 1.0).then_some((
            what,
            weight,
            child.weight,
            child.contribution * (1.0 / child.weight - 1.0),
        ))
    })
    .collect();
    let subsets: Vec<Vec<usize>> = match children.len() {
        0 => return None,
        1 => vec![vec![0]],
        _ => vec![vec![0], vec![1], vec![0, 1]],
    };
    for subset in subsets {
        let extra = subset
            .iter()
            .fold(DVec3::ZERO, |sum, &i| sum + children[i].3);
        if extra.max_element() <= 0.0 || !close(yours, node.color + extra) {
            continue;
        }
        let parts: Vec<String> = subset
            .iter()
            .map(|&i| {
                let (what, name, w, _) = children[i];
                format!(
                    "the weight {name} is missing: your {what} part is ours ÷ {name} \
                     ({name} = {}), the {what} colour added as it came back, not weighted",
                    num(w)
                )
            })
            .collect();
        return Some((
            Kind::WeightMissing,
            format!(
                "{} (MODEL §6: I = … + k_s I_r + k_t I_t)",
                parts.join("; and ")
            ),
        ));
    }
    None
}

/// A specular term multiplied by the object colour O_d, which MODEL §4's
/// specular_i = S f_att I_p k_s (N·H)^n does not have.
pub(super) fn object_colour(
    ours: &OurRays,
    ray: usize,
    yours: DVec3,
    theirs: DVec3,
) -> Option<(Kind, String)> {
    let o_d = ours.node(ray).hit.as_ref()?.factors.o_d;
    if o_d == DVec3::ONE || theirs == DVec3::ZERO || !close(yours, theirs * o_d) {
        return None;
    }
    Some((
        Kind::ObjectColour,
        format!(
            "yours is ours multiplied by the object colour O_d = {}: MODEL §4's specular term \
             S f_att I_p k_s (N·H)^n has no O_d (a highlight takes the light's colour)",
            vec3(o_d)
        ),
    ))
}

/// A shadow ray of yours blocked where ours is not: by the surface it
/// starts on at t ≈ 0 (no EPS), or by something past the light (no d_L).
/// Told by tracing ours again with the shadow segment (0, d_L), then
/// (EPS, ∞), and finding your S there; failing that, a fully blocked ray
/// is told by its own surface's root within EPS of its start.
pub(super) fn shadow_segment(
    scene: &Scene,
    ours: &OurRays,
    ray: usize,
    yours: f64,
) -> Option<(Kind, String)> {
    retraced(scene, ours, ray, yours).or_else(|| own_surface(scene, ours, ray, yours))
}

fn retraced(scene: &Scene, ours: &OurRays, ray: usize, yours: f64) -> Option<(Kind, String)> {
    let path = &ours.rays()[ray].path;
    // Towards a directional light the segment has no end: nothing lies
    // past the light (MODEL §8), so only a missing EPS is left to try.
    let d_l = ours.light(ray)?.distance;
    let mistakes: &[Mistake] = match d_l {
        Some(_) => &[Mistake::ShadowAcne, Mistake::ShadowsPastLight],
        None => &[Mistake::ShadowAcne],
    };
    for &mistake in mistakes {
        let settings = Settings {
            mistakes: ours.tree.settings.mistakes.with(mistake),
            ..ours.tree.settings
        };
        let (x, y) = ours.tree.pixel;
        let under = OurRays::of(raystep_engine::record::record_pixel(scene, &settings, x, y));
        let Some(found) = under.find(path) else {
            continue;
        };
        if !under.rays()[found]
            .s
            .is_some_and(|s| (s - yours).abs() <= 1e-9)
        {
            continue;
        }
        let shadow = under.light(found)?.shadow.as_ref()?;
        let words = if mistake == Mistake::ShadowAcne {
            let blocker = shadow.blockers.iter().find(|b| b.t < 1e-4)?;
            (
                Kind::SelfHit,
                format!(
                    "yours is blocked at t = {:e} by object {} ({}), the surface it starts on: \
                     a shadow ray looks for blockers over (EPS, d_L), EPS = 1e-4 (MODEL §4), or \
                     it finds its own surface",
                    blocker.t, blocker.object_index, blocker.object
                ),
            )
        } else {
            let d_l = d_l?;
            let blocker = shadow.blockers.iter().find(|b| b.t >= d_l)?;
            (
                Kind::PastLight,
                format!(
                    "yours is blocked by object {} ({}) at t = {}, past the light at d_L = {}: \
                     a shadow ray looks for blockers over (EPS, d_L) (MODEL §4), and nothing \
                     beyond the light shadows it",
                    blocker.object_index,
                    blocker.object,
                    num(blocker.t),
                    num(d_l)
                ),
            )
        };
        return Some(words);
    }
    None
}

/// Whether a ray finds the surface it leaves, under a segment from 0, is a
/// coin toss of rounding (its root there is ±1e-15), and our point lies a
/// rounding away from yours: where ours traced again is not blocked, a
/// fully blocked ray whose own surface meets it within EPS of its start is
/// told by that root, which is what a missing EPS lets through.
fn own_surface(scene: &Scene, ours: &OurRays, ray: usize, yours: f64) -> Option<(Kind, String)> {
    if yours != 0.0 {
        return None;
    }
    let logged = &ours.rays()[ray];
    let shadow = Ray::new(logged.origin?, logged.dir?);
    let object = ours.source(ray)?.hit.as_ref()?.object_index;
    let t = (scene.objects.get(object)?.shape)
        .roots(&shadow, Interval::new(-EPS, EPS))
        .as_slice()
        .iter()
        .copied()
        .min_by(|a, b| a.abs().total_cmp(&b.abs()))?;
    Some((
        Kind::SelfHit,
        format!(
            "the surface it starts on, object {object} ({}), meets it at t = {t:e}, within \
             EPS of its start (on our point; on yours the sign of so small a root is \
             rounding): a shadow ray looks for blockers over (EPS, d_L), EPS = 1e-4 \
             (MODEL §4), or it finds its own surface",
            scene.object_name(object)
        ),
    ))
}
