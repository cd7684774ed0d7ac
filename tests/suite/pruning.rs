//! Adaptive tree-depth control, the per-pixel ray budget (MODEL §5) and a
//! light at the hit point (MODEL §4), against values derived by hand.
//! Regression tests for issue 13: a valid scene must neither hang nor exhaust
//! memory.

use std::path::Path;
use std::process::Command;

use glam::DVec3;
use raystep_engine::record::{RayTree, explain, record_pixel, text};
use raystep_engine::render::render;
use raystep_engine::scene::{Scene, parse};
use raystep_engine::trace::{NotCast, PruneRule, RayKind, RayStats};

use crate::support::{record, scene};

const GLASS_PLANES: &str = include_str!("../scenes/three-glass-planes.toml");

/// Two facing mirrors z = -1 and z = 1 of reflectance `ks`, with `settings`
/// lines added to `[settings]`; no lights.
fn mirrors(ks: f64, settings: &str) -> Scene {
    scene(&format!(
        "[camera]
        eye = [0, 0, 0]
        look_at = [0, 0, -1]
        [settings]
        {settings}
        [materials.mirror]
        kd = 0
        ks = {ks}
        [[object]]
        material = \"mirror\"
        plane = {{ normal = [0, 0, 1], point = [0, 0, -1] }}
        [[object]]
        material = \"mirror\"
        plane = {{ normal = [0, 0, -1], point = [0, 0, 1] }}"
    ))
}

/// The ray straight down the z axis between the mirrors: it bounces for ever.
fn bounce(scene: &Scene) -> RayTree {
    record(scene, [0.0, 0.0, 0.0], [0.0, 0.0, -1.0])
}

/// Every node's not-cast entries, with the node they belong to.
fn not_cast(tree: &RayTree) -> Vec<(usize, NotCast)> {
    (0..tree.nodes.len())
        .flat_map(|id| tree.nodes[id].not_cast.iter().map(move |n| (id, *n)))
        .collect()
}

#[test]
fn the_third_reflection_between_mirrors_of_ks_one_tenth_is_not_cast() {
    // Accumulated weights: the primary 1, the first reflection 0.1, the
    // second 0.01, the third 0.001 < 1/512 = 0.00195: not cast, although
    // max_depth 5 would allow it (depth 4).
    let tree = bounce(&mirrors(0.1, ""));
    let depths: Vec<u32> = tree.nodes.iter().map(|n| n.depth).collect();
    assert_eq!(depths, [1, 2, 3]);
    let pruned = not_cast(&tree);
    assert_eq!(pruned.len(), 1);
    let (node, ray) = pruned[0];
    assert_eq!(node, 2);
    assert_eq!(ray.kind, RayKind::Reflected);
    assert_eq!(ray.weight, 0.1);
    assert!((ray.path_weight - 0.001).abs() < 1e-15);
    assert_eq!(
        ray.rule,
        PruneRule::MinWeight {
            min_weight: 1.0 / 512.0
        }
    );
    assert!(tree.nodes[2].reflected.is_none());
    assert!(
        text(&tree).contains("reflected ray not cast: accumulated weight 0.001 < min_weight 1/512")
    );
    // Graphviz puts the ray, the rule and the reason on three lines of one
    // grey dashed box.
    assert!(raystep_engine::record::dot(&tree).contains(
        "n2p0 [shape=box, style=dashed, color=\"grey\", fontcolor=\"grey40\", label=\"reflected ray\\nnot cast: min_weight\\naccumulated weight 0.001 < min_weight 1/512\"];"
    ));
}

#[test]
fn without_a_cutoff_max_depth_alone_stops_the_mirrors() {
    // min_weight = 0 (what NFF scenes get): depths 1 to 5, nothing pruned.
    let tree = bounce(&mirrors(0.1, "min_weight = 0"));
    assert_eq!(tree.nodes.len(), 5);
    assert!(not_cast(&tree).is_empty());
}

#[test]
fn a_weight_equal_to_the_cutoff_is_still_cast() {
    // ks = 0.5, min_weight = 0.25: weights 1, 0.5, 0.25 (not below: cast),
    // then 0.125 < 0.25, not cast. All exact in binary.
    let tree = bounce(&mirrors(0.5, "min_weight = 0.25"));
    assert_eq!(tree.nodes.len(), 3);
    let pruned = not_cast(&tree);
    assert_eq!(pruned.len(), 1);
    assert_eq!((pruned[0].0, pruned[0].1.path_weight), (2, 0.125));
}

#[test]
fn perfect_mirrors_stop_at_the_ray_budget() {
    // ks = 1: the weight never falls, max_depth 64 is far; max_rays = 3 lets
    // the primary ray and two reflections be cast, and the third is not.
    let tree = bounce(&mirrors(1.0, "max_depth = 64\nmax_rays = 3"));
    assert_eq!(tree.nodes.len(), 3);
    let pruned = not_cast(&tree);
    assert_eq!(pruned.len(), 1);
    let (node, ray) = pruned[0];
    assert_eq!(
        (node, ray.kind, ray.path_weight),
        (2, RayKind::Reflected, 1.0)
    );
    assert_eq!(ray.rule, PruneRule::MaxRays { max_rays: 3 });
    assert!(
        text(&tree)
            .contains("reflected ray not cast: the pixel's tree already has max_rays = 3 rays")
    );
    assert!(explain(&tree).contains("Deeper in the tree 1 secondary ray was not cast"));
}

/// The glass-planes scene with ks = kt = 1: no weight ever falls.
fn lossless_glass_planes(max_rays: Option<u32>) -> Scene {
    let mut text = GLASS_PLANES
        .replace("ks = 0.5", "ks = 1")
        .replace("kt = 0.5", "kt = 1");
    if let Some(max_rays) = max_rays {
        let budget = format!("\nmax_depth = 64\nmax_rays = {max_rays}\n");
        text = text.replace("\nmax_depth = 64\n", &budget);
    }
    scene(&text)
}

#[test]
fn every_pixel_of_lossless_glass_planes_holds_exactly_max_rays_rays() {
    // Each pixel's reflected chain stays between two planes and never ends
    // before depth 64, so every tree fills its budget of 10: 32 x 24 pixels
    // x 10 rays = 7680 primary, reflected and transmitted rays.
    let scene = lossless_glass_planes(Some(10));
    let (_, stats) = render::<RayStats>(&scene, &scene.settings, &|| {});
    assert_eq!(stats.primary, 768);
    assert_eq!(stats.primary + stats.reflected + stats.transmitted, 7680);
    assert!(stats.not_cast > 0);
}

#[test]
fn the_default_budget_bounds_a_lossless_tree() {
    // The full tree would hold far more than 4096 rays (it branches at
    // every hit for 64 levels): the recording holds exactly the default 4096.
    let scene = lossless_glass_planes(None);
    let tree = record_pixel(&scene, &scene.settings, 16, 12);
    assert_eq!(tree.nodes.len(), 4096);
}

#[test]
fn the_three_glass_planes_render_with_a_bounded_tree() {
    // Half the weight goes each way: 0.5^9 = 1/512 is still cast, 0.5^10 is
    // not, so no ray is deeper than 10 and a tree holds at most 2^10 - 1.
    let scene = scene(GLASS_PLANES);
    let (_, stats) = render::<RayStats>(&scene, &scene.settings, &|| {});
    let rays = stats.primary + stats.reflected + stats.transmitted;
    assert!(rays <= 768 * 1023, "{rays} rays");
    assert!(stats.not_cast > 0);
    let tree = record_pixel(&scene, &scene.settings, 16, 12);
    assert!(tree.nodes.iter().all(|n| n.depth <= 10));
}

#[test]
fn inspect_json_of_the_three_glass_planes_finishes_bounded() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/three-glass-planes.toml");
    let output = Command::new(env!("CARGO_BIN_EXE_raystep"))
        .args([
            "inspect",
            path.to_str().unwrap(),
            "--pixel",
            "16,12",
            "--format",
            "json",
        ])
        .output()
        .unwrap();
    assert!(output.status.success());
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    fn count(node: &serde_json::Value, pruned: &mut Vec<serde_json::Value>) -> usize {
        if node.is_null() {
            return 0;
        }
        pruned.extend(node["not_cast"].as_array().into_iter().flatten().cloned());
        1 + count(&node["reflected"], pruned) + count(&node["transmitted"], pruned)
    }
    let mut pruned = Vec::new();
    let nodes = count(&json["tree"], &mut pruned);
    assert!((1..=1023).contains(&nodes), "{nodes} nodes");
    // Each entry says kind, weights and rule: here always 0.5 of 1/512 = 0.5^9,
    // giving 0.5^10.
    assert!(!pruned.is_empty());
    for entry in &pruned {
        assert_eq!(entry["rule"], "min_weight");
        assert_eq!(entry["min_weight"], 1.0 / 512.0);
        assert_eq!(entry["weight"], 0.5);
        assert_eq!(entry["path_weight"], 1.0 / 1024.0);
    }
    let events = json["events"].as_array().unwrap();
    let pruned_events = events.iter().filter(|e| e["event"] == "not_cast").count();
    assert_eq!(pruned_events, pruned.len());
}

#[test]
fn nff_scenes_have_no_weight_cutoff() {
    let scene = parse(
        Path::new("test.nff"),
        "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 4 4\n\
         l 0 5 5\nf 1 1 1 0.5 0.5 10 0 1\ns 0 0 0 1\n",
    )
    .unwrap();
    assert_eq!(
        (scene.settings.min_weight, scene.settings.max_depth),
        (0.0, 5)
    );
    assert_eq!(scene.settings.max_rays, 4096);
}

fn settings_error(line: &str) -> String {
    let text = format!("[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n[settings]\n{line}\n");
    parse(Path::new("bad.toml"), &text)
        .expect_err("refused")
        .to_string()
}

#[test]
fn out_of_range_cutoffs_and_budgets_are_refused_with_their_place() {
    for (line, message) in [
        (
            "min_weight = -0.1",
            "`settings.min_weight` must be between 0 and 1, got -0.1",
        ),
        (
            "min_weight = 1.5",
            "`settings.min_weight` must be between 0 and 1, got 1.5",
        ),
        (
            "max_rays = 0",
            "max_rays must be between 1 and 65536, got 0",
        ),
        (
            "max_rays = 65537",
            "max_rays must be between 1 and 65536, got 65537",
        ),
    ] {
        let error = settings_error(line);
        assert!(error.contains(message), "{error}");
        assert!(error.contains("bad.toml:5:"), "{error}");
    }
}

/// A white floor y = 0 lit by lights at `positions`; the ray comes straight
/// down onto (0, 0, 0).
fn floor_lit_from(positions: &[[f64; 3]]) -> RayTree {
    let lights: String = positions
        .iter()
        .map(|p| format!("[[light]]\nposition = [{}, {}, {}]\n", p[0], p[1], p[2]))
        .collect();
    let scene = scene(&format!(
        "[camera]
        eye = [0, 1, 0]
        look_at = [0, 0, 0]
        up = [0, 0, 1]
        [settings]
        ambient = [0.1, 0.1, 0.1]
        [materials.white]
        kd = 1
        {lights}
        [[object]]
        material = \"white\"
        plane = {{ normal = [0, 1, 0], point = [0, 0, 0] }}"
    ));
    record(&scene, [0.0, 1.0, 0.0], [0.0, -1.0, 0.0])
}

#[test]
fn a_light_within_eps_of_the_point_adds_nothing_and_casts_no_shadow_ray() {
    // The ray hits (0, 0, 0) exactly at t = 1. A light there (distance 0) and
    // one 5e-5 above it (< EPS = 1e-4) have no usable direction: recorded with
    // L = 0, N·L = 0, facing away, no shadow ray. A light 2e-4 above is past
    // EPS: L = N = (0, 1, 0), N·L = 1, its shadow segment (1e-4, 2e-4) is
    // empty, S = 1, diffuse = 1 x 1 x 1 = 1.
    let tree = floor_lit_from(&[[0.0, 0.0, 0.0], [0.0, 5e-5, 0.0], [0.0, 2e-4, 0.0]]);
    let lights = &tree.root().lights;
    for light in &lights[..2] {
        assert!(light.at_point && light.faces_away);
        assert_eq!((light.to_light, light.n_dot_l), (DVec3::ZERO, 0.0));
        assert!(light.shadow.is_none());
        assert_eq!(light.diffuse + light.specular, DVec3::ZERO);
        assert!(light.f_att.is_finite() && light.specular_cosine.is_finite());
    }
    assert_eq!(lights[0].distance, Some(0.0));
    assert!(!lights[2].at_point);
    assert_eq!(
        (lights[2].n_dot_l, lights[2].shadow.as_ref().unwrap().s),
        (1.0, 1.0)
    );
    // ambient 0.1 + the third light's diffuse 1.
    assert_eq!(tree.color(), DVec3::splat(1.1));
    // Every number of the recording is finite: serde_json writes NaN as null.
    let root = &tree.to_json()["tree"];
    for light in root["lights"].as_array().unwrap() {
        for key in [
            "to_light",
            "distance",
            "n_dot_l",
            "f_att",
            "specular_cosine",
            "diffuse",
        ] {
            assert!(!light[key].is_null(), "{key} of {light}");
        }
    }
    assert_eq!(root["lights"][0]["at_point"], true);
    assert!(root["lights"][2].get("at_point").is_none());
    assert!(text(&tree).contains("light 0: at the point (distance 0 < EPS = 0.0001)"));
    assert!(
        explain(&tree).contains("light 1: sits on the point (distance 5.000e-5 < EPS = 0.0001)")
    );
}

#[test]
fn the_debugger_step_list_and_details_show_a_ray_not_cast() {
    use raystep::tui::view::details;
    use raystep_engine::record::EventKind;
    use raystep_engine::record::describe_event;
    // The mirrors of ks = 0.1: the third reflection, from ray r2, is not cast.
    let scene = mirrors(0.1, "");
    let tree = bounce(&scene);
    let at = tree
        .events
        .iter()
        .position(|e| matches!(e.kind, EventKind::NotCast(_)))
        .expect("a not_cast event");
    // It comes after r2's own terms and before r2 is done.
    assert_eq!(tree.events[at].node, 2);
    assert!(matches!(
        tree.events[at + 1].kind,
        EventKind::RayDone { .. }
    ));
    let line = "reflected ray not cast: accumulated weight 0.001 < min_weight 1/512";
    let (text, _) = describe_event(&tree, &scene, &tree.events[at]);
    assert_eq!(text, format!("r2: {line}"));
    let about = details::marked(&tree, 2, Some(at));
    let marked: Vec<String> = details::ray_lines(&tree, 2)
        .iter()
        .filter(|l| l.about == about)
        .map(|l| l.to_string())
        .collect();
    assert_eq!(marked, [line]);
}

#[test]
fn the_debugger_opens_lossless_glass_planes_at_depth_64() {
    // ks = kt = 1, max_depth 64, the default budget: the debugger renders the
    // image and records the centre pixel, 4096 rays, and does not grow.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("lossless.toml");
    let text = GLASS_PLANES
        .replace("ks = 0.5", "ks = 1")
        .replace("kt = 0.5", "kt = 1");
    std::fs::write(&path, text).unwrap();
    let app = raystep::tui::App::open(Some(path), true).unwrap();
    assert_eq!(app.pixel().tree().nodes.len(), 4096);
}
