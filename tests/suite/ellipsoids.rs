//! Spheres under an affine transform (ellipsoids, MODEL §3) through the
//! whole engine: a TOML `sphere` with `scale` and `rotate`, hit where the
//! stretched surface is, with the inverse transpose's normal, and its
//! working recorded in the sphere's own space and said so.

use std::path::Path;

use raystep_engine::record::text;
use raystep_engine::scene::{self, SceneError};
use raystep_model::shapes::{Shape, Working};

use crate::support::{record, scene};

/// The unit sphere at the origin under `placing` (the rest of a `sphere = {}`),
/// lit from the camera's side.
fn placed(placing: &str) -> String {
    format!(
        r#"[camera]
eye = [0, 0, 10]
look_at = [0, 0, 0]

[materials.white]
color = [1, 1, 1]

[[light]]
position = [0, 0, 10]

[[object]]
material = "white"
sphere = {{ center = [0, 0, 0], radius = 1{placing} }}
"#
    )
}

const DOWN: [f64; 3] = [0.0, 0.0, -1.0];

#[test]
fn a_scaled_sphere_is_hit_where_the_ellipsoid_is() {
    // scale [2, 1, 1]: x^2/4 + y^2 + z^2 = 1. Down -z from z = 10: at x = 1.9
    // a hit (1.9^2/4 = 0.9025 < 1), at x = 2.1 a miss (1.1025 > 1); at x = 1
    // the surface is at z = sqrt(1 - 1/4) = sqrt(0.75), t = 10 - sqrt(0.75).
    let s = scene(&placed(", scale = [2, 1, 1]"));
    assert_eq!(s.objects[0].shape.kind(), "ellipsoid");
    assert!(record(&s, [1.9, 0.0, 10.0], DOWN).root().hit.is_some());
    assert!(record(&s, [2.1, 0.0, 10.0], DOWN).root().hit.is_none());
    let tree = record(&s, [1.0, 0.0, 10.0], DOWN);
    let hit = tree.root().hit.as_ref().unwrap();
    assert!((hit.t - (10.0 - 0.75f64.sqrt())).abs() < 1e-12);
}

#[test]
fn its_normal_is_the_inverse_transposes() {
    // Along -x at y = sqrt 0.5 the ray meets x^2/4 + 0.5 = 1 at x = sqrt 2:
    // p = (sqrt 2, sqrt 0.5, 0), t = 10 - sqrt 2. p' = M^-1 p =
    // (sqrt 0.5, sqrt 0.5, 0), M^-T p' = (sqrt 0.5 / 2, sqrt 0.5, 0), which
    // normalised is (1, 2, 0)/sqrt 5, not (p - c)/|p - c| = (2, 1, 0)/sqrt 5.
    let s = scene(&placed(", scale = [2, 1, 1]"));
    let tree = record(&s, [10.0, 0.5f64.sqrt(), 0.0], [-1.0, 0.0, 0.0]);
    let hit = tree.root().hit.as_ref().unwrap();
    assert!((hit.t - (10.0 - 2f64.sqrt())).abs() < 1e-12);
    let n = hit.geometric_normal;
    let expected = [1.0 / 5f64.sqrt(), 2.0 / 5f64.sqrt(), 0.0];
    assert!((n.to_array().iter().zip(expected)).all(|(a, b)| (a - b).abs() < 1e-12));
    assert!(
        n.dot(hit.point.normalize()) < 0.9,
        "not the direction from the centre"
    );
}

#[test]
fn a_turned_ellipsoid_is_turned_about_its_centre() {
    // rotate [0, 0, 90] turns x onto y: y^2/4 + x^2 + z^2 = 1 about the
    // centre (0, 0, 0). Down -z: at y = 1.9 a hit, at x = 1.9 a miss.
    let s = scene(&placed(", scale = [2, 1, 1], rotate = [0, 0, 90]"));
    assert!(record(&s, [0.0, 1.9, 10.0], DOWN).root().hit.is_some());
    assert!(record(&s, [1.9, 0.0, 10.0], DOWN).root().hit.is_none());
}

#[test]
fn a_uniform_scale_is_a_plain_sphere() {
    // scale [2, 2, 2] turned any way is the sphere of radius 2 r = 2.
    let s = scene(&placed(", scale = [2, 2, 2], rotate = [10, 20, 30]"));
    let Shape::Sphere(sphere) = &s.objects[0].shape else {
        panic!("a uniform scale gives a sphere");
    };
    assert_eq!(sphere.radius, 2.0);
    assert_eq!(s.objects[0].name.to_string(), "sphere 0");
}

fn error_of(placing: &str) -> SceneError {
    scene::parse(Path::new("t.toml"), &placed(placing))
        .map(|_| ())
        .expect_err("refused")
}

#[test]
fn a_zero_or_negative_scale_is_refused_where_it_is_written() {
    // Line 13: `sphere = { center = [0, 0, 0], radius = 1, scale = [2, 0, 1] }`;
    // "sphere = { " is 11 characters, "center = [0, 0, 0], " 20, "radius = 1, " 12,
    // "scale = [2, " 12: the 0 is the 56th.
    let error = error_of(", scale = [2, 0, 1]");
    let at = error.location.unwrap();
    assert_eq!((at.line, at.column), (13, 56));
    assert_eq!(
        error.message,
        "`object[0].sphere.scale[1]` is 0: a zero scale flattens the sphere and its transform \
         has no inverse; a scale factor must be between 0.001 and 10000"
    );
    let error = error_of(", scale = [-2, 1, 1]");
    assert_eq!(
        error.message,
        "`object[0].sphere.scale[0]` must be between 0.001 and 10000, got -2"
    );
}

#[test]
fn the_working_is_recorded_in_the_spheres_own_space() {
    // The ray of the first test, x = 1 down -z: o' = M^-1 o = (0.5, 0, 10),
    // d' = (0, 0, -1); A = 1, B = -20, C = 0.25 + 100 - 1 = 99.25,
    // discriminant 400 - 397 = 3, t0 = (20 - sqrt 3)/2 = 9.1340.
    // p' = (0.5, 0, sqrt 0.75) = n', M^-T n' = (0.25, 0, 0.8660), N_g =
    // (0.25, 0, 0.8660)/0.9014 = (0.2774, 0, 0.9608).
    let s = scene(&placed(", scale = [2, 1, 1]"));
    let tree = record(&s, [1.0, 0.0, 10.0], DOWN);
    let hit = tree.root().hit.as_ref().unwrap();
    let Working::Ellipsoid(w) = &hit.working else {
        panic!("an ellipsoid's working");
    };
    assert_eq!(w.object_origin.to_array(), [0.5, 0.0, 10.0]);
    let q = w.quadratic;
    assert_eq!((q.a, q.b, q.c, q.discriminant), (1.0, -20.0, 99.25, 3.0));
    let json = tree.to_json();
    let working = &json["tree"]["hit"]["working"];
    assert_eq!(working["shape"], "ellipsoid");
    assert_eq!(
        working["object_origin"],
        serde_json::json!([0.5, 0.0, 10.0])
    );
    snapshot!("working_in_object_space", text(&tree));
}

#[test]
fn a_ray_log_with_the_normal_from_the_centre_is_told_the_inverse_transpose() {
    // A student's tracer that takes an ellipsoid's normal as a sphere's,
    // (p - M c)/|p - M c|, logs everything else as ours: the first
    // divergence is the normal, and what ours is says how it was made.
    let log = crate::support::raystep(&[
        "inspect",
        "scenes/ellipsoid.toml",
        "--pixel",
        "112,50",
        "--format",
        "raylog",
    ]);
    assert!(log.status.success());
    let first = String::from_utf8(log.stdout).unwrap();
    let mut primary: serde_json::Value =
        serde_json::from_str(first.lines().next().unwrap()).unwrap();
    // The squashed ball's centre M c is its `center`, (1.6, 1, 0).
    let p: Vec<f64> = serde_json::from_value(primary["point"].clone()).unwrap();
    let v = [p[0] - 1.6, p[1] - 1.0, p[2]];
    let length = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    primary["normal"] = serde_json::json!([v[0] / length, v[1] / length, v[2] / length]);
    let file = std::env::temp_dir().join(format!("ellipsoid-{}.raylog", std::process::id()));
    std::fs::write(&file, format!("{primary}\n")).unwrap();
    let out = crate::support::raystep(&[
        "compare",
        "scenes/ellipsoid.toml",
        "--rays",
        file.to_str().unwrap(),
    ]);
    std::fs::remove_file(&file).ok();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("First divergence: P normal"), "{text}");
    assert!(
        text.contains(
            "an ellipsoid's normal comes from the inverse transpose: p' = M⁻¹ p = \
             (0.015552, 0.684268, 0.729065)"
        ),
        "{text}"
    );
    assert!(text.contains("not (p − M c)/|p − M c|"), "{text}");
}

#[test]
fn a_ray_through_its_box_that_misses_is_a_near_miss_in_the_spheres_own_space() {
    // Down -z at (1.9, 0.9): inside the box [-2, 2] x [-1, 1] of
    // x^2/4 + y^2 + z^2 = 1, but 1.9^2/4 + 0.9^2 = 1.7125 > 1: a miss. In the
    // sphere's own space o' = (0.95, 0.9, 10), d' = (0, 0, -1): the line
    // comes nearest the centre at t = 10, at distance sqrt(0.95^2 + 0.9^2)
    // = sqrt 1.7125 = 1.3086, more than r = 1.
    let s = scene(&placed(", scale = [2, 1, 1]"));
    let tree = record(&s, [1.9, 0.9, 10.0], DOWN);
    assert!(tree.root().hit.is_none());
    // Both wrap their lines: read them as running text.
    let words = |text: String| text.split_whitespace().collect::<Vec<_>>().join(" ");
    let inspect = words(text(&tree));
    assert!(
        inspect.contains(
            "the ray passes the sphere by: its line comes within 1.3086 of the centre in the \
             sphere's own space (at t = 10), more than the radius 1"
        ),
        "{inspect}"
    );
    let told = words(raystep_engine::record::explain(&tree));
    assert!(
        told.contains(
            "crosses the bounding box of ellipsoid 0 but passes it by: its line comes within \
             1.3086 of the centre in the sphere's own space"
        ),
        "{told}"
    );
}
