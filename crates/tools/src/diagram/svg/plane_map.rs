//! The figure's map of the diagram's plane: the uniform mapping from the
//! plane to the figure (fitted, then magnified), and objects' outlines
//! drawn, laid out for label placement and labelled in it.

use std::fmt::Write;

use glam::DVec2;

use super::frame_geometry::clip;
use super::{FRAME, HEIGHT, MARGIN, WIDTH};
use crate::diagram::{Outline, magnified_centre};

/// The mapping from the plane to the figure: uniform scale, y up.
pub(super) struct PlaneMap {
    pub(super) centre: DVec2,
    pub(super) scale: f64,
}

impl PlaneMap {
    pub(super) fn fit(points: &[DVec2]) -> PlaneMap {
        let finite: Vec<DVec2> = points.iter().copied().filter(|p| p.is_finite()).collect();
        let min = finite.iter().fold(DVec2::INFINITY, |a, &p| a.min(p));
        let max = finite.iter().fold(DVec2::NEG_INFINITY, |a, &p| a.max(p));
        let (min, max) = if finite.is_empty() {
            (DVec2::splat(-1.0), DVec2::splat(1.0))
        } else {
            (min, max)
        };
        let size = (max - min).max(DVec2::splat(1e-3));
        let room = FRAME.1 - FRAME.0 - DVec2::splat(2.0 * MARGIN);
        PlaneMap {
            centre: (min + max) / 2.0,
            scale: (room.x / size.x).min(room.y / size.y),
        }
    }

    /// Magnified `zoom` times about `focus`, which moves toward the middle
    /// as it grows (its offset from the middle divided by `zoom`): kept in
    /// place, a hit near the edge would leave the figure on the first zoom.
    pub(super) fn zoomed(self, zoom: f64, focus: DVec2) -> PlaneMap {
        PlaneMap {
            centre: magnified_centre(self.centre, focus, zoom),
            scale: self.scale * zoom.max(1.0),
        }
    }

    pub(super) fn to_figure(&self, p: DVec2) -> DVec2 {
        let middle = (FRAME.0 + FRAME.1) / 2.0;
        let v = (p - self.centre) * self.scale;
        DVec2::new(middle.x + v.x, middle.y - v.y)
    }
}

pub(super) fn write_outline(out: &mut String, map: &PlaneMap, outline: &Outline) {
    let style = "fill=\"none\" stroke=\"#999999\" stroke-width=\"1.5\"";
    match outline {
        Outline::Circle { center, radius } => {
            let c = map.to_figure(*center);
            let _ = writeln!(
                out,
                "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"{:.1}\" {style}/>",
                c.x,
                c.y,
                radius * map.scale
            );
        }
        Outline::Polyline(points) => {
            let list: Vec<String> = points
                .iter()
                .map(|&p| map.to_figure(p))
                .map(|p| format!("{:.1},{:.1}", p.x, p.y))
                .collect();
            let _ = writeln!(out, "<polyline points=\"{}\" {style}/>", list.join(" "));
        }
        Outline::Line { normal, c } => {
            let (a, b) = line_ends(*normal, *c, map);
            let _ = writeln!(
                out,
                "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" {style}/>",
                a.x, a.y, b.x, b.y
            );
        }
    }
}

/// An outline as straight pieces in the figure, for keeping labels off it:
/// a circle as a 24-gon, an infinite line across the figure.
pub(super) fn outline_segments(outline: &Outline, map: &PlaneMap) -> Vec<(DVec2, DVec2)> {
    let points: Vec<DVec2> = match outline {
        Outline::Circle { center, radius } => (0..=24)
            .map(|i| {
                let angle = std::f64::consts::TAU * i as f64 / 24.0;
                map.to_figure(*center + DVec2::from_angle(angle) * *radius)
            })
            .collect(),
        Outline::Polyline(points) => points.iter().map(|&p| map.to_figure(p)).collect(),
        Outline::Line { normal, c } => {
            let (a, b) = line_ends(*normal, *c, map);
            vec![a, b]
        }
    };
    points.windows(2).map(|w| (w[0], w[1])).collect()
}

/// Where an object's name goes: beside its outline; for a plane's line,
/// at `hit` (where a ray meets it in the frame) if given, else just inside
/// where the line enters the frame.
pub(super) fn label_anchor(outline: &Outline, map: &PlaneMap, hit: Option<DVec2>) -> Option<DVec2> {
    match outline {
        Outline::Circle { center, radius } => {
            Some(map.to_figure(*center + DVec2::new(radius * 0.7, radius * 0.7)))
        }
        Outline::Polyline(points) => {
            let sum = points.iter().fold(DVec2::ZERO, |a, &p| a + p);
            (!points.is_empty()).then(|| map.to_figure(sum / points.len() as f64))
        }
        Outline::Line { normal, c } => hit.or_else(|| {
            let (a, b) = line_ends(*normal, *c, map);
            let (enter, leave) = clip(a, b, FRAME)?;
            // 40 units in along the line (or halfway, for a short cut), so
            // the name has room on either side.
            let inward = (leave - enter).clamp_length_max(40.0);
            let step = if (leave - enter).length() < 80.0 {
                (leave - enter) / 2.0
            } else {
                inward
            };
            Some(enter + step)
        }),
    }
}

/// The line a·x + c = 0 as two ends beyond the figure: the point nearest
/// the map's centre, then far both ways along the line.
fn line_ends(normal: DVec2, c: f64, map: &PlaneMap) -> (DVec2, DVec2) {
    let n = normal / normal.length_squared();
    let foot = map.centre - n * (normal.dot(map.centre) + c);
    let along = normal.perp().normalize() * (WIDTH + HEIGHT) / map.scale;
    (map.to_figure(foot - along), map.to_figure(foot + along))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plane_is_named_at_its_hit_or_where_it_enters_the_frame() {
        // Unit scale about the origin: the plane's point (0, 0) maps to the
        // frame's middle (400, 293). The line y = 0 runs across the frame
        // at y 293, entering from the right edge x 794 (line_ends runs
        // along perp((0, 1)) = (-1, 0) from +x); 40 units in: (754, 293).
        let map = PlaneMap {
            centre: DVec2::ZERO,
            scale: 1.0,
        };
        let line = Outline::Line {
            normal: DVec2::new(0.0, 1.0),
            c: 0.0,
        };
        let at = label_anchor(&line, &map, None).unwrap();
        assert!((at - DVec2::new(754.0, 293.0)).length() < 1e-9, "{at}");
        let hit = DVec2::new(500.0, 293.0);
        assert_eq!(label_anchor(&line, &map, Some(hit)), Some(hit));
        // The line y = 1000 lies off the frame: no name.
        let off = Outline::Line {
            normal: DVec2::new(0.0, 1.0),
            c: -1000.0,
        };
        assert_eq!(label_anchor(&off, &map, None), None);
    }
}
