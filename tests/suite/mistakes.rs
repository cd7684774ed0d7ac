//! The classic mistakes of MODEL §8: each one, on a small scene, changes a
//! number derived here by hand; under every mistake the recordings still
//! agree with the image; the command line takes them by name.

use std::path::Path;

use glam::DVec3;
use raystep_engine::record::{Children, RayTree, explain, node_lines, record_pixel};
use raystep_engine::render::render;
use raystep_engine::scene::{Scene, Settings, parse};
use raystep_engine::terms::render_terms;
use raystep_engine::trace::NoRecorder;
use raystep_model::mistakes::{Mistake, Mistakes};

use crate::support::{raystep, scene};

const SQRT_HALF: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// The trees of one ray traced correctly and with `mistake`.
fn both(scene: &Scene, mistake: Mistake, origin: [f64; 3], direction: [f64; 3]) -> [RayTree; 2] {
    let mut wrong = scene.clone();
    wrong.settings.mistakes = Mistakes::NONE.with(mistake);
    [
        crate::support::record(scene, origin, direction),
        crate::support::record(&wrong, origin, direction),
    ]
}

fn settings_with(scene: &Scene, mistake: Mistake) -> Settings {
    Settings {
        mistakes: Mistakes::NONE.with(mistake),
        ..scene.settings
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-12
}

/// A white floor y = `height` (kd 1) lit by a light at (0, 5, 0), and
/// `objects` (TOML) beside it.
fn floor(height: &str, settings: &str, objects: &str) -> Scene {
    scene(&format!(
        "[camera]
        eye = [0, 1, 0]
        look_at = [0, 0, 0]
        up = [0, 0, -1]
        [settings]
        {settings}
        [materials.floor]
        color = [1, 1, 1]
        kd = 1
        [[light]]
        position = [0, 5, 0]
        [[object]]
        material = \"floor\"
        plane = {{ normal = [0, 1, 0], point = [0, {height}, 0] }}
        {objects}"
    ))
}

/// The floor point's light: (S, diffuse red).
fn lit(tree: &RayTree) -> (Option<f64>, f64) {
    let light = &tree.root().lights[0];
    (light.shadow.as_ref().map(|s| s.s), light.diffuse.x)
}

const DOWN: ([f64; 3], [f64; 3]) = ([0.0, 1.0, 0.0], [0.0, -1.0, 0.0]);

#[test]
fn shadow_acne_lets_the_floor_shadow_itself() {
    let s = floor("0.1", "", "");
    // The ray from (0, 1, 0) straight down meets y = 0.1 at
    // t = -(1 - 0.1) / -1 = 0.9 rounded, 0.900000000000000022; the point's
    // y = 1 - 0.900000000000000022 = 0.099999999999999978, just below the
    // plane's 0.1000000000000000055. The shadow ray from there straight up
    // meets the floor again at t = 0.1000000000000000055 - 0.099999999999999978
    // = 2.8e-17: above 0, below EPS. Correct: no crossing, S = 1, diffuse 1 (N·L = 1).
    // shadow-acne: the floor blocks itself, S = 0, diffuse 0.
    let [right, wrong] = both(&s, Mistake::ShadowAcne, DOWN.0, DOWN.1);
    assert_eq!(lit(&right), (Some(1.0), 1.0));
    assert_eq!(lit(&wrong), (Some(0.0), 0.0));
    let blockers = &wrong.root().lights[0].shadow.as_ref().unwrap().blockers;
    assert_eq!(blockers.len(), 1);
    assert_eq!(blockers[0].object_index, 0);
    assert!(
        blockers[0].t > 0.0 && blockers[0].t < 1e-16,
        "{}",
        blockers[0].t
    );
}

#[test]
fn shadow_acne_is_told_as_the_surface_the_shadow_ray_leaves() {
    // The floor above: under shadow-acne its shadow ray meets the floor
    // itself at t = 2.8e-17, below EPS: the point the ray leaves. explain
    // and the inspect lines say so rather than print a bare 2.776e-17.
    let s = floor("0.1", "", "");
    let [_, wrong] = both(&s, Mistake::ShadowAcne, DOWN.0, DOWN.1);
    let story = explain(&wrong)
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    let inspect: String = node_lines(&wrong, 0, Children::Listed)
        .iter()
        .map(|l| format!("{l}\n"))
        .collect();
    for text in [&story, &inspect] {
        assert!(text.contains("≈ 0 (the point the ray leaves)"), "{text}");
        assert!(!text.contains("e-17"), "{text}");
    }
    assert!(
        story.contains("blocked by plane 0 (opaque) at distance ≈ 0 (the point the ray leaves)"),
        "{story}"
    );
}

#[test]
fn no_normal_flip_lights_the_back_of_a_plane_from_the_wrong_side() {
    // Eye under the floor y = 0 looking up at it, the light under it too.
    let s = scene(
        "[camera]
        eye = [0, -2, 0]
        look_at = [0, 0, 0]
        up = [0, 0, -1]
        [materials.floor]
        color = [1, 1, 1]
        kd = 0.5
        [[light]]
        position = [0, -4, 0]
        [[object]]
        material = \"floor\"
        plane = { normal = [0, 1, 0], point = [0, 0, 0] }",
    );
    // Hit (0, 0, 0) at t = 2, N_g = (0, 1, 0), d = (0, 1, 0): N = -N_g = (0, -1, 0).
    // L = (0, -1, 0). Correct: N·L = 1, diffuse = 0.5. no-normal-flip:
    // N_g·L = -1, the light faces away, diffuse 0 (and no shadow ray).
    let [right, wrong] = both(&s, Mistake::NoNormalFlip, [0.0, -2.0, 0.0], [0.0, 1.0, 0.0]);
    let (r, w) = (&right.root().lights[0], &wrong.root().lights[0]);
    assert_eq!((r.n_dot_l, r.faces_away, r.diffuse.x), (1.0, false, 0.5));
    assert_eq!((w.n_dot_l, w.faces_away, w.diffuse.x), (-1.0, true, 0.0));
    assert!(w.shadow.is_none());
}

/// A glass plane y = 0 (ior 1.5, ks 0.2, kt 0.7), no lights.
fn glass_plane() -> Scene {
    scene(
        "[camera]
        eye = [0, 1, 0]
        look_at = [0, 0, 0]
        up = [0, 0, -1]
        [materials.glass]
        ks = 0.2
        kt = 0.7
        ior = 1.5
        [[object]]
        material = \"glass\"
        plane = { normal = [0, 1, 0], point = [0, 0, 0] }",
    )
}

#[test]
fn eta_inverted_turns_entering_glass_into_total_internal_reflection() {
    // Entering at 45 degrees: cos_i = sqrt(1/2).
    // Correct: eta = 1 / 1.5, k = 1 - (1 / 2.25)(1 - 1/2) = 7/9 >= 0: transmitted.
    // eta-inverted: eta = 1.5, k = 1 - 2.25 (1/2) = -0.125 < 0: TIR.
    let [right, wrong] = both(
        &glass_plane(),
        Mistake::EtaInverted,
        [-1.0, 1.0, 0.0],
        [SQRT_HALF, -SQRT_HALF, 0.0],
    );
    let (r, w) = (
        right.root().refraction.unwrap(),
        wrong.root().refraction.unwrap(),
    );
    assert!(close(r.eta, 1.0 / 1.5) && close(r.k, 7.0 / 9.0) && !r.tir);
    assert!(close(w.eta, 1.5) && close(w.k, -0.125) && w.tir);
}

#[test]
fn tir_dropped_leaves_k_t_out_of_the_reflected_weight() {
    // Leaving the glass upwards at 45 degrees: eta = 1.5, k = -0.125: TIR.
    // Correct: the reflected weight is k_s + k_t = 0.2 + 0.7 = 0.9.
    // tir-dropped: k_s = 0.2 alone.
    let [right, wrong] = both(
        &glass_plane(),
        Mistake::TirDropped,
        [-1.0, -1.0, 0.0],
        [SQRT_HALF, SQRT_HALF, 0.0],
    );
    for (tree, weight) in [(&right, 0.9), (&wrong, 0.2)] {
        assert!(tree.root().tir());
        let reflected = tree.root().reflected.expect("a reflected ray");
        assert!(close(tree.nodes[reflected].weight, weight));
    }
}

#[test]
fn phong_not_blinn_uses_r_dot_v() {
    // Floor y = 0 seen from straight above, V = (0, 1, 0); light at (2, 2, 0),
    // L = (1, 1, 0) / sqrt 2. N·H = cos 22.5° = sqrt(2 + sqrt 2) / 2 = 0.92388;
    // R = 2 (N·L) N - L = (-1, 1, 0) / sqrt 2, R·V = sqrt(1/2) = 0.70711.
    // With k_s = 1, n = 1 and S = f_att = 1 that is the specular term.
    let s = scene(
        "[camera]
        eye = [0, 1, 0]
        look_at = [0, 0, 0]
        up = [0, 0, -1]
        [materials.shiny]
        ks = 1
        n = 1
        [[light]]
        position = [2, 2, 0]
        [[object]]
        material = \"shiny\"
        plane = { normal = [0, 1, 0], point = [0, 0, 0] }",
    );
    let [right, wrong] = both(&s, Mistake::PhongNotBlinn, DOWN.0, DOWN.1);
    let (r, w) = (&right.root().lights[0], &wrong.root().lights[0]);
    let n_dot_h = (2.0 + 2f64.sqrt()).sqrt() / 2.0;
    assert!(close(r.specular_cosine, n_dot_h) && close(r.specular.x, n_dot_h));
    assert!(close(w.specular_cosine, SQRT_HALF) && close(w.specular.x, SQRT_HALF));
}

const BALL_ABOVE: &str = "[materials.glass]
        kt = 0.5
        [[object]]
        material = \"glass\"
        sphere = { center = [0, 2, 0], radius = 0.5 }";

#[test]
fn opaque_shadows_let_a_glass_ball_block_fully() {
    // The shadow segment from (0, 0, 0) up to the light crosses the ball
    // (k_t 0.5) at t = 1.5 and 2.5. Correct: S = 0.5 * 0.5 = 0.25, diffuse
    // 0.25. opaque-shadows: S = 0, diffuse 0.
    let s = floor("0", "", BALL_ABOVE);
    let [right, wrong] = both(&s, Mistake::OpaqueShadows, DOWN.0, DOWN.1);
    assert_eq!(lit(&right), (Some(0.25), 0.25));
    assert_eq!(lit(&wrong), (Some(0.0), 0.0));
}

#[test]
fn shadows_past_light_let_a_ball_behind_the_light_cast_a_shadow() {
    // The opaque ball at (0, 7, 0) is beyond the light (d_L = 5): its
    // crossings at t = 6.5 and 7.5 are not on the segment (EPS, 5): S = 1.
    // shadows-past-light: the segment goes on for ever, S = 0.
    let ball = "[materials.black]
        [[object]]
        material = \"black\"
        sphere = { center = [0, 7, 0], radius = 0.5 }";
    let s = floor("0", "", ball);
    let [right, wrong] = both(&s, Mistake::ShadowsPastLight, DOWN.0, DOWN.1);
    assert_eq!(lit(&right), (Some(1.0), 1.0));
    assert_eq!(lit(&wrong), (Some(0.0), 0.0));
    let blockers = &wrong.root().lights[0].shadow.as_ref().unwrap().blockers;
    assert!(close(blockers[0].t, 6.5) && close(blockers[1].t, 7.5));
}

#[test]
fn no_light_attenuation_keeps_f_att_at_one() {
    // Light 5 away with (c1, c2, c3) = (0, 0, 1): f_att = 1 / 25 = 0.04,
    // diffuse 0.04. no-light-attenuation: f_att = 1, diffuse 1.
    let s = floor("0", "light_attenuation = [0, 0, 1]", "");
    let [right, wrong] = both(&s, Mistake::NoLightAttenuation, DOWN.0, DOWN.1);
    let (r, w) = (&right.root().lights[0], &wrong.root().lights[0]);
    assert!(close(r.f_att, 0.04) && close(r.diffuse.x, 0.04));
    assert_eq!((w.f_att, w.diffuse.x), (1.0, 1.0));
}

#[test]
fn depth_off_by_one_stops_a_level_early() {
    // Two facing mirrors (k_s 1) and max_depth 3: correct, the primary ray
    // (depth 1) and its reflection (depth 2) spawn, depth 3 does not: 3 rays.
    // depth-off-by-one: only depth < 2 spawns: 2 rays.
    let s = scene(
        "[camera]
        eye = [0, 0, 0]
        look_at = [0, 0, -1]
        [settings]
        max_depth = 3
        [materials.mirror]
        ks = 1
        [[object]]
        material = \"mirror\"
        plane = { normal = [0, 0, 1], point = [0, 0, -1] }
        [[object]]
        material = \"mirror\"
        plane = { normal = [0, 0, -1], point = [0, 0, 1] }",
    );
    let [right, wrong] = both(&s, Mistake::DepthOffByOne, [0.0; 3], [0.0, 0.0, -1.0]);
    assert_eq!((right.nodes.len(), wrong.nodes.len()), (3, 2));
}

#[test]
fn no_epsilon_lets_a_mirror_reflect_off_itself() {
    // The floor of `shadow_acne_lets_the_floor_shadow_itself`, a mirror now
    // (k_s 0.5): the point is (0, 0.099999999999999978, 0), just below the
    // plane's y = 0.1000000000000000055. N = (0, 1, 0), R = d - 2 (d·N) N
    // = (0, -1, 0) + 2 (0, 1, 0) = (0, 1, 0): straight up, from below the
    // plane, which it meets at t = 2.8e-17. Correct: that is below EPS, P/R
    // misses. no-epsilon: P/R hits the floor itself there; the shadow ray,
    // as under shadow-acne, is blocked by the floor (S = 0).
    let s = scene(
        "[camera]
        eye = [0, 1, 0]
        look_at = [0, 0, 0]
        up = [0, 0, -1]
        [materials.floor]
        kd = 1
        ks = 0.5
        [[light]]
        position = [0, 5, 0]
        [[object]]
        material = \"floor\"
        plane = { normal = [0, 1, 0], point = [0, 0.1, 0] }",
    );
    let [right, wrong] = both(&s, Mistake::NoEpsilon, DOWN.0, DOWN.1);
    let reflected = |tree: &RayTree| {
        let id = tree.root().reflected.expect("a reflected ray");
        (tree.nodes[id].direction, tree.nodes[id].hit.clone())
    };
    let (direction, hit) = reflected(&right);
    assert_eq!(direction, DVec3::Y);
    assert!(hit.is_none());
    let (direction, hit) = reflected(&wrong);
    assert_eq!(direction, DVec3::Y);
    let hit = hit.expect("the floor again");
    assert_eq!(hit.object_index, 0);
    assert!(hit.t > 0.0 && hit.t < 1e-16, "{}", hit.t);
    assert_eq!(lit(&right), (Some(1.0), 1.0));
    assert_eq!(lit(&wrong), (Some(0.0), 0.0));
}

#[test]
fn light_not_normalised_scales_n_dot_l_by_the_distance() {
    // Floor y = 0 seen from straight above, V = (0, 1, 0); k_d = 1, k_s = 1,
    // n = 1; light at (0, 3, 4): P_L - p = (0, 3, 4), d_L = 5.
    // Correct: L = (0, 0.6, 0.8), N·L = 0.6, diffuse 0.6; L + V =
    // (0, 1.6, 0.8), |.| = √3.2, N·H = 1.6 / √3.2 = 0.894427.
    // light-not-normalised: N·L = 3, diffuse 3; L + V = (0, 4, 4),
    // N·H = 4 / √32 = √(1/2) = 0.707107. The shadow ray still goes along
    // the unit (0, 0.6, 0.8).
    let s = scene(
        "[camera]
        eye = [0, 1, 0]
        look_at = [0, 0, 0]
        up = [0, 0, -1]
        [materials.shiny]
        kd = 1
        ks = 1
        n = 1
        [[light]]
        position = [0, 3, 4]
        [[object]]
        material = \"shiny\"
        plane = { normal = [0, 1, 0], point = [0, 0, 0] }",
    );
    let [right, wrong] = both(&s, Mistake::LightNotNormalised, DOWN.0, DOWN.1);
    let (r, w) = (&right.root().lights[0], &wrong.root().lights[0]);
    assert!(close(r.n_dot_l, 0.6) && close(r.diffuse.x, 0.6));
    assert!(close(r.specular_cosine, 1.6 / 3.2f64.sqrt()));
    assert!(close(w.n_dot_l, 3.0) && close(w.diffuse.x, 3.0));
    assert!(close(w.specular_cosine, SQRT_HALF));
    assert_eq!(w.to_light, DVec3::new(0.0, 3.0, 4.0));
    let shadow = w.shadow.as_ref().unwrap();
    assert!((shadow.direction - DVec3::new(0.0, 0.6, 0.8)).length() < 1e-15);
}

#[test]
fn reflection_sign_sends_the_reflected_ray_back_through_the_mirror() {
    // The glass plane y = 0 (k_s 0.2) hit at 45°: d = (a, -a, 0), a = √(1/2),
    // N = (0, 1, 0). R = d - 2 (d·N) N = (a, -a, 0) + 2a (0, 1, 0) = (a, a, 0).
    // reflection-sign: 2 (d·N) N - d = (-a, -a, 0), down through the plane.
    let [right, wrong] = both(
        &glass_plane(),
        Mistake::ReflectionSign,
        [-1.0, 1.0, 0.0],
        [SQRT_HALF, -SQRT_HALF, 0.0],
    );
    let reflected = |tree: &RayTree| tree.nodes[tree.root().reflected.unwrap()].direction;
    assert!((reflected(&right) - DVec3::new(SQRT_HALF, SQRT_HALF, 0.0)).length() < 1e-15);
    assert!((reflected(&wrong) - DVec3::new(-SQRT_HALF, -SQRT_HALF, 0.0)).length() < 1e-15);
}

#[test]
fn refraction_outward_normal_turns_the_ray_leaving_a_ball_back_in() {
    // A water ball (ior 4/3, k_t 1) at the origin, the ray down -z at
    // height 0.8. It enters at p = (0, 0.8, 0.6) (t = 4.4), N = N_g = p:
    // cos_i = 0.6, eta = 0.75, k = 1 - 0.5625 (0.64) = 0.64,
    // T = 0.75 d + (0.45 - 0.8) N = (0, -0.28, -0.96), the same both ways.
    // It leaves at q = (0, 0.352, -0.936) (t = 1.6): N_g = q, N = -q.
    // Correct: cos_i = -T·N = 0.8, eta = 4/3, k = 1 - (16/9) 0.36 = 0.36,
    // T' = (4/3) T + ((4/3) 0.8 - 0.6) N = (0, -0.5376, -0.8432).
    // refraction-outward-normal: cos_i = -T·N_g = -0.8, k = 0.36,
    // T' = (4/3) T + (-(4/3) 0.8 - 0.6) q = (0, -0.96, 0.28): back inside.
    let s = scene(
        "[camera]
        eye = [0, 0.8, 5]
        look_at = [0, 0.8, 0]
        [materials.water]
        kd = 0
        kt = 1
        ior = 1.3333333333333333
        [[object]]
        material = \"water\"
        sphere = { center = [0, 0, 0], radius = 1 }",
    );
    let [right, wrong] = both(
        &s,
        Mistake::RefractionOutwardNormal,
        [0.0, 0.8, 5.0],
        [0.0, 0.0, -1.0],
    );
    let leaving = |tree: &RayTree| {
        let inside = tree.root().transmitted.expect("into the ball");
        let node = &tree.nodes[inside];
        (
            node.refraction.unwrap(),
            tree.nodes[node.transmitted.unwrap()].direction,
        )
    };
    let (refraction, out) = leaving(&right);
    assert!((refraction.cos_i - 0.8).abs() < 1e-9);
    assert!((out - DVec3::new(0.0, -0.5376, -0.8432)).length() < 1e-9);
    let (refraction, out) = leaving(&wrong);
    assert!((refraction.cos_i + 0.8).abs() < 1e-9 && (refraction.k - 0.36).abs() < 1e-9);
    assert!((out - DVec3::new(0.0, -0.96, 0.28)).length() < 1e-9);
}

#[test]
fn two_sided_diffuse_lights_a_wall_from_behind() {
    // The wall z = 0 (k_d 0.5) seen from (0, 0, 5), the light behind it at
    // (0, 3, -4): L = (0, 0.6, -0.8), N = (0, 0, 1), N·L = -0.8. Correct:
    // the light faces away, no shadow ray, diffuse 0. two-sided-diffuse:
    // |N·L| = 0.8, a shadow ray (nothing in the way, S = 1), diffuse 0.4.
    let s = scene(
        "[camera]
        eye = [0, 0, 5]
        look_at = [0, 0, 0]
        [materials.chalk]
        kd = 0.5
        [[light]]
        position = [0, 3, -4]
        [[object]]
        material = \"chalk\"
        plane = { normal = [0, 0, 1], point = [0, 0, 0] }",
    );
    let [right, wrong] = both(
        &s,
        Mistake::TwoSidedDiffuse,
        [0.0, 0.0, 5.0],
        [0.0, 0.0, -1.0],
    );
    let (r, w) = (&right.root().lights[0], &wrong.root().lights[0]);
    assert!(r.faces_away && r.shadow.is_none() && r.diffuse.x == 0.0);
    assert!(close(r.n_dot_l, -0.8));
    assert!(!w.faces_away && close(w.n_dot_l, 0.8) && close(w.diffuse.x, 0.4));
    assert_eq!(w.shadow.as_ref().map(|s| s.s), Some(1.0));
    // The inspect lines name the cosine the mistake used: |N·L|, not N·L
    // (which is -0.8 here).
    let inspect: String = node_lines(&wrong, 0, Children::Listed)
        .iter()
        .map(|l| format!("{l}\n"))
        .collect();
    assert!(inspect.contains("light 0: |N·L| = 0.8, S = 1"), "{inspect}");
    assert!(
        inspect.contains("diffuse = S · f_att · I_p · k_d · O_d · (|N·L|)"),
        "{inspect}"
    );
    let right_lines: String = node_lines(&right, 0, Children::Listed)
        .iter()
        .map(|l| format!("{l}\n"))
        .collect();
    assert!(!right_lines.contains("|N·L|"), "{right_lines}");
}

#[test]
fn a_light_straight_behind_the_point_counted_by_a_mistake_gives_n_dot_h_zero() {
    // The wall z = 0 (k_d = k_s = 0.5) seen from (0, 0, 5), V = (0, 0, 1);
    // the light at (0, 0, -4), straight behind the point: L = (0, 0, -1),
    // L + V = 0. two-sided-diffuse counts it (|N·L| = 1), and so does
    // no-normal-flip on the wall turned round (N_g = (0, 0, -1), N_g·L =
    // 1): H = normalize(0) would be NaN; it is 0, so N·H = 0 and the
    // specular term 0, and the JSON recording holds only finite numbers.
    for (normal, mistake) in [
        ("[0, 0, 1]", Mistake::TwoSidedDiffuse),
        ("[0, 0, -1]", Mistake::NoNormalFlip),
    ] {
        let s = scene(&format!(
            "[camera]
            eye = [0, 0, 5]
            look_at = [0, 0, 0]
            [materials.chalk]
            kd = 0.5
            ks = 0.5
            [[light]]
            position = [0, 0, -4]
            [[object]]
            material = \"chalk\"
            plane = {{ normal = {normal}, point = [0, 0, 0] }}"
        ));
        let [_, wrong] = both(&s, mistake, [0.0, 0.0, 5.0], [0.0, 0.0, -1.0]);
        let light = &wrong.root().lights[0];
        assert!(!light.faces_away, "{mistake}");
        assert_eq!(light.specular_cosine, 0.0, "{mistake}");
        assert_eq!(light.specular, DVec3::ZERO, "{mistake}");
        assert!(close(light.diffuse.x, 0.5), "{mistake}");
    }
}

#[test]
fn clamp_before_adding_clamps_a_reflected_surface_before_it_is_weighed() {
    // A mirror floor y = 0 (k_d 0, k_s 0.5) under a wall z = -2 of k_d 1 lit
    // head-on by a light of 3 at (0, 1, 3); the eye at (0, 1, 1) looks down
    // at 45° to the floor's origin. P/R goes along (0, a, -a), a = √(1/2),
    // and meets the wall at (0, 2, -2): L = (0, -1, 5) / √26, N·L = 5/√26,
    // diffuse = 3 × 5/√26 = 2.941742, its local colour. Correct: the floor
    // gets 0.5 × 2.941742 = 1.470871. clamp-before-adding: the wall's colour
    // is min(1, 2.941742) = 1, the floor gets 0.5. The floor's own local
    // colour is 0 (k_d 0, k_s's highlight is not towards the eye: N·H < 1
    // raised to n = 20 is small but not 0), so its clamp changes nothing.
    let s = scene(
        "[camera]
        eye = [0, 1, 1]
        look_at = [0, 0, 0]
        [materials.mirror]
        kd = 0
        ks = 0.5
        n = 1000000
        [materials.wall]
        kd = 1
        [[light]]
        position = [0, 1, 3]
        color = [3, 3, 3]
        [[object]]
        material = \"mirror\"
        plane = { normal = [0, 1, 0], point = [0, 0, 0] }
        [[object]]
        material = \"wall\"
        plane = { normal = [0, 0, 1], point = [0, 0, -2] }",
    );
    let a = SQRT_HALF;
    let [right, wrong] = both(
        &s,
        Mistake::ClampBeforeAdding,
        [0.0, 1.0, 1.0],
        [0.0, -a, -a],
    );
    let wall = 3.0 * 5.0 / 26f64.sqrt();
    let r_wall = &right.nodes[right.root().reflected.unwrap()];
    assert!(close(r_wall.lights[0].diffuse.x, wall));
    assert!(close(r_wall.color.x, wall));
    assert!(close(right.color().x, 0.5 * wall), "{}", right.color().x);
    let w_wall = &wrong.nodes[wrong.root().reflected.unwrap()];
    // The terms as computed; the colour clamped.
    assert!(close(w_wall.lights[0].diffuse.x, wall));
    assert_eq!(w_wall.color.x, 1.0);
    assert!(close(wrong.color().x, 0.5), "{}", wrong.color().x);
}

#[test]
fn inverse_square_makes_f_att_one_over_d_squared() {
    // The light 5 above the floor, the scene's attenuation (1, 0, 0): f_att
    // = 1, diffuse 1. inverse-square: f_att = min(1, 1 / 5²) = 0.04,
    // diffuse 0.04. With (0, 0, 1) given by the scene it changes nothing.
    let s = floor("0", "", "");
    let [right, wrong] = both(&s, Mistake::InverseSquare, DOWN.0, DOWN.1);
    let (r, w) = (&right.root().lights[0], &wrong.root().lights[0]);
    assert_eq!((r.f_att, r.diffuse.x), (1.0, 1.0));
    assert!(close(w.f_att, 0.04) && close(w.diffuse.x, 0.04));
    let s = floor("0", "light_attenuation = [0, 0, 1]", "");
    let [right, wrong] = both(&s, Mistake::InverseSquare, DOWN.0, DOWN.1);
    assert_eq!(right.root().lights[0].f_att, wrong.root().lights[0].f_att);
    // A light half a unit away: 1 / 0.25 = 4, kept at 1 by the min.
    let s = floor("4.5", "", "");
    let [_, wrong] = both(
        &s,
        Mistake::InverseSquare,
        [0.0, 4.9, 0.0],
        [0.0, -1.0, 0.0],
    );
    assert_eq!(wrong.root().lights[0].f_att, 1.0);
}

/// A white ball filling a 1 x 1 image, no lights, ambient `ambient`: the
/// pixel's colour is the ambient term itself.
fn ambient_ball(ambient: &str) -> Scene {
    scene(&format!(
        "[camera]
        eye = [0, 0, 5]
        look_at = [0, 0, 0]
        [image]
        width = 1
        height = 1
        [settings]
        ambient = {ambient}
        [materials.white]
        color = [1, 1, 1]
        [[object]]
        material = \"white\"
        sphere = {{ center = [0, 0, 0], radius = 1 }}"
    ))
}

#[test]
fn no_ambient_leaves_the_ambient_term_out() {
    // Ambient 0.1 * white = 0.1, all of the colour; no-ambient: 0.
    let s = ambient_ball("[0.1, 0.1, 0.1]");
    let [right, wrong] = both(&s, Mistake::NoAmbient, [0.0, 0.0, 5.0], [0.0, 0.0, -1.0]);
    assert_eq!(right.root().ambient, DVec3::splat(0.1));
    assert_eq!(wrong.root().ambient, DVec3::ZERO);
    assert_eq!(wrong.color(), DVec3::ZERO);
}

/// The 1 x 1 pixel as the render stores it and as its recording reports it.
fn stored_pixel(scene: &Scene, mistake: Mistake) -> ([u8; 3], [u8; 3]) {
    let settings = settings_with(scene, mistake);
    let (image, _) = render::<NoRecorder>(scene, &settings, &|| {});
    let tree = record_pixel(scene, &settings, 0, 0);
    (image.get_pixel(0, 0).0, tree.rgb8())
}

#[test]
fn byte_wrap_and_gamma_change_the_bytes_in_the_image_and_the_recording() {
    // The colour is (1.2, 0.5, 0.2).
    // Correct:   (255, floor(128.0) = 128, floor(51.5) = 51).
    // byte-wrap: floor(306.5) = 306 mod 256 = 50; 128; 51.
    // gamma:     clamped 1.2^(1/2.2) > 1 -> 255; 0.5^(1/2.2) = 0.72974,
    //            floor(186.08 + 0.5) = 186; 0.2^(1/2.2) = 0.48115,
    //            floor(122.69 + 0.5) = 123.
    let s = ambient_ball("[1.2, 0.5, 0.2]");
    let correct = record_pixel(&s, &s.settings, 0, 0);
    assert!((correct.color() - DVec3::new(1.2, 0.5, 0.2)).length() < 1e-15);
    assert_eq!(correct.rgb8(), [255, 128, 51]);
    assert_eq!(
        stored_pixel(&s, Mistake::ByteWrap),
        ([50, 128, 51], [50, 128, 51])
    );
    assert_eq!(
        stored_pixel(&s, Mistake::Gamma),
        ([255, 186, 123], [255, 186, 123])
    );
    // Both: 1.2^(1/2.2) = 1.0864, floor(277.0 + 0.5) = 277 mod 256 = 21.
    let both: Mistakes = [Mistake::ByteWrap, Mistake::Gamma].into_iter().collect();
    assert_eq!(both.rgb8(DVec3::new(1.2, 0.5, 0.2)), [21, 186, 123]);
}

/// A 1 x 2 image (fov 90, looking down -z from the origin) of nothing.
fn two_pixels(width: u32, height: u32) -> Scene {
    scene(&format!(
        "[camera]
        eye = [0, 0, 0]
        look_at = [0, 0, -1]
        fov = 90
        [image]
        width = {width}
        height = {height}"
    ))
}

fn primary_direction(scene: &Scene, mistake: Mistake, x: u32, y: u32) -> DVec3 {
    record_pixel(scene, &settings_with(scene, mistake), x, y)
        .root()
        .direction
}

#[test]
fn flipped_y_traces_the_mirrored_row() {
    // 1 x 2, s = tan 45° = 1. Row 0: py = 1 - 2 (0.5) / 2 = 0.5, direction
    // (0, 0.5, -1) / |.|. flipped-y: image row 0 shows row 1, py = -0.5.
    let s = two_pixels(1, 2);
    let norm = 1.25f64.sqrt();
    let right = record_pixel(&s, &s.settings, 0, 0).root().direction;
    assert!((right - DVec3::new(0.0, 0.5, -1.0) / norm).length() < 1e-15);
    let wrong = primary_direction(&s, Mistake::FlippedY, 0, 0);
    assert!((wrong - DVec3::new(0.0, -0.5, -1.0) / norm).length() < 1e-15);
}

#[test]
fn pixel_corner_traces_through_the_top_left_corner() {
    // 1 x 1, s = 1: the centre gives px = py = 0, straight ahead;
    // pixel-corner: px = (2 * 0 / 1 - 1) = -1, py = 1 - 0 = 1:
    // direction (-1, 1, -1) / sqrt 3.
    let s = two_pixels(1, 1);
    let right = record_pixel(&s, &s.settings, 0, 0).root().direction;
    assert_eq!(right, DVec3::new(0.0, 0.0, -1.0));
    let wrong = primary_direction(&s, Mistake::PixelCorner, 0, 0);
    assert!((wrong - DVec3::new(-1.0, 1.0, -1.0) / 3f64.sqrt()).length() < 1e-15);
}

#[test]
fn fov_full_angle_takes_the_tangent_of_the_whole_angle() {
    // 1 x 2, fov 60. Row 0: py = 0.5 s. Correct: s = tan 30° = 1/√3,
    // direction (0, 0.5/√3, -1) / |.|. fov-full-angle: s = tan 60° = √3,
    // direction (0, 0.5 √3, -1) / |.| = (0, 0.866025, -1) / √1.75.
    let s = scene(
        "[camera]
        eye = [0, 0, 0]
        look_at = [0, 0, -1]
        fov = 60
        [image]
        width = 1
        height = 2",
    );
    let right = record_pixel(&s, &s.settings, 0, 0).root().direction;
    let py = 0.5 / 3f64.sqrt();
    assert!((right - DVec3::new(0.0, py, -1.0) / (1.0 + py * py).sqrt()).length() < 1e-15);
    let wrong = primary_direction(&s, Mistake::FovFullAngle, 0, 0);
    let py = 0.5 * 3f64.sqrt();
    assert!((wrong - DVec3::new(0.0, py, -1.0) / 1.75f64.sqrt()).length() < 1e-15);
}

#[test]
fn under_every_mistake_the_recording_agrees_with_the_image() {
    let scene = parse(
        Path::new(raystep_engine::scene::builtin::NAME),
        raystep_engine::scene::builtin::TEXT,
    )
    .unwrap();
    let all: Mistakes = Mistake::ALL.into_iter().collect();
    let sets = Mistake::ALL
        .into_iter()
        .map(|m| Mistakes::NONE.with(m))
        .chain([all]);
    let (w, h) = (scene.width, scene.height);
    let pixels = [(0, 0), (w / 2, h / 2), (w - 1, h - 1), (w / 3, 2 * h / 3)];
    for mistakes in sets {
        let settings = Settings {
            mistakes,
            ..scene.settings
        };
        let (image, _) = render::<NoRecorder>(&scene, &settings, &|| {});
        let (terms, _) = render_terms::<NoRecorder>(&scene, &settings, &|| {});
        assert_eq!(terms.color_image(), image, "{mistakes}");
        // The corners, a few inside, and the whole middle row.
        let row = (0..w).map(|x| (x, h / 2));
        for (x, y) in pixels.into_iter().chain(row) {
            let tree = record_pixel(&scene, &settings, x, y);
            assert_eq!(
                tree.rgb8(),
                image.get_pixel(x, y).0,
                "{mistakes} ({x}, {y})"
            );
            assert_eq!(tree.pixel, (x, y));
            assert_eq!(tree.mistakes, mistakes);
        }
    }
}

#[test]
fn an_unknown_mistake_is_a_bad_command_line_that_lists_the_names() {
    let out = raystep(&[
        "inspect",
        "scenes/seven-rays.toml",
        "--pixel",
        "80,60",
        "--mistake",
        "shadow_acne",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    for mistake in Mistake::ALL {
        assert!(stderr.contains(mistake.name()), "{stderr}");
    }
}

#[test]
fn inspect_with_mistakes_reports_them_and_their_bytes() {
    let args = ["scenes/seven-rays.toml", "--pixel", "80,60"];
    let json = |extra: &[&str]| {
        let out = raystep(&[&["inspect"], &args[..], &["--format", "json"], extra].concat());
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice::<serde_json::Value>(&out.stdout).unwrap()
    };
    let correct = json(&[]);
    assert!(correct.get("mistakes").is_none());
    let wrong = json(&["--mistake", "gamma", "--mistake", "no-ambient"]);
    // Catalogue order, whatever the order on the command line.
    assert_eq!(
        wrong["mistakes"],
        serde_json::json!(["no-ambient", "gamma"])
    );
    // The bytes are the gamma curve's of the mistaken colour.
    let channel = |c: &serde_json::Value| {
        let c = c.as_f64().unwrap().max(0.0).powf(1.0 / 2.2);
        (255.0 * c + 0.5).floor().min(255.0)
    };
    let expected: Vec<f64> = wrong["color"]
        .as_array()
        .unwrap()
        .iter()
        .map(channel)
        .collect();
    let bytes: Vec<f64> = wrong["rgb8"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b.as_f64().unwrap())
        .collect();
    assert_eq!(bytes, expected);
    let explain = raystep(&[&["explain"], &args[..], &["--mistake", "gamma"]].concat());
    assert!(String::from_utf8_lossy(&explain.stdout).contains("on purpose: gamma"));
}

#[test]
fn render_with_a_mistake_writes_the_mistaken_image() {
    let dir = std::env::temp_dir().join(format!("raystep-mistakes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("flipped.png");
    let out = raystep(&[
        "render",
        "scenes/seven-rays.toml",
        "--size",
        "16x12",
        "--mistake",
        "flipped-y",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let image = image::open(&png).unwrap().to_rgb8();
    let s = raystep_engine::scene::load(Path::new("scenes/seven-rays.toml"))
        .unwrap()
        .with_size(16, 12)
        .unwrap();
    let correct = render::<NoRecorder>(&s, &s.settings, &|| {}).0;
    // Image row y is the correct image's row 11 - y.
    for y in 0..12 {
        for x in 0..16 {
            assert_eq!(image.get_pixel(x, y), correct.get_pixel(x, 11 - y));
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
