//! CSE 167's `.test` scenes read as the course means them (issue 42): the
//! cse167 profile (MODEL §11), each pixel's value worked by hand from the
//! course's equation I = A + E + Σ V L / (c0 + c1 d + c2 d²) [D (N·L)₊ +
//! S (N·H)₊^s] + S I_R. Every scene is 3x3 with the camera at z = 5 looking
//! down -z: the centre pixel (1, 1) meets a unit sphere at the origin at
//! (0, 0, 1), where N = V = (0, 0, 1).

use std::path::Path;

use raystep_engine::record::record_pixel;
use raystep_engine::scene::{Profile, Scene, parse};
use raystep_model::math::to_rgb8;

const HEAD: &str = "size 3 3\ncamera 0 0 5 0 0 0 0 1 0 30\n";

fn test_scene(body: &str) -> Scene {
    parse(Path::new("scene.test"), &format!("{HEAD}{body}")).unwrap()
}

fn centre(body: &str) -> [u8; 3] {
    let scene = test_scene(body);
    to_rgb8(record_pixel(&scene, &scene.settings, 1, 1).root().color)
}

#[test]
fn a_test_file_is_traced_with_the_cse167_profile() {
    let scene = test_scene("sphere 0 0 0 1\n");
    assert_eq!(scene.settings.profile, Profile::Cse167);
    let tree = record_pixel(&scene, &scene.settings, 1, 1);
    assert_eq!(tree.to_json()["profile"], "cse167");
    // The default ambient, 0.2 grey, and nothing else: 0.2 * 255 + 0.5 = 51.5.
    assert_eq!(centre("sphere 0 0 0 1\n"), [51, 51, 51]);
}

#[test]
fn ambient_only_and_emission_only_spheres() {
    // I = A = (0.4, 0.2, 0.1): 102, 51.5 -> 51, 26.
    assert_eq!(
        centre("ambient 0.4 0.2 0.1\nsphere 0 0 0 1\n"),
        [102, 51, 26]
    );
    // I = E = (0.2, 0.6, 0.4) with A = 0: 51.5 -> 51, 153.5 -> 153, 102.5 -> 102.
    assert_eq!(
        centre("ambient 0 0 0\nemission 0.2 0.6 0.4\nsphere 0 0 0 1\n"),
        [51, 153, 102]
    );
}

#[test]
fn a_diffuse_sphere_under_a_directional_light() {
    // L = (0, 3, 4) / 5 = (0, 0.6, 0.8), N·L = 0.8, never attenuated (the
    // file's attenuation applies to point lights only): I = D N·L =
    // (0.5, 0.25, 0.1) * 0.8 = (0.4, 0.2, 0.08) -> 102, 51, 20.9 -> 20.
    let body = "ambient 0 0 0\nattenuation 0 0 1\ndiffuse 0.5 0.25 0.1\n\
                directional 0 3 4 1 1 1\nsphere 0 0 0 1\n";
    assert_eq!(centre(body), [102, 51, 20]);
}

#[test]
fn a_point_light_past_the_clamp() {
    // d = 0.5 from (0, 0, 1.5): 1 / (0 + 0 + 0.25) = 4, no clamp; L = N, so
    // I = 4 * 0.6 * D = 2.4 * (0.1, 0.2, 0.12) = (0.24, 0.48, 0.288)
    // -> 61.7 -> 61, 122.9 -> 122, 73.94 -> 73.
    let body = "ambient 0 0 0\ndiffuse 0.1 0.2 0.12\nattenuation 0 0 1\n\
                point 0 0 1.5 0.6 0.6 0.6\nsphere 0 0 0 1\n";
    assert_eq!(centre(body), [61, 122, 73]);
}

#[test]
fn maxdepth_counts_bounces() {
    // The spec: "maxdepth depth: the maximum depth (number of bounces) for
    // a ray". Two bounces are the primary ray's hit and two mirror rays:
    // depth 3 in MODEL §5's count, where the primary ray has depth 1.
    assert_eq!(
        test_scene("maxdepth 2\nsphere 0 0 0 1\n")
            .settings
            .max_depth,
        3
    );
    assert_eq!(test_scene("sphere 0 0 0 1\n").settings.max_depth, 6);
}

#[test]
fn a_sphere_turned_and_scaled_alike_stays_a_sphere() {
    // scale 2 2 2 after a turn: radius 0.5 * 2 = 1 at the origin, as the
    // plain unit sphere: the same ambient pixel, 0.2 grey.
    let scene = test_scene("rotate 0 1 0 30\nscale 2 2 2\nsphere 0 0 0 0.5\n");
    let sphere = format!("{:?}", scene.objects[0].shape);
    assert!(sphere.starts_with("Sphere"), "{sphere}");
    assert_eq!(
        centre("rotate 0 1 0 30\nscale 2 2 2\nsphere 0 0 0 0.5\n"),
        [51, 51, 51]
    );
}

#[test]
fn an_ellipsoids_silhouette_and_normal() {
    // `scale 2 1 1` then a unit sphere: the ellipsoid x²/4 + y² + z² = 1,
    // met by rays straight down -z from z = 5.
    let scene = test_scene("scale 2 1 1\nambient 0.4 0.4 0.4\nsphere 0 0 0 1\n");
    let ellipsoid = &scene.objects[0].shape;
    assert!(format!("{ellipsoid:?}").starts_with("Ellipsoid"));
    // A ray down -z at x = 1.9 meets x²/4 + z² = 1 (y = 0) at
    // z = √(1 - 0.9025) = 0.31225, t = 5 - 0.31225; at x = 2.1 it misses.
    let tree = crate::support::record(&scene, [1.9, 0.0, 5.0], [0.0, 0.0, -1.0]);
    let hit = tree
        .root()
        .hit
        .as_ref()
        .expect("x = 1.9 is inside the rim x = 2");
    assert!(
        (hit.t - (5.0 - 0.0975f64.sqrt())).abs() < 1e-12,
        "{}",
        hit.t
    );
    // The normal by the inverse transpose: M⁻ᵀ (p'/1) with p' = (0.95, 0,
    // 0.31225), M⁻ᵀ = diag(1/2, 1, 1): (0.475, 0, 0.31225) normalised,
    // not p / |p| = (1.9, 0, 0.31225) normalised.
    let expected = glam::DVec3::new(0.475, 0.0, 0.0975f64.sqrt()).normalize();
    assert!(
        (hit.geometric_normal - expected).length() < 1e-12,
        "{:?}",
        hit.geometric_normal
    );
    let tree = crate::support::record(&scene, [2.1, 0.0, 5.0], [0.0, 0.0, -1.0]);
    assert!(tree.root().hit.is_none());
}

#[test]
fn the_debuggers_header_names_the_profile_and_the_bounces() {
    // `maxdepth 2`: two bounces, depth 3 in MODEL §5's count.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("two.test");
    std::fs::write(&path, format!("{HEAD}maxdepth 2\nsphere 0 0 0 1\n")).unwrap();
    let mut app = raystep::tui::App::open(Some(path), true).unwrap();
    let terminal = crate::support::debugger::screen(&mut app, 160, 48);
    let buffer = terminal.backend().buffer();
    let header: String = (0..160)
        .map(|x| buffer[(x, 0)].symbol().to_string())
        .collect();
    assert!(header.contains("depth 3 (2 bounces)"), "{header}");
    assert!(header.contains("profile cse167"), "{header}");
    // No transmission to switch (MODEL §11): not in the header, and `t`
    // says why instead of flipping a switch that changes nothing.
    assert!(
        header.contains(" · shadows reflection ambient · "),
        "{header}"
    );
    let settings = *app.session().settings();
    app.update(raystep::tui::Action::Toggle(
        raystep::tui::Switch::Transmission,
    ));
    assert_eq!(*app.session().settings(), settings);
    let terminal = crate::support::debugger::screen(&mut app, 160, 48);
    let status: String = (0..160)
        .map(|x| terminal.backend().buffer()[(x, 47)].symbol().to_string())
        .collect();
    assert!(
        status.contains("transmission has no meaning under the cse167 profile"),
        "{status}"
    );
}
