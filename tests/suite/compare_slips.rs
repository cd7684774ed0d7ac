//! Issue 39: a name is a claim. `compare` tried on the student tracer's
//! slips outside the catalogue (tests/student/whitted.py's second block):
//! no mistake the slip does not make is named as the cause or as what the
//! image looks like; a ray that missed is told before any term; the
//! geometry and what the image shows (channels swapped, a constant factor,
//! edges only, noise) supersede a mistake that only explains part; with a
//! ray log beside the image, the log's verdict supersedes the image's.
//! On main each of these named a wrong mistake: prism.toml without a TIR
//! test was `eta-inverted 99.4%`, a highlight times the object's colour
//! `phong-not-blinn 41.7%`, half a turn `flipped-y 94%`, colours times 0.8
//! `no-ambient 49.9%` on highlights.toml.

use serde_json::Value;

use crate::support::student::{TRACER, run_tracer};
use crate::support::{TEACHING_SCENES, program_or_skip, raystep, stdout};

/// The slips outside the catalogue that change the image.
const SLIPS: [&str; 8] = [
    "no-tir",
    "specular-times-od",
    "polygon-miss",
    "turn-180",
    "channels-swapped",
    "dim",
    "antialias",
    "jpeg-noise",
];

/// The student's render of `scene` with `slip`, compared: `compare`'s JSON
/// (and with `rays`, the log's JSON with the image's under "image").
fn compared(scene: &str, slip: &str, rays: Option<(u32, u32)>) -> Value {
    compared_at(scene, slip, rays, None)
}

/// `compared` with the image rendered at `size` ("WxH"; the scene's own
/// when `None`).
fn compared_at(scene: &str, slip: &str, rays: Option<(u32, u32)>, size: Option<&str>) -> Value {
    let dir = tempfile::tempdir().unwrap();
    let image = dir.path().join("student.png");
    let image = image.to_str().unwrap();
    let mut tracer = vec![TRACER, scene, "-o", image, "--mistake", slip];
    if let Some(size) = size {
        tracer.extend(["--size", size]);
    }
    run_tracer(&tracer);
    let mut args = vec!["compare", scene, image, "--format", "json"];
    let log = dir.path().join("student.jsonl");
    let log = log.to_str().unwrap();
    if let Some((x, y)) = rays {
        let (x, y) = (x.to_string(), y.to_string());
        let output = run_tracer(&[TRACER, scene, &x, &y, "--mistake", slip]);
        std::fs::write(log, output.stdout).unwrap();
        args.extend(["--rays", log]);
    }
    let output = raystep(&args);
    assert!(output.status.success(), "compare {scene}: {output:?}");
    serde_json::from_str(&stdout(&output)).unwrap()
}

/// The listed mistakes as (name, verdict).
fn named(report: &Value) -> Vec<(String, String)> {
    report["mistakes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| {
            let s = |k: &str| m[k].as_str().unwrap_or("").to_string();
            (s("name"), s("verdict"))
        })
        .collect()
}

/// Every region's diagnosis.
fn diagnoses(report: &Value) -> Vec<String> {
    report["regions"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|r| r["diagnosis"].as_str().map(str::to_string))
        .collect()
}

#[test]
fn no_slip_outside_the_catalogue_is_named_on_any_teaching_scene() {
    if program_or_skip("python3").is_none() {
        return;
    }
    // At 80 x 60, a quarter of the pixels: the verdicts are those of the
    // scenes' own 160 x 120 (checked by hand, issue 39), in a quarter of
    // the time.
    for scene in TEACHING_SCENES {
        for slip in SLIPS {
            let report = compared_at(scene, slip, None, Some("80x60"));
            for (name, verdict) in named(&report) {
                // Half a turn of a scene symmetric left to right is exactly
                // the image upside down: flipped-y's render reproduces it.
                let true_claim = slip == "turn-180" && name == "flipped-y" && verdict == "is";
                assert!(
                    verdict == "superseded" || true_claim,
                    "{scene} {slip}: {name} {verdict}: {:#}",
                    report["mistakes"]
                );
            }
            for d in diagnoses(&report) {
                let wrong = raystep_model::mistakes::Mistake::ALL.iter().any(|m| {
                    d.starts_with(&format!("{m} "))
                        && !(slip == "turn-180" && *m == raystep_model::mistakes::Mistake::FlippedY)
                });
                assert!(!wrong, "{scene} {slip}: a region named {d}");
            }
        }
    }
}

#[test]
fn a_missing_tir_test_is_a_ray_that_missed_not_eta_inverted() {
    if program_or_skip("python3").is_none() {
        return;
    }
    let report = compared("scenes/prism.toml", "no-tir", None);
    assert_eq!(
        named(&report),
        [("eta-inverted".into(), "superseded".into())]
    );
    let by = report["mistakes"][0]["superseded_by"].as_str().unwrap();
    assert!(by.contains("totally internally reflected ray"), "{by}");
    let first = &diagnoses(&report)[0];
    assert!(first.contains("no TIR test?"), "{first}");
    assert!(first.ends_with("a ray missed, not a term"), "{first}");
}

#[test]
fn an_anti_aliased_edge_is_too_thin_to_tell_not_a_missed_ray() {
    if program_or_skip("python3").is_none() {
        return;
    }
    // The student's 2 x 2 supersampling of prism.toml softens the prism's
    // left and right silhouettes: columns x = 35 and x = 124, one pixel
    // wide and 25 tall. Seen as a region they fit "your transmitted ray
    // missed" at 12 of 13 samples, which would send the student to correct
    // refraction code; a line at most 2 pixels wide is too thin to tell.
    let report = compared("scenes/prism.toml", "antialias", None);
    let all = diagnoses(&report);
    assert!(all.iter().all(|d| !d.contains("missed")), "{all:#?}");
    let thin = all
        .iter()
        .filter(|d| d.starts_with("too thin to tell"))
        .count();
    assert!(thin >= 2, "{all:#?}");
}

#[test]
fn a_missed_polygon_is_a_primary_ray_that_missed_not_a_term() {
    if program_or_skip("python3").is_none() {
        return;
    }
    for (scene, object) in [
        ("scenes/prism.toml", "prism front"),
        ("scenes/polygons.toml", "triangle"),
    ] {
        let report = compared(scene, "polygon-miss", None);
        let told = diagnoses(&report);
        assert!(
            told[0].starts_with("your primary ray missed") && told[0].contains(object),
            "{scene}: {told:?}"
        );
        assert!(
            !told.iter().any(|d| d.starts_with("yours ≈")),
            "{scene}: {told:?}"
        );
    }
}

#[test]
fn half_a_turn_supersedes_flipped_y() {
    if program_or_skip("python3").is_none() {
        return;
    }
    let report = compared("scenes/highlights.toml", "turn-180", None);
    assert_eq!(report["geometry"]["flip"], "both");
    let flipped = &report["mistakes"][0];
    assert_eq!(flipped["name"], "flipped-y");
    assert_eq!(flipped["verdict"], "superseded");
    let by = flipped["superseded_by"].as_str().unwrap();
    assert!(
        by.starts_with("the geometry differs") && by.contains("half a turn"),
        "{by}"
    );
}

#[test]
fn a_highlight_times_the_colour_is_not_phong_not_blinn() {
    if program_or_skip("python3").is_none() {
        return;
    }
    let report = compared("scenes/highlights.toml", "specular-times-od", None);
    assert_eq!(
        named(&report),
        Vec::<(String, String)>::new(),
        "{:#}",
        report["mistakes"]
    );
}

#[test]
fn what_the_image_shows_outside_the_catalogue_is_said() {
    if program_or_skip("python3").is_none() {
        return;
    }
    for (scene, slip, kind, words) in [
        (
            "scenes/glass.toml",
            "channels-swapped",
            "channels-swapped",
            "B, G, R",
        ),
        (
            "scenes/highlights.toml",
            "dim",
            "constant-factor",
            "times 0.80",
        ),
        (
            "scenes/two-lights.toml",
            "jpeg-noise",
            "noise",
            "compression",
        ),
    ] {
        let report = compared(scene, slip, None);
        assert_eq!(
            report["shows"]["kind"], kind,
            "{scene} {slip}: {:#}",
            report["shows"]
        );
        let said = report["shows"]["words"].as_str().unwrap();
        assert!(said.contains(words), "{scene} {slip}: {said}");
        for (name, verdict) in named(&report) {
            assert_eq!(verdict, "superseded", "{scene} {slip}: {name}");
        }
    }
}

#[test]
fn the_student_tracers_anti_aliasing_matches() {
    // whitted.py's 2 x 2 rays a pixel, averaged, on polygons.toml: on main
    // it differed, and what the image shows was "differences only along
    // edges ... anti-aliased?". Another tracer's anti-aliasing (its own
    // rounding, colours clamped before averaging) is a match now (issue
    // 40), and the report says it is anti-aliased.
    if program_or_skip("python3").is_none() {
        return;
    }
    let report = compared("scenes/polygons.toml", "antialias", None);
    assert_eq!(report["matches"], true, "{:#}", report["metrics"]);
    assert!(report["metrics"]["anti_aliased_pixels"].as_u64().unwrap() > 100);
    assert_eq!(report["shows"], Value::Null);
}

#[test]
fn a_catalogued_slip_that_does_not_reproduce_is_only_looked_like() {
    // whitted.py's t > 0 speckles other pixels than raystep's no-epsilon:
    // it fits 86% but does not reproduce the image, so it is "looks like",
    // with the command that tells the look-alikes apart.
    if program_or_skip("python3").is_none() {
        return;
    }
    let scene = "scenes/glass.toml";
    let report = compared(scene, "no-epsilon", None);
    assert_eq!(
        named(&report)[0],
        ("no-epsilon".into(), "looks_like".into())
    );
    let dir = tempfile::tempdir().unwrap();
    let image = dir.path().join("student.png");
    let image = image.to_str().unwrap();
    run_tracer(&[TRACER, scene, "-o", image, "--mistake", "no-epsilon"]);
    let text = stdout(&raystep(&["compare", scene, image]));
    assert!(text.contains("  looks like no-epsilon"), "{text}");
    assert!(
        text.contains("other bugs give nearly this picture")
            && text.contains(&format!("run `raystep compare {scene} --rays LOG`")),
        "{text}"
    );
}

#[test]
fn with_a_ray_log_the_logs_verdict_supersedes_the_images() {
    // The image alone: eta-inverted superseded by the region's missed ray;
    // with the log of a pixel there, by the log's own first divergence.
    if program_or_skip("python3").is_none() {
        return;
    }
    let scene = "scenes/prism.toml";
    let alone = compared(scene, "no-tir", None);
    let pixel = &alone["regions"][0]["pixel"];
    let at = (
        pixel[0].as_u64().unwrap() as u32,
        pixel[1].as_u64().unwrap() as u32,
    );
    let both = compared(scene, "no-tir", Some(at));
    let image = &both["image"];
    let mistakes = image["mistakes"].as_array().unwrap();
    assert!(!mistakes.is_empty(), "{both:#}");
    for m in mistakes {
        assert_eq!(m["verdict"], "superseded", "{m:#}");
        let by = m["superseded_by"].as_str().unwrap();
        assert!(
            by.starts_with(&format!(
                "your ray log: pixel ({}, {}) first differs at",
                at.0, at.1
            )),
            "{by}"
        );
    }
}
