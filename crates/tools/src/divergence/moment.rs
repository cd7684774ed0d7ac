//! The order of a trace's steps, in which "the first divergence" is the
//! first: a ray is cast, its hit found, its ambient term taken, then for
//! each light its shadow ray and that light's terms, then its reflected
//! subtree, its transmitted subtree, and last the colour it brings back
//! (MODEL §6's order, the order of the debugger's step list).

use std::cmp::Ordering;
use std::fmt;

use crate::raylog::{RayPath, Step};

/// One number of a ray, as docs/RAYLOG.md names its key.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Field {
    /// The ray itself: cast in one tree and not in the other.
    Ray,
    Origin,
    Dir,
    Weight,
    Hit,
    T,
    Point,
    Normal,
    S,
    Ambient,
    Diffuse(usize),
    Specular(usize),
    Color,
}

impl fmt::Display for Field {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Field::Ray => f.write_str("ray"),
            Field::Origin => f.write_str("origin"),
            Field::Dir => f.write_str("dir"),
            Field::Weight => f.write_str("weight"),
            Field::Hit => f.write_str("hit"),
            Field::T => f.write_str("t"),
            Field::Point => f.write_str("point"),
            Field::Normal => f.write_str("normal"),
            Field::S => f.write_str("S"),
            Field::Ambient => f.write_str("ambient"),
            Field::Diffuse(i) => write!(f, "diffuse[{i}]"),
            Field::Specular(i) => write!(f, "specular[{i}]"),
            Field::Color => f.write_str("color"),
        }
    }
}

/// Where a field of a ray falls among the steps of its node, as a rank:
/// the ray's own shadow rays and children are ranked by `step_rank`.
fn field_rank(field: Field) -> u64 {
    match field {
        Field::Ray | Field::Origin | Field::Dir | Field::Weight => 0,
        Field::Hit | Field::T | Field::Point | Field::Normal | Field::S => 1,
        Field::Ambient => 2,
        // After light i's shadow ray (3 + 2i).
        Field::Diffuse(i) | Field::Specular(i) => 4 + 2 * i as u64,
        Field::Color => u64::MAX,
    }
}

fn step_rank(step: Step) -> u64 {
    match step {
        Step::Shadow(i) => 3 + 2 * i as u64,
        Step::Reflected => u64::MAX - 2,
        Step::Transmitted => u64::MAX - 1,
    }
}

/// The ranks of a field of the ray at `path`, compared in order: the
/// earlier step of the trace has the smaller sequence.
fn ranks(path: &RayPath, field: Field) -> impl Iterator<Item = u64> + '_ {
    path.steps
        .iter()
        .map(|&step| step_rank(step))
        .chain(std::iter::once(field_rank(field)))
}

/// Orders two fields of two rays as the trace computes them.
pub(crate) fn in_trace_order(a: (&RayPath, Field), b: (&RayPath, Field)) -> Ordering {
    ranks(a.0, a.1).cmp(ranks(b.0, b.1))
}

/// Orders two rays as the tracer casts them (a ray, its shadow rays in
/// light order, its reflected subtree, its transmitted subtree).
pub(crate) fn cast_order(a: &RayPath, b: &RayPath) -> Ordering {
    in_trace_order((a, Field::Ray), (b, Field::Ray))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn path(text: &str) -> RayPath {
        RayPath::parse(text, 3).unwrap()
    }

    #[test]
    fn rays_sort_in_the_order_the_tracer_casts_them() {
        let mut paths: Vec<RayPath> = ["P/T", "P/R/S0", "P/S1", "P/R", "P", "P/T/R", "P/S0"]
            .into_iter()
            .map(path)
            .collect();
        paths.sort_by(cast_order);
        let text: Vec<String> = paths.iter().map(|p| p.to_string()).collect();
        assert_eq!(text, ["P", "P/S0", "P/S1", "P/R", "P/R/S0", "P/T", "P/T/R"]);
    }

    #[test]
    fn a_lights_terms_come_after_its_shadow_ray_and_the_colour_after_the_children() {
        let p = path("P");
        let before =
            |a: (&RayPath, Field), b: (&RayPath, Field)| in_trace_order(a, b) == Ordering::Less;
        assert!(before((&p, Field::Dir), (&p, Field::Hit)));
        assert!(before((&p, Field::Ambient), (&path("P/S0"), Field::Dir)));
        assert!(before((&path("P/S0"), Field::S), (&p, Field::Diffuse(0))));
        assert!(before(
            (&p, Field::Diffuse(0)),
            (&path("P/S1"), Field::Origin)
        ));
        assert!(before((&p, Field::Specular(2)), (&path("P/R"), Field::Ray)));
        assert!(before((&path("P/T/R/R"), Field::Color), (&p, Field::Color)));
        assert!(before(
            (&path("P/R/R/R/R/R"), Field::Ray),
            (&path("P/R/R/R/R"), Field::Color)
        ));
    }
}
