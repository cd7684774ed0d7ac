//! `raystep diagram`: a pixel's rays as an SVG figure. The figure parses as
//! XML, holds what the recording holds, and is pinned by a reviewed snapshot.

mod support;

use support::{raystep, stderr};

/// Writes the figure of glass.toml's TIR pixel and returns its text.
fn figure(dir: &std::path::Path, plane: &str) -> String {
    let out = dir.join(format!("{plane}.svg"));
    let output = raystep(&[
        "diagram",
        "scenes/glass.toml",
        "--pixel",
        "135,58",
        "--plane",
        plane,
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    std::fs::read_to_string(out).unwrap()
}

#[test]
fn the_figure_is_svg_with_every_ray_light_and_blocker() {
    // The pixel's tree: 7 rays (primary, the reflected miss, the
    // transmitted ray and its TIR chain), each with its normal where it
    // hits; 10 shadow rays cast (2 lights at 5 hits; 2 face away);
    // blockers marked with an × each.
    let dir = tempfile::tempdir().unwrap();
    for plane in ["top", "side", "ray"] {
        let svg = figure(dir.path(), plane);
        let doc = roxmltree::Document::parse(&svg).expect("well-formed XML");
        let root = doc.root_element();
        assert_eq!(root.tag_name().name(), "svg");
        let texts: Vec<&str> = root
            .descendants()
            .filter(|n| n.has_tag_name("text"))
            .filter_map(|n| n.text())
            .collect();
        for expected in [
            "eye",
            "light key",
            "light fill",
            "glass block top",
            "primary",
        ] {
            assert!(
                texts.contains(&expected),
                "{plane}: no {expected:?} in {texts:?}"
            );
        }
    }
    let scene = raystep::scene::load(std::path::Path::new("scenes/glass.toml")).unwrap();
    let tree = raystep::record::record_pixel(&scene, &scene.settings, 135, 58);
    let shadows = tree
        .nodes
        .iter()
        .flat_map(|n| &n.lights)
        .filter(|l| l.shadow.is_some())
        .count();
    let blockers: usize = tree
        .nodes
        .iter()
        .flat_map(|n| &n.lights)
        .filter_map(|l| l.shadow.as_ref())
        .map(|s| s.blockers.len())
        .sum();
    let hits = tree.nodes.iter().filter(|n| n.hit.is_some()).count();
    let svg = figure(dir.path(), "top");
    // Lines: a ray and a normal per hit, a ray per miss, the shadow rays,
    // and six in the legend.
    let lines = svg.matches("<line ").count();
    assert_eq!(lines, tree.nodes.len() + hits + shadows + 6, "{svg}");
    assert_eq!(svg.matches("l8 8m0 -8l-8 8").count(), blockers);
}

#[test]
fn the_figure_is_pinned() {
    let dir = tempfile::tempdir().unwrap();
    let svg = figure(dir.path(), "top");
    insta::with_settings!({ snapshot_path => "../snapshots", prepend_module_to_snapshot => false }, {
        insta::assert_snapshot!("figure__glass_135_58_top", svg);
    });
}
