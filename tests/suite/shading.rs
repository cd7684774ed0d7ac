//! The illumination model against values derived by hand (MODEL §4-§6).

use glam::DVec3;
use raystep_engine::scene::Scene;

use crate::support::{record, scene};

fn close(a: DVec3, b: [f64; 3]) -> bool {
    (a - DVec3::from_array(b)).abs().max_element() < 1e-12
}

const CAMERA: &str = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n";

#[test]
fn one_light_head_on() {
    let s = scene(&format!(
        "{CAMERA}
        [image]
        width = 1
        height = 1
        [settings]
        ambient = [0.1, 0.1, 0.1]
        [materials.m]
        color = [1, 0.5, 0.25]
        kd = 0.8
        ks = 0.5
        n = 10
        [[light]]
        position = [0, 0, 10]
        [[object]]
        material = \"m\"
        sphere = {{ center = [0, 0, 0], radius = 1 }}"
    ));
    // The 1x1 image's only ray goes straight down -z and hits (0,0,1) at t = 4.
    // N = L = V = H = (0,0,1): N·L = 1, N·H = 1, S = 1, f_att = 1.
    // ambient  = 0.1 * (1, .5, .25)          = (0.1, 0.05, 0.025)
    // diffuse  = 1 * (1, .5, .25) * 0.8 * 1  = (0.8, 0.4, 0.2)
    // specular = 1 * 0.5 * 1^10              = (0.5, 0.5, 0.5)
    // sum = (1.4, 0.95, 0.725) -> bytes (255, floor(242.75) = 242, floor(185.375) = 185).
    let tree = raystep_engine::record::record_pixel(&s, &s.settings, 0, 0);
    let root = tree.root();
    assert_eq!(root.hit.as_ref().unwrap().t, 4.0);
    assert!(close(root.ambient, [0.1, 0.05, 0.025]));
    let light = &root.lights[0];
    assert_eq!(
        (light.n_dot_l, light.specular_cosine, light.f_att),
        (1.0, 1.0, 1.0)
    );
    assert_eq!(light.shadow.as_ref().unwrap().s, 1.0);
    assert!(close(light.diffuse, [0.8, 0.4, 0.2]));
    assert!(close(light.specular, [0.5, 0.5, 0.5]));
    assert!(close(root.color, [1.4, 0.95, 0.725]));
    assert_eq!(raystep_model::math::to_rgb8(root.color), [255, 242, 185]);
}

/// A floor at y = 0 lit from (0, 4, 0) through a ball of radius 0.5 at (0, 2, 0).
fn blocked_floor(blocker_kt: f64) -> Scene {
    scene(&format!(
        "{CAMERA}
        [materials.floor]
        color = [1, 1, 1]
        kd = 1
        [materials.ball]
        kt = {blocker_kt}
        [[light]]
        name = \"lamp\"
        position = [0, 4, 0]
        [[object]]
        name = \"floor\"
        material = \"floor\"
        plane = {{ normal = [0, 1, 0], point = [0, 0, 0] }}
        [[object]]
        name = \"ball\"
        material = \"ball\"
        sphere = {{ center = [0, 2, 0], radius = 0.5 }}"
    ))
}

#[test]
fn opaque_blocker_casts_a_full_shadow() {
    // A ray from (0, 1, 0) straight down meets the floor at the origin (t = 1).
    // Its shadow ray goes up to the light (d_L = 4) and crosses the ball at
    // t = 1.5 and 2.5; the ball is opaque, so S = 0 and the light adds nothing.
    let tree = record(&blocked_floor(0.0), [0.0, 1.0, 0.0], [0.0, -1.0, 0.0]);
    let light = &tree.root().lights[0];
    let shadow = light.shadow.as_ref().unwrap();
    assert_eq!(shadow.s, 0.0);
    // The recording lists every blocker, nearest first, even past the first opaque one.
    let blockers: Vec<(&str, f64)> = shadow
        .blockers
        .iter()
        .map(|b| (b.object.as_str(), b.t))
        .collect();
    assert_eq!(blockers, [("ball", 1.5), ("ball", 2.5)]);
    assert_eq!(light.diffuse, DVec3::ZERO);
    assert_eq!(tree.color(), DVec3::ZERO);
}

#[test]
fn half_transparent_blocker_lets_a_quarter_through() {
    // Same geometry with k_t = 0.5: the shadow ray crosses the ball twice,
    // S = 0.5 * 0.5 = 0.25. N·L = 1, f_att = 1, k_d O_d = 1:
    // diffuse = 0.25 * (1, 1, 1).
    let tree = record(&blocked_floor(0.5), [0.0, 1.0, 0.0], [0.0, -1.0, 0.0]);
    let light = &tree.root().lights[0];
    assert_eq!(light.shadow.as_ref().unwrap().s, 0.25);
    assert!(close(light.diffuse, [0.25, 0.25, 0.25]));
}

#[test]
fn light_and_ray_attenuation() {
    // Light at distance 2 with (c1, c2, c3) = (1, 0.5, 0.25):
    // f_att = min(1, 1 / (1 + 0.5 * 2 + 0.25 * 4)) = 1/3; diffuse = 1/3 * 0.5 * 1 = 1/6.
    // The floor also mirrors (k_s = 0.5) up to a ceiling 3 above it, which shows
    // only its ambient (0.2, 0.4, 0.6). Ray attenuation (1, 1, 0) at t = 3:
    // 1 / (1 + 3) = 0.25, so the reflected ray adds 0.5 * 0.25 * (0.2, 0.4, 0.6).
    let s = scene(&format!(
        "{CAMERA}
        [settings]
        ambient = [1, 1, 1]
        light_attenuation = [1, 0.5, 0.25]
        ray_attenuation = [1, 1, 0]
        max_depth = 2
        [materials.floor]
        color = [1, 1, 1]
        kd = 0.5
        ks = 0.5
        n = 1
        ka = 0
        [materials.ceiling]
        color = [0.2, 0.4, 0.6]
        kd = 0
        [[light]]
        position = [0, 2, 0]
        [[object]]
        material = \"floor\"
        plane = {{ normal = [0, 1, 0], point = [0, 0, 0] }}
        [[object]]
        material = \"ceiling\"
        plane = {{ normal = [0, -1, 0], point = [0, 3, 0] }}"
    ));
    let tree = record(&s, [0.0, 1.0, 0.0], [0.0, -1.0, 0.0]);
    let root = tree.root();
    let light = &root.lights[0];
    assert!((light.f_att - 1.0 / 3.0).abs() < 1e-15);
    assert!(close(light.diffuse, [1.0 / 6.0; 3]));
    let reflected = &tree.nodes[root.reflected.unwrap()];
    assert_eq!(reflected.hit.as_ref().unwrap().t, 3.0);
    assert_eq!(reflected.attenuation, 0.25);
    assert!(close(reflected.contribution, [0.025, 0.05, 0.075]));
    assert_eq!(Some(root.color), tree.sum_of_terms(0));
}

#[test]
fn total_internal_reflection_moves_kt_to_the_reflected_ray() {
    // Inside a glass ball (r = 1, ior 1.5) a ray at height 0.9 along +x meets
    // the surface at x = sqrt(1 - 0.81) = 0.43589, leaving the glass:
    // N = -(p - c), cos_i = -d·N = 0.43589, eta = 1.5,
    // k = 1 - 2.25 (1 - 0.19) = -0.8225 < 0: TIR. No transmitted ray; the
    // reflected ray gets k_s + k_t = 0 + 1 and goes along
    // d - 2 (d·N) N = (1 - 2 * 0.19, -2 * 0.43589 * 0.9, 0) = (0.62, -0.78460, 0).
    let s = scene(&format!(
        "{CAMERA}
        [settings]
        max_depth = 2
        [materials.glass]
        kd = 0
        kt = 1
        ior = 1.5
        [[object]]
        material = \"glass\"
        sphere = {{ center = [0, 0, 0], radius = 1 }}"
    ));
    let tree = record(&s, [0.0, 0.9, 0.0], [1.0, 0.0, 0.0]);
    let root = tree.root();
    assert!(!root.hit.as_ref().unwrap().entering);
    let refraction = root.refraction.unwrap();
    assert!((refraction.cos_i - 0.19f64.sqrt()).abs() < 1e-12);
    assert_eq!(refraction.eta, 1.5);
    assert!((refraction.k + 0.8225).abs() < 1e-12);
    assert!(root.tir() && refraction.direction.is_none());
    assert!(root.transmitted.is_none());
    let reflected = &tree.nodes[root.reflected.unwrap()];
    assert_eq!(reflected.weight, 1.0);
    let expected = DVec3::new(0.62, -2.0 * 0.19f64.sqrt() * 0.9, 0.0);
    assert!((reflected.direction - expected).length() < 1e-12);
}

#[test]
fn light_behind_the_surface_casts_no_shadow_ray() {
    // Floor hit from above, light below the floor: N·L = -1 <= 0, faces away.
    let s = scene(&format!(
        "{CAMERA}
        [materials.m]
        kd = 1
        [[light]]
        position = [0, -2, 0]
        [[object]]
        material = \"m\"
        plane = {{ normal = [0, 1, 0], point = [0, 0, 0] }}"
    ));
    let tree = record(&s, [0.0, 1.0, 0.0], [0.0, -1.0, 0.0]);
    let light = &tree.root().lights[0];
    assert!(light.faces_away && light.shadow.is_none());
    assert_eq!(light.n_dot_l, -1.0);
    assert_eq!(tree.color(), DVec3::ZERO);
}

#[test]
fn ray_through_a_concave_notch_records_the_polygon_it_passed() {
    // A "U" in the plane z = 0, counter-clockwise seen from +z; its notch is
    // x in (1, 2), y in (1, 3). A ray down -z at (1.5, 2) meets the plane at
    // t = 5 inside the bounding box, but right of the point only the edges at
    // x = 2 and x = 3 cross +U: 2 crossings, even, outside. It goes on to miss.
    let s = scene(&format!(
        "{CAMERA}
        [materials.m]
        kd = 1
        [[object]]
        name = \"u\"
        material = \"m\"
        polygon = {{ vertices = [[0, 0, 0], [3, 0, 0], [3, 3, 0], [2, 3, 0], [2, 1, 0], [1, 1, 0], [1, 3, 0], [0, 3, 0]] }}"
    ));
    let tree = record(&s, [1.5, 2.0, 5.0], [0.0, 0.0, -1.0]);
    let root = tree.root();
    assert!(root.hit.is_none());
    assert_eq!(root.near_misses.len(), 1);
    let raystep_model::shapes::Working::Polygon(working) = root.near_misses[0].working else {
        panic!("a polygon")
    };
    assert_eq!(working.plane.t, Some(5.0));
    let test = working.crossing.unwrap();
    assert_eq!((test.crossings, test.inside), (2, false));
}
