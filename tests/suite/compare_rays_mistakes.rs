//! `compare --rays` on a student's mistakes (issue 21's "Done when"):
//! hand-written logs of tiny scenes, every logged number worked out by hand
//! from docs/MODEL.md in a comment, each with the first divergence and its
//! kind it must give; and for every mistake of the catalogue a ray can
//! show, the log raystep prints under it, named at tree level, its first
//! divergence where MODEL §8 says the mistake first acts.

use std::path::Path;

use raystep_engine::record::record_pixel;
use raystep_engine::scene::{Scene, Settings};
use raystep_model::mistakes::{Mistake, Mistakes};
use raystep_tools::divergence::{Divergence, Kind, PixelReport, Tolerance, Value, compare_log};
use raystep_tools::raylog::{RaylogReader, raylog};

use crate::support::{scene, scene_at};

/// `log`, all of one pixel, beside raystep's tree of that pixel.
fn compared(scene: &Scene, log: &str) -> PixelReport {
    let reader = RaylogReader::new("LOG", log.as_bytes(), scene);
    let comparison = compare_log(scene, reader, Tolerance::default()).unwrap();
    assert_eq!(comparison.pixels.len(), 1, "one pixel logged");
    comparison.pixels.into_iter().next().unwrap()
}

/// The first divergence, which must be at `path` and `field`, of `kind`.
fn first<'a>(report: &'a PixelReport, path: &str, field: &str, kind: Kind) -> &'a Divergence {
    let first = report
        .first_divergence
        .as_ref()
        .expect("the log differs from ours");
    let at = format!("{} {}", first.path, first.field);
    assert_eq!(at, format!("{path} {field}"), "{first:#?}");
    assert_eq!(first.kind, kind, "{first:#?}");
    assert!(!report.matches);
    first
}

fn vector(value: Option<Value>) -> [f64; 3] {
    match value {
        Some(Value::Vector(v)) => v.to_array(),
        other => panic!("not a vector: {other:?}"),
    }
}

/// A plane mirror, the floor y = 0 (k_s = 0.5), seen from (0, 1, 1).
const MIRROR_FLOOR: &str = r#"
    [camera]
    eye = [0, 1, 1]
    look_at = [0, 0, 0]
    [image]
    width = 1
    height = 1
    [materials.mirror]
    kd = 0.5
    ks = 0.5
    [[object]]
    name = "floor"
    material = "mirror"
    plane = { normal = [0, 1, 0], point = [0, 0, 0] }
"#;

#[test]
fn a_reflection_with_its_sign_changed_is_named_negated() {
    // MODEL §2: f = normalize((0, 0, 0) − (0, 1, 1)) = (0, −a, −a) with
    // a = 1/√2 = 0.7071067811865476; a 1x1 image's only ray (px = py = 0)
    // goes along f. It meets y = 0 at t = 1/a = √2 = 1.4142135623730951,
    // at the origin, N = (0, 1, 0) (N·d = −a ≤ 0: already facing the ray).
    // MODEL §5: R = d − 2 (d·N) N = (0, −a, −a) + 2a (0, 1, 0) = (0, a, −a).
    // The student's R = 2 (N·d) N − d = −R = (0, −a, a).
    let s = scene(MIRROR_FLOOR);
    let log = r#"
{"pixel": [0, 0], "path": "P", "origin": [0, 1, 1], "dir": [0, -0.7071067811865476, -0.7071067811865476], "hit": 0, "t": 1.4142135623730951, "point": [0, 0, 0], "normal": [0, 1, 0]}
{"pixel": [0, 0], "path": "P/R", "origin": [0, 0, 0], "dir": [0, -0.7071067811865476, 0.7071067811865476]}
"#;
    let report = compared(&s, log);
    let d = first(&report, "P/R", "dir", Kind::Negated);
    assert!(d.words.contains("−1 × ours"), "{}", d.words);
    assert!(
        d.meaning[0].contains("R = d − 2 (d·N) N"),
        "{:?}",
        d.meaning
    );
    // Ours is R = (0, a, −a).
    let [x, y, z] = vector(d.ours);
    let a = std::f64::consts::FRAC_1_SQRT_2;
    assert!(x.abs() < 1e-12 && (y - a).abs() < 1e-12 && (z + a).abs() < 1e-12);
}

#[test]
fn a_reflected_ray_without_eps_finds_the_mirror_it_leaves() {
    // The mirror floor again: ours P/R leaves the origin along (0, a, −a),
    // rising away from y = 0, and hits nothing. The student's intersection
    // test accepts t > 0: rounding puts P/R's start a hair below the floor,
    // and P/R finds the floor itself at t = 1e-17.
    let s = scene(MIRROR_FLOOR);
    let log = r#"
{"pixel": [0, 0], "path": "P", "origin": [0, 1, 1], "dir": [0, -0.7071067811865476, -0.7071067811865476], "hit": 0, "t": 1.4142135623730951}
{"pixel": [0, 0], "path": "P/R", "origin": [0, 0, 0], "dir": [0, 0.7071067811865476, -0.7071067811865476], "hit": 0, "t": 1e-17}
"#;
    let report = compared(&s, log);
    let d = first(&report, "P/R", "hit", Kind::SelfHit);
    assert_eq!(d.ours, Some(Value::Hit(raystep_tools::raylog::Hit::Miss)));
    assert!(
        d.words.contains(
            "yours hit object 0 (floor), the surface the ray starts on; ours hit nothing"
        ),
        "{}",
        d.words
    );
    assert!(d.words.contains("t > EPS = 1e-4"), "{}", d.words);
}

/// A water ball (ior 4/3, k_t = 1, nothing else) at the origin; the only
/// pixel's ray runs down −z at height 0.8.
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
    name = "ball"
    material = "water"
    sphere = { center = [0, 0, 0], radius = 1 }
"#;

#[test]
fn refraction_leaving_a_ball_with_the_outward_normal_is_named() {
    // P: from (0, 0.8, 5) along d = (0, 0, −1); the ball's surface at
    // z = √(1 − 0.64) = 0.6: t = 4.4, p = (0, 0.8, 0.6), N = N_g = p
    // (entering, N_g·d = −0.6 < 0).
    // P/T (MODEL §5): cos_i = −d·N = 0.6, η = 1/ior = 0.75,
    // k = 1 − 0.5625 (1 − 0.36) = 0.64, √k = 0.8;
    // T = 0.75 d + (0.75 × 0.6 − 0.8) N = (0, 0, −0.75) − 0.35 (0, 0.8, 0.6)
    // = (0, −0.28, −0.96). Entering, N_g = N: the student's P/T is right.
    // Inside, from p along T: t² + 2 (p·T) t + (|p|² − 1) = t² − 1.6 t = 0,
    // t = 1.6, q = (0, 0.8 − 0.448, 0.6 − 1.536) = (0, 0.352, −0.936).
    // Leaving: N_g = q, N_g·T = 0.8 > 0, so N = −q = (0, −0.352, 0.936).
    // P/T/T, ours: cos_i = −T·N = 0.8, η = ior = 4/3,
    // k = 1 − (16/9)(0.36) = 0.36, √k = 0.6;
    // (4/3) T + ((4/3) 0.8 − 0.6) N = (0, −0.37333, −1.28) + 0.46667 N
    // = (0, −0.5376, −0.8432).
    // The student's, with N_g = q: cos_i = −T·q = −0.8, k = 0.36 again,
    // (4/3) T + (−(4/3) 0.8 − 0.6) q = (0, −0.37333, −1.28) − 1.66667 q
    // = (0, −0.96, 0.28), which leaves into the ball again.
    let s = scene(WATER_BALL);
    let log = r#"
{"pixel": [0, 0], "path": "P", "origin": [0, 0.8, 5], "dir": [0, 0, -1], "hit": 0, "t": 4.4, "point": [0, 0.8, 0.6], "normal": [0, 0.8, 0.6]}
{"pixel": [0, 0], "path": "P/T", "origin": [0, 0.8, 0.6], "dir": [0, -0.28, -0.96], "hit": 0, "t": 1.6, "point": [0, 0.352, -0.936], "normal": [0, -0.352, 0.936]}
{"pixel": [0, 0], "path": "P/T/T", "origin": [0, 0.352, -0.936], "dir": [0, -0.96, 0.28]}
"#;
    let report = compared(&s, log);
    let d = first(&report, "P/T/T", "dir", Kind::OutwardNormal);
    assert!(d.words.contains("the same η"), "{}", d.words);
    let ours = vector(d.ours);
    assert!((ours[1] + 0.5376).abs() < 1e-9 && (ours[2] + 0.8432).abs() < 1e-9);
    assert!(
        d.meaning.iter().any(|l| l.contains("leaving")),
        "{:?}",
        d.meaning
    );
}

#[test]
fn refraction_entering_with_eta_and_one_over_eta_swapped_is_named() {
    // The water ball, the ray at height 0.3: p = (0, 0.3, √0.91),
    // N = p, cos_i = √0.91 = 0.953939, sin² = 0.09.
    // Ours, η = 1/ior = 0.75: k = 1 − 0.5625 × 0.09 = 0.949375,
    // √k = 0.974359; T = 0.75 d + (0.715454 − 0.974359) N
    // = (0, −0.077671, −0.75 − 0.246980) = (0, −0.077671, −0.996980).
    // The student's η = ior = 4/3: k = 1 − (16/9) 0.09 = 0.84, √k = 0.916515;
    // T = (4/3) d + (1.271919 − 0.916515) N = (0, 0.106621, −0.994299).
    let s = scene(
        &WATER_BALL
            .replace("0.8, 5]", "0.3, 5]")
            .replace("0.8, 0]", "0.3, 0]"),
    );
    let log = r#"
{"pixel": [0, 0], "path": "P", "dir": [0, 0, -1], "hit": 0}
{"pixel": [0, 0], "path": "P/T", "dir": [0, 0.106621, -0.994299]}
"#;
    let report = compared(&s, log);
    let d = first(&report, "P/T", "dir", Kind::EtaSwapped);
    assert!(
        d.words
            .contains("yours is refracted with η = 1.3333, ours with η = 0.75 (entering"),
        "{}",
        d.words
    );
    let [x, y, z] = vector(d.ours);
    assert!(x.abs() < 1e-9 && (y + 0.077671).abs() < 1e-6 && (z + 0.996980).abs() < 1e-6);
}

/// A chalk ball (k_d = 0.5, O_d = (1, 0.5, 0.25)) at the origin seen from
/// (0, 0, 5), a white lamp at (0, 3, 5).
const CHALK_BALL: &str = r#"
    [camera]
    eye = [0, 0, 5]
    look_at = [0, 0, 0]
    [image]
    width = 1
    height = 1
    [materials.chalk]
    color = [1, 0.5, 0.25]
    kd = 0.5
    [[light]]
    name = "lamp"
    position = [0, 3, 5]
    [[object]]
    name = "ball"
    material = "chalk"
    sphere = { center = [0, 0, 0], radius = 1 }
"#;

// The chalk ball's one ray, by hand: down −z from (0, 0, 5), it meets the
// ball at t = 4, p = (0, 0, 1), N = (0, 0, 1). MODEL §4: P_L − p = (0, 3, 4),
// d_L = 5, L = (0, 0.6, 0.8), N·L = 0.8 > 0: a shadow ray, nothing in the
// way, S = 1; f_att = 1; diffuse = 0.5 (1, 0.5, 0.25) 0.8 = (0.4, 0.2, 0.1).

#[test]
fn an_unnormalised_l_is_named_with_its_length() {
    // The student's L = P_L − p = (0, 3, 4), length 5; their N·L = 4, so
    // their diffuse is 0.5 (1, 0.5, 0.25) 4 = (2, 1, 0.5), 5 × ours.
    let s = scene(CHALK_BALL);
    let log = r#"
{"pixel": [0, 0], "path": "P", "origin": [0, 0, 5], "dir": [0, 0, -1], "hit": 0, "t": 4, "point": [0, 0, 1], "normal": [0, 0, 1], "diffuse": [[2, 1, 0.5]]}
{"pixel": [0, 0], "path": "P/S0", "origin": [0, 0, 1], "dir": [0, 3, 4], "S": 1}
"#;
    let report = compared(&s, log);
    let d = first(&report, "P/S0", "dir", Kind::NotNormalised);
    assert!(d.words.contains("length 5 (ours 1)"), "{}", d.words);
    // The diffuse term that follows from it is counted, not a cause.
    assert_eq!(report.later_differences, 1);
}

#[test]
fn an_unnormalised_l_seen_only_in_the_diffuse_term_is_named_by_its_factor() {
    // The same student, whose log gives the shadow ray's S but not its
    // direction: the diffuse term (2, 1, 0.5) is the first number that
    // differs, 5 = d_L times ours.
    let s = scene(CHALK_BALL);
    let log = r#"
{"pixel": [0, 0], "path": "P", "origin": [0, 0, 5], "dir": [0, 0, -1], "hit": 0, "t": 4, "point": [0, 0, 1], "normal": [0, 0, 1], "diffuse": [[2, 1, 0.5]]}
{"pixel": [0, 0], "path": "P/S0", "S": 1}
"#;
    let report = compared(&s, log);
    let d = first(&report, "P", "diffuse[0]", Kind::Scaled);
    assert!(
        d.words
            .contains("yours is 5 × ours: d_L = 5: L = P_L − p not normalised"),
        "{}",
        d.words
    );
}

#[test]
fn a_missing_shadow_ray_is_only_ours_with_the_rule_that_casts_it() {
    // The student shades with S = 1 and casts no shadow ray: their diffuse
    // is right, (0.4, 0.2, 0.1), but MODEL §4 casts P/S0 (N·L = 0.8 > 0).
    let s = scene(CHALK_BALL);
    let log = r#"
{"pixel": [0, 0], "path": "P", "origin": [0, 0, 5], "dir": [0, 0, -1], "hit": 0, "t": 4, "point": [0, 0, 1], "normal": [0, 0, 1], "diffuse": [[0.4, 0.2, 0.1]]}
"#;
    let report = compared(&s, log);
    let d = first(&report, "P/S0", "ray", Kind::OnlyOurs);
    assert_eq!(
        (d.yours, d.ours),
        (Value::Cast(false), Some(Value::Cast(true)))
    );
    assert_eq!(report.later_differences, 0);
    assert_eq!(report.only_ours.len(), 1);
    assert_eq!(report.only_ours[0].path.to_string(), "P/S0");
    assert!(
        report.only_ours[0].rule.contains("N·L = 0.8 > 0"),
        "{}",
        report.only_ours[0].rule
    );
}

/// A chalk wall, the plane z = 0 (k_d = 0.5, white), seen from (0, 0, 5),
/// the lamp behind it at (0, 3, −4).
const WALL_LIT_FROM_BEHIND: &str = r#"
    [camera]
    eye = [0, 0, 5]
    look_at = [0, 0, 0]
    [image]
    width = 1
    height = 1
    [materials.chalk]
    kd = 0.5
    [[light]]
    name = "lamp"
    position = [0, 3, -4]
    [[object]]
    name = "wall"
    material = "chalk"
    plane = { normal = [0, 0, 1], point = [0, 0, 0] }
"#;

#[test]
fn abs_n_dot_l_casts_a_shadow_ray_to_a_light_behind_the_surface() {
    // P meets the wall at t = 5, p = (0, 0, 0), N = (0, 0, 1).
    // P_L − p = (0, 3, −4), d_L = 5, L = (0, 0.6, −0.8), N·L = −0.8 ≤ 0:
    // MODEL §4, the light is behind the surface: no shadow ray, diffuse 0.
    // The student's |N·L| = 0.8 casts P/S0 along L (nothing in the way,
    // S = 1) and adds 0.5 × 0.8 = 0.4 grey.
    let s = scene(WALL_LIT_FROM_BEHIND);
    let log = r#"
{"pixel": [0, 0], "path": "P", "origin": [0, 0, 5], "dir": [0, 0, -1], "hit": 0, "t": 5, "point": [0, 0, 0], "normal": [0, 0, 1], "diffuse": [[0.4, 0.4, 0.4]]}
{"pixel": [0, 0], "path": "P/S0", "origin": [0, 0, 0], "dir": [0, 0.6, -0.8], "S": 1}
"#;
    let report = compared(&s, log);
    let d = first(&report, "P/S0", "ray", Kind::OnlyYours);
    assert!(
        d.meaning[0].contains("behind the surface (N·L = -0.8 ≤ 0)"),
        "{:?}",
        d.meaning
    );
    // The diffuse term, which follows from it.
    assert_eq!(report.later_differences, 1);
    assert_eq!(report.only_yours.len(), 1);
}

#[test]
fn abs_n_dot_l_without_a_shadow_ray_shows_in_the_diffuse_term() {
    // The same student, logging no shadow ray: diffuse[0] is the first
    // number that differs, 0.4 grey where ours is 0.
    let s = scene(WALL_LIT_FROM_BEHIND);
    let log = r#"
{"pixel": [0, 0], "path": "P", "origin": [0, 0, 5], "dir": [0, 0, -1], "hit": 0, "t": 5, "point": [0, 0, 0], "normal": [0, 0, 1], "diffuse": [[0.4, 0.4, 0.4]]}
"#;
    let report = compared(&s, log);
    let d = first(&report, "P", "diffuse[0]", Kind::Other);
    assert_eq!(vector(d.ours), [0.0; 3]);
    assert!(
        d.words
            .contains("light 0 is behind the surface (N·L = -0.8 ≤ 0) and adds nothing"),
        "{}",
        d.words
    );
    assert!(d.words.contains("|N·L|"), "{}", d.words);
    assert!(
        d.meaning[0].contains("behind the surface"),
        "{:?}",
        d.meaning
    );
}

#[test]
fn a_horizontal_field_of_view_used_as_vertical_is_named_with_its_fov() {
    // fov = 90 on a 3x1 image, pixel (2, 0). MODEL §2: s = tan 45° = 1,
    // px = (2 × 2.5 / 3 − 1) × 1 × (3 / 1) = 2, py = 0; f = (0, 0, −1),
    // r = f × up = (1, 0, 0): ours normalize((2, 0, −1)) = (2, 0, −1)/√5.
    // The student takes 90° as the horizontal fov: px = (2/3) × 1 = 2/3,
    // normalize((2/3, 0, −1)) = (2, 0, −3)/√13 = (0.5547001962252291, 0,
    // −0.8320502943378437); px is 1/3 of ours, the rays of a vertical fov
    // of 2 atan(tan 45° / 3) = 2 atan(1/3) = 36.8699°.
    let s = scene(
        r#"
        [camera]
        eye = [0, 0, 5]
        look_at = [0, 0, 0]
        fov = 90
        [image]
        width = 3
        height = 1
        "#,
    );
    let log = r#"{"pixel": [2, 0], "path": "P", "origin": [0, 0, 5], "dir": [0.5547001962252291, 0, -0.8320502943378437], "hit": null}"#;
    let report = compared(&s, log);
    let d = first(&report, "P", "dir", Kind::FieldOfView);
    assert!(
        d.words
            .contains("vertical field of view of 36.8699° (ours 90°"),
        "{}",
        d.words
    );
    assert!(d.words.contains("0.3333 × ours"), "{}", d.words);
}

#[test]
fn a_field_of_view_in_degrees_taken_as_radians_is_named_with_its_fov() {
    // fov = 90 on a 3x3 image, pixel (2, 1). Ours: s = tan 45° = 1,
    // px = 2 × 2.5 / 3 − 1 = 2/3, py = 0: (2, 0, −3)/√13.
    // The student's tan(90 / 2) of 45 radians: 45 − 14π = 1.0177 rad,
    // tan = 1.6197751905438615, px = 1.0798501270292409,
    // normalize((px, 0, −1)) = (0.7337136668575717, 0, −0.6794587957090675);
    // the fov whose s that is: 2 × 1.0177 rad = 116.6202°.
    let s = scene(
        r#"
        [camera]
        eye = [0, 0, 5]
        look_at = [0, 0, 0]
        fov = 90
        [image]
        width = 3
        height = 3
        "#,
    );
    let log = r#"{"pixel": [2, 1], "path": "P", "origin": [0, 0, 5], "dir": [0.7337136668575717, 0, -0.6794587957090675]}"#;
    let report = compared(&s, log);
    let d = first(&report, "P", "dir", Kind::FieldOfView);
    assert!(
        d.words.contains("vertical field of view of 116.62"),
        "{}",
        d.words
    );
    assert!(d.words.contains("(ours 90°"), "{}", d.words);
    assert!(d.words.contains("1.6198 × ours"), "{}", d.words);
}

#[test]
fn a_ray_past_max_depth_is_only_yours_with_the_depth_rule() {
    // Two mirrors facing each other, z = 0 and z = 6, the eye between at
    // (0, 0, 5), max_depth = 2. P (depth 1) meets z = 0 at t = 5,
    // N = (0, 0, 1); P/R (depth 2, weight k_s = 0.5) goes back along
    // (0, 0, 1) and meets z = 6 at t = 6. MODEL §5: a hit at depth 2 spawns
    // nothing when max_depth = 2. The student's test is depth <= max_depth:
    // they cast P/R/R from (0, 0, 6) along (0, 0, −1), weight 0.25.
    let s = scene(
        r#"
        [camera]
        eye = [0, 0, 5]
        look_at = [0, 0, 0]
        [image]
        width = 1
        height = 1
        [settings]
        max_depth = 2
        [materials.mirror]
        kd = 0
        ks = 0.5
        [[object]]
        name = "front mirror"
        material = "mirror"
        plane = { normal = [0, 0, 1], point = [0, 0, 0] }
        [[object]]
        name = "back mirror"
        material = "mirror"
        plane = { normal = [0, 0, 1], point = [0, 0, 6] }
        "#,
    );
    let log = r#"
{"pixel": [0, 0], "path": "P", "origin": [0, 0, 5], "dir": [0, 0, -1], "hit": 0, "t": 5, "weight": 1}
{"pixel": [0, 0], "path": "P/R", "origin": [0, 0, 0], "dir": [0, 0, 1], "hit": 1, "t": 6, "normal": [0, 0, -1], "weight": 0.5}
{"pixel": [0, 0], "path": "P/R/R", "origin": [0, 0, 6], "dir": [0, 0, -1], "hit": 0, "t": 6, "weight": 0.25}
"#;
    let report = compared(&s, log);
    let d = first(&report, "P/R/R", "ray", Kind::OnlyYours);
    assert_eq!(
        (d.yours, d.ours),
        (Value::Cast(true), Some(Value::Cast(false)))
    );
    assert!(
        d.meaning[0].contains("this hit is at depth 2 and max_depth is 2"),
        "{:?}",
        d.meaning
    );
    assert_eq!(report.only_yours[0].path.to_string(), "P/R/R");
    assert!(report.only_ours.is_empty());
}

#[test]
fn a_nan_from_a_negative_cosine_to_a_fractional_power_is_named() {
    // A shiny wall z = 0 (k_d = k_s = 0.5, n = 10.5, Phong) seen from
    // (−3, 0, 4): f = (0.6, 0, −0.8), t = 5 to the origin, N = (0, 0, 1),
    // V = −d = (−0.6, 0, 0.8). The lamp at (−4.8, 0, 1.4): d_L = 5,
    // L = (−0.96, 0, 0.28), N·L = 0.28 > 0, S = 1 (nothing in the way).
    // diffuse = 0.5 × 0.28 = 0.14 grey.
    // R = 2 (N·L) N − L = (0, 0, 0.56) − L = (0.96, 0, 0.28),
    // R·V = −0.576 + 0.224 = −0.352. Ours: max(0, −0.352)^10.5 = 0.
    // The student's pow(−0.352, 10.5), without the max, is NaN, and so is
    // the colour it goes into.
    let s = scene(
        r#"
        [camera]
        eye = [-3, 0, 4]
        look_at = [0, 0, 0]
        [image]
        width = 1
        height = 1
        [settings]
        specular = "phong"
        [materials.shiny]
        kd = 0.5
        ks = 0.5
        n = 10.5
        [[light]]
        position = [-4.8, 0, 1.4]
        [[object]]
        name = "wall"
        material = "shiny"
        plane = { normal = [0, 0, 1], point = [0, 0, 0] }
        "#,
    );
    let log = r#"
{"pixel": [0, 0], "path": "P", "origin": [-3, 0, 4], "dir": [0.6, 0, -0.8], "hit": 0, "t": 5, "point": [0, 0, 0], "normal": [0, 0, 1], "diffuse": [[0.14, 0.14, 0.14]], "specular": [[NaN, NaN, NaN]], "color": [NaN, NaN, NaN]}
{"pixel": [0, 0], "path": "P/S0", "origin": [0, 0, 0], "dir": [-0.96, 0, 0.28], "S": 1}
"#;
    let report = compared(&s, log);
    let d = first(&report, "P", "specular[0]", Kind::Nan);
    assert_eq!(vector(d.ours), [0.0; 3]);
    assert!(d.words.contains("yours is NaN"), "{}", d.words);
    // The colour, and P/R (k_s > 0), which the student did not log.
    assert_eq!(report.later_differences, 2);
}

/// A mirror floor (k_d 1, k_s 0.5, n 1000) lit from straight above by a
/// lamp of 2, seen from (0, 1, 1) against a grey background of 0.2.
const BRIGHT_FLOOR: &str = r#"
    [camera]
    eye = [0, 1, 1]
    look_at = [0, 0, 0]
    [image]
    width = 1
    height = 1
    [settings]
    background = [0.2, 0.2, 0.2]
    [materials.mirror]
    kd = 1
    ks = 0.5
    n = 1000
    [[light]]
    position = [0, 2, 0]
    color = [2, 2, 2]
    [[object]]
    name = "floor"
    material = "mirror"
    plane = { normal = [0, 1, 0], point = [0, 0, 0] }
"#;

#[test]
fn a_colour_clamped_before_the_reflection_is_added_is_named_so() {
    // MODEL §2: the only ray goes along f = (0, −a, −a), a = 1/√2, and
    // meets the floor at the origin, t = √2, N = (0, 1, 0); no ambient.
    // §4: P_L − p = (0, 2, 0), d_L = 2, L = (0, 1, 0), N·L = 1, nothing in
    // the way (S = 1), f_att = 1: diffuse = k_d O_d (N·L) I_p = 2. With
    // V = (0, a, a), N·H = cos 22.5° = 0.92388 and 0.92388^1000 ≈ 5e-35:
    // specular ≈ 0. §5: R = d − 2 (d·N) N = (0, a, −a) meets nothing, its
    // colour the background 0.2, weight k_s = 0.5: it adds 0.1. §6: ours is
    // 2 + 0.1 = 2.1. The student's clamp-before-adding gives min(1, 2) +
    // 0.1 = 1.1 (on main: "scaled: yours is 0.5238 × ours", which blames
    // a factor that is not there).
    let s = scene(BRIGHT_FLOOR);
    let log = r#"
{"pixel": [0, 0], "path": "P", "origin": [0, 1, 1], "dir": [0, -0.7071067811865476, -0.7071067811865476], "hit": 0, "t": 1.4142135623730951, "point": [0, 0, 0], "normal": [0, 1, 0], "ambient": [0, 0, 0], "diffuse": [[2, 2, 2]], "specular": [[0, 0, 0]], "color": [1.1, 1.1, 1.1]}
{"pixel": [0, 0], "path": "P/S0", "origin": [0, 0, 0], "dir": [0, 1, 0], "S": 1}
{"pixel": [0, 0], "path": "P/R", "origin": [0, 0, 0], "dir": [0, 0.7071067811865476, -0.7071067811865476], "hit": null, "color": [0.2, 0.2, 0.2], "weight": 0.5}
"#;
    let report = compared(&s, log);
    let d = first(&report, "P", "color", Kind::Clamped);
    assert_eq!(vector(Some(d.yours)), [1.1; 3]);
    let ours = vector(d.ours);
    assert!(ours.iter().all(|c| (c - 2.1).abs() < 1e-9), "{ours:?}");
    assert!(
        d.words
            .contains("yours is min(1, local) + k_s I_r + k_t I_t = (1, 1, 1) + (0.1, 0.1, 0.1)"),
        "{}",
        d.words
    );
    assert!(
        d.words.contains(
            "the local colour, ambient + the lights' terms = (2, 2, 2), was clamped to 1 \
             before the reflected and transmitted terms were added (clamp-before-adding)"
        ),
        "{}",
        d.words
    );
    assert_eq!(d.kind.name(), "clamped");
    // A 1x1 image: one pixel alone cannot tell the mistake from a
    // coincidence, so it is consistent, not named (issue 39).
    assert!(report.mistakes.is_empty(), "{:?}", report.mistakes);
    assert!(
        report
            .consistent
            .iter()
            .any(|c| c.mistake == Mistake::ClampBeforeAdding)
    );
}

/// A mistake of the catalogue, a pixel of a scene of scenes/ (or
/// `BRIGHT_MIRROR`) at 32x24 where it acts, and the path and field where it
/// first acts.
struct Row {
    mistake: Mistake,
    scene: &'static str,
    pixel: (u32, u32),
    path: &'static str,
    field: &'static str,
    /// Words the first divergence must hold.
    words: &'static str,
}

/// Why each row's path is where its mistake first acts (MODEL §8), in
/// the order of the tracer (MODEL §6: a ray, its hit, ambient, per light
/// its shadow ray then its terms, the reflected then the transmitted
/// subtree, the colour).
///
/// glass.toml (12, 6) at 32x24: P enters the glass ball (front side, N =
/// N_g, cos_i = 0.34); both lights face P's hit and nothing is in their way
/// (S = 1); P/R (weight k_s = 0.1) misses; P/T meets the ball's far side
/// from inside (back side, N = −N_g), its shadow rays cross the ball once
/// (S = k_t = 0.9); P/T/R and P/T/R/R reflect inside the ball, P/T/R/R is at
/// depth 4 and its transmitted child P/T/R/R/T at depth 5.
fn rows() -> Vec<Row> {
    let row = |mistake, scene, pixel, path, field, words| Row {
        mistake,
        scene,
        pixel,
        path,
        field,
        words,
    };
    vec![
        // Its segment (0, d_L) takes the surface a shadow ray starts on at
        // t ~ 1e-16 when rounding puts the start on the blocking side. P's
        // shadow rays leave the ball outwards: their own root there is at
        // t ≈ 0 or behind them (here rounding keeps them clear). P/T's leave
        // the ball from inside, through the glass: the start surface is
        // counted as one more crossing, S = 0.9 × 0.9 = 0.81.
        row(
            Mistake::ShadowAcne,
            "glass",
            (12, 6),
            "P/T/S0",
            "S",
            "S = 0.81; ours is partly blocked, S = 0.9",
        ),
        // N_g in N·L: nothing changes on P's front-side hit (N = N_g); on
        // P/T's back-side hit N·L with N_g is −N·L ≤ 0, so light 0 "faces
        // away" and no shadow ray is cast: P/T/S0 is missing, after P/T's
        // ambient, which does not use N.
        row(
            Mistake::NoNormalFlip,
            "glass",
            (12, 6),
            "P/T/S0",
            "ray",
            "you never cast it",
        ),
        // η = ior = 1.5 entering: k = 1 − 2.25 (1 − 0.34²) < 0 at P's hit,
        // TIR: no P/T, and k_t moves to P/R, whose weight is 0.1 + 0.9 = 1
        // where ours is 0.1. P/R's direction uses N only, so its weight is
        // its first number that differs (P/R comes before P/T).
        row(
            Mistake::EtaInverted,
            "glass",
            (12, 6),
            "P/R",
            "weight",
            "yours is 10 × ours: k_s + k_t, the weight of total internal reflection",
        ),
        // prism.toml (9, 6): P enters the long face (no TIR); P/T meets a
        // short face at about 45° inside the glass, TIR. The prism has
        // k_s = 0, so under tir-dropped its reflected weight is 0 and no
        // reflected ray is spawned: P/T/R, ours, is missing.
        row(
            Mistake::TirDropped,
            "prism",
            (9, 6),
            "P/T/R",
            "ray",
            "you never cast it",
        ),
        // highlights.toml (10, 6): the Blinn ball of n = 30 near its
        // highlight, max_depth = 1, one lamp. R·V in place of N·H changes
        // the specular term of P's only hit, its first number after the
        // shadow ray (which it does not touch); R·V < N·H, so it is smaller.
        row(
            Mistake::PhongNotBlinn,
            "highlights",
            (10, 6),
            "P",
            "specular[0]",
            "yours is 0.3168 × ours",
        ),
        // P's shadow rays cross nothing; P/T/S0 is the first to cross glass
        // (k_t = 0.9), which the mistake makes opaque: S = 0.
        row(
            Mistake::OpaqueShadows,
            "glass",
            (12, 6),
            "P/T/S0",
            "S",
            "fully blocked; ours is partly blocked, S = 0.9",
        ),
        // prism.toml (7, 6): P hits the prism's front face (z = 0); the
        // lamp at (0, 5, 8) is in front of it with nothing between, and the
        // green wall, the plane z = 12, lies beyond the lamp: the shadow
        // ray's line, going towards +z, meets it past d_L. The segment
        // (EPS, ∞) takes it: P/S0, the first shadow ray, is fully blocked
        // where ours is not.
        row(
            Mistake::ShadowsPastLight,
            "prism",
            (7, 6),
            "P/S0",
            "S",
            "fully blocked; ours is unblocked",
        ),
        // attenuation.toml (3, 1): P hits a lit surface; f_att = 1 in place
        // of 0.848 first changes P's diffuse[0] (f_att is no logged number
        // of its own, and S does not use it).
        row(
            Mistake::NoLightAttenuation,
            "attenuation",
            (3, 1),
            "P",
            "diffuse[0]",
            "1/f_att (f_att = 0.848)",
        ),
        // max_depth = 5: under the mistake a hit at depth 4 spawns nothing.
        // The only ray ours casts from a depth-4 hit is P/T/R/R/T (P/T/R/R's
        // reflected ray is below min_weight); P/T/R/R's colour, which
        // changes with it, comes after its children.
        row(
            Mistake::DepthOffByOne,
            "glass",
            (12, 6),
            "P/T/R/R/T",
            "ray",
            "you never cast it",
        ),
        // The ambient term of the first hit, P's (I_a = 0.08 grey).
        row(
            Mistake::NoAmbient,
            "glass",
            (12, 6),
            "P",
            "ambient",
            "yours is 0 where ours is (0.08, 0.08, 0.08)",
        ),
        // Row 6 of 24 gets the ray of row 24 − 1 − 6 = 17: P's direction,
        // through (12.5, 17.5) in pixel units.
        row(
            Mistake::FlippedY,
            "glass",
            (12, 6),
            "P",
            "dir",
            "yours crosses the image at (12.5, 17.5)",
        ),
        // P through the pixel's corner (12, 6), not its centre.
        row(
            Mistake::PixelCorner,
            "glass",
            (12, 6),
            "P",
            "dir",
            "yours crosses the image at (12, 6) in pixel units; ours at (12.5, 6.5)",
        ),
        // P's shadow rays leave the ball outwards and rounding keeps them
        // clear of it, and P/R leaves it outwards and misses; P/T, which
        // starts on the surface it has just crossed, finds that surface
        // again at t ≈ 6e-15 once t > 0 is accepted.
        row(
            Mistake::NoEpsilon,
            "glass",
            (12, 6),
            "P/T",
            "t",
            "a hit must lie at t > EPS = 1e-4",
        ),
        // P's first light (N·L = 0.873, unblocked): the shadow ray is cast
        // along the unit L as before, so N·L = d_L × ours first shows in
        // P's diffuse[0].
        row(
            Mistake::LightNotNormalised,
            "glass",
            (12, 6),
            "P",
            "diffuse[0]",
            "d_L = 7.8202: L = P_L − p not normalised",
        ),
        // P/R, the first reflected ray, goes the other way.
        row(
            Mistake::ReflectionSign,
            "glass",
            (12, 6),
            "P/R",
            "dir",
            "yours is −1 × ours",
        ),
        // Entering (P) N = N_g: nothing changes. Rays leave the ball at
        // P/T, P/T/R and P/T/R/R (no TIR at any); in the tracer's order,
        // reflected subtrees first, the first transmitted ray out of the
        // glass is P/T/R/R/T.
        row(
            Mistake::RefractionOutwardNormal,
            "glass",
            (12, 6),
            "P/T/R/R/T",
            "dir",
            "(N_g when leaving), and the same η",
        ),
        // Every light faces the hits of P, P/T and P/T/R; at P/T/R/R both
        // are behind the surface (N·L = −0.805 and −0.699): |N·L| casts
        // P/T/R/R/S0, which ours does not.
        row(
            Mistake::TwoSidedDiffuse,
            "glass",
            (12, 6),
            "P/T/R/R/S0",
            "ray",
            "ours never casts this ray",
        ),
        // bright-mirror (18, 18): P hits the mirror floor, whose own light
        // is below 1; P/R hits the white ball where a lamp of 2.5 makes its
        // local colour 1.44, clamped to 1: P/R's colour (on main, "yours is
        // 0.6934 × ours", 1 / 1.44, as if scaled).
        row(
            Mistake::ClampBeforeAdding,
            "bright-mirror",
            (18, 18),
            "P/R",
            "color",
            "(1.4422, 1.4422, 1.4422), was clamped to 1 before the reflected and transmitted terms were added",
        ),
        // P's first light is d_L = 7.82 away; the scene has no attenuation,
        // so f_att = 1 / 7.82² in place of 1, first in P's diffuse[0].
        row(
            Mistake::InverseSquare,
            "glass",
            (12, 6),
            "P",
            "diffuse[0]",
            "1/d_L² (d_L = 7.8202)",
        ),
        // s = tan 40° in place of tan 20°: the rays of an 80° field of view.
        row(
            Mistake::FovFullAngle,
            "glass",
            (12, 6),
            "P",
            "dir",
            "vertical field of view of 80° (ours 40°",
        ),
    ]
}

/// The log raystep prints of `pixel` of `scene` under `mistakes`.
fn log_under(scene: &Scene, mistakes: Mistakes, (x, y): (u32, u32)) -> String {
    let settings = Settings {
        mistakes,
        ..scene.settings
    };
    raylog(&record_pixel(scene, &settings, x, y))
}

/// A white ball (k_d 1) above a mirror floor (k_d 0.2, k_s 0.7), lit from
/// the side by a lamp of 2.5: the ball's lit side is brighter than 1, and
/// the mirror shows it.
pub(crate) const BRIGHT_MIRROR: &str = r#"
    [camera]
    eye = [0, 1, 5]
    look_at = [0, -0.5, 0]
    [image]
    width = 64
    height = 48
    [materials.white]
    kd = 1
    [materials.mirror]
    kd = 0.2
    ks = 0.7
    [[light]]
    position = [4, 0, 4]
    color = [2.5, 2.5, 2.5]
    [[object]]
    name = "ball"
    material = "white"
    sphere = { center = [0, 0.3, 0], radius = 1 }
    [[object]]
    name = "mirror"
    material = "mirror"
    plane = { normal = [0, 1, 0], point = [0, -1, 0] }
"#;

/// A scene of scenes/ at 32x24, or `BRIGHT_MIRROR` at 32x24 for "bright-mirror".
fn scene_of(name: &str) -> Scene {
    if name == "bright-mirror" {
        return scene(BRIGHT_MIRROR)
            .with_size(32, 24)
            .expect("a valid size");
    }
    let path = format!("{}/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    scene_at(Path::new(&path), Some((32, 24)))
}

#[test]
fn every_traceable_mistake_is_named_at_tree_level_where_it_first_acts() {
    let rows = rows();
    let tried: Vec<Mistake> = rows.iter().map(|r| r.mistake).collect();
    let traceable: Vec<Mistake> = Mistake::ALL
        .into_iter()
        .filter(|m| ![Mistake::ByteWrap, Mistake::Gamma].contains(m))
        .collect();
    assert_eq!(
        tried, traceable,
        "one row per traceable mistake, in catalogue order"
    );
    for row in rows {
        let context = format!("{} on {} {:?}", row.mistake, row.scene, row.pixel);
        let scene = scene_of(row.scene);
        let log = log_under(&scene, Mistakes::NONE.with(row.mistake), row.pixel);
        let report = compared(&scene, &log);
        // One pixel logged: consistent with the mistake, never named from
        // it alone (issue 39), with a pixel to log that would tell.
        let consistent: Vec<Mistake> = report.consistent.iter().map(|c| c.mistake).collect();
        assert!(
            consistent.contains(&row.mistake) && report.mistakes.is_empty(),
            "{context}: named {:?}, consistent with {consistent:?}",
            report.mistakes
        );
        let first = report.first_divergence.as_ref().expect(&context);
        assert_eq!(
            format!("{} {}", first.path, first.field),
            format!("{} {}", row.path, row.field),
            "{context}: {first:#?}"
        );
        assert!(
            first.words.contains(row.words),
            "{context}: {}",
            first.words
        );
    }
}

#[test]
fn a_mistake_of_the_bytes_leaves_the_log_as_ours() {
    // gamma and byte-wrap act after every ray is traced (MODEL §6, §8):
    // the log printed under them is ours, ray for ray.
    let scene = scene_of("glass");
    for mistake in [Mistake::Gamma, Mistake::ByteWrap] {
        let log = log_under(&scene, Mistakes::NONE.with(mistake), (12, 6));
        let report = compared(&scene, &log);
        assert!(report.matches, "{mistake}");
        assert!(report.first_divergence.is_none() && report.mistakes.is_empty());
    }
}
