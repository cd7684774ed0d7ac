//! What a difference looks like, in words a student recognises: negated,
//! mirrored, not normalised, scaled by a factor with a name, η and 1/η
//! swapped, another object, a missing epsilon, a colour clamped too early,
//! a NaN.

use glam::DVec3;
use serde::Serialize;

mod colour;
mod direction;
mod factors;
mod slips;

use colour::clamped_before_adding;
use direction::direction_kind;
use factors::{candidates, scaled_words};

use super::checks::{Check, Value};
use super::moment::Field;
use super::ours::OurRays;
use crate::raylog::{Hit, Step};
use raystep_engine::record::{LightFate, num};
use raystep_engine::scene::Scene;

/// The kinds of difference `compare --rays` recognises; their JSON names
/// are a contract (docs/RAYLOG.md), written once, in `Kind::name`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A ray in your log that our tree does not cast.
    OnlyYours,
    /// A ray of our tree your log does not have.
    OnlyOurs,
    Nan,
    Infinite,
    Negated,
    /// Reflected in the surface's plane, or turned half a turn about N.
    Mirrored,
    /// The same direction with another length.
    NotNormalised,
    /// A constant factor times ours.
    Scaled,
    /// Refracted with 1/η in place of η.
    EtaSwapped,
    /// Refracted with the normal that faces away from the ray.
    OutwardNormal,
    /// A primary ray through another point of the image plane, as another
    /// field of view gives.
    FieldOfView,
    OtherObject,
    /// Yours hit nothing where ours hit an object.
    Missed,
    /// Yours hit an object where ours hit nothing.
    HitWhereOursMissed,
    /// The surface the ray starts on, at t ≈ 0: a missing epsilon.
    SelfHit,
    /// The same object at another distance.
    OtherT,
    /// Yours is 0 where ours is not: a term or factor left out.
    Zero,
    /// A primary ray through another point of the image than the pixel's
    /// centre.
    OtherPixel,
    /// A colour whose local part (ambient and the lights' terms) was
    /// clamped to 1 before the reflected and transmitted terms were added.
    Clamped,
    /// A reflected direction d + 2 (d·N) N: the formula's sign changed.
    ReflectionFormula,
    /// A reflected or transmitted colour added without its weight.
    WeightMissing,
    /// A specular term multiplied by the object colour O_d.
    ObjectColour,
    /// A shadow ray blocked by something past the light.
    PastLight,
    Other,
}

impl Kind {
    /// The JSON name.
    pub fn name(self) -> &'static str {
        match self {
            Kind::OnlyYours => "only_yours",
            Kind::OnlyOurs => "only_ours",
            Kind::Nan => "nan",
            Kind::Infinite => "infinite",
            Kind::Negated => "negated",
            Kind::Mirrored => "mirrored",
            Kind::NotNormalised => "not_normalised",
            Kind::Scaled => "scaled",
            Kind::EtaSwapped => "eta_swapped",
            Kind::OutwardNormal => "outward_normal",
            Kind::FieldOfView => "field_of_view",
            Kind::OtherObject => "other_object",
            Kind::Missed => "missed",
            Kind::HitWhereOursMissed => "hit_where_ours_missed",
            Kind::SelfHit => "self_hit",
            Kind::OtherT => "other_t",
            Kind::Zero => "zero",
            Kind::OtherPixel => "other_pixel",
            Kind::Clamped => "clamped",
            Kind::ReflectionFormula => "reflection_formula",
            Kind::WeightMissing => "weight_missing",
            Kind::ObjectColour => "object_colour",
            Kind::PastLight => "past_light",
            Kind::Other => "other",
        }
    }
}

/// As its JSON name: serde and the JSON report name a kind alike.
impl Serialize for Kind {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

/// A distance below which a hit is on the surface the ray left: a
/// tracer without MODEL §3's EPS finds its own surface at t ≈ 1e-16.
const SELF_HIT_T: f64 = 1e-6;

/// Two vectors equal up to rounding, for recognising a kind (looser than
/// any tolerance a student would set, so the kind is found at any).
pub(super) fn close(a: DVec3, b: DVec3) -> bool {
    (a - b).length() <= 1e-3 * a.length().max(b.length()).max(1e-12)
}

pub(super) fn close_numbers(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-3 * a.abs().max(b.abs()).max(1e-12)
}

/// What ray `ray` of `ours` (the one `check` is on) tells about the
/// difference, and the kind, in words.
pub(crate) fn classify(scene: &Scene, ours: &OurRays, ray: usize, check: &Check) -> (Kind, String) {
    if let Some(what) = check.yours.non_finite() {
        let kind = if what == "NaN" {
            Kind::Nan
        } else {
            Kind::Infinite
        };
        let ours = if check.ours.is_some() {
            "ours is finite".to_string()
        } else {
            format!("ours has no {}", check.field)
        };
        return (kind, format!("yours is {what}; {ours}"));
    }
    let Some(our_value) = check.ours else {
        return match check.yours {
            Value::Number(_) | Value::Vector(_) if ours.rays()[ray].hit == Some(Hit::Miss) => (
                Kind::HitWhereOursMissed,
                format!("yours has a {}; ours hit nothing, so has none", check.field),
            ),
            _ => (Kind::Other, format!("ours has no {}", check.field)),
        };
    };
    match (check.yours, our_value) {
        (Value::Hit(yours), Value::Hit(theirs)) => hit(scene, ours, ray, yours, theirs),
        (Value::Number(yours), Value::Number(theirs)) => {
            number(scene, ours, ray, check.field, yours, theirs)
        }
        (Value::Vector(yours), Value::Vector(theirs)) => {
            vector(scene, ours, ray, check.field, yours, theirs)
        }
        _ => (Kind::Other, String::new()),
    }
}

fn hit(scene: &Scene, ours: &OurRays, ray: usize, yours: Hit, theirs: Hit) -> (Kind, String) {
    let name = |o: usize| format!("{o} ({})", scene.object_name(o));
    let logged_t = ours.rays()[ray].t;
    let starts_on = ours
        .source(ray)
        .and_then(|s| s.hit.as_ref())
        .map(|h| h.object_index);
    match (yours, theirs) {
        (Hit::Miss, Hit::Object(o)) => (
            Kind::Missed,
            format!("yours hit nothing; ours hit object {}", name(o)),
        ),
        // Where ours hits nothing as much as where it hits another object:
        // a reflected ray leaving a plane finds that plane only at t ≈ 0.
        (Hit::Object(y), _) if starts_on == Some(y) => {
            let ours_hit = match theirs {
                Hit::Object(o) => format!(
                    "ours hit object {}{}",
                    name(o),
                    logged_t.map_or(String::new(), |t| format!(" at t = {}", num(t)))
                ),
                Hit::Miss => "ours hit nothing".to_string(),
            };
            (
                Kind::SelfHit,
                format!(
                    "yours hit object {}, the surface the ray starts on; {ours_hit}: \
                     a hit must lie at t > EPS = 1e-4 (MODEL §3), or a ray finds its own surface",
                    name(y),
                ),
            )
        }
        (Hit::Object(o), Hit::Miss) => (
            Kind::HitWhereOursMissed,
            format!("yours hit object {}; ours hit nothing", name(o)),
        ),
        (Hit::Object(y), Hit::Object(o)) => (
            Kind::OtherObject,
            format!("yours hit object {}; ours hit object {}", name(y), name(o)),
        ),
        (Hit::Miss, Hit::Miss) => (Kind::Other, String::new()),
    }
}

fn number(
    scene: &Scene,
    ours: &OurRays,
    ray: usize,
    field: Field,
    yours: f64,
    theirs: f64,
) -> (Kind, String) {
    if field == Field::T {
        if yours.abs() < SELF_HIT_T {
            return (
                Kind::SelfHit,
                format!(
                    "yours is t = {yours:e}, the point the ray starts from: a hit must lie at \
                     t > EPS = 1e-4 (MODEL §3), or a ray finds its own surface"
                ),
            );
        }
        let node = ours.node(ray);
        if let Some(other) = node
            .hit
            .as_ref()
            .and_then(|h| h.working.nearer_root(theirs))
            .map(|(nearer, roots)| roots[1 - nearer])
            && close_numbers(yours, other)
        {
            return (
                Kind::OtherT,
                format!(
                    "yours is the other root of the quadratic, t = {}; the nearest hit past EPS is t = {}",
                    num(other),
                    num(theirs)
                ),
            );
        }
    }
    if field == Field::S {
        let light = match ours.rays()[ray].path.steps.last() {
            Some(Step::Shadow(i)) => *i,
            _ => 0,
        };
        let seen = |s: f64| match s {
            0.0 => "fully blocked".to_string(),
            1.0 => "unblocked".to_string(),
            s => format!("partly blocked, S = {}", num(s)),
        };
        let words = format!(
            "your shadow ray to light {light} is {}; ours is {}",
            seen(yours),
            seen(theirs)
        );
        if yours < theirs
            && let Some((kind, cause)) = slips::shadow_segment(scene, ours, ray, yours)
        {
            return (kind, format!("{words}: {cause}"));
        }
        let kind = if yours == 0.0 {
            Kind::Zero
        } else {
            Kind::Other
        };
        return (kind, words);
    }
    if theirs != 0.0 && yours == 0.0 {
        return (
            Kind::Zero,
            format!("yours is 0 where ours is {}: left out?", num(theirs)),
        );
    }
    if theirs != 0.0 && close_numbers(yours, -theirs) {
        return (Kind::Negated, "yours is ours with its sign changed".into());
    }
    if theirs != 0.0 && yours != 0.0 {
        let factor = yours / theirs;
        return (
            Kind::Scaled,
            scaled_words(factor, &candidates(ours, ray, field)),
        );
    }
    let kind = if field == Field::T {
        Kind::OtherT
    } else {
        Kind::Other
    };
    (kind, String::new())
}

fn vector(
    scene: &Scene,
    ours: &OurRays,
    ray: usize,
    field: Field,
    yours: DVec3,
    theirs: DVec3,
) -> (Kind, String) {
    if field == Field::Color
        && let Some(found) = clamped_before_adding(ours, ray, yours)
    {
        return found;
    }
    if field == Field::Color
        && let Some(found) = slips::weight_missing(ours, ray, yours)
    {
        return found;
    }
    if field == Field::Dir
        && let Some(found) = slips::reflection_formula(ours, ray, yours)
    {
        return found;
    }
    if matches!(field, Field::Specular(_))
        && let Some(found) = slips::object_colour(ours, ray, yours, theirs)
    {
        return found;
    }
    let direction = matches!(field, Field::Dir | Field::Normal);
    if direction && yours.length() > 0.0 && theirs.length() > 0.0 {
        let (unit_yours, unit_ours) = (yours.normalize(), theirs.normalize());
        if close(unit_yours, unit_ours) {
            return (
                Kind::NotNormalised,
                format!(
                    "the same direction with length {} (ours {}): MODEL normalises it",
                    num(yours.length()),
                    num(theirs.length())
                ),
            );
        }
    }
    if theirs != DVec3::ZERO && yours == DVec3::ZERO {
        return (
            Kind::Zero,
            format!("yours is 0 where ours is {}: left out?", vec3(theirs)),
        );
    }
    if theirs != DVec3::ZERO && close(yours, -theirs) {
        let words = if field == Field::Dir
            && ours.rays()[ray].path.steps.last() == Some(&crate::raylog::Step::Reflected)
        {
            "yours is −1 × ours: 2 (d·N) N − d, MODEL §5's R = d − 2 (d·N) N with both signs \
             changed"
        } else {
            "yours is −1 × ours"
        };
        return (Kind::Negated, words.into());
    }
    if theirs == DVec3::ZERO
        && yours != DVec3::ZERO
        && let Some(found) = light_facing_away(ours, ray, field)
    {
        return found;
    }
    if direction && let Some(found) = direction_kind(scene, ours, ray, field, yours, theirs) {
        return found;
    }
    if let Some(factor) = common_factor(yours, theirs) {
        return (
            Kind::Scaled,
            scaled_words(factor, &candidates(ours, ray, field)),
        );
    }
    (Kind::Other, String::new())
}

/// A light's term that ours leaves at 0 because the light is behind the
/// surface, and yours does not.
fn light_facing_away(ours: &OurRays, ray: usize, field: Field) -> Option<(Kind, String)> {
    let (Field::Diffuse(i) | Field::Specular(i)) = field else {
        return None;
    };
    let light = ours.node(ray).lights.iter().find(|l| l.light_index == i)?;
    matches!(LightFate::of(light), LightFate::FacesAway).then(|| {
        (
            Kind::Other,
            format!(
                "ours is 0: light {i} is behind the surface (N·L = {} ≤ 0) and adds nothing \
                 (MODEL §4); yours adds to it: |N·L| in place of N·L, or N_g in place of N \
                 facing the ray?",
                num(light.n_dot_l)
            ),
        )
    })
}

/// The factor c with yours = c × ours, when there is one (c ≠ 1).
fn common_factor(yours: DVec3, theirs: DVec3) -> Option<f64> {
    let norm = theirs.length_squared();
    if norm == 0.0 {
        return None;
    }
    let c = yours.dot(theirs) / norm;
    (c != 0.0 && close(yours, c * theirs) && !close_numbers(c, 1.0)).then_some(c)
}

pub(super) fn vec3(v: DVec3) -> String {
    raystep_engine::record::vector(v)
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::raylog::RayPath;
    use raystep_model::mistakes::Mistake;

    /// A water ball (ior 4/3, k_t = 1) at the origin; the only pixel's ray
    /// runs down -z at height 0.8 and enters at p = (0, 0.8, 0.6).
    const WATER_BALL: &str = r#"
        [camera]
        eye = [0, 0.8, 5]
        look_at = [0, 0.8, 0]
        [image]
        width = 1
        height = 1
        [materials.water]
        kd = 0
        kt = 1
        ior = 1.3333333333333333
        [[object]]
        material = "water"
        sphere = { center = [0, 0, 0], radius = 1 }
    "#;

    #[test]
    fn refraction_with_the_outward_normal_is_named_so_not_mirrored() {
        let scene = raystep_engine::scene::parse(Path::new("x.toml"), WATER_BALL).unwrap();
        let ours = OurRays::record(&scene, &scene.settings, (0, 0));
        // In at p = (0, 0.8, 0.6), N = p, cos_i = 0.6, η = 3/4, k = 0.64:
        // T = 0.75 (0, 0, -1) − 0.35 N = (0, −0.28, −0.96). Out after
        // t = 1.6 at q = (0, 0.352, −0.936), N = −q, cos_i = 0.8, η = 4/3,
        // k = 1 − (16/9)(0.36) = 0.36: ours (0, −0.5376, −0.8432). With
        // N_g = q instead: cos_i = −0.8, T = (4/3) d + (−16/15 − 0.6) q
        // = (0, −0.96, 0.28), which is also ours mirrored in the plane.
        let ray = ours.find(&RayPath::parse("P/T/T", 0).unwrap()).unwrap();
        let check = Check {
            field: Field::Dir,
            yours: Value::Vector(DVec3::new(0.0, -0.96, 0.28)),
            ours: ours.rays()[ray].dir.map(Value::Vector),
            agrees: false,
        };
        let (kind, words) = classify(&scene, &ours, ray, &check);
        assert_eq!(kind, Kind::OutwardNormal, "{words}");
        assert!(words.contains("the same η"), "{words}");
    }

    /// A plane mirror, the floor y = 0, seen from (0, 1, 1): the only
    /// pixel's ray meets it at the origin, and its reflected ray
    /// (0, a, −a), a = 1/√2, rises away from it and hits nothing.
    const MIRROR_FLOOR: &str = r#"
        [camera]
        eye = [0, 1, 1]
        look_at = [0, 0, 0]
        [image]
        width = 1
        height = 1
        [materials.mirror]
        ks = 0.5
        [[object]]
        name = "floor"
        material = "mirror"
        plane = { normal = [0, 1, 0], point = [0, 0, 0] }
    "#;

    #[test]
    fn a_ray_that_finds_the_surface_it_leaves_is_a_self_hit_where_ours_misses() {
        let scene = raystep_engine::scene::parse(Path::new("x.toml"), MIRROR_FLOOR).unwrap();
        let ours = OurRays::record(&scene, &scene.settings, (0, 0));
        let ray = ours.find(&RayPath::parse("P/R", 0).unwrap()).unwrap();
        // Without EPS the student's P/R finds the floor it starts on.
        let check = Check {
            field: Field::Hit,
            yours: Value::Hit(Hit::Object(0)),
            ours: Some(Value::Hit(Hit::Miss)),
            agrees: false,
        };
        let (kind, words) = classify(&scene, &ours, ray, &check);
        assert_eq!(kind, Kind::SelfHit, "{words}");
        assert!(
            words.contains("the surface the ray starts on; ours hit nothing"),
            "{words}"
        );
    }

    #[test]
    fn an_infinite_t_where_ours_has_none_is_not_said_to_be_finite() {
        // The mirror floor's P/R misses: ours has no t (issue 39 found
        // "yours is infinity; ours is finite" here).
        let scene = raystep_engine::scene::parse(Path::new("x.toml"), MIRROR_FLOOR).unwrap();
        let ours = OurRays::record(&scene, &scene.settings, (0, 0));
        let ray = ours.find(&RayPath::parse("P/R", 0).unwrap()).unwrap();
        let check = Check {
            field: Field::T,
            yours: Value::Number(f64::INFINITY),
            ours: None,
            agrees: false,
        };
        let (kind, words) = classify(&scene, &ours, ray, &check);
        assert_eq!(kind, Kind::Infinite);
        assert_eq!(words, "yours is infinity; ours has no t");
    }

    /// A chalk ball (k_d = 0.5, white) at the origin seen from (0, 0, 5),
    /// the lamp at (0, 3, 5): the only ray meets it at p = (0, 0, 1),
    /// N = (0, 0, 1), P_L − p = (0, 3, 4), d_L = 5, N·L = 0.8; diffuse
    /// 0.5 × 0.8 = 0.4 grey. With the lamp at (0, 3, −3) instead,
    /// P_L − p = (0, 3, −4) and N·L = −0.8: behind the surface.
    fn chalk_ball(lamp_z: f64) -> Scene {
        let text = format!(
            r#"
            [camera]
            eye = [0, 0, 5]
            look_at = [0, 0, 0]
            [image]
            width = 1
            height = 1
            [materials.chalk]
            kd = 0.5
            [[light]]
            position = [0, 3, {lamp_z}]
            [[object]]
            material = "chalk"
            sphere = {{ center = [0, 0, 0], radius = 1 }}
            "#
        );
        raystep_engine::scene::parse(Path::new("x.toml"), &text).unwrap()
    }

    fn diffuse_check(scene: &Scene, yours: f64) -> (Kind, String) {
        let ours = OurRays::record(scene, &scene.settings, (0, 0));
        let check = Check {
            field: Field::Diffuse(0),
            yours: Value::Vector(DVec3::splat(yours)),
            ours: ours.rays()[0].diffuse.as_ref().map(|d| Value::Vector(d[0])),
            agrees: false,
        };
        classify(scene, &ours, 0, &check)
    }

    #[test]
    fn a_diffuse_term_d_l_times_ours_is_named_an_unnormalised_l() {
        // The student's N·L with L = (0, 3, 4): 4, diffuse 0.5 × 4 = 2.
        let (kind, words) = diffuse_check(&chalk_ball(5.0), 2.0);
        assert_eq!(kind, Kind::Scaled);
        assert!(
            words.contains("yours is 5 × ours: d_L = 5: L = P_L − p not normalised"),
            "{words}"
        );
    }

    #[test]
    fn a_term_of_a_light_behind_the_surface_is_said_to_be_one() {
        // The student's |N·L| = 0.8: diffuse 0.4 where ours is 0.
        let (kind, words) = diffuse_check(&chalk_ball(-3.0), 0.4);
        assert_eq!(kind, Kind::Other);
        assert!(
            words.contains("light 0 is behind the surface (N·L = -0.8 ≤ 0)"),
            "{words}"
        );
        assert!(words.contains("|N·L|"), "{words}");
    }

    /// `text` (a TOML scene) recorded at `pixel` with `mistake` on.
    fn ours_under(text: &str, mistake: Mistake, pixel: (u32, u32)) -> (Scene, OurRays) {
        let scene = raystep_engine::scene::parse(Path::new("x.toml"), text).unwrap();
        let settings = raystep_engine::scene::Settings {
            mistakes: raystep_model::mistakes::Mistakes::from_iter([mistake]),
            ..scene.settings
        };
        let ours = OurRays::record(&scene, &settings, pixel);
        (scene, ours)
    }

    fn direction_check(ours: &OurRays, ray: usize, yours: DVec3) -> Check {
        Check {
            field: Field::Dir,
            yours: Value::Vector(yours),
            ours: ours.rays()[ray].dir.map(Value::Vector),
            agrees: false,
        }
    }

    #[test]
    fn a_model_refraction_beside_ours_under_eta_inverted_is_eta_swapped_against_our_eta() {
        // The water ball met lower, at p = (0, 0.3, √0.91), N = p: even
        // η = 4/3 (ours, eta-inverted: ior entering) refracts there.
        let text = WATER_BALL.replace("0.8", "0.3");
        let (scene, ours) = ours_under(&text, Mistake::EtaInverted, (0, 0));
        let ray = ours.find(&RayPath::parse("P/T", 0).unwrap()).unwrap();
        // The student's T by MODEL §5, η = 1/ior = 3/4:
        // T = η d + (η cos_i − √k) N, cos_i = −d·N, k = 1 − η² (1 − cos_i²).
        let d = ours.rays()[0].dir.unwrap();
        let n = ours.tree.root().hit.as_ref().unwrap().normal;
        let (eta, cos_i) = (0.75, -d.dot(n));
        let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
        let yours = eta * d + (eta * cos_i - k.sqrt()) * n;
        let (kind, words) = classify(&scene, &ours, ray, &direction_check(&ours, ray, yours));
        assert_eq!(kind, Kind::EtaSwapped, "{words}");
        assert!(
            words.contains(&format!("ours with η = {}", num(4.0 / 3.0))),
            "{words}"
        );
    }

    #[test]
    fn a_centre_ray_beside_ours_under_pixel_corner_names_our_corner() {
        // A 4 x 2 image, fov 90 (s = 1, W / H = 2), from the origin down −z.
        // Pixel (0, 0)'s centre ray by MODEL §2: px = (2 × 0.5 / 4 − 1) × 2
        // = −1.5, py = (1 − 2 × 0.5 / 2) = 0.5; ours (pixel-corner) goes
        // through the corner (0, 0), px = −2, py = 1: ratios 0.75 and 0.5,
        // not one field of view but another point of the image.
        let text = r#"
            [camera]
            eye = [0, 0, 0]
            look_at = [0, 0, -1]
            fov = 90
            [image]
            width = 4
            height = 2
            [materials.wall]
            kd = 1
            [[object]]
            material = "wall"
            plane = { normal = [0, 0, 1], point = [0, 0, -10] }
        "#;
        let (scene, ours) = ours_under(text, Mistake::PixelCorner, (0, 0));
        let yours = DVec3::new(-1.5, 0.5, -1.0).normalize();
        let (kind, words) = classify(&scene, &ours, 0, &direction_check(&ours, 0, yours));
        assert_eq!(kind, Kind::OtherPixel, "{words}");
        assert!(words.contains("at (0.5, 0.5) in pixel units"), "{words}");
        assert!(
            words.contains("ours at (0, 0), the top-left corner"),
            "{words}"
        );
    }
}
