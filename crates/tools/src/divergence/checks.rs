//! One ray of a log beside ours, field by field: every key the student
//! logged is checked against our number, in the order the trace computes
//! them.

use glam::DVec3;

use super::moment::Field;
use super::tolerance::Tolerance;
use crate::raylog::{Hit, LoggedRay, uniform};

/// A logged number: a vector, a scalar, what a ray hit, or whether the
/// ray was cast at all.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    Vector(DVec3),
    Number(f64),
    Hit(Hit),
    Cast(bool),
}

impl Value {
    /// Whether any of its numbers is NaN, or else infinite.
    pub(crate) fn non_finite(&self) -> Option<&'static str> {
        let numbers: Vec<f64> = match *self {
            Value::Vector(v) => v.to_array().to_vec(),
            Value::Number(x) => vec![x],
            Value::Hit(_) | Value::Cast(_) => Vec::new(),
        };
        if numbers.iter().any(|x| x.is_nan()) {
            Some("NaN")
        } else if numbers.iter().any(|x| x.is_infinite()) {
            Some("infinity")
        } else {
            None
        }
    }
}

/// One field of a ray in both logs: `ours` is `None` where our ray has no
/// such number (a miss has no t).
#[derive(Clone, Debug, PartialEq)]
pub struct Check {
    pub field: Field,
    pub yours: Value,
    pub ours: Option<Value>,
    pub agrees: bool,
}

/// The fields `yours` logged, each against `ours`, in trace order.
pub(crate) fn checks(yours: &LoggedRay, ours: &LoggedRay, tolerance: &Tolerance) -> Vec<Check> {
    let mut out = Vec::new();
    each_check(yours, ours, tolerance, |check| out.push(check));
    out
}

/// Whether every field `yours` logged agrees with `ours` (what a counted
/// pixel needs, without keeping the checks).
pub(crate) fn all_agree(yours: &LoggedRay, ours: &LoggedRay, tolerance: &Tolerance) -> bool {
    let mut all = true;
    each_check(yours, ours, tolerance, |check| all &= check.agrees);
    all
}

fn each_check(
    yours: &LoggedRay,
    ours: &LoggedRay,
    tolerance: &Tolerance,
    mut visit: impl FnMut(Check),
) {
    let mut check = |field, yours: Option<Value>, ours: Option<Value>| {
        let Some(yours) = yours else { return };
        let agrees = ours.is_some_and(|ours| agree(field, yours, ours, tolerance));
        visit(Check {
            field,
            yours,
            ours,
            agrees,
        });
    };
    let vector = |v: Option<DVec3>| v.map(Value::Vector);
    let number = |x: Option<f64>| x.map(Value::Number);
    if ours.path.is_shadow() {
        // A shadow ray has an origin, a direction and S (MODEL §4); a hit,
        // a weight or a colour a tracer prints for it is its own business.
        check(Field::Origin, vector(yours.origin), vector(ours.origin));
        check(Field::Dir, vector(yours.dir), vector(ours.dir));
        check(Field::S, number(yours.s), number(ours.s));
        return;
    }
    check(Field::Origin, vector(yours.origin), vector(ours.origin));
    check(Field::Dir, vector(yours.dir), vector(ours.dir));
    let (your_weight, our_weight) = weights(yours.weight, ours.weight);
    check(Field::Weight, your_weight, our_weight);
    // A miss that logs t = Infinity, -1 or null is a miss without a t.
    let miss = super::miss_t::reads_as_miss(yours);
    let your_hit = if miss { Some(Hit::Miss) } else { yours.hit };
    check(
        Field::Hit,
        your_hit.map(Value::Hit),
        ours.hit.map(Value::Hit),
    );
    let your_t = if miss { None } else { yours.t };
    check(Field::T, number(your_t), number(ours.t));
    check(Field::Point, vector(yours.point), vector(ours.point));
    check(Field::Normal, vector(yours.normal), vector(ours.normal));
    check(Field::S, number(yours.s), number(ours.s));
    check(Field::Ambient, vector(yours.ambient), vector(ours.ambient));
    let lights = yours
        .diffuse
        .as_ref()
        .map_or(0, Vec::len)
        .max(yours.specular.as_ref().map_or(0, Vec::len));
    // A log is read against the scene, one term per light; the debugger
    // keeps it across a reload that may take a light away.
    let term = |terms: &Option<Vec<DVec3>>, i: usize| {
        terms
            .as_ref()
            .and_then(|t| t.get(i))
            .map(|&v| Value::Vector(v))
    };
    for i in 0..lights {
        check(
            Field::Diffuse(i),
            term(&yours.diffuse, i),
            term(&ours.diffuse, i),
        );
        check(
            Field::Specular(i),
            term(&yours.specular, i),
            term(&ours.specular, i),
        );
    }
    check(Field::Color, vector(yours.color), vector(ours.color));
}

/// Two weights as numbers when both are the same on every channel (every
/// weight of the lecture's model), else as colours: a CSE 167 tracer's
/// mirror weight S is a colour, and 0.4 is the grey (0.4, 0.4, 0.4).
fn weights(yours: Option<DVec3>, ours: Option<DVec3>) -> (Option<Value>, Option<Value>) {
    let as_numbers = [yours, ours]
        .iter()
        .all(|w| w.is_none_or(|w| uniform(w).is_some()));
    let value = |w: DVec3| match uniform(w) {
        Some(x) if as_numbers => Value::Number(x),
        _ => Value::Vector(w),
    };
    (yours.map(value), ours.map(value))
}

fn agree(field: Field, yours: Value, ours: Value, tolerance: &Tolerance) -> bool {
    match (yours, ours) {
        (Value::Vector(a), Value::Vector(b)) => match field {
            Field::Origin | Field::Dir | Field::Point | Field::Normal => tolerance.vectors(a, b),
            _ => tolerance.colours(a, b),
        },
        (Value::Number(a), Value::Number(b)) => match field {
            Field::T => tolerance.lengths(a, b),
            _ => tolerance.factors(a, b),
        },
        (Value::Hit(a), Value::Hit(b)) => a == b,
        (Value::Cast(a), Value::Cast(b)) => a == b,
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raylog::RayPath;

    #[test]
    fn only_the_logged_fields_are_checked_in_trace_order() {
        let mut ours = LoggedRay::new((0, 0), RayPath::primary());
        ours.origin = Some(DVec3::ZERO);
        ours.dir = Some(DVec3::Z);
        ours.hit = Some(Hit::Object(1));
        ours.t = Some(2.0);
        ours.color = Some(DVec3::splat(0.5));
        ours.diffuse = Some(vec![DVec3::splat(0.25), DVec3::ZERO]);
        let mut yours = LoggedRay::new((0, 0), RayPath::primary());
        yours.color = Some(DVec3::splat(0.5));
        yours.t = Some(2.00001);
        yours.dir = Some(-DVec3::Z);
        yours.diffuse = Some(vec![DVec3::splat(0.25), DVec3::splat(0.1)]);
        let found = checks(&yours, &ours, &Tolerance::default());
        let fields: Vec<String> = found.iter().map(|c| c.field.to_string()).collect();
        assert_eq!(fields, ["dir", "t", "diffuse[0]", "diffuse[1]", "color"]);
        let agrees: Vec<bool> = found.iter().map(|c| c.agrees).collect();
        assert_eq!(agrees, [false, true, true, false, true]);
    }

    #[test]
    fn a_shadow_ray_is_checked_on_its_origin_direction_and_s_only() {
        // An unblocked shadow ray, logged with hit null, a t and a weight
        // as a student's tracer may print them: none of those is a shadow
        // ray's number in MODEL §4, so only dir and S are checked.
        let path = RayPath::primary().child(crate::raylog::Step::Shadow(0));
        let mut ours = LoggedRay::new((0, 0), path.clone());
        ours.dir = Some(DVec3::Y);
        ours.s = Some(1.0);
        let mut yours = LoggedRay::new((0, 0), path);
        yours.dir = Some(DVec3::Y);
        yours.s = Some(1.0);
        yours.hit = Some(Hit::Miss);
        yours.t = Some(4.0);
        yours.weight = Some(DVec3::ONE);
        let found = checks(&yours, &ours, &Tolerance::default());
        let fields: Vec<String> = found.iter().map(|c| c.field.to_string()).collect();
        assert_eq!(fields, ["dir", "S"]);
        assert!(found.iter().all(|c| c.agrees));
    }

    #[test]
    fn a_number_ours_lacks_disagrees() {
        // Ours missed, so it has no t; yours logged one.
        let mut ours = LoggedRay::new((0, 0), RayPath::primary());
        ours.hit = Some(Hit::Miss);
        let mut yours = LoggedRay::new((0, 0), RayPath::primary());
        yours.t = Some(3.0);
        let found = checks(&yours, &ours, &Tolerance::default());
        assert_eq!(found.len(), 1);
        assert_eq!(found[0].ours, None);
        assert!(!found[0].agrees);
    }
}
