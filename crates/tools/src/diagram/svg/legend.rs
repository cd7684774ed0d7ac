//! The ray diagram's legend: a sample of each kind of mark and its meaning,
//! in rows across the band below the figure.

use std::fmt::Write;

use super::escaping::escape;
use super::{FACES_AWAY, HEIGHT, LEGEND, MARGIN, PASSED, WIDTH, stroke_colour};
use crate::diagram::{LegendRow, Stroke};

/// The legend's text size, and its width a character (0.6 em, the
/// estimate the labels use).
const SIZE: f64 = 11.0;
const CHAR: f64 = SIZE * 0.6;

/// Writes the legend's `rows` (the assembly says which the figure holds).
pub(crate) fn write(out: &mut String, rows: &[LegendRow]) {
    let line = |stroke: Stroke, dash: &str| {
        format!(
            "<line x1=\"0\" y1=\"0\" x2=\"20\" y2=\"0\" stroke=\"{}\" stroke-width=\"2\"{dash}/>",
            stroke_colour(stroke)
        )
    };
    let dashed = " stroke-dasharray=\"6 4\"";
    let items: Vec<(String, &str)> = (rows.iter())
        .map(|row| match row {
            LegendRow::Primary => (line(Stroke::Primary, ""), "primary"),
            LegendRow::Reflected => (line(Stroke::Reflected, ""), "reflected"),
            LegendRow::Transmitted => (line(Stroke::Transmitted, ""), "transmitted"),
            LegendRow::ShadowLit => (line(Stroke::ShadowLit, dashed), "shadow ray, lit"),
            LegendRow::ShadowBlocked => (
                line(Stroke::ShadowBlocked, dashed),
                "shadow ray, blocked (× at the blocker)",
            ),
            LegendRow::ShadowPartial => (
                line(Stroke::ShadowPartial, dashed),
                "shadow ray, partly blocked (0 < S < 1)",
            ),
            LegendRow::Normal => (line(Stroke::Normal, ""), "normal N"),
            LegendRow::Hit => (
                "<circle cx=\"10\" cy=\"0\" r=\"3\" fill=\"black\"/>".to_string(),
                "hit",
            ),
            LegendRow::PassedBy => (
                format!("<circle cx=\"10\" cy=\"0\" r=\"6\" fill=\"none\" stroke=\"{PASSED}\" stroke-width=\"2\"/>"),
                "passed by: ray crosses a polygon's plane, or comes nearest a sphere",
            ),
            LegendRow::FacesAway => (
                format!("<line x1=\"0\" y1=\"0\" x2=\"20\" y2=\"0\" stroke=\"{FACES_AWAY}\" stroke-width=\"2\" stroke-dasharray=\"2 4\"/>"),
                "light facing away (no shadow ray)",
            ),
        })
        .collect();
    let items: Vec<(&str, &str)> = items.iter().map(|(m, n)| (m.as_str(), *n)).collect();
    write_rows(out, &items, HEIGHT - LEGEND + 14.0);
}

/// Each (mark, meaning) pair left to right from the margin at height `y`,
/// a new row when one is full; a mark is drawn in a 20-unit box at its
/// row's middle height.
pub(crate) fn write_rows(out: &mut String, items: &[(&str, &str)], y: f64) {
    let (mut x, mut y) = (MARGIN, y);
    for (mark, name) in items {
        let width = 24.0 + name.chars().count() as f64 * CHAR;
        if x + width > WIDTH - 10.0 {
            (x, y) = (MARGIN, y + 18.0);
        }
        let _ = writeln!(
            out,
            "<g transform=\"translate({x:.1} {y:.1})\">{mark}</g>\n<text x=\"{:.1}\" y=\"{:.1}\" font-size=\"{SIZE}\">{name}</text>",
            x + 24.0,
            y + 4.0,
            name = escape(name)
        );
        x += width + 16.0;
    }
}
