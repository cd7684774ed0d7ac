//! `raystep diagram`: a pixel's rays as an SVG figure. The figure parses as
//! XML, holds what the recording holds, and is pinned by a reviewed snapshot.

use crate::support::{raystep, stderr};

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
    let scene = raystep_engine::scene::load(std::path::Path::new("scenes/glass.toml")).unwrap();
    let tree = raystep_engine::record::record_pixel(&scene, &scene.settings, 135, 58);
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
    let faces_away = tree
        .nodes
        .iter()
        .flat_map(|n| &n.lights)
        .filter(|l| l.faces_away)
        .count();
    assert_eq!(faces_away, 2);
    let svg = figure(dir.path(), "top");
    // Lines: a ray and a normal per hit, a ray per miss, the shadow rays,
    // a dotted line per light facing away, and eight in the legend (seven
    // kinds of ray, partly blocked among them as glass passes some light
    // at S = 0.81 and 0.9, and the dotted line).
    let partial = (tree.nodes.iter())
        .flat_map(|n| &n.lights)
        .filter_map(|l| l.shadow.as_ref())
        .filter(|s| s.s > 0.0 && s.s < 1.0)
        .count();
    assert!(partial > 0);
    let lines = svg.matches("<line ").count();
    assert_eq!(
        lines,
        tree.nodes.len() + hits + shadows + faces_away + 8,
        "{svg}"
    );
    assert_eq!(
        svg.matches("stroke-dasharray=\"2 4\"").count(),
        faces_away + 1
    );
    // An arrowhead on each ray long enough to hold one (24 units: its tip
    // 8 short of the end, its base 18), none on a normal.
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let mut arrows = 0;
    for line in doc
        .root_element()
        .children()
        .filter(|n| n.has_tag_name("line"))
    {
        let at = |name| line.attribute(name).unwrap().parse::<f64>().unwrap();
        let length = (at("x2") - at("x1")).hypot(at("y2") - at("y1"));
        let normal = line.attribute("stroke") == Some("#009988");
        let dotted = line.attribute("stroke-dasharray") == Some("2 4");
        let arrow = line.attribute("marker-end").is_some();
        assert_eq!(arrow, !normal && !dotted && length > 24.0, "{line:?}");
        arrows += usize::from(arrow);
    }
    assert!(arrows > tree.nodes.len(), "{arrows}");
    // An × per blocker, a dot per hit (and one in the legend).
    assert_eq!(svg.matches("l8 8m0 -8l-8 8").count(), blockers);
    assert_eq!(svg.matches("r=\"3\" fill=\"black\"").count(), hits + 1);
}

#[test]
fn the_figure_is_pinned() {
    let dir = tempfile::tempdir().unwrap();
    let svg = figure(dir.path(), "top");
    snapshot!("glass_135_58_top", svg);
}

/// Each figure the tester reviewed: scene, pixel, plane and extra arguments.
const REVIEWED: [(&str, &str, &str, &[&str]); 10] = [
    ("prism", "90,60", "top", &[]),
    ("prism", "90,60", "side", &[]),
    ("prism", "90,60", "ray", &[]),
    ("prism", "90,60", "top", &["--zoom", "4"]),
    ("glass", "135,58", "top", &[]),
    ("glass", "135,58", "top", &["--zoom", "4"]),
    ("two-lights", "3,64", "top", &[]),
    ("two-lights", "92,61", "side", &[]),
    ("polygons", "40,54", "top", &[]),
    ("polygons", "40,54", "crossing", &[]),
];

fn reviewed(
    dir: &std::path::Path,
    (scene, pixel, plane, extra): (&str, &str, &str, &[&str]),
) -> String {
    let out = dir.join("reviewed.svg");
    let scene = format!("scenes/{scene}.toml");
    let mut args = vec!["diagram", &scene, "--pixel", pixel, "--plane", plane];
    args.extend_from_slice(extra);
    args.extend(["-o", out.to_str().unwrap()]);
    let output = raystep(&args);
    assert!(output.status.success(), "{}", stderr(&output));
    std::fs::read_to_string(out).unwrap()
}

/// A text element's estimated box (0.6 em a character, the font size high,
/// 3 below the baseline for descenders), as the label placer estimates it.
fn text_box(node: roxmltree::Node, root_size: f64) -> [f64; 4] {
    let number = |name| {
        node.attribute(name)
            .map(|v: &str| v.parse::<f64>().unwrap())
    };
    let size = number("font-size").unwrap_or(root_size);
    let width = node.text().unwrap_or("").chars().count() as f64 * size * 0.6;
    let (x, y) = (number("x").unwrap(), number("y").unwrap());
    let left = match node.attribute("text-anchor") {
        Some("end") => x - width,
        Some("middle") => x - width / 2.0,
        _ => x,
    };
    [left, y - size, left + width, y + 3.0]
}

#[test]
fn every_label_is_inside_the_figure_and_none_overlaps_another() {
    let dir = tempfile::tempdir().unwrap();
    for case in REVIEWED {
        let svg = reviewed(dir.path(), case);
        let doc = roxmltree::Document::parse(&svg).expect("well-formed XML");
        let root = doc.root_element();
        let view: Vec<f64> = (root.attribute("viewBox").unwrap().split(' '))
            .map(|v| v.parse().unwrap())
            .collect();
        let root_size: f64 = root.attribute("font-size").unwrap().parse().unwrap();
        let texts: Vec<(&str, [f64; 4])> = root
            .descendants()
            .filter(|n| n.has_tag_name("text"))
            .map(|n| (n.text().unwrap_or(""), text_box(n, root_size)))
            .collect();
        assert!(texts.len() > 5, "{case:?}: {texts:?}");
        for (text, b) in &texts {
            let inside = b[0] >= view[0]
                && b[1] >= view[1]
                && b[2] <= view[0] + view[2]
                && b[3] <= view[1] + view[3];
            assert!(inside, "{case:?}: {text:?} at {b:?} leaves the figure");
        }
        for (i, (a, p)) in texts.iter().enumerate() {
            for (b, q) in &texts[i + 1..] {
                let overlap = p[0] < q[2] && q[0] < p[2] && p[1] < q[3] && q[1] < p[3];
                assert!(!overlap, "{case:?}: {a:?} at {p:?} overlaps {b:?} at {q:?}");
            }
        }
    }
}

#[test]
fn a_polygon_passed_by_is_ringed_not_hit() {
    // polygons.toml's pixel (40, 54): the primary ray passes the star by
    // (its plane met inside the star's box, the crossing test even) on its
    // way to the backdrop: a ring where it crosses the plane, "passed by"
    // beside it and in the legend.
    let dir = tempfile::tempdir().unwrap();
    let svg = reviewed(dir.path(), REVIEWED[8]);
    let scene = raystep_engine::scene::load(std::path::Path::new("scenes/polygons.toml")).unwrap();
    let tree = raystep_engine::record::record_pixel(&scene, &scene.settings, 40, 54);
    let passed = tree
        .root()
        .near_misses
        .iter()
        .filter(|n| n.crossing_figure.is_some())
        .count();
    assert!(passed >= 1);
    assert!(tree.root().near_misses.iter().any(|n| n.object == "star"));
    assert_eq!(svg.matches("class=\"passed-by\"").count(), passed, "{svg}");
    assert!(
        svg.contains(">passed by</text>") || svg.contains(": passed by</text>"),
        "{svg}"
    );
    assert!(
        svg.contains(">passed by: ray crosses a polygon's plane, or comes nearest a sphere</text>"),
        "{svg}"
    );
}

#[test]
fn zoom_magnifies_about_the_first_hit_and_cuts_at_the_frame() {
    // prism.toml's pixel (90, 60) at --zoom 4: the lights and the far wall
    // fall outside, so some rays are cut at the frame's edge, and no label
    // names what is off it; every line's ends stay inside the figure.
    let dir = tempfile::tempdir().unwrap();
    let whole = reviewed(dir.path(), REVIEWED[0]);
    let zoomed = reviewed(dir.path(), REVIEWED[3]);
    assert!(whole.contains(">light lamp</text>") && whole.contains(">eye</text>"));
    assert!(!zoomed.contains(">light lamp</text>"), "{zoomed}");
    assert!(!zoomed.contains(">eye</text>"), "{zoomed}");
    assert!(zoomed.contains("magnified 4×"));
    let doc = roxmltree::Document::parse(&zoomed).unwrap();
    // The rays are the root's own lines (outlines sit in the clipped
    // group, the legend's samples in theirs).
    let root = doc.root_element();
    for line in root.children().filter(|n| n.has_tag_name("line")) {
        for (x, y) in [("x1", "y1"), ("x2", "y2")] {
            let x: f64 = line.attribute(x).unwrap().parse().unwrap();
            let y: f64 = line.attribute(y).unwrap().parse().unwrap();
            let in_frame = (6.0..=794.0).contains(&x) && (34.0..=552.0).contains(&y);
            assert!(in_frame, "{line:?}");
        }
    }
    // Out of 1..=1e4 is refused with the value named: below 1, negative
    // (not taken for an option), or so large the coordinates overflow.
    let out = dir.path().join("no.svg");
    for zoom in ["0.5", "-1", "1e308"] {
        let output = raystep(&[
            "diagram",
            "scenes/prism.toml",
            "--pixel",
            "90,60",
            "--zoom",
            zoom,
            "-o",
            out.to_str().unwrap(),
        ]);
        assert_eq!(output.status.code(), Some(2), "{zoom}");
        assert!(
            stderr(&output).contains(&format!(
                "\"{zoom}\" is not a zoom factor: give a number from 1 to 10000"
            )),
            "{}",
            stderr(&output)
        );
    }
    // The crossing figure has no zoom: refused, not silently ignored.
    let output = raystep(&[
        "diagram",
        "scenes/polygons.toml",
        "--pixel",
        "40,54",
        "--plane",
        "crossing",
        "--zoom",
        "2",
        "-o",
        out.to_str().unwrap(),
    ]);
    // A bad flag combination is a usage error (issue 27): status 2.
    assert_eq!(output.status.code(), Some(2));
    assert!(stderr(&output).contains("--zoom magnifies the top, side and ray diagrams"));
    assert!(!out.exists(), "nothing written");
}

#[test]
fn a_partly_blocked_shadow_ray_has_its_own_colour() {
    // two-lights 3,64: the left light's shadow ray passes the glass ball
    // and pane (S = 0.288, between 0 and 1), the right one's nothing
    // (S = 1). Each kind counts its rays from the recording's S values;
    // the legend adds one line of each (the partly blocked one only when
    // the figure has such a ray).
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("two.svg");
    let output = raystep(&[
        "diagram",
        "scenes/two-lights.toml",
        "--pixel",
        "3,64",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let svg = std::fs::read_to_string(out).unwrap();
    roxmltree::Document::parse(&svg).expect("well-formed XML");
    let scene =
        raystep_engine::scene::load(std::path::Path::new("scenes/two-lights.toml")).unwrap();
    let tree = raystep_engine::record::record_pixel(&scene, &scene.settings, 3, 64);
    let shadows: Vec<_> = (tree.nodes.iter())
        .flat_map(|n| &n.lights)
        .filter_map(|l| l.shadow.as_ref())
        .collect();
    let count = |test: &dyn Fn(f64) -> bool| shadows.iter().filter(|s| test(s.s)).count();
    let (lit, partial, blocked) = (
        count(&|s| s >= 1.0),
        count(&|s| s > 0.0 && s < 1.0),
        count(&|s| s <= 0.0),
    );
    assert_eq!((lit, partial, blocked), (1, 1, 0), "the pixel as described");
    let lines = |colour: &str| {
        let stroke = format!("<line x1=\"0\" y1=\"0\" x2=\"20\" y2=\"0\" stroke=\"{colour}\"");
        let legend = svg.matches(&stroke).count();
        let rays = (svg.lines())
            .filter(|l| l.starts_with("<line") && l.contains(&format!("stroke=\"{colour}\"")))
            .count();
        rays + legend
    };
    assert_eq!(lines("#ddaa33"), lit + 1, "lit, yellow");
    assert_eq!(lines("#ee7733"), partial + 1, "partly blocked, orange");
    assert_eq!(lines("#cc3311"), blocked + 1, "blocked, red");
    assert!(svg.contains("shadow ray, partly blocked (0 &lt; S &lt; 1)"));
    // An orange × at each blocker of the partly blocked ray, no red one.
    let blockers: usize = shadows.iter().map(|s| s.blockers.len()).sum();
    assert!(blockers >= 2, "ball and pane");
    let crosses = |colour: &str| {
        svg.lines()
            .filter(|l| l.contains("l8 8m0 -8l-8 8") && l.contains(colour))
            .count()
    };
    assert_eq!(crosses("#ee7733"), blockers);
    assert_eq!(crosses("#cc3311"), 0);
}

#[test]
fn a_sphere_passed_by_is_ringed_where_the_ray_comes_nearest() {
    // balls-small 200,300: the recording's near misses are spheres (each
    // with its closest approach, distance > radius). Each gets a ring in
    // the fitted figure, which holds every ring's point.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("balls.svg");
    let output = raystep(&[
        "diagram",
        "scenes/spd/balls-small.nff",
        "--pixel",
        "200,300",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let svg = std::fs::read_to_string(out).unwrap();
    let scene =
        raystep_engine::scene::load(std::path::Path::new("scenes/spd/balls-small.nff")).unwrap();
    let tree = raystep_engine::record::record_pixel(&scene, &scene.settings, 200, 300);
    let near: Vec<_> = tree.nodes.iter().flat_map(|n| &n.near_misses).collect();
    assert!(!near.is_empty());
    for n in &near {
        let c = n.closest_approach.expect("a sphere's near miss");
        assert!(c.distance > c.radius, "passed by, not hit");
    }
    assert_eq!(svg.matches("class=\"passed-by\"").count(), near.len());
    assert!(svg.contains("comes nearest a sphere"));
}

#[test]
fn planes_are_named() {
    // Before, a plane's line had no label. prism 90,60's rays end on the
    // green wall, polygons 40,54's on the back wall, two-lights 3,64's
    // primary on the floor (all planes, as the scene files say).
    let dir = tempfile::tempdir().unwrap();
    for (case, name) in [
        (REVIEWED[0], "green wall"),
        (REVIEWED[8], "back wall"),
        (REVIEWED[6], "floor"),
    ] {
        let svg = reviewed(dir.path(), case);
        assert!(svg.contains(&format!(">{name}</text>")), "{case:?}: {svg}");
    }
}

#[test]
fn diff_against_is_refused_and_set_draws_the_changed_scene() {
    // Before, `diagram --diff-against` was accepted, ignored, and its help
    // promised a text no figure has. Now clap refuses it (exit 2), nothing
    // is written, and diagram's help names neither it nor a text.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("diff.svg");
    let args = ["diagram", "scenes/glass.toml", "--pixel", "135,58"];
    let with = |extra: &[&str]| {
        let mut all = args.to_vec();
        all.extend_from_slice(extra);
        all.extend(["-o", out.to_str().unwrap()]);
        raystep(&all)
    };
    let output = with(&["--diff-against", "scenes/prism.toml"]);
    assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
    assert!(
        stderr(&output).contains("error: invalid value")
            && stderr(&output).contains("diagram takes no --diff-against"),
        "{}",
        stderr(&output)
    );
    assert!(!out.exists(), "nothing written");
    let help = crate::support::stdout(&raystep(&["diagram", "--help"]));
    assert!(!help.contains("--diff-against"), "{help}");
    assert!(!help.contains("the text"), "{help}");
    assert!(
        help.contains("the figure is drawn with the changed scene"),
        "{help}"
    );
    // --set is drawn: at max_depth 1 the primary ray alone is cast (no
    // reflected or transmitted ray), so the figure has its one ray, its
    // normal, its shadow rays (the recording's, at depth 1), the dotted
    // lines to lights facing away, and the legend's eight lines.
    let output = with(&["--set", "settings.max_depth=1"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let svg = std::fs::read_to_string(&out).unwrap();
    let mut scene = raystep_engine::scene::load(std::path::Path::new("scenes/glass.toml")).unwrap();
    scene.settings.max_depth = 1;
    let tree = raystep_engine::record::record_pixel(&scene, &scene.settings, 135, 58);
    assert_eq!(tree.nodes.len(), 1);
    let lights = &tree.root().lights;
    let shadows = lights.iter().filter(|l| l.shadow.is_some()).count();
    let away = lights.iter().filter(|l| l.faces_away).count();
    let legend = if away > 0 { 8 } else { 7 };
    let partial = (lights.iter().filter_map(|l| l.shadow.as_ref())).any(|s| s.s > 0.0 && s.s < 1.0);
    let legend = legend - usize::from(!partial);
    assert_eq!(
        svg.matches("<line ").count(),
        1 + 1 + shadows + away + legend,
        "{svg}"
    );
}

#[test]
fn the_title_names_the_scene_pixel_plane_mistakes_and_sets() {
    // Before, the figure's only title was "Pixel (135, 58), from above
    // (in the camera's frame)": no scene, and nothing of a --mistake or
    // --set it was drawn with. Now the SVG's <title> (its first child) and
    // its heading name them all, for each plane and the crossing figure.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("titled.svg");
    for (scene, pixel, plane, view) in [
        (
            "glass",
            "135,58",
            "top",
            "from above (in the camera's frame)",
        ),
        (
            "glass",
            "135,58",
            "side",
            "from the right (in the camera's frame)",
        ),
        (
            "glass",
            "135,58",
            "ray",
            "primary ray's plane (in the camera's frame)",
        ),
        (
            "polygons",
            "40,54",
            "crossing",
            "the crossing test of star (#2), passed by the primary ray",
        ),
    ] {
        let file = format!("scenes/{scene}.toml");
        let output = raystep(&[
            "diagram",
            &file,
            "--pixel",
            pixel,
            "--plane",
            plane,
            "--mistake",
            "tir-dropped",
            "--mistake",
            "no-ambient",
            "--set",
            "settings.max_depth=3",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(output.status.success(), "{}", stderr(&output));
        let svg = std::fs::read_to_string(&out).unwrap();
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let first = doc.root_element().first_element_child().unwrap();
        assert_eq!(first.tag_name().name(), "title", "{plane}");
        let words = format!(
            "{scene}.toml, pixel ({}), {view}; drawn with --mistake tir-dropped, \
             --mistake no-ambient, --set settings.max_depth=3",
            pixel.replace(',', ", ")
        );
        assert_eq!(first.text(), Some(words.as_str()), "{plane}");
        let heading = (doc.descendants())
            .find(|n| n.has_tag_name("text"))
            .and_then(|n| n.text());
        assert_eq!(heading, Some(words.as_str()), "{plane}");
    }
}

#[test]
fn shadows_primary_or_none_leave_shadow_rays_out() {
    // glass.toml 135,58 draws 10 shadow rays (2 lights at 5 hits) and 2
    // dotted lines to lights facing away with --shadows all (as before).
    // --shadows primary keeps the primary ray's hit's (node 0's) alone;
    // none keeps none, no blocker's × and no dotted line, and the legend
    // drops the shadow rays' rows. Each count below is the recording's.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shadows.svg");
    let draw = |shadows: &str| {
        let output = raystep(&[
            "diagram",
            "scenes/glass.toml",
            "--pixel",
            "135,58",
            "--shadows",
            shadows,
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(output.status.success(), "{}", stderr(&output));
        std::fs::read_to_string(&out).unwrap()
    };
    let scene = raystep_engine::scene::load(std::path::Path::new("scenes/glass.toml")).unwrap();
    let tree = raystep_engine::record::record_pixel(&scene, &scene.settings, 135, 58);
    let hits = tree.nodes.iter().filter(|n| n.hit.is_some()).count();
    let lights = |nodes: &[raystep_engine::record::Node]| {
        let lights: Vec<_> = nodes.iter().flat_map(|n| &n.lights).collect();
        let shadows: Vec<_> = lights.iter().filter_map(|l| l.shadow.as_ref()).collect();
        (
            shadows.len(),
            lights.iter().filter(|l| l.faces_away).count(),
            shadows.iter().map(|s| s.blockers.len()).sum::<usize>(),
            shadows.iter().any(|s| s.s > 0.0 && s.s < 1.0),
        )
    };
    let all = lights(&tree.nodes);
    assert_eq!((all.0, all.1), (10, 2), "the pixel as described");
    let primary = lights(&tree.nodes[..1]);
    assert!(primary.0 < all.0 && primary.0 > 0);
    let crosses = |svg: &str| svg.matches("l8 8m0 -8l-8 8").count();
    let dotted = |svg: &str| svg.matches("stroke-dasharray=\"2 4\"").count();
    // Rays and normals, then shadow rays and dotted lines; the legend's
    // lines: primary, reflected, transmitted, normal, the shadow rays' lit
    // and blocked, partly blocked and dotted when drawn.
    let legend = |(_, away, _, partial): (usize, usize, usize, bool), shadows: bool| {
        4 + 2 * usize::from(shadows) + usize::from(partial) + usize::from(away > 0)
    };
    let whole = tree.nodes.len() + hits;
    let svg = draw("all");
    assert_eq!(
        svg.matches("<line ").count(),
        whole + all.0 + all.1 + legend(all, true)
    );
    assert_eq!((crosses(&svg), dotted(&svg)), (all.2, all.1 + 1));
    let svg = draw("primary");
    assert_eq!(
        svg.matches("<line ").count(),
        whole + primary.0 + primary.1 + legend(primary, true),
        "{svg}"
    );
    assert_eq!(crosses(&svg), primary.2);
    assert_eq!(dotted(&svg), primary.1 + usize::from(primary.1 > 0));
    assert!(svg.contains("drawn with --shadows primary</title>"));
    let svg = draw("none");
    assert_eq!(svg.matches("<line ").count(), whole + 4, "{svg}");
    assert_eq!((crosses(&svg), dotted(&svg)), (0, 0));
    assert!(!svg.contains("shadow ray"), "{svg}");
    // The glass block's front face only blocks shadow rays (no ray hits
    // it): without them it is not drawn or named.
    let front = (scene.objects.iter())
        .position(|o| o.name == "glass block front")
        .unwrap();
    let hit = |n: &raystep_engine::record::Node| n.hit.as_ref().map(|h| h.object_index);
    assert!(tree.nodes.iter().all(|n| hit(n) != Some(front)));
    assert!(draw("all").contains(">glass block front</text>"));
    assert!(!draw("none").contains("glass block front"));
    // The crossing figure has no shadow rays: refused, not ignored.
    let output = raystep(&[
        "diagram",
        "scenes/polygons.toml",
        "--pixel",
        "40,54",
        "--plane",
        "crossing",
        "--shadows",
        "none",
        "-o",
        out.to_str().unwrap(),
    ]);
    // A bad flag combination is a usage error (issue 27): status 2.
    assert_eq!(output.status.code(), Some(2));
    assert!(stderr(&output).contains("the crossing figure has none"));
}

/// Whether the segment from `a` to `b` meets the box `[x0, y0, x1, y1]`:
/// the segment's parameter range cut down by each side's slab.
fn segment_meets_box(a: (f64, f64), b: (f64, f64), r: [f64; 4]) -> bool {
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (start, d, lo, hi) in [(a.0, b.0 - a.0, r[0], r[2]), (a.1, b.1 - a.1, r[1], r[3])] {
        if d == 0.0 {
            if start < lo || start > hi {
                return false;
            }
            continue;
        }
        let (ta, tb) = ((lo - start) / d, (hi - start) / d);
        t0 = t0.max(ta.min(tb));
        t1 = t1.min(ta.max(tb));
    }
    t0 <= t1
}

/// Whether a circle's line passes through the box: part of the box is
/// nearer the centre than r and part further.
fn circle_meets_box((cx, cy, radius): (f64, f64, f64), r: [f64; 4]) -> bool {
    let near = (cx.clamp(r[0], r[2]) - cx).hypot(cy.clamp(r[1], r[3]) - cy);
    let far = (cx - r[0])
        .abs()
        .max((cx - r[2]).abs())
        .hypot((cy - r[1]).abs().max((cy - r[3]).abs()));
    near < radius && far > radius
}

#[test]
fn labels_keep_off_every_outline() {
    // Before, labels were kept off outlines only as off rays (crossing
    // one when no ring near was free of both), and the crossing figure
    // kept none off the polygon: "2: edge 5→6" sat across edge 5→6. Now
    // an outline is kept clear first, further out if need be. seven-rays
    // is drawn from above and in the ray's plane: its rays all lie in
    // the horizontal plane through the eye and both balls' centres, so
    // from the side every ray lies on one line.
    let dir = tempfile::tempdir().unwrap();
    for case in [
        ("glass", "135,58", "top", &[][..]),
        ("glass", "135,58", "side", &[]),
        ("polygons", "40,54", "top", &[]),
        ("polygons", "40,54", "crossing", &[]),
        ("seven-rays", "80,60", "top", &[]),
        ("seven-rays", "80,60", "ray", &[]),
    ] {
        let svg = reviewed(dir.path(), case);
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let root = doc.root_element();
        let number = |n: roxmltree::Node, name| n.attribute(name).unwrap().parse::<f64>().unwrap();
        let points = |n: roxmltree::Node| -> Vec<(f64, f64)> {
            (n.attribute("points").unwrap().split(' '))
                .map(|p| p.split_once(',').unwrap())
                .map(|(x, y)| (x.parse().unwrap(), y.parse().unwrap()))
                .collect()
        };
        // The outlines: the clipped group's shapes, or the crossing
        // figure's polygon (closed).
        let mut segments = Vec::new();
        let mut circles = Vec::new();
        for n in root.descendants().filter(|n| n.is_element()) {
            let outline = n
                .parent_element()
                .and_then(|p| p.attribute("clip-path"))
                .is_some();
            match n.tag_name().name() {
                "circle" if outline => {
                    circles.push((number(n, "cx"), number(n, "cy"), number(n, "r")))
                }
                "line" if outline => segments.push((
                    (number(n, "x1"), number(n, "y1")),
                    (number(n, "x2"), number(n, "y2")),
                )),
                "polyline" if outline => {
                    let p = points(n);
                    segments.extend(p.windows(2).map(|w| (w[0], w[1])));
                }
                "polygon" => {
                    let p = points(n);
                    let closed = p.iter().zip(p.iter().cycle().skip(1));
                    segments.extend(closed.map(|(a, b)| (*a, *b)));
                }
                _ => {}
            }
        }
        assert!(!segments.is_empty() || !circles.is_empty(), "{case:?}");
        // The labels: every text between the headings (the crossing
        // figure's three end at 64, the others' one at 24) and the legend.
        let top = if case.2 == "crossing" { 70.0 } else { 30.0 };
        let root_size: f64 = root.attribute("font-size").unwrap().parse().unwrap();
        let labels = (root.descendants())
            .filter(|n| n.has_tag_name("text"))
            .filter(|n| (top..556.0).contains(&number(*n, "y")));
        for label in labels {
            let b = text_box(label, root_size);
            let text = label.text().unwrap_or("");
            for (a, c) in &segments {
                assert!(
                    !segment_meets_box(*a, *c, b),
                    "{case:?}: {text:?} at {b:?} crosses {a:?}-{c:?}"
                );
            }
            for c in &circles {
                assert!(
                    !circle_meets_box(*c, b),
                    "{case:?}: {text:?} at {b:?} crosses circle {c:?}"
                );
            }
        }
    }
}

/// How far the circle's line is from the box: 0 when it passes through;
/// else how far the box lies outside it, or inside it.
fn circle_box_distance((cx, cy, radius): (f64, f64, f64), r: [f64; 4]) -> f64 {
    let near = (cx.clamp(r[0], r[2]) - cx).hypot(cy.clamp(r[1], r[3]) - cy);
    let far = (cx - r[0])
        .abs()
        .max((cx - r[2]).abs())
        .hypot((cy - r[1]).abs().max((cy - r[3]).abs()));
    (near - radius).max(radius - far).max(0.0)
}

#[test]
fn a_balls_name_sits_nearer_its_own_outline_than_the_other_ball() {
    // seven-rays seen from the right: the green ball (nearer the eye) is
    // drawn left of the glass ball, touching it. On main its name sat
    // above the glass ball, 19 units from the glass ball's circle and 57
    // from its own. In every plane, each ball's name must be nearer its
    // own circle. The slide draws the objects met in object order: the
    // glass ball's circle first, then the green ball's.
    let dir = tempfile::tempdir().unwrap();
    for case in [
        ("seven-rays", "80,60", "side", &[][..]),
        ("seven-rays", "79,63", "side", &[]),
        ("seven-rays", "80,60", "top", &[]),
        ("seven-rays", "80,60", "ray", &[]),
    ] {
        let svg = reviewed(dir.path(), case);
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let root = doc.root_element();
        let number = |n: roxmltree::Node, name| n.attribute(name).unwrap().parse::<f64>().unwrap();
        let circles: Vec<(f64, f64, f64)> = (root.descendants())
            .filter(|n| n.has_tag_name("circle"))
            .filter(|n| (n.parent_element()).is_some_and(|p| p.attribute("clip-path").is_some()))
            .map(|n| (number(n, "cx"), number(n, "cy"), number(n, "r")))
            .collect();
        assert_eq!(circles.len(), 2, "{case:?}");
        let root_size: f64 = root.attribute("font-size").unwrap().parse().unwrap();
        for (name, own, other) in [("glass ball", 0, 1), ("green ball", 1, 0)] {
            let label = (root.descendants())
                .find(|n| n.has_tag_name("text") && n.text() == Some(name))
                .unwrap_or_else(|| panic!("{case:?}: no {name:?}"));
            let b = text_box(label, root_size);
            let (mine, theirs) = (
                circle_box_distance(circles[own], b),
                circle_box_distance(circles[other], b),
            );
            assert!(
                mine < theirs,
                "{case:?}: {name:?} at {b:?}: {mine} from its own circle, {theirs} from the other"
            );
        }
    }
}

#[test]
fn rays_seen_edge_on_are_said_to_be_so() {
    // seven-rays' centre pixel: every ray lies in the horizontal plane
    // through the eye (eye, look_at and both balls' centres at y = 0.6,
    // and row 60 of 121 is the middle: py = 0), so from the side all are
    // drawn on one line. The figure says so and names a plane that shows
    // them apart; from above, in the ray's plane, or one row further down
    // (79,63: seven rays again, tilted), it says nothing.
    let dir = tempfile::tempdir().unwrap();
    let note = "every ray lies in one plane seen edge-on here, one line: \
                --plane ray shows them apart";
    let svg = reviewed(dir.path(), ("seven-rays", "80,60", "side", &[]));
    assert!(svg.contains(&format!(">{note}</text>")), "{svg}");
    for case in [
        ("seven-rays", "80,60", "top", &[][..]),
        ("seven-rays", "80,60", "ray", &[]),
        ("seven-rays", "79,63", "side", &[]),
    ] {
        assert!(!reviewed(dir.path(), case).contains("edge-on"), "{case:?}");
    }
}
