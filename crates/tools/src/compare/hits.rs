//! Before any term, the hit: where the student's pixel shows the
//! background, or what lies behind the object raystep's primary ray hits,
//! the student's primary ray missed that object, and no term is the cause
//! (issue 39: a polygon's crossing-test bug was told "yours ≈ reference −
//! diffuse", sending the student to correct lighting code).

use super::metrics::{TOLERANCE_STEPS, channel_gap};
use raystep_engine::record::{RayTree, count, record_pixel};
use raystep_engine::scene::Scene;
use raystep_model::math::to_rgb8;

/// Whether a region's diagnosis says a ray missed (the primary ray here,
/// a secondary ray in `diagnosis::missed_secondary`).
pub(crate) fn is_missed_ray(diagnosis: &str) -> bool {
    diagnosis.starts_with(PRIMARY_MISSED) || diagnosis.ends_with(super::diagnosis::SECONDARY_MISSED)
}

/// How a primary ray's miss is told.
const PRIMARY_MISSED: &str = "your primary ray missed ";

/// At most this many objects are taken away to see what lies behind.
const OBJECTS_TRIED: usize = 4;

/// "your primary ray missed OBJECT: ..." when, of the region's sampled
/// pixels, at least two thirds are pixels where raystep's primary ray hits
/// an object and yours shows the background (where raystep's does not),
/// or what raystep's ray meets with that object taken away. `samples` are
/// the region's sampled pixels, recorded, with the student's values.
pub(crate) fn primary_missed(scene: &Scene, samples: &[(RayTree, [u8; 3])]) -> Option<String> {
    let n = samples.len();
    if n == 0 {
        return None;
    }
    let background = to_rgb8(scene.settings.background);
    let mut missed: Vec<String> = Vec::new();
    let mut behind: Vec<String> = Vec::new();
    let mut on_background = 0;
    let mut fits = 0;
    let mut without: Vec<(usize, Scene)> = Vec::new();
    for (tree, mine) in samples {
        let Some(hit) = tree.root().hit.as_ref() else {
            continue;
        };
        let reference = to_rgb8(tree.color());
        let apart = channel_gap(reference, *mine);
        if apart <= TOLERANCE_STEPS {
            continue;
        }
        let seen = if channel_gap(*mine, background) <= TOLERANCE_STEPS
            && channel_gap(reference, background) > TOLERANCE_STEPS
        {
            on_background += 1;
            Some("the background".to_string())
        } else {
            let object = hit.object_index;
            if !without.iter().any(|(o, _)| *o == object) {
                if without.len() >= OBJECTS_TRIED || scene.objects.len() < 2 {
                    continue;
                }
                without.push((object, scene.without(object)));
            }
            let (_, past_scene) = without.iter().find(|(o, _)| *o == object).expect("made");
            let (x, y) = tree.pixel;
            let past = record_pixel(past_scene, &past_scene.settings, x, y);
            (channel_gap(to_rgb8(past.color()), *mine) <= TOLERANCE_STEPS).then(|| {
                past.root()
                    .hit
                    .as_ref()
                    .map_or("the background".into(), |h| h.object.clone())
            })
        };
        if let Some(seen) = seen {
            fits += 1;
            if !missed.contains(&hit.object) {
                missed.push(hit.object.clone());
            }
            if !behind.contains(&seen) {
                behind.push(seen);
            }
        }
    }
    if 3 * fits < 2 * n {
        return None;
    }
    let of = format!(
        "fits {fits} of {}",
        count(n as u64, "sampled pixel", "sampled pixels")
    );
    let missed = at_most_three(&missed);
    Some(if on_background == fits {
        format!(
            "{PRIMARY_MISSED}{missed}: yours shows the background where raystep's primary ray hits it ({of}); check its intersection test, not a term"
        )
    } else {
        format!(
            "{PRIMARY_MISSED}{missed}: yours shows what lies behind, {} ({of}); check its intersection test, not a term",
            at_most_three(&behind)
        )
    })
}

/// Names listed in full up to three; a mesh's many triangles as the first
/// three and how many more (a hole in a teapot listed 24 patches).
fn at_most_three(names: &[String]) -> String {
    if names.len() <= 3 {
        names.join(", ")
    } else {
        format!("{} and {} more", names[..3].join(", "), names.len() - 3)
    }
}

#[cfg(test)]
mod tests {
    use super::at_most_three;

    #[test]
    fn names_past_three_are_counted_not_listed() {
        let names = |n: usize| (1..=n).map(|i| format!("patch {i}")).collect::<Vec<_>>();
        assert_eq!(at_most_three(&names(1)), "patch 1");
        assert_eq!(at_most_three(&names(3)), "patch 1, patch 2, patch 3");
        // 24 patches: three named, 24 - 3 = 21 counted.
        assert_eq!(
            at_most_three(&names(24)),
            "patch 1, patch 2, patch 3 and 21 more"
        );
    }
}
