//! The crossing test laid out whole, for the recording and the figure: the
//! projected polygon moved so the hit point is the origin (as the lecture
//! draws it) and, per edge, whether and where it crosses the +U axis.
//! Computed only when recording; the tracer's `count_crossings` stays lean.

use glam::{DVec2, DVec3};
use serde::Serialize;

use super::polygon::{Axis, Polygon, crosses, straddles, u_at_axis};

/// The projected polygon around the hit point, and every edge's verdict.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CrossingFigure {
    pub(crate) dropped_axis: Axis,
    /// The hit point projected to (U, V), before the move to the origin.
    pub(crate) point: [f64; 2],
    /// Each vertex in (U, V) minus `point`, in the polygon's order.
    pub vertices: Vec<[f64; 2]>,
    /// Edge i runs from vertex i to vertex i + 1 (the last back to 0).
    pub edges: Vec<EdgeCrossing>,
}

/// One edge of the crossing test (MODEL §3).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct EdgeCrossing {
    pub from: usize,
    pub to: usize,
    /// One end has V >= 0 and the other V < 0: the edge meets the line V = 0.
    pub straddles: bool,
    /// Where it meets V = 0, when it straddles.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub u: Option<f64>,
    /// It crosses the +U half-line (U > 0): one of the counted crossings.
    pub counts: bool,
}

impl CrossingFigure {
    /// How many edges count: the same number as `CrossingTest::crossings`.
    pub fn crossings(&self) -> usize {
        self.edges.iter().filter(|e| e.counts).count()
    }

    pub fn inside(&self) -> bool {
        self.crossings() % 2 == 1
    }

    /// The (U, V) coordinate names: "dropped z: U = x, V = y".
    pub fn axes(&self) -> (&'static str, &'static str, &'static str) {
        match self.dropped_axis {
            Axis::X => ("x", "y", "z"),
            Axis::Y => ("y", "x", "z"),
            Axis::Z => ("z", "x", "y"),
        }
    }
}

impl Polygon {
    /// The crossing test for `point` (on the polygon's plane), edge by edge.
    /// Each edge's verdict is `crosses`, the tracer's own test.
    pub fn crossing_figure(&self, point: DVec3) -> CrossingFigure {
        let p = self.dropped.project(point);
        let moved: Vec<DVec2> = self.projected().map(|v| v - p).collect();
        let n = moved.len();
        let edges = (0..n)
            .map(|i| {
                let (a, b) = (moved[i], moved[(i + 1) % n]);
                let straddles = straddles(a, b);
                EdgeCrossing {
                    from: i,
                    to: (i + 1) % n,
                    straddles,
                    u: straddles.then(|| u_at_axis(a, b)),
                    counts: crosses(a, b),
                }
            })
            .collect();
        CrossingFigure {
            dropped_axis: self.dropped,
            point: [p.x, p.y],
            vertices: moved.iter().map(|v| [v.x, v.y]).collect(),
            edges,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn notch_of_a_u_shape_crosses_two_edges_right_of_the_point() {
        // The "U" of polygon.rs's tests, point (1.5, 2) in its notch. Drop z.
        // Moved vertices: v0 (-1.5,-2) v1 (1.5,-2) v2 (1.5,1) v3 (0.5,1)
        // v4 (0.5,-1) v5 (-0.5,-1) v6 (-0.5,1) v7 (-1.5,1).
        // Straddling V = 0: 1→2 at U = 1.5 (counts), 3→4 at U = 0.5 (counts),
        // 5→6 at U = -0.5 and 7→0 at U = -1.5 (left: do not count). 2: outside.
        let u_shape = Polygon::new(
            [
                [0.0, 0.0],
                [3.0, 0.0],
                [3.0, 3.0],
                [2.0, 3.0],
                [2.0, 1.0],
                [1.0, 1.0],
                [1.0, 3.0],
                [0.0, 3.0],
            ]
            .iter()
            .map(|[x, y]| DVec3::new(*x, *y, 0.0))
            .collect(),
        )
        .unwrap();
        let figure = u_shape.crossing_figure(DVec3::new(1.5, 2.0, 0.0));
        assert_eq!(figure.point, [1.5, 2.0]);
        assert_eq!(figure.vertices[4], [0.5, -1.0]);
        let straddling: Vec<(usize, usize, f64, bool)> = figure
            .edges
            .iter()
            .filter(|e| e.straddles)
            .map(|e| (e.from, e.to, e.u.unwrap(), e.counts))
            .collect();
        assert_eq!(
            straddling,
            [
                (1, 2, 1.5, true),
                (3, 4, 0.5, true),
                (5, 6, -0.5, false),
                (7, 0, -1.5, false)
            ]
        );
        assert_eq!((figure.crossings(), figure.inside()), (2, false));
        assert_eq!(figure.axes(), ("z", "x", "y"));
    }
}
