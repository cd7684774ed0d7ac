//! docs/MODEL.md and docs/RAYLOG.md are the student's whole contract
//! (issue 39): what they state that a student's tracer must match is
//! checked here against what raystep does.

use std::fs;
use std::path::Path;

use glam::DVec3;
use raystep_engine::record::record_pixel;
use raystep_tools::raylog::{RaylogReader, raylog};
use serde_json::Value;

use crate::support::{record, scene, scene_at};

fn doc(name: &str) -> String {
    fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("docs")
            .join(name),
    )
    .unwrap()
}

/// The text of the `## ` section whose heading starts with `heading`, up to
/// the next `## ` heading.
fn section<'a>(text: &'a str, heading: &str) -> &'a str {
    let start = text
        .find(&format!("\n## {heading}"))
        .unwrap_or_else(|| panic!("no section '## {heading}'"));
    let body = &text[start + 1..];
    let end = body[3..].find("\n## ").map_or(body.len(), |i| i + 3);
    &body[..end]
}

/// The keys of a JSON object written on one line, in the order written.
fn keys_in_order(line: &str) -> Vec<String> {
    let value: serde_json::Map<String, Value> = serde_json::from_str(line).unwrap();
    let mut keys: Vec<(usize, String)> = value
        .keys()
        .map(|k| (line.find(&format!("\"{k}\": ")).unwrap(), k.clone()))
        .collect();
    keys.sort();
    keys.into_iter().map(|(_, k)| k).collect()
}

/// Whether two JSON values are equal, numbers within a relative 1e-9.
fn close(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            (x - y).abs() <= 1e-9 * x.abs().max(y.abs()).max(1.0)
        }
        (Value::Array(x), Value::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(x, y)| close(x, y))
        }
        (Value::Object(x), Value::Object(y)) => {
            x.len() == y.len() && x.iter().all(|(k, v)| y.get(k).is_some_and(|w| close(v, w)))
        }
        _ => a == b,
    }
}

const WRITTEN_ORDER: [&str; 14] = [
    "pixel", "path", "origin", "dir", "hit", "t", "point", "normal", "color", "ambient", "diffuse",
    "specular", "S", "weight",
];

#[test]
fn raylogs_example_lines_are_what_inspect_prints_for_the_pixel_it_names() {
    let text = doc("RAYLOG.md");
    // The order of a line's keys, as the page states it, is the writer's.
    assert!(
        text.contains(&format!("```\n{}\n```", WRITTEN_ORDER.join(", "))),
        "RAYLOG.md states the order of a line's keys"
    );
    let marker = "<!-- the hit, the shadow ray and the miss: tests/suite/docs_contract.rs reads them -->\n```\n";
    let start = text.find(marker).expect("RAYLOG.md's example lines") + marker.len();
    let block = &text[start..start + text[start..].find("```").unwrap()];
    let documented: Vec<&str> = block.lines().collect();
    assert_eq!(documented.len(), 3, "{block}");
    assert!(
        text.contains("raystep inspect scenes/seven-rays.toml --pixel 80,60\n--format raylog"),
        "the page names the scene and pixel of its example"
    );
    let scene = scene_at(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/seven-rays.toml"),
        None,
    );
    // Each is a line the reader reads.
    let read: Vec<_> = RaylogReader::new("RAYLOG.md", block.as_bytes(), &scene)
        .collect::<Result<_, _>>()
        .unwrap();
    assert_eq!(read.len(), 3);
    let ours = raylog(&record_pixel(&scene, &scene.settings, 80, 60));
    for line in &documented {
        let value: Value = serde_json::from_str(line).unwrap();
        let mine = ours
            .lines()
            .find(|l| {
                let v: Value = serde_json::from_str(l).unwrap();
                v["path"] == value["path"]
            })
            .unwrap_or_else(|| panic!("no ray {} in ours", value["path"]));
        assert_eq!(keys_in_order(line), keys_in_order(mine), "{line}");
        assert!(
            close(&value, &serde_json::from_str(mine).unwrap()),
            "{line}\n{mine}"
        );
    }
    // A hit with every key but S; a shadow ray; a miss without the hit's keys.
    let every_key_but_s: Vec<&str> = WRITTEN_ORDER.into_iter().filter(|k| *k != "S").collect();
    assert_eq!(keys_in_order(documented[0]), every_key_but_s);
    assert_eq!(
        keys_in_order(documented[1]),
        ["pixel", "path", "origin", "dir", "S"]
    );
    assert_eq!(
        keys_in_order(documented[2]),
        ["pixel", "path", "origin", "dir", "hit", "color", "weight"]
    );
    assert!(documented[2].contains("\"hit\": null"));
    // And the words on a miss name what it leaves out.
    let miss = text
        .split("\n- ")
        .find(|item| item.starts_with("**A miss**"))
        .expect("RAYLOG.md says what a miss logs");
    for key in ["t", "point", "normal", "ambient", "diffuse", "specular"] {
        assert!(
            miss.contains(&format!("`{key}`")),
            "a miss leaves out {key}"
        );
    }
}

#[test]
fn raylogs_checklist_names_each_rule_and_its_model_section() {
    let text = doc("RAYLOG.md");
    let checklist = section(&text, "What your tracer must do for its log to match");
    // Numbered items ("1. ..."), each with its indented lines, on one line.
    let mut items: Vec<String> = vec![];
    for line in checklist.lines() {
        let numbered = line
            .split_once(". ")
            .filter(|(n, _)| n.parse::<u32>().is_ok());
        if let Some((_, rest)) = numbered {
            items.push(rest.to_string());
        } else if let (Some(item), true) = (items.last_mut(), line.starts_with("   ")) {
            *item += " ";
            *item += line.trim();
        }
    }
    let rules = [
        ("**No shadow ray when N·L ≤ 0**", "(MODEL §4)"),
        ("**The min_weight cutoff is on by default**", "(MODEL §5)"),
        ("**A reflected ray only when k_s > 0**", "(MODEL §5)"),
        ("**The depth rule**", "(MODEL §5)"),
        ("**The order of a line's fields**", "MODEL §6"),
    ];
    for (rule, model) in rules {
        let item = items
            .iter()
            .find(|item| item.starts_with(rule))
            .unwrap_or_else(|| panic!("the checklist has {rule}: {items:?}"));
        assert!(item.contains(model), "{rule} names {model}: {item}");
    }
    // What the items say is what the code does.
    let defaults = minimal_scene();
    assert_eq!(defaults.settings.min_weight, 1.0 / 512.0);
    assert!(items.iter().any(|i| i.contains("1/512 = 0.001953125")));
    assert_eq!(defaults.settings.max_depth, 5);
    assert!(items.iter().any(|i| i.contains("(default 5)")));
}

fn minimal_scene() -> raystep_engine::scene::Scene {
    scene(
        r#"
[camera]
eye = [0, 0, 5]
look_at = [0, 0, 0]
[materials.m]
[[light]]
position = [0, 5, 5]
[[object]]
material = "m"
sphere = { center = [0, 0, 0], radius = 1 }
"#,
    )
}

#[test]
fn models_defaults_table_is_what_the_toml_loader_gives() {
    let text = doc("MODEL.md");
    let table = section(&text, "Defaults");
    let s = minimal_scene();
    let m = &s.materials[0];
    let v = |x: DVec3| serde_json::json!([x.x, x.y, x.z]);
    let shininess: f64 = {
        let debug = format!("{m:?}");
        let after = &debug[debug.find("shininess: ").unwrap() + 11..];
        after[..after.find(',').unwrap()].parse().unwrap()
    };
    let st = &s.settings;
    let mut checked = vec![];
    for row in table
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| symbol"))
    {
        let cells: Vec<&str> = row.split(" | ").collect();
        let key = cells[1].trim();
        let default = cells[2].split('`').nth(1).unwrap();
        let documented: Value = serde_json::from_str(default).unwrap();
        let actual = match key {
            "`camera.up`" => v(s.camera.up),
            "`camera.fov`" => serde_json::json!(s.camera.fov),
            "`image.width`, `image.height`" => serde_json::json!([s.width, s.height]),
            "`settings.background`" => v(st.background),
            "`settings.ambient`" => v(st.ambient),
            "`settings.light_attenuation`" => serde_json::json!(st.light_attenuation),
            "`settings.ray_attenuation`" => serde_json::json!(st.ray_attenuation),
            "`settings.max_depth`" => serde_json::json!(st.max_depth),
            "`settings.min_weight`" => serde_json::json!(st.min_weight),
            "`settings.max_rays`" => serde_json::json!(st.max_rays),
            "`settings.specular`" => serde_json::to_value(st.specular).unwrap(),
            "material `color`" => v(m.color),
            "material `kd`" => serde_json::json!(m.kd),
            "material `ks`" => serde_json::json!(m.ks),
            "material `n`" => serde_json::json!(shininess),
            "material `kt`" => serde_json::json!(m.kt),
            "material `ior`" => serde_json::json!(m.ior),
            "material `ka`" => serde_json::json!(m.ka),
            "material `reflect`" => serde_json::json!(m.reflects),
            "light `color`" => v(s.lights[0].color),
            other => panic!("MODEL.md's defaults name {other}, which this test does not know"),
        };
        assert!(
            close(&documented, &actual),
            "{key}: MODEL.md {documented}, the loader {actual}"
        );
        checked.push(key);
    }
    // Every camera and material default, and the settings a tracer needs.
    assert_eq!(checked.len(), 20, "{checked:?}");
}

#[test]
fn model_writes_the_highlight_with_max_and_defines_h_on_its_own_line() {
    let text = doc("MODEL.md");
    let notes = section(&text, "1. What the course notes say");
    assert!(notes.contains("k_s max(0, N·H_i)^n ]"), "{notes}");
    assert!(
        notes
            .lines()
            .any(|l| l.trim() == "H_i = normalize(L_i + V), the half vector of light i (§4)."),
        "H on its own line"
    );
}

#[test]
fn model_keeps_where_in_the_code_and_the_recording_in_an_appendix() {
    let text = doc("MODEL.md");
    let appendix = text
        .find("\n## Appendix: implementation notes\n")
        .expect("MODEL.md's appendix");
    let (rules, notes) = text.split_at(appendix);
    assert!(!rules.contains("Where in the code"));
    assert!(!rules.contains("Near misses (recorded"));
    assert!(!rules.contains("The crossing test laid out"));
    // How lights, blockers and rays not cast are recorded is not a rule of
    // the tracer either (issue 39 found these three inside §4 and §5).
    for recording in [
        "`at_point`",
        "recorded tree lists every",
        "the recording lists it",
    ] {
        assert!(!rules.contains(recording), "{recording} in §1-§10");
    }
    for recording in [
        "`at_point`",
        "the recorded\n  tree lists every",
        "listed on its parent",
    ] {
        assert!(notes.contains(recording), "{recording} in the appendix");
    }
    assert!(notes.contains("### Where in the code"));
    // The numbered sections stay as other pages cite them, in order.
    let mut at = 0;
    for n in 1..=10 {
        let heading = format!("\n## {n}. ");
        at += rules[at..].find(&heading).unwrap_or_else(|| panic!("§{n}"));
        assert!(
            notes.contains(&format!("- §{n} (")) || n == 9,
            "§{n} in the appendix"
        );
    }
}

/// The cylinder's and cone's equations, as MODEL §3 writes them, evaluated
/// here term by term: their nearest root and normal are the ones the
/// shape gives (a few rays: the side, through the open end, the tip).
#[test]
fn models_cone_equations_give_the_shapes_own_hits_and_normals() {
    let text = doc("MODEL.md");
    let hits = section(&text, "3. Hits and normals");
    for formula in [
        "Δ = o - b, Δ_s = Δ·u, d_s = d·u, Δ⊥ = Δ - Δ_s u, d⊥ = d - d_s u.",
        "r1 = k d_s.",
        "A = |d⊥|^2 - r1^2, B = 2 (Δ⊥·d⊥ - r0 r1), C = |Δ⊥|^2 - r0^2.",
        "For a cylinder (k = 0): A = |d⊥|^2, B = 2 Δ⊥·d⊥, C = |Δ⊥|^2 - r_b^2.",
        "between the ends, 0 <= s <= h, and r0 + r1 t >= 0",
        "N_g = normalize(normalize(q⊥) - k u).",
        "N_g = normalize(-k u), the axis pointing from the wide end",
    ] {
        let flat = hits.split_whitespace().collect::<Vec<_>>().join(" ");
        assert!(flat.contains(formula), "MODEL §3 gives {formula}");
    }
    const EPS: f64 = 1e-4;
    // The documented formulas.
    let documented = |b: DVec3, rb: f64, a: DVec3, ra: f64, o: DVec3, d: DVec3| {
        let h = (a - b).length();
        let u = (a - b) / h;
        let k = (ra - rb) / h;
        let delta = o - b;
        let (delta_s, d_s) = (delta.dot(u), d.dot(u));
        let (delta_perp, d_perp) = (delta - delta_s * u, d - d_s * u);
        let (r0, r1) = (rb + k * delta_s, k * d_s);
        let qa = d_perp.length_squared() - r1 * r1;
        let qb = 2.0 * (delta_perp.dot(d_perp) - r0 * r1);
        let qc = delta_perp.length_squared() - r0 * r0;
        let disc = qb * qb - 4.0 * qa * qc;
        let roots = if qa == 0.0 {
            vec![-qc / qb]
        } else if disc < 0.0 {
            vec![]
        } else {
            let (x, y) = (
                (-qb - disc.sqrt()) / (2.0 * qa),
                (-qb + disc.sqrt()) / (2.0 * qa),
            );
            vec![x.min(y), x.max(y)]
        };
        let t = roots.into_iter().find(|&t| {
            let s = delta_s + t * d_s;
            t > EPS && (0.0..=h).contains(&s) && r0 + r1 * t >= 0.0
        })?;
        let q = o + t * d - b;
        let q_perp = q - q.dot(u) * u;
        let n_g = (q_perp.normalize_or_zero() - k * u).normalize();
        // N faces the ray (MODEL §3).
        Some((t, if n_g.dot(d) > 0.0 { -n_g } else { n_g }))
    };
    let shapes = [
        (
            "cylinder = { base = [0, -1, 0], apex = [0, 1, 0], radius = 0.5 }",
            0.5,
            0.5,
        ),
        (
            "cone = { base = [0, -1, 0], base_radius = 0.8, apex = [0, 1, 0], apex_radius = 0 }",
            0.8,
            0.0,
        ),
        (
            "cone = { base = [0, -1, 0], base_radius = 0.3, apex = [0, 1, 0], apex_radius = 0.6 }",
            0.3,
            0.6,
        ),
    ];
    let rays = [
        ([0.0, 0.2, 5.0], [0.0, 0.0, -1.0]),
        ([0.1, 0.3, 5.0], [0.05, -0.1, -1.0]),
        ([0.0, 3.0, 0.0], [0.0, -1.0, 0.0]),
        ([0.2, 3.0, 0.1], [-0.03, -1.0, 0.01]),
        ([0.0, -4.0, 0.2], [0.0, 1.0, 0.0]),
        ([2.0, 2.0, 2.0], [-1.0, -1.2, -1.0]),
        ([3.0, 0.0, 0.0], [-1.0, 0.0, 0.0]),
    ];
    let mut hit = 0;
    for (shape, rb, ra) in shapes {
        let s = scene(&format!(
            "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n[materials.m]\n[[object]]\nmaterial = \"m\"\n{shape}\n"
        ));
        for (o, d) in rays {
            let tree = record(&s, o, d);
            let node = &tree.nodes[0];
            let expected = documented(
                DVec3::new(0.0, -1.0, 0.0),
                rb,
                DVec3::new(0.0, 1.0, 0.0),
                ra,
                DVec3::from_array(o),
                DVec3::from_array(d),
            );
            match (&node.hit, expected) {
                (None, None) => {}
                (Some(h), Some((t, n))) => {
                    hit += 1;
                    assert!(
                        (h.t - t).abs() < 1e-9,
                        "{shape} {o:?} {d:?}: t {} vs {t}",
                        h.t
                    );
                    assert!(
                        (h.normal - n).length() < 1e-9,
                        "{shape} {o:?}: N {} vs {n}",
                        h.normal
                    );
                }
                (h, e) => panic!("{shape} {o:?} {d:?}: the shape {h:?}, the formulas {e:?}"),
            }
        }
    }
    assert!(hit >= 12, "{hit} hits");
    // Down the axis onto the cone's tip: N is the axis, from the wide end
    // towards the tip.
    let cone = scene(&format!(
        "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n[materials.m]\n[[object]]\nmaterial = \"m\"\n{}\n",
        shapes[1].0
    ));
    let tip = record(&cone, [0.0, 3.0, 0.0], [0.0, -1.0, 0.0]);
    let tip = tip.nodes[0].hit.as_ref().expect("the tip is hit");
    assert!(
        (tip.t - 2.0).abs() < 1e-9 && tip.normal == DVec3::Y,
        "{tip:?}"
    );
}

#[test]
fn model_and_cse167_name_the_mistakes_cse167_does_not_offer() {
    // Whatever `Profile::offers` leaves out under cse167 is named in MODEL
    // §11 and in CSE167.md, which counts what is left.
    use raystep_engine::scene::Profile;
    use raystep_model::mistakes::Mistake;
    let model = doc("MODEL.md");
    let profiles = section(&model, "11. Profiles");
    let course = doc("CSE167.md");
    let mistakes = section(&course, "Classic mistakes");
    let not_offered: Vec<Mistake> = (Mistake::ALL.into_iter())
        .filter(|&m| !Profile::Cse167.offers(m))
        .collect();
    assert!(!not_offered.is_empty());
    for mistake in &not_offered {
        let named = format!("`{mistake}`");
        assert!(profiles.contains(&named), "{named} in MODEL §11");
        assert!(mistakes.contains(&named), "{named} in CSE167.md");
    }
    let offered = Mistake::ALL.len() - not_offered.len();
    assert!(mistakes.contains(&format!("offered the {offered} that")));
}
