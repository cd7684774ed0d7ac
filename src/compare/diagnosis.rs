//! Which term a pixel's difference looks like: the reference's recorded terms
//! taken out (or added again) one at a time, and the result that lands on
//! the student's value named: "yours ≈ reference − specular".

use super::metrics::{TOLERANCE_STEPS, channel_gap};
use crate::math::{Color, to_rgb8};
use crate::record::{RayTree, count};

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

/// What most of a region's sampled pixels look like: the change of the
/// reference's terms that fits the most of them, when it fits at least two
/// thirds. (Half let a half-pixel shift pass as "− diffuse" on 15 of 24.)
/// Each sample is a recording and the student's value there.
pub(crate) fn diagnose(samples: &[(RayTree, [u8; 3])]) -> Option<String> {
    let mut tally: Vec<(String, usize)> = Vec::new();
    for (tree, yours) in samples {
        if let Some(label) = best_fit(tree, *yours) {
            match tally.iter_mut().find(|(l, _)| *l == label) {
                Some((_, n)) => *n += 1,
                None => tally.push((label, 1)),
            }
        }
    }
    let (label, fits) = tally.into_iter().max_by_key(|(_, n)| *n)?;
    (3 * fits >= 2 * samples.len()).then(|| {
        format!(
            "yours ≈ {label} (fits {fits} of {})",
            count(samples.len() as u64, "sampled pixel", "sampled pixels")
        )
    })
}

/// The change of the reference's terms that best gives `yours` at one
/// pixel, when one comes close: within the tolerance, or within a quarter
/// of how far `yours` is from the reference.
fn best_fit(tree: &RayTree, yours: [u8; 3]) -> Option<String> {
    let apart = channel_gap(to_rgb8(tree.color()), yours);
    if apart <= TOLERANCE_STEPS {
        return None;
    }
    let (gap, label) = candidates(tree)
        .into_iter()
        .map(|(label, c)| (channel_gap(to_rgb8(c), yours), label))
        .min_by_key(|(gap, _)| *gap)?;
    (gap <= TOLERANCE_STEPS.max(apart / 4)).then_some(label)
}

/// The reference with one term, or one light, taken out or added again.
fn candidates(tree: &RayTree) -> Vec<(String, Color)> {
    let root = tree.root();
    let c = root.color;
    let sum = |f: fn(&crate::record::LightRecord) -> Color| {
        root.lights.iter().map(f).fold(Color::ZERO, |a, b| a + b)
    };
    let mut out = vec![
        ("reference − ambient".to_string(), c - root.ambient),
        (
            "reference + ambient (ambient counted twice)".into(),
            c + root.ambient,
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
