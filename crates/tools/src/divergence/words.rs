//! The report of `compare --rays`, for people (text) and for graders
//! (JSON, whose keys are a contract: docs/RAYLOG.md).

use std::fmt::Write;

use serde_json::{Value as Json, json as object};

use super::checks::Value;
use super::meaning::{fine, fine3};
use super::pixel_report::{PixelReport, Unpaired};
use super::{CATALOGUE_RAYS, HELD_RAYS, LogComparison, PIXELS_SHOWN};
use crate::raylog::Hit;
use raystep_engine::record::count;

/// The report in words. `image_matches` is whether the image compared
/// beside the log matched, when one was given.
pub fn text(
    comparison: &LogComparison,
    log: &str,
    scene: &str,
    image_matches: Option<bool>,
) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "Your rays ({log}) beside raystep's ({scene}); tolerance: {}.",
        comparison.tolerance
    );
    if let Some(line) = traced_at_text(comparison) {
        out.push_str(&line);
    }
    // What matters first: the pixels whose colour differs from ours, then
    // those whose rays differ where they add nothing, then those that
    // match, each in the log's order (JSON keeps the log's order).
    let mut ranked: Vec<&PixelReport> = comparison.pixels.iter().collect();
    ranked.sort_by_key(|p| (p.matches, p.differs_where_it_adds_nothing()));
    for pixel in ranked {
        out.push('\n');
        pixel_text(&mut out, pixel);
    }
    let more = comparison.pixel_count - comparison.pixels.len();
    out.push('\n');
    let _ = write!(
        out,
        "{} logged ({}), {} matching ours",
        count(comparison.pixel_count as u64, "pixel", "pixels"),
        count(comparison.rays_read as u64, "ray", "rays"),
        comparison.matching
    );
    if comparison.colour_agreeing > 0 {
        let _ = write!(
            out,
            ", {} more whose colour agrees with ours (their rays differ where they add nothing)",
            comparison.colour_agreeing
        );
    }
    if more > 0 {
        let _ = write!(
            out,
            "; the first {PIXELS_SHOWN} are shown, the other {more} only counted"
        );
    }
    out.push_str(".\n");
    let all_match = comparison.matching == comparison.pixel_count;
    if all_match {
        out.push_str(match image_matches {
            Some(false) => {
                "Your rays match ours but your image does not: the difference comes after \
                 tracing, where a colour becomes a byte (clamping, rounding, gamma, byte-wrap), \
                 which no ray log shows (MODEL §6).\n"
            }
            _ => {
                "Every logged ray matches. Mistakes of the bytes (gamma, byte-wrap) act after \
                 tracing and are out of a log's reach: compare your image to check them.\n"
            }
        });
    }
    if comparison.catalogue_stopped {
        let _ = writeln!(
            out,
            "The catalogue stopped: its budget of {CATALOGUE_RAYS} rays of our trees ran out \
             before every mistake was tried at every pixel shown (log fewer or smaller pixels \
             to try them all)."
        );
    }
    if !comparison.unknown_keys.is_empty() {
        let (count, at_least) = comparison.unknown_key_count;
        let more = count.saturating_sub(comparison.unknown_keys.len());
        let more = match (more, at_least) {
            (0, _) => String::new(),
            (n, false) => format!(" and {n} more"),
            (n, true) => format!(" and at least {n} more"),
        };
        let _ = writeln!(
            out,
            "Keys raystep doesn't know, ignored: {}{more}.",
            comparison.unknown_keys.join(", ")
        );
    }
    out
}

/// The size trap named: every primary ray is the centre ray of its pixel
/// in an image of another size.
fn traced_at_text(comparison: &LogComparison) -> Option<String> {
    let (w, h) = comparison.traced_at?;
    Some(format!(
        "Your log looks traced at {w}x{h}: pass --size {w}x{h}. Every primary ray in it is the \
         centre ray of its pixel in a {w}x{h} image (the field of view kept), none in the size \
         it was read at.\n"
    ))
}

fn pixel_text(out: &mut String, pixel: &PixelReport) {
    let (x, y) = pixel.pixel;
    let rays = format!(
        "{} logged, {} in ours, shadow rays included",
        count(
            (pixel.yours.len() + pixel.counted_only.total()) as u64,
            "ray",
            "rays"
        ),
        pixel.rays_ours
    );
    let Some(first) = &pixel.first_divergence else {
        let _ = writeln!(out, "Pixel ({x}, {y}): matches ours ({rays}).");
        for note in &pixel.notes {
            let _ = writeln!(out, "  Note: {note}.");
        }
        return;
    };
    if pixel.differs_where_it_adds_nothing() {
        let _ = writeln!(
            out,
            "Pixel ({x}, {y}): your colour agrees; your rays differ where they add nothing: \
             first at {} {} ({}) ({rays}).",
            first.path,
            first.field,
            first.kind.name()
        );
    } else {
        let _ = writeln!(out, "Pixel ({x}, {y}): differs ({rays}).");
    }
    for note in &pixel.notes {
        let _ = writeln!(out, "  Note: {note}.");
    }
    let _ = writeln!(out, "  First divergence: {} {}", first.path, first.field);
    let _ = writeln!(out, "    yours  {}", value_text(Some(first.yours)));
    let _ = writeln!(out, "    ours   {}", value_text(first.ours));
    if first.words.is_empty() {
        let _ = writeln!(out, "    {}", first.kind.name());
    } else {
        let _ = writeln!(out, "    {}: {}", first.kind.name(), first.words);
    }
    if !first.meaning.is_empty() {
        let _ = writeln!(out, "  What ours is:");
        for line in &first.meaning {
            let _ = writeln!(out, "    {line}");
        }
    }
    if pixel.later_differences > 0 {
        let _ = writeln!(
            out,
            "  {} from the first.",
            count(
                pixel.later_differences as u64,
                "difference after it follows",
                "differences after it follow"
            )
        );
    }
    unpaired_text(
        out,
        "Only in yours",
        &pixel.only_yours,
        pixel.unpaired_total.0,
    );
    counted_text(out, pixel);
    unpaired_text(
        out,
        "Only in ours",
        &pixel.only_ours,
        pixel.unpaired_total.1,
    );
    if pixel.catalogue_stopped {
        let _ = writeln!(
            out,
            "  The catalogue's budget ({CATALOGUE_RAYS} rays of our trees) ran out: not every \
             mistake was tried here."
        );
    }
    for line in consistent_lines(pixel) {
        let _ = writeln!(
            out,
            "  {line} A mistake is named only where its tree is your log at every logged \
             pixel and changes the colour at two of them."
        );
    }
    if pixel.mistakes.is_empty() && pixel.consistent.is_empty() {
        out.push_str("  No mistake of raystep's catalogue gives your rays: the first divergence is where to look.\n");
    } else if !pixel.mistakes.is_empty() {
        let names: Vec<&str> = pixel.mistakes.iter().map(|m| m.name()).collect();
        let _ = writeln!(
            out,
            "  Your rays are raystep's under the catalogue's mistake: {}.",
            names.join(", ")
        );
    }
}

/// "Consistent with X here; log pixel A,B to tell", one line for the
/// mistakes a pixel alone cannot tell from a coincidence.
pub fn consistent_lines(pixel: &PixelReport) -> Vec<String> {
    if pixel.consistent.is_empty() {
        return Vec::new();
    }
    let names: Vec<&str> = pixel.consistent.iter().map(|c| c.mistake.name()).collect();
    let tell = match pixel.consistent[0].tell {
        Some((x, y)) => format!("log pixel {x},{y} to tell"),
        None => "log more pixels to tell".to_string(),
    };
    vec![format!(
        "Consistent with {} here; {tell}.",
        names.join(" or ")
    )]
}

/// Your rays of a pixel counted, not compared one by one (`held`).
fn counted_text(out: &mut String, pixel: &PixelReport) {
    let counted = &pixel.counted_only;
    if counted.deeper > 0 {
        let _ = writeln!(
            out,
            "  and {} deeper, down to depth {}, counted only: ours never casts them \
             (your tracer does not stop at max_depth, MODEL §5)",
            count(counted.deeper as u64, "ray", "rays"),
            counted.deepest
        );
    }
    if counted.over > 0 {
        let _ = writeln!(
            out,
            "  and {} more counted only: past the most our tree of a pixel holds (max_rays, \
             and a shadow ray per light for each, MODEL §5), or past the {HELD_RAYS} rays held \
             over the pixels shown",
            count(counted.over as u64, "ray", "rays"),
        );
    }
}

/// At most this many rays in one tree only are listed per pixel.
const UNPAIRED_SHOWN: usize = 8;

/// `rays`: the first of `total` rays in one tree only.
fn unpaired_text(out: &mut String, title: &str, rays: &[Unpaired], total: usize) {
    if rays.is_empty() {
        return;
    }
    let _ = writeln!(out, "  {title}:");
    for ray in rays.iter().take(UNPAIRED_SHOWN) {
        let _ = writeln!(out, "    {}: {}", ray.path, ray.rule);
    }
    if total > UNPAIRED_SHOWN {
        let _ = writeln!(out, "    and {} more", total - UNPAIRED_SHOWN);
    }
}

/// A logged value as the report writes it.
pub fn value_text(value: Option<Value>) -> String {
    match value {
        None => "(none)".into(),
        Some(Value::Vector(v)) => fine3(v),
        Some(Value::Number(x)) => fine(x),
        Some(Value::Hit(Hit::Object(i))) => format!("object {i}"),
        Some(Value::Hit(Hit::Miss)) => "nothing (a miss)".into(),
        Some(Value::Cast(true)) => "cast".into(),
        Some(Value::Cast(false)) => "not cast".into(),
    }
}

/// A number for JSON: NaN and the infinities, which JSON lacks, as strings.
fn number(x: f64) -> Json {
    if x.is_finite() {
        object!(x)
    } else if x.is_nan() {
        object!("NaN")
    } else if x > 0.0 {
        object!("Infinity")
    } else {
        object!("-Infinity")
    }
}

fn value_json(value: Option<Value>) -> Json {
    match value {
        None => Json::Null,
        Some(Value::Vector(v)) => Json::Array(v.to_array().map(number).to_vec()),
        Some(Value::Number(x)) => number(x),
        Some(Value::Hit(Hit::Object(i))) => object!(i),
        Some(Value::Hit(Hit::Miss)) => Json::Null,
        Some(Value::Cast(cast)) => object!(cast),
    }
}

/// The report as JSON.
pub fn json(comparison: &LogComparison) -> Json {
    let pixels: Vec<Json> = comparison.pixels.iter().map(pixel_json).collect();
    let mut report = object!({
        "pixels": pixels,
        "pixel_count": comparison.pixel_count,
        "matching_pixels": comparison.matching,
        "colour_agreeing_pixels": comparison.colour_agreeing,
        "traced_at": comparison.traced_at.map(|(w, h)| object!([w, h])),
        "rays_read": comparison.rays_read,
        "tolerance": {
            "geometry": comparison.tolerance.geometry,
            "colour": comparison.tolerance.colour,
        },
        "unknown_keys": comparison.unknown_keys,
        "unknown_key_count": comparison.unknown_key_count.0,
    });
    if comparison.catalogue_stopped {
        report["catalogue_stopped"] = object!(true);
    }
    report
}

fn pixel_json(pixel: &PixelReport) -> Json {
    let paths =
        |rays: &[Unpaired]| -> Vec<String> { rays.iter().map(|r| r.path.to_string()).collect() };
    let rules = |rays: &[Unpaired], side: &str| -> Vec<Json> {
        rays.iter()
            .map(|r| object!({"path": r.path.to_string(), "in": side, "rule": r.rule}))
            .collect()
    };
    let first = pixel.first_divergence.as_ref().map_or(Json::Null, |d| {
        object!({
            "path": d.path.to_string(),
            "field": d.field.to_string(),
            "yours": value_json(Some(d.yours)),
            "ours": value_json(d.ours),
            "kind": d.kind.name(),
            "words": d.words,
            "meaning": d.meaning,
        })
    });
    let mistakes: Vec<Json> = pixel
        .mistakes
        .iter()
        .map(|m| object!({"name": m.name()}))
        .collect();
    let consistent: Vec<Json> = pixel
        .consistent
        .iter()
        .map(|c| object!({"name": c.mistake.name(), "tell": c.tell.map(|(x, y)| object!([x, y]))}))
        .collect();
    let mut unpaired = rules(&pixel.only_yours, "yours");
    unpaired.extend(rules(&pixel.only_ours, "ours"));
    let mut report = object!({
        "pixel": [pixel.pixel.0, pixel.pixel.1],
        "matches": pixel.matches,
        "first_divergence": first,
        "later_differences": pixel.later_differences,
        "only_yours": paths(&pixel.only_yours),
        "only_ours": paths(&pixel.only_ours),
        "unpaired": unpaired,
        "mistakes": mistakes,
        "consistent_with": consistent,
        "colour_agrees": pixel.colour_agrees,
        "notes": pixel.notes,
        "rays_yours": pixel.yours.len() + pixel.counted_only.total(),
        "rays_ours": pixel.rays_ours,
    });
    // Only when something was counted or left untried: a log within the
    // bounds reads as it always did.
    let counted = &pixel.counted_only;
    if counted.total() > 0 {
        report["counted_only"] = object!({
            "deeper": counted.deeper,
            "deepest": counted.deepest,
            "over": counted.over,
        });
    }
    // Only when the lists stop short (`UNPAIRED_KEPT`): how many rays of
    // each side they leave out.
    let left_out = (
        pixel.unpaired_total.0 - pixel.only_yours.len(),
        pixel.unpaired_total.1 - pixel.only_ours.len(),
    );
    if left_out != (0, 0) {
        report["unpaired_not_listed"] = object!({
            "yours": left_out.0,
            "ours": left_out.1,
        });
    }
    if pixel.catalogue_stopped {
        report["catalogue_stopped"] = object!(true);
    }
    report
}
