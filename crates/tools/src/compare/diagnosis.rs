//! Which term a pixel's difference looks like: the reference's recorded terms
//! taken out (or added again) one at a time, and the result that lands on
//! the student's value named: "yours ≈ reference − specular".
//!
//! A wrong diagnosis is worse than none, so a term must fit clearly: two
//! thirds of the sampled pixels, not by clamping alone, and an ambient
//! change also the pixels around the region where the images agree.

use super::metrics::{TOLERANCE_STEPS, channel_gap};
use raystep_engine::record::{RayTree, count};
use raystep_engine::trace::RayKind;
use raystep_model::math::{Color, to_rgb8};

/// A region needs this many pixels for a term diagnosis: on fewer, an
/// edge's or a speckle's pixels fit some term by chance.
pub(crate) const MIN_PIXELS: usize = 10;

/// What a region of fewer than `MIN_PIXELS` pixels gets instead of a term.
pub(crate) fn too_small(pixels: usize) -> String {
    format!(
        "too small to tell: {} (a term diagnosis needs {MIN_PIXELS})",
        count(pixels as u64, "pixel", "pixels")
    )
}

/// A region at most two pixels wide: what an edge that moved or was
/// anti-aliased leaves, where a missed ray or a term fits by chance
/// (a 1-pixel column of an anti-aliased prism fit "your transmitted ray
/// missed" at 12 of 13 samples).
pub(crate) fn too_thin(pixels: usize) -> String {
    format!(
        "too thin to tell: a line of {} at most 2 pixels wide, as an edge that moved or was anti-aliased leaves",
        count(pixels as u64, "pixel", "pixels")
    )
}

/// The changes made of the ambient term. Every hit has it, whatever the
/// lights, shadows and geometry, so a tracer that leaves it out or counts
/// it twice changes every pixel where it shows, not a patch: where pixels
/// next to the region agree though their ambient shows, it is not the
/// cause. (An edge moved half a pixel gave patches that "− ambient" or
/// "+ ambient" fitted pixel by pixel: pixel-corner on prism.toml, 19 of
/// 19, and on rings-small.nff at 100x75, 12 of 13.)
const AMBIENT: [&str; 2] = [
    "reference − ambient",
    "reference + ambient (ambient counted twice)",
];
/// An ambient change is ruled out when at least this share of the
/// agreeing pixels around the region would differ under it.
const AGREEING_AGAINST: f64 = 0.25;

/// What most of a region's sampled pixels look like: the change of the
/// reference's terms that fits the most of them, when it fits at least two
/// thirds (half let a half-pixel shift pass as "− diffuse" on 15 of 24)
/// and, for an ambient change, the pixels around the region where the
/// images agree (`nearby`, recorded only then) do not rule it out. Each
/// sample is a recording and the student's value there.
pub(crate) fn diagnose(
    samples: &[(RayTree, [u8; 3])],
    nearby: impl FnOnce() -> Vec<RayTree>,
) -> Option<String> {
    // Each change, with how many samples it fits and its summed gap there.
    let mut tally: Vec<(String, usize, u64)> = Vec::new();
    for (tree, yours) in samples {
        for (label, gap) in fits(tree, *yours) {
            match tally.iter_mut().find(|(l, _, _)| *l == label) {
                Some((_, n, sum)) => {
                    *n += 1;
                    *sum += gap as u64;
                }
                None => tally.push((label, 1, gap as u64)),
            }
        }
    }
    // The change that fits the most samples, the closer among equals, the
    // first listed among those. (Counting only each pixel's closest change
    // let "− ambient" take 16 of 24 where a light's loss, about as large,
    // fitted all 24: prism.toml's shadow cast past its light.)
    let (label, fits, _) = tally
        .into_iter()
        .rev()
        .max_by(|a, b| a.1.cmp(&b.1).then(b.2.cmp(&a.2)))?;
    if 3 * fits < 2 * samples.len()
        || (AMBIENT.contains(&label.as_str()) && ruled_out(&label, &nearby()))
    {
        return None;
    }
    Some(format!(
        "yours ≈ {label} (fits {fits} of {})",
        count(samples.len() as u64, "sampled pixel", "sampled pixels")
    ))
}

/// How a secondary ray's miss ends.
pub(crate) const SECONDARY_MISSED: &str = ": a ray missed, not a term";

/// Whether a secondary ray of the student's tracer missed where raystep's
/// hits: the reference with one secondary ray's colour replaced by the
/// background fits at least two thirds of the sampled pixels. Checked
/// before any term: a ray that meets nothing is not a wrong term (issue
/// 39: without a TIR test the NaN direction misses, and prism.toml was
/// named `eta-inverted`).
pub(crate) fn missed_secondary(
    samples: &[(RayTree, [u8; 3])],
    background: Color,
) -> Option<String> {
    let mut tally: Vec<(String, usize)> = Vec::new();
    for (tree, yours) in samples {
        let apart = channel_gap(to_rgb8(tree.color()), *yours);
        if apart <= TOLERANCE_STEPS {
            continue;
        }
        let mut labels: Vec<String> = misses(tree, background)
            .into_iter()
            .filter(|(_, c)| channel_gap(to_rgb8(*c), *yours) <= TOLERANCE_STEPS.max(apart / 4))
            .map(|(label, _)| label)
            .collect();
        labels.dedup();
        for label in labels {
            match tally.iter_mut().find(|(l, _)| *l == label) {
                Some((_, n)) => *n += 1,
                None => tally.push((label, 1)),
            }
        }
    }
    let (label, fits) = tally.into_iter().rev().max_by_key(|(_, n)| *n)?;
    (3 * fits >= 2 * samples.len()).then(|| {
        format!(
            "{label} (fits {fits} of {}){SECONDARY_MISSED}",
            count(samples.len() as u64, "sampled pixel", "sampled pixels")
        )
    })
}

/// The pixel's colour were one secondary ray that hits something to miss
/// instead (its colour the background, no distance attenuation), for each
/// such ray, by what it is.
fn misses(tree: &RayTree, background: Color) -> Vec<(String, Color)> {
    let mut out: Vec<(String, Color)> = Vec::new();
    for node in &tree.nodes {
        let Some(parent) = node.parent else { continue };
        if node.hit.is_none() {
            continue;
        }
        // What the change adds at the parent, then weighed on the way up.
        let mut change = background * node.weight - node.contribution;
        let mut up = Some(parent);
        while let Some(a) = up {
            change *= tree.nodes[a].weight * tree.nodes[a].attenuation;
            up = tree.nodes[a].parent;
        }
        let label = if tree.nodes[parent].tir() {
            "yours shows the background where raystep's totally internally reflected ray hits something (no TIR test? its NaN direction meets nothing)"
        } else if node.kind == RayKind::Transmitted {
            "yours shows the background where raystep's transmitted ray hits something: your transmitted ray missed"
        } else {
            "yours shows the background where raystep's reflected ray hits something: your reflected ray missed"
        };
        out.push((label.to_string(), tree.root().color + change));
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

/// Whether at least `AGREEING_AGAINST` of the agreeing pixels `around`
/// would differ past the tolerance under the change `label`.
fn ruled_out(label: &str, around: &[RayTree]) -> bool {
    let against = around
        .iter()
        .filter(|tree| {
            candidates(tree).into_iter().any(|(l, c)| {
                l == label && channel_gap(to_rgb8(c), to_rgb8(tree.color())) > TOLERANCE_STEPS
            })
        })
        .count();
    against > 0 && against as f64 >= AGREEING_AGAINST * around.len() as f64
}

/// The changes of the reference's terms that give `yours` at one pixel,
/// each with its gap: within the tolerance, or within a quarter of how
/// far `yours` is from the reference.
fn fits(tree: &RayTree, yours: [u8; 3]) -> Vec<(String, u8)> {
    let apart = channel_gap(to_rgb8(tree.color()), yours);
    if apart <= TOLERANCE_STEPS {
        return Vec::new();
    }
    let reference = to_rgb8(tree.color());
    candidates(tree)
        .into_iter()
        .filter(|&(_, c)| !clamped_alike(reference, c, yours))
        .map(|(label, c)| (label, channel_gap(to_rgb8(c), yours)))
        .filter(|&(_, gap)| gap <= TOLERANCE_STEPS.max(apart / 4))
        .collect()
}

/// Whether `changed` meets `yours` only by clamping, in a channel where
/// yours differs from the reference: a white pixel of yours is as much
/// "+ ambient" as any change past 1, which says nothing.
fn clamped_alike(reference: [u8; 3], changed: Color, yours: [u8; 3]) -> bool {
    (0..3).any(|k| {
        yours[k].abs_diff(reference[k]) > TOLERANCE_STEPS
            && ((yours[k] == 255 && changed[k] > 1.0) || (yours[k] == 0 && changed[k] < 0.0))
    })
}

/// The reference with one term, or one light, taken out or added again.
fn candidates(tree: &RayTree) -> Vec<(String, Color)> {
    let root = tree.root();
    let c = root.color;
    let sum = |f: fn(&raystep_engine::record::LightRecord) -> Color| {
        root.lights.iter().map(f).fold(Color::ZERO, |a, b| a + b)
    };
    // A tracer that leaves the ambient out, or counts it twice, does so
    // at every hit: the reflected and transmitted rays' ambient too. (The
    // first hit's alone fitted depth-off-by-one's lost deep rays on
    // glass.toml, 22 of 22, and no-ambient's glass only 16 of 24.)
    let ambient = ambient_everywhere(tree);
    let mut out = vec![
        ("reference − ambient".to_string(), c - ambient),
        (
            "reference + ambient (ambient counted twice)".into(),
            c + ambient,
        ),
        ("reference − specular".into(), c - sum(|l| l.specular)),
        ("reference − diffuse".into(), c - sum(|l| l.diffuse)),
        (
            "reference − every light (ambient and secondary rays only)".into(),
            c - sum(|l| l.diffuse + l.specular),
        ),
    ];
    if root.lights.len() > 1 {
        for light in &root.lights {
            out.push((
                format!("reference without {}'s contribution", light.light),
                c - light.diffuse - light.specular,
            ));
        }
    }
    for (child, what) in [
        (root.reflected, "the reflected ray"),
        (root.transmitted, "the transmitted ray"),
    ] {
        if let Some(id) = child {
            out.push((
                format!("reference without {what}"),
                c - tree.nodes[id].contribution,
            ));
        }
    }
    out
}

/// The ambient terms of every hit of the tree, each weighed as it reaches
/// the pixel (by the weights and attenuations on its way up).
fn ambient_everywhere(tree: &RayTree) -> Color {
    (0..tree.nodes.len())
        .map(|id| {
            let mut share = 1.0;
            let mut node = Some(id);
            while let Some(n) = node {
                share *= tree.nodes[n].weight * tree.nodes[n].attenuation;
                node = tree.nodes[n].parent;
            }
            tree.nodes[id].ambient * share
        })
        .fold(Color::ZERO, |a, b| a + b)
}
