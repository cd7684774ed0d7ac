//! How the house writes numbers: short decimals, the few small values
//! whose smallness is the lesson, roots at the point a ray leaves, vectors,
//! colours, cutoffs as fractions, counts with their noun. Every text form
//! of a recording (inspect, explain, dot, the debugger) writes them here.

use glam::DVec3;

use raystep_model::math::EPS;

/// A number with at most four decimals and no trailing zeros; one that
/// rounds to 0 at four decimals (rounding noise such as -2.2e-16) is `0`.
pub fn num(x: f64) -> String {
    if x.abs() < 5e-5 {
        return "0".into();
    }
    precise(x)
}

/// Like `num`, but a small value keeps its digits (`1.110e-16`): for the
/// few numbers whose smallness is the lesson (a shadow-acne blocker's t, a
/// ray's accumulated weight, EPS).
pub fn precise(x: f64) -> String {
    if x != 0.0 && (x.abs() >= 1e6 || x.abs() < 1e-4) {
        return format!("{x:.3e}");
    }
    let s = format!("{x:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// A distance along a ray within EPS of 0: the point the ray leaves (a
/// secondary or shadow ray starts on the surface), said so rather than
/// shown as rounding noise such as 1.110e-16.
fn leaves(t: f64) -> bool {
    t.abs() < EPS
}

const LEAVES: &str = "≈ 0 (the point the ray leaves)";

/// A distance along a ray, as `precise` writes it, or `≈ 0 (the point the
/// ray leaves)`. The inspect text, the details pane and `explain` write a
/// root or a blocker's distance here or through `root`.
pub(crate) fn along(t: f64) -> String {
    if leaves(t) { LEAVES.into() } else { precise(t) }
}

/// A root of a ray's quadratic: `t0 = 1.6081`, or `t0 ≈ 0 (the point the
/// ray leaves)`.
pub fn root(name: &str, t: f64) -> String {
    if leaves(t) {
        format!("{name} {LEAVES}")
    } else {
        format!("{name} = {}", precise(t))
    }
}

pub fn vector(v: DVec3) -> String {
    format!("({}, {}, {})", num(v.x), num(v.y), num(v.z))
}

/// A colour with three decimals per channel (never `-0.000`).
pub fn color(c: DVec3) -> String {
    let channel = |x: f64| {
        let s = format!("{x:.3}");
        if s == "-0.000" { "0.000".into() } else { s }
    };
    format!("({}, {}, {})", channel(c.x), channel(c.y), channel(c.z))
}

/// A cutoff such as 1/512 as a fraction when it is one, else as `num` writes it.
pub(crate) fn fraction(x: f64) -> String {
    let inverse = 1.0 / x;
    if x > 0.0 && inverse.fract() == 0.0 && inverse <= 1e6 {
        format!("1/{inverse}")
    } else {
        precise(x)
    }
}

/// "1 primitive", "2 primitives": a count with its noun.
pub fn count(n: impl Into<u64>, singular: &str, plural: &str) -> String {
    let n = n.into();
    format!("{n} {}", if n == 1 { singular } else { plural })
}

#[cfg(test)]
mod tests {
    use super::{along, color, num, precise, root};
    use glam::DVec3;

    #[test]
    fn numbers_are_short() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(0.25), "0.25");
        assert_eq!(num(-0.0), "0");
        assert_eq!(num(2.0 / 3.0), "0.6667");
        assert_eq!(num(2.5e7), "2.500e7");
    }

    #[test]
    fn what_rounds_to_zero_prints_zero() {
        // Rounding noise such as 1 - (1 - 2^-52) - 2^-52... prints as 0 at
        // four decimals; 0.00005 rounds up to 0.0001 and stays.
        assert_eq!(num(-2.220446049250313e-16), "0");
        assert_eq!(num(-0.00001), "0");
        assert_eq!(num(0.00005), "5.000e-5");
        assert_eq!(color(DVec3::new(-1e-9, 0.5, -0.0)), "(0.000, 0.500, 0.000)");
    }

    #[test]
    fn precise_numbers_keep_small_values() {
        assert_eq!(precise(-0.00001), "-1.000e-5");
        assert_eq!(precise(1.1102230246251565e-16), "1.110e-16");
    }

    #[test]
    fn a_root_within_eps_is_the_point_the_ray_leaves() {
        // EPS = 1e-4: 1.1e-16 and -3e-5 are the surface a ray starts on;
        // 1e-4 itself is a root like any other, written with four decimals.
        assert_eq!(
            root("t0", 1.1102230246251565e-16),
            "t0 ≈ 0 (the point the ray leaves)"
        );
        assert_eq!(along(-3e-5), "≈ 0 (the point the ray leaves)");
        assert_eq!(root("t1", 1.6081), "t1 = 1.6081");
        assert_eq!(root("t", 1e-4), "t = 0.0001");
    }
}
