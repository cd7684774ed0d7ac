//! `raystep diagram --plane crossing`: the lecture's 2-D figure of the
//! crossing test for one polygon. The polygon is projected by dropping an
//! axis and moved so the hit point is the origin; the +U half-line leaves
//! it, each edge it crosses is highlighted and its crossing numbered, and
//! the count's parity is the verdict (MODEL §3).

use std::fmt::Write;

use glam::DVec2;

use super::Caption;
use super::labels::Labels;
use raystep_engine::record::{NodeId, RayTree, count};
use raystep_model::shapes::CrossingFigure;

const WIDTH: f64 = 800.0;
const HEIGHT: f64 = 600.0;
const MARGIN: f64 = 50.0;
/// The title's band at the top and the legend's at the bottom.
const TOP: f64 = 70.0;
const BOTTOM: f64 = 40.0;

const RAY: &str = "#0077bb";
const COUNTS: &str = "#ee7733";
const LEFT: &str = "#999999";

/// The polygon the figure is about, and how the ray met it.
pub struct Subject<'a> {
    pub(crate) object: &'a str,
    pub(crate) object_index: usize,
    pub(crate) node: NodeId,
    /// True for a hit, false for a polygon the ray passed by.
    pub(crate) hit: bool,
    pub(crate) figure: &'a CrossingFigure,
}

/// The first polygon or patch hit in the tree, in event order; failing
/// that, the first one a ray passed by (a near miss); else none.
pub fn subject(tree: &RayTree) -> Option<Subject<'_>> {
    let hit = tree.events.iter().find_map(|event| {
        let hit = tree.nodes[event.node].hit.as_ref()?;
        let figure = hit.crossing_figure.as_ref()?;
        matches!(event.kind, raystep_engine::record::EventKind::Hit { .. }).then_some(Subject {
            object: &hit.object,
            object_index: hit.object_index,
            node: event.node,
            hit: true,
            figure,
        })
    });
    hit.or_else(|| {
        tree.nodes.iter().enumerate().find_map(|(node, n)| {
            n.near_misses.iter().find_map(|near| {
                Some(Subject {
                    object: &near.object,
                    object_index: near.object_index,
                    node,
                    hit: false,
                    figure: near.crossing_figure.as_ref()?,
                })
            })
        })
    })
}

/// The figure of `subject`'s crossing test, for pixel `pixel`.
pub fn svg(pixel: (u32, u32), subject: &Subject, caption: &Caption) -> String {
    let figure = subject.figure;
    let vertices: Vec<DVec2> = figure.vertices.iter().map(|v| DVec2::from(*v)).collect();
    let map = UvMap::fit(&vertices);
    let (dropped, u, v) = figure.axes();
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{HEIGHT}\" \
         viewBox=\"0 0 {WIDTH} {HEIGHT}\" font-family=\"Helvetica, Arial, sans-serif\" \
         font-size=\"13\">\n"
    );
    let met = if subject.hit { "hit by" } else { "passed by" };
    let ray = match subject.node {
        0 => "the primary ray".to_string(),
        n => format!("ray #{n}"),
    };
    let view = format!(
        "the crossing test of {} (#{}), {met} {ray}",
        subject.object, subject.object_index
    );
    let (title, heading) = caption.elements(pixel, &view, (MARGIN, 26.0));
    out.push_str(&title);
    out.push_str("<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");
    out.push_str(&heading);
    // Passed by, the ray meets the polygon's plane but not the polygon.
    let point = if subject.hit {
        "hit point"
    } else {
        "plane point"
    };
    let _ = writeln!(
        out,
        "<text x=\"{MARGIN}\" y=\"46\">dropped {dropped}: U = {u}, V = {v}; the {point} moved to the origin</text>"
    );
    // Marks first, then the labels around them, none over another or a
    // mark, all between the title and the legend.
    let bounds = (
        DVec2::new(4.0, 52.0),
        DVec2::new(WIDTH - 4.0, HEIGHT - BOTTOM - 4.0),
    );
    let mut labels = Labels::new(13.0, bounds);
    // The polygon's fill first: the +U half-line must show inside it.
    write_polygon(&mut out, &map, figure, &vertices);
    // Its edges kept clear: "2: edge 5→6" sat across edge 5→6.
    let corners: Vec<DVec2> = vertices.iter().map(|p| map.to_figure(*p)).collect();
    for (i, a) in corners.iter().enumerate() {
        labels.reserve_outline(*a, corners[(i + 1) % corners.len()], subject.object_index);
    }
    write_axes(&mut out, &map, u, v, &mut labels);
    let o = map.to_figure(DVec2::ZERO);
    labels.reserve(o, 4.5);
    write_crossings(&mut out, &map, figure, &mut labels);
    let _ = writeln!(
        out,
        "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"4.5\" fill=\"black\"/>",
        o.x, o.y
    );
    labels.place_centred(&mut out, o + DVec2::new(0.0, 20.0), point, "");
    write_vertex_numbers(&mut out, &map, &vertices, &mut labels);
    let n = figure.crossings();
    let verdict = if figure.inside() {
        "odd, inside"
    } else {
        "even, outside"
    };
    // On its own row: its box (y 49..67) lies between the subtitle's
    // (ending at 49) and the V axis name's (from TOP + 10 - 13 = 67).
    let _ = writeln!(
        out,
        "<text x=\"{:.1}\" y=\"64\" font-size=\"15\" font-weight=\"bold\" text-anchor=\"end\">{}: {verdict}</text>",
        WIDTH - MARGIN,
        count(n as u64, "crossing", "crossings")
    );
    write_legend(&mut out);
    out.push_str("</svg>\n");
    out
}

/// The U and V axes through the hit point, and the +U half-line as the ray.
fn write_axes(out: &mut String, map: &UvMap, u: &str, v: &str, labels: &mut Labels) {
    let o = map.to_figure(DVec2::ZERO);
    let (left, right) = (MARGIN / 2.0, WIDTH - MARGIN / 2.0);
    let (top, bottom) = (TOP, HEIGHT - BOTTOM - 10.0);
    let _ = writeln!(
        out,
        "<line x1=\"{left:.1}\" y1=\"{:.1}\" x2=\"{right:.1}\" y2=\"{:.1}\" stroke=\"#cccccc\"/>",
        o.y, o.y
    );
    let _ = writeln!(
        out,
        "<line x1=\"{:.1}\" y1=\"{top:.1}\" x2=\"{:.1}\" y2=\"{bottom:.1}\" stroke=\"#cccccc\"/>",
        o.x, o.x
    );
    let _ = writeln!(
        out,
        "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\" fill=\"#666666\">U = {u}</text>",
        right,
        o.y + 18.0
    );
    let _ = writeln!(
        out,
        "<text x=\"{:.1}\" y=\"{:.1}\" fill=\"#666666\">V = {v}</text>",
        o.x + 6.0,
        top + 10.0
    );
    let v_name = format!("V = {v}");
    labels.reserve_text(DVec2::new(o.x + 6.0, top + 10.0), &v_name);
    // U's name ends at the right edge (text-anchor end): 0.6 em a character.
    let u_name = format!("U = {u}");
    let u_width = u_name.chars().count() as f64 * 13.0 * 0.6;
    labels.reserve_text(DVec2::new(right - u_width, o.y + 18.0), &u_name);
    // The +U half-line, with an arrow head at the figure's edge.
    let end = right - 40.0;
    let _ = writeln!(
        out,
        "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{end:.1}\" y2=\"{:.1}\" stroke=\"{RAY}\" stroke-width=\"2.5\"/>",
        o.x, o.y, o.y
    );
    let _ = writeln!(
        out,
        "<path d=\"M{:.1} {:.1}l-10 -5v10z\" fill=\"{RAY}\"/>",
        end + 4.0,
        o.y
    );
}

/// The polygon, and its counted edges highlighted.
fn write_polygon(out: &mut String, map: &UvMap, figure: &CrossingFigure, vertices: &[DVec2]) {
    let points: Vec<String> = vertices
        .iter()
        .map(|p| map.to_figure(*p))
        .map(|p| format!("{:.1},{:.1}", p.x, p.y))
        .collect();
    let _ = writeln!(
        out,
        "<polygon points=\"{}\" fill=\"#f4ecd8\" stroke=\"#777777\" stroke-width=\"1.5\"/>",
        points.join(" ")
    );
    for edge in figure.edges.iter().filter(|e| e.counts) {
        let (a, b) = (
            map.to_figure(vertices[edge.from]),
            map.to_figure(vertices[edge.to]),
        );
        let _ = writeln!(
            out,
            "<line class=\"counted-edge\" x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"{COUNTS}\" stroke-width=\"4\"/>",
            a.x, a.y, b.x, b.y
        );
    }
}

/// Each vertex's number just outside its corner, away from the centroid.
fn write_vertex_numbers(out: &mut String, map: &UvMap, vertices: &[DVec2], labels: &mut Labels) {
    labels.set_font_size(11.0);
    let centre = vertices.iter().fold(DVec2::ZERO, |a, p| a + *p) / vertices.len() as f64;
    for (i, p) in vertices.iter().enumerate() {
        let out_by = (*p - centre).normalize_or_zero() * 14.0;
        let at = map.to_figure(*p) + DVec2::new(out_by.x, -out_by.y);
        let text = i.to_string();
        labels.place_centred(out, at, &text, "font-size=\"11\" fill=\"#555555\"");
    }
}

/// Each edge meeting V = 0: numbered on +U when it counts, hollow when left.
fn write_crossings(out: &mut String, map: &UvMap, figure: &CrossingFigure, labels: &mut Labels) {
    let marks: Vec<(DVec2, bool, usize, usize)> = figure
        .edges
        .iter()
        .filter(|e| e.straddles)
        .filter_map(|e| Some((map.to_figure(DVec2::new(e.u?, 0.0)), e.counts, e.from, e.to)))
        .collect();
    for (p, counts, ..) in &marks {
        labels.reserve(*p, 6.0);
        let _ = if *counts {
            writeln!(
                out,
                "<circle class=\"crossing\" cx=\"{:.1}\" cy=\"{:.1}\" r=\"6\" fill=\"{COUNTS}\" stroke=\"black\"/>",
                p.x, p.y
            )
        } else {
            writeln!(
                out,
                "<circle class=\"left-crossing\" cx=\"{:.1}\" cy=\"{:.1}\" r=\"5\" fill=\"white\" stroke=\"{LEFT}\" stroke-width=\"2\"/>",
                p.x, p.y
            )
        };
    }
    let counted = marks.iter().filter(|m| m.1);
    for (number, (p, _, from, to)) in (1..).zip(counted) {
        // Alternate above and below the axis so close crossings stay legible.
        let dy = if number % 2 == 1 { -16.0 } else { 20.0 };
        let text = format!("{number}: edge {from}→{to}");
        labels.place_centred(out, *p + DVec2::new(0.0, dy), &text, "font-weight=\"bold\"");
    }
}

fn write_legend(out: &mut String) {
    let items: [(&str, &str); 4] = [
        (
            "<line x1=\"0\" y1=\"0\" x2=\"20\" y2=\"0\" stroke=\"#0077bb\" stroke-width=\"2.5\"/>",
            "the +U half-line",
        ),
        (
            "<line x1=\"0\" y1=\"0\" x2=\"20\" y2=\"0\" stroke=\"#ee7733\" stroke-width=\"4\"/>",
            "an edge that counts",
        ),
        (
            "<circle cx=\"10\" cy=\"0\" r=\"6\" fill=\"#ee7733\" stroke=\"black\"/>",
            "a crossing of +U, numbered",
        ),
        (
            "<circle cx=\"10\" cy=\"0\" r=\"5\" fill=\"white\" stroke=\"#999999\" stroke-width=\"2\"/>",
            "meets V = 0 left of the point: not counted",
        ),
    ];
    super::legend::write_rows(out, &items, HEIGHT - BOTTOM + 10.0);
}

/// From (U, V) to the figure: uniform scale, V up, the origin kept in map.
struct UvMap {
    centre: DVec2,
    scale: f64,
}

impl UvMap {
    fn fit(vertices: &[DVec2]) -> UvMap {
        let (min, max) = vertices
            .iter()
            .fold((DVec2::ZERO, DVec2::ZERO), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        let size = (max - min).max(DVec2::splat(1e-9));
        // Room on the right for the half-line to leave the polygon.
        let room = DVec2::new(WIDTH - 2.0 * MARGIN - 80.0, HEIGHT - TOP - BOTTOM - 60.0);
        UvMap {
            centre: (min + max) / 2.0,
            scale: (room.x / size.x).min(room.y / size.y),
        }
    }

    fn to_figure(&self, p: DVec2) -> DVec2 {
        let middle = DVec2::new(
            WIDTH / 2.0 - 40.0,
            TOP + 30.0 + (HEIGHT - TOP - BOTTOM - 60.0) / 2.0,
        );
        let v = (p - self.centre) * self.scale;
        DVec2::new(middle.x + v.x, middle.y - v.y)
    }
}
