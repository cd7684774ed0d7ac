//! A miss that logs a t: `Infinity`, `-1` or `null`, what tracers print
//! for "no hit". A miss has no t (docs/RAYLOG.md): such a ray is read as
//! a miss, its t left unchecked, and a note says so.

use crate::raylog::{Hit, LoggedRay};

/// How a logged t says "no hit", if it does.
pub(crate) fn miss_spelling(ray: &LoggedRay) -> Option<&'static str> {
    if ray.t_null {
        return Some("null");
    }
    match ray.t? {
        t if t == f64::INFINITY => Some("Infinity"),
        -1.0 => Some("-1"),
        _ => None,
    }
}

/// Whether `ray` is read as a miss whose t is only a stand-in: its t says
/// "no hit" and its `hit` is `null` or absent.
pub(crate) fn reads_as_miss(ray: &LoggedRay) -> bool {
    miss_spelling(ray).is_some() && matches!(ray.hit, None | Some(Hit::Miss))
}

/// The notes for your rays of one pixel: each miss that logs a t.
pub(crate) fn notes(yours: &[LoggedRay]) -> Vec<String> {
    let mut found: Vec<&LoggedRay> = yours.iter().filter(|r| reads_as_miss(r)).collect();
    found.sort_by(|a, b| super::moment::cast_order(&a.path, &b.path));
    found
        .into_iter()
        .map(|ray| {
            format!(
                "{} logs t = {} on a miss: read as a miss; a miss needs no t (leave the key out)",
                ray.path,
                miss_spelling(ray).unwrap_or_default()
            )
        })
        .collect()
}
