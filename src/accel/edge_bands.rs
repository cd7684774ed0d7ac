//! The edges of a many-sided polygon sorted into horizontal bands of V, so the
//! crossing test looks only at the edges that can straddle the point's V.
//!
//! The crossing test counts an edge only when one end has V >= v and the other
//! V < v, that is when min V < v <= max V. Every such edge of a point in band
//! k (bounds[k] < v <= bounds[k + 1]) has min V < bounds[k + 1] and max V >
//! bounds[k], so listing those edges in band k loses none: the count, and so
//! the lecture's working, is the same as over every edge. A gear face of the
//! SPD has 144 edges; a band holds a handful.

use glam::DVec2;

use crate::shapes::crosses;

/// Polygons with fewer vertices are tested over all their edges.
pub(super) const MIN_VERTICES: usize = 16;
/// About this many edges per band on average.
const EDGES_PER_BAND: usize = 2;
/// Bands per polygon at most, so the lists stay linear in the edges.
const MAX_BANDS: usize = 64;

#[derive(Clone, Debug)]
pub(super) struct EdgeBands {
    /// Band k covers V in (bounds[k], bounds[k + 1]]; bounds[0] is the
    /// polygon's least V and the last its greatest.
    bounds: Vec<f64>,
    /// Bands per unit of V, to find a point's band in one step.
    scale: f64,
    /// Band k's edges are `edges[starts[k]..starts[k + 1]]`.
    starts: Vec<u32>,
    /// Edge i runs from vertex i - 1 (the last for i = 0) to vertex i.
    edges: Vec<u32>,
    /// The polygon's vertices projected to (U, V), which the edges join
    /// (the polygon keeps none; banded polygons are few and large).
    projected: Box<[DVec2]>,
}

impl EdgeBands {
    /// `None` for polygons small enough to test whole, or too large to band.
    pub(crate) fn new(projected: Vec<DVec2>) -> Option<EdgeBands> {
        let n = projected.len();
        if n < MIN_VERTICES {
            return None;
        }
        let (low, high) = projected
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.y), hi.max(p.y))
            });
        let span = high - low;
        if !(span.is_finite() && span > 0.0) {
            return None;
        }
        let count = (n / EDGES_PER_BAND).min(MAX_BANDS);
        let mut bounds: Vec<f64> = (0..count)
            .map(|k| low + span * (k as f64 / count as f64))
            .collect();
        bounds.push(high);
        let mut bands = vec![Vec::new(); count];
        let mut listed = 0;
        for i in 0..n {
            let (a, b) = (projected[(i + n - 1) % n].y, projected[i].y);
            // Bands k with bounds[k + 1] > min V and bounds[k] < max V.
            let first = bounds[1..].partition_point(|&bound| bound <= a.min(b));
            let end = bounds[..count].partition_point(|&bound| bound < a.max(b));
            for band in &mut bands[first..end.max(first)] {
                band.push(i as u32);
            }
            listed += end.saturating_sub(first);
        }
        // A zigzag whose every edge spans most bands gains nothing from them.
        if listed > n * MAX_BANDS / 4 {
            return None;
        }
        let mut starts = Vec::with_capacity(count + 1);
        let mut edges = Vec::with_capacity(listed);
        for band in bands {
            starts.push(edges.len() as u32);
            edges.extend(band);
        }
        starts.push(edges.len() as u32);
        Some(EdgeBands {
            bounds,
            scale: count as f64 / span,
            starts,
            edges,
            projected: projected.into_boxed_slice(),
        })
    }

    /// The edges that may straddle V = v, in increasing order; none when v
    /// lies outside the polygon's V range (or is NaN), where no edge does.
    pub(crate) fn edges_near(&self, v: f64) -> &[u32] {
        let last = self.bounds.len() - 2;
        if !(v > self.bounds[0] && v <= self.bounds[last + 1]) {
            return &[];
        }
        // The estimate may be one band off by rounding; the bounds decide.
        let mut k = (((v - self.bounds[0]) * self.scale) as usize).min(last);
        while v <= self.bounds[k] {
            k -= 1;
        }
        while v > self.bounds[k + 1] {
            k += 1;
        }
        &self.edges[self.starts[k] as usize..self.starts[k + 1] as usize]
    }

    /// `shapes::count_crossings(projected, p)`, the crossing test's count,
    /// from the edges near p's V only.
    pub(crate) fn crossings(&self, p: DVec2) -> u32 {
        let projected = &self.projected;
        let n = projected.len();
        let edge_crosses = |i: usize| {
            let a = projected[(i + n - 1) % n] - p;
            u32::from(crosses(a, projected[i] - p))
        };
        self.edges_near(p.y)
            .iter()
            .map(|&edge| edge_crosses(edge as usize))
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::shapes::{Axis, Polygon};

    /// A star of `n` points around the origin, radii alternating 1 and 0.4.
    fn star(n: usize) -> Vec<DVec2> {
        (0..n)
            .map(|i| {
                let angle = i as f64 * std::f64::consts::TAU / n as f64;
                let r = if i % 2 == 0 { 1.0 } else { 0.4 };
                DVec2::new(r * angle.cos(), r * angle.sin())
            })
            .collect()
    }

    /// The edges a crossing test at V = v counts from, by the definition.
    fn straddling(projected: &[DVec2], v: f64) -> Vec<u32> {
        let n = projected.len();
        (0..n as u32)
            .filter(|&i| {
                let a = projected[(i as usize + n - 1) % n].y;
                let b = projected[i as usize].y;
                (a - v >= 0.0) != (b - v >= 0.0)
            })
            .collect()
    }

    #[test]
    fn small_polygons_have_no_bands() {
        assert!(EdgeBands::new(star(MIN_VERTICES - 1)).is_none());
        assert!(EdgeBands::new(star(MIN_VERTICES)).is_some());
    }

    #[test]
    fn a_band_holds_every_straddling_edge_and_few_others() {
        let points = star(144);
        let bands = EdgeBands::new(points.clone()).unwrap();
        // Probe every vertex's V (where ties decide), the band bounds, values
        // just beside them and a fine sweep, across and beyond the range.
        let mut probes: Vec<f64> = points.iter().map(|p| p.y).collect();
        probes.extend(&bands.bounds);
        for v in probes.clone() {
            probes.extend([v.next_up(), v.next_down()]);
        }
        probes.extend((0..=2000).map(|i| -1.2 + 2.4 * i as f64 / 2000.0));
        probes.push(f64::NAN);
        let mut listed = 0;
        for &v in &probes {
            let near = bands.edges_near(v);
            for edge in straddling(&points, v) {
                assert!(near.contains(&edge), "v = {v:e}: edge {edge} missing");
            }
            listed += near.len();
        }
        // 144 edges in 64 bands. The star's spikes are long (each edge spans
        // several bands, and a line across the star meets up to ~20 edges),
        // yet a probe looks at under a quarter of the edges.
        let mean = listed as f64 / probes.len() as f64;
        assert!(mean < 36.0, "{mean} edges per probe");
    }

    #[test]
    fn outside_the_range_no_edge_is_listed() {
        let bands = EdgeBands::new(star(32)).unwrap();
        // The star's least V is the vertex at angle 270 degrees, the greatest at 90.
        let (low, high) = (bands.bounds[0], *bands.bounds.last().unwrap());
        assert!(bands.edges_near(low).is_empty());
        assert!(bands.edges_near(high.next_up()).is_empty());
        assert!(!bands.edges_near(high).is_empty());
        assert!(bands.edges_near(f64::NAN).is_empty());
    }

    #[test]
    fn many_sided_polygon_counts_as_if_every_edge_were_tested() {
        // A gear outline like the SPD's: 36 teeth, 144 vertices, concave.
        let vertices: Vec<DVec3> = (0..144)
            .map(|i| {
                let angle = (i / 2) as f64 * std::f64::consts::TAU / 72.0;
                let r = if (i + 1) % 4 < 2 { 1.0 } else { 0.8 };
                DVec3::new(r * angle.cos(), r * angle.sin(), 0.0)
            })
            .collect();
        let gear = Polygon::new(vertices.clone()).unwrap();
        let bands = EdgeBands::new(gear.projected().collect()).unwrap();
        let banded = |point: DVec3| bands.crossings(Axis::Z.project(point));
        // The centre: one crossing to its right (the rim at U = 1 or 0.8): inside.
        assert_eq!(banded(DVec3::ZERO), 1);
        // Left of everything on V = 0.1: both sides of the rim, outside.
        assert_eq!(banded(DVec3::new(-2.0, 0.1, 0.0)), 2);
        // A sweep, and every vertex's own V, where ties decide.
        let mut points: Vec<DVec3> = (0..4000)
            .map(|i| {
                let f = i as f64;
                DVec3::new(
                    (f * 0.618).fract() * 2.4 - 1.2,
                    (f * 0.414).fract() * 2.4 - 1.2,
                    0.0,
                )
            })
            .collect();
        points.extend(vertices.iter().map(|v| DVec3::new(0.3 * v.x, v.y, 0.0)));
        for point in points {
            assert_eq!(
                banded(point),
                gear.crossing_test(point).crossings,
                "{point}"
            );
        }
    }
}
