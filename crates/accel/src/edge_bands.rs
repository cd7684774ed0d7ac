//! The edges of a many-sided polygon sorted into horizontal bands of V, so the
//! crossing test looks only at the edges that can straddle the point's V.
//!
//! The crossing test counts an edge only when one end has V >= v and the other
//! V < v, that is when min V < v <= max V. Every such edge of a point in band
//! k (bounds[k] < v <= bounds[k + 1]) has min V < bounds[k + 1] and max V >
//! bounds[k], so listing those edges in band k loses none: the count, and so
//! the lecture's working, is the same as over every edge. A gear face of the
//! SPD has 144 edges; a band holds a handful.
//!
//! Most points need no counting at all: a grid of `GRID` x `GRID` cells over
//! the polygon's (U, V) box marks each cell INSIDE, OUTSIDE or MIXED, and
//! only a point in a MIXED cell (or off the grid) counts over its band.
//!
//! Why the grid answers as the count does, to the bit. Let M be the largest
//! |U| or |V| of a vertex, and m = 2^-30 M the margin. A cell is classified
//! only when no edge comes within m of it grown by `REACH` of a cell on
//! each side (the grown cell is what the proof below is about):
//!
//! 1. The count at a point p no edge comes within m of is the geometric
//!    one (exact arithmetic on the same vertices and p). The straddle test
//!    is exact: `vertex.y - p.y` is one correctly rounded subtraction, so
//!    its sign is the sign of the exact difference. A straddling edge meets
//!    V = p.y at a point of the edge, so its exact `u_at_axis` is at least
//!    the distance from p to the edge, more than m, in magnitude; the
//!    computed one is off by a few rounding errors of numbers at most 4M
//!    (p lies in the box, so a and b, each rounded once, are at most 2M;
//!    then `b.x - a.x`, a product, a quotient whose ratio a.y / (b.y - a.y)
//!    is at most 1 in magnitude, and a difference): under 2^-45 M, far
//!    below m, so its sign, and whether the edge counts, is exact.
//! 2. The geometric count's parity is the same at every point of a region
//!    no edge meets and that is connected (the even-odd rule: it changes
//!    only where the point crosses an edge). A grown cell is such a region,
//!    and so is the union of two classified neighbours' grown cells, which
//!    overlap: each run of classified cells side by side in a row takes
//!    the parity of a classified cell below it, or where there is none,
//!    the parity `count_crossings` over every edge gives at the centre of
//!    its first cell (exact there by 1; counted by the bands, the same
//!    count, as above).
//! 3. The cell of p is computed from (p - corner) times cells per unit, a
//!    subtraction and a product each rounded once: on the grid (at most
//!    `GRID` cells from the corner) that is off by under 2^-40 of a cell,
//!    so p lies in the cell it is looked up in grown by much less than
//!    `REACH`, which 1 and 2 cover. Points off the grid (or NaN) go to the
//!    bands.
//!
//! The test of an edge against a grown cell is conservative: it finds the
//! U extent of the part of the edge within the cell's row (its V range,
//! grown), which meets the cell's U range (grown) exactly when the edge
//! meets the grown cell; it grows the cell by a further 2m, so its own
//! rounding (errors under 2^-45 M in the extent) cannot pass an edge
//! that comes within m of the cell. Polygons whose M lies outside
//! [1e-150, 1e150] get no grid, so nothing underflows or overflows.

use glam::DVec2;

use raystep_model::shapes::crosses;

/// Polygons with fewer vertices are tested over all their edges.
pub(super) const MIN_VERTICES: usize = 16;
/// About this many edges per band on average.
const EDGES_PER_BAND: usize = 2;
/// Bands per polygon at most, so the lists stay linear in the edges.
const MAX_BANDS: usize = 64;
/// Cells per side of the inside/outside grid (at most 64: a row is a `u64`).
const GRID: usize = 64;
/// How far, in cells, a classified cell's clearance reaches past its sides.
const REACH: f64 = 1.0 / 8.0;
/// What cell indices computed from coordinates are widened by, in cells, for
/// their rounding (under 2^-40 of a cell on the grid).
const SLACK: f64 = 1.0 / (1u64 << 20) as f64;
/// The margin m in units of the largest |U| or |V| of a vertex: 2^-30.
const MARGIN: f64 = 1.0 / (1u64 << 30) as f64;
/// A row's cells, as bits.
const ROW: u64 = u64::MAX >> (64 - GRID);

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
    /// The inside/outside grid; `None` for polygons outside its range.
    grid: Option<Box<InsideGrid>>,
}

/// Which cells of the polygon's (U, V) box no edge comes near (`known`),
/// and of those which are inside: bit i of row j is the cell i to the right
/// of the box's least U and j up from its least V.
#[derive(Clone, Debug)]
struct InsideGrid {
    /// The box's least (U, V).
    corner: DVec2,
    /// Cells per unit of U and of V.
    scale: DVec2,
    known: [u64; GRID],
    inside: [u64; GRID],
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
        let mut bands = EdgeBands {
            bounds,
            scale: count as f64 / span,
            starts,
            edges,
            projected: projected.into_boxed_slice(),
            grid: None,
        };
        bands.grid = InsideGrid::new(&bands.projected, |p| bands.crossings(p)).map(Box::new);
        Some(bands)
    }

    /// Whether `shapes::count_crossings(projected, p)` is odd: from the grid
    /// when p's cell is classified, else from the crossings near p's V.
    #[inline]
    pub(crate) fn inside(&self, p: DVec2) -> bool {
        match self.grid.as_ref().and_then(|grid| grid.inside(p)) {
            Some(inside) => inside,
            None => self.crossings(p) % 2 == 1,
        }
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

impl InsideGrid {
    /// The grid of a polygon's projected vertices (see the module's doc for
    /// why its answers are the count's), `count` giving `count_crossings`
    /// over them at a point; `None` when the box is flat or the coordinates
    /// out of the range the proof covers.
    fn new(projected: &[DVec2], count: impl Fn(DVec2) -> u32) -> Option<InsideGrid> {
        let (mut low, mut high) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
        let mut largest: f64 = 0.0;
        for &p in projected {
            (low, high) = (low.min(p), high.max(p));
            largest = largest.max(p.x.abs()).max(p.y.abs());
        }
        let span = high - low;
        let finite = projected.iter().all(|p| p.is_finite());
        let in_range = finite && (1e-150..=1e150).contains(&largest);
        if !(in_range && span.x > 0.0 && span.y > 0.0) {
            return None;
        }
        let cell = span / GRID as f64;
        // The clearance tested: REACH of a cell, then the margin m twice
        // (once for the proof, once for the test's own rounding).
        let reach = cell * REACH + DVec2::splat(2.0 * MARGIN * largest);
        let mut mixed = [0u64; GRID];
        let n = projected.len();
        for i in 0..n {
            let (a, b) = (projected[(i + n - 1) % n], projected[i]);
            // The rows whose grown box may meet the edge's box: row r's
            // reaches from low + r cell - reach to low + (r + 1) cell + reach.
            let Some(rows) = cells_reaching(
                (a.y.min(b.y) - reach.y - low.y) / cell.y,
                (a.y.max(b.y) + reach.y - low.y) / cell.y,
            ) else {
                continue;
            };
            for row in rows {
                // The cells of this row whose grown box the edge meets: those
                // whose U range (grown) meets the U extent of the part of the
                // edge within the row's V range (grown).
                let bottom = low.y + row as f64 * cell.y - reach.y;
                let top = low.y + (row + 1) as f64 * cell.y + reach.y;
                let Some((left, right)) = u_extent_between(a, b, bottom, top) else {
                    continue;
                };
                if let Some(columns) = cells_reaching(
                    (left - reach.x - low.x) / cell.x,
                    (right + reach.x - low.x) / cell.x,
                ) {
                    let (from, to) = (columns.start(), columns.end());
                    mixed[row] |= (u64::MAX >> (63 - to)) & (u64::MAX << from);
                }
            }
        }
        // A run of classified cells side by side in a row shares one parity,
        // and so does a run with any classified cell below it: the parity
        // is copied from there, or else counted at the run's first centre.
        let mut inside = [0u64; GRID];
        for row in 0..GRID {
            let mut free = !mixed[row] & ROW;
            while free != 0 {
                let start = free.trailing_zeros();
                let length = (!(free >> start)).trailing_zeros();
                let run = (u64::MAX >> (64 - length)) << start;
                free &= !run;
                let below = if row > 0 { run & !mixed[row - 1] } else { 0 };
                let odd = if below != 0 {
                    inside[row - 1] >> below.trailing_zeros() & 1
                } else {
                    let centre = low + (DVec2::new(start as f64, row as f64) + 0.5) * cell;
                    u64::from(count(centre) % 2)
                };
                if odd == 1 {
                    inside[row] |= run;
                }
            }
        }
        Some(InsideGrid {
            corner: low,
            scale: DVec2::splat(GRID as f64) / span,
            known: mixed.map(|row| !row & ROW),
            inside,
        })
    }

    /// Whether p is inside, when its cell is classified; `None` when the
    /// cell is MIXED or p is off the grid (or NaN).
    #[inline]
    fn inside(&self, p: DVec2) -> Option<bool> {
        let at = (p - self.corner) * self.scale;
        let on_grid = |x: f64| x >= 0.0 && x < GRID as f64;
        if !(on_grid(at.x) && on_grid(at.y)) {
            return None;
        }
        let (column, row) = (at.x as usize, at.y as usize);
        (self.known[row] >> column & 1 == 1).then(|| self.inside[row] >> column & 1 == 1)
    }
}

/// The cells c (0 to GRID - 1) from c = `from` - 1 to c = `to`, in cells
/// from the grid's corner: those whose span (c to c + 1, grown as the
/// caller grew `from` and `to`) meets the span from `from` to `to`, widened
/// by SLACK for the rounding of the two; `None` when that misses the grid.
fn cells_reaching(from: f64, to: f64) -> Option<std::ops::RangeInclusive<usize>> {
    let (from, to) = (from - 1.0 - SLACK, to + SLACK);
    if !(to >= 0.0 && from <= (GRID - 1) as f64) {
        return None;
    }
    // Truncation of what is clamped to 0..GRID - 1 is its floor; the first
    // cell is from's ceiling.
    let first = from.max(0.0) as usize;
    let first = first + usize::from((first as f64) < from);
    Some(first..=to.min((GRID - 1) as f64) as usize)
}

/// The least and greatest U of the part of the segment from a to b with
/// V from `bottom` to `top`; `None` when no part of it is.
fn u_extent_between(a: DVec2, b: DVec2, bottom: f64, top: f64) -> Option<(f64, f64)> {
    if a.y.max(b.y) < bottom || a.y.min(b.y) > top {
        return None;
    }
    if a.y == b.y {
        return Some((a.x.min(b.x), a.x.max(b.x)));
    }
    let u_at = |v: f64| a.x + ((v - a.y) / (b.y - a.y)).clamp(0.0, 1.0) * (b.x - a.x);
    let (u_0, u_1) = (u_at(bottom), u_at(top));
    Some((u_0.min(u_1), u_0.max(u_1)))
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use raystep_model::shapes::{Axis, Polygon, count_crossings};

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

    /// The first 144-vertex polygon of the SPD gears (a gear's top face),
    /// projected as the accelerator projects it.
    fn spd_gear_face() -> Vec<DVec2> {
        let text = include_str!("../../../scenes/spd/gears.nff");
        let mut lines = text
            .lines()
            .skip_while(|line| line.trim() != "p 144")
            .skip(1);
        let vertices: Vec<DVec3> = (&mut lines)
            .take(144)
            .map(|line| {
                let xyz: Vec<f64> = line
                    .split_whitespace()
                    .map(|w| w.parse().unwrap())
                    .collect();
                DVec3::new(xyz[0], xyz[1], xyz[2])
            })
            .collect();
        assert_eq!(vertices.len(), 144);
        Polygon::new(vertices).unwrap().projected().collect()
    }

    /// A comb: a spine on the left and `teeth` long thin teeth to the right,
    /// so that most cells lie between close edges.
    fn comb(teeth: usize) -> Vec<DVec2> {
        let mut points = vec![DVec2::new(0.0, 0.0)];
        for k in 0..teeth {
            let y = k as f64;
            points.extend([
                DVec2::new(10.0, y),
                DVec2::new(10.0, y + 0.5),
                DVec2::new(1.0, y + 0.5),
                DVec2::new(1.0, y + 1.0),
            ]);
        }
        points.push(DVec2::new(0.0, teeth as f64));
        points
    }

    /// A zigzag band: every edge spans the whole V range (too many for
    /// the bands, so the grid is tested on its own).
    fn zigzag(n: usize) -> Vec<DVec2> {
        let mut points: Vec<DVec2> = (0..n)
            .map(|i| DVec2::new(i as f64 * 0.1, if i % 2 == 0 { 0.0 } else { 1.0 }))
            .collect();
        points.push(DVec2::new(n as f64 * 0.1, -0.5));
        points.push(DVec2::new(0.0, -0.5));
        points
    }

    /// Points to ask about: seeded pseudo-random ones over the box and
    /// beyond it, every vertex, points exactly on edges and within 1e-12
    /// (relative) of them, the grid's cell borders and their neighbours
    /// by one unit in the last place, and non-finite ones.
    fn probes(points: &[DVec2], grid: Option<&InsideGrid>) -> Vec<DVec2> {
        let (low, high) = points
            .iter()
            .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        let span = high - low;
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut random = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut probes: Vec<DVec2> = (0..20_000)
            .map(|_| low - span * 0.1 + span * 1.2 * DVec2::new(random(), random()))
            .collect();
        let n = points.len();
        let nudge = 1e-12 * span.max_element();
        for i in 0..n {
            let (a, b) = (points[(i + n - 1) % n], points[i]);
            probes.push(b);
            let normal = (b - a).perp().normalize_or_zero();
            for t in [0.0, 0.25, 0.5, 1.0 / 3.0, random()] {
                let on = a + (b - a) * t;
                probes.extend([on, on + normal * nudge, on - normal * nudge]);
            }
        }
        if let Some(grid) = grid {
            let cell = DVec2::ONE / grid.scale;
            for k in 0..=GRID {
                let border = grid.corner + cell * k as f64;
                for _ in 0..8 {
                    let inner = grid.corner + span * DVec2::new(random(), random());
                    for p in [DVec2::new(border.x, inner.y), DVec2::new(inner.x, border.y)] {
                        probes.extend([p, p.map(f64::next_up), p.map(f64::next_down)]);
                    }
                }
            }
        }
        probes.extend([
            DVec2::NAN,
            DVec2::new(f64::NAN, low.y),
            DVec2::new(low.x, f64::INFINITY),
            DVec2::INFINITY,
            DVec2::NEG_INFINITY,
            high,
            high.map(f64::next_up),
        ]);
        probes
    }

    #[test]
    fn the_grid_answers_as_every_edge_counted() {
        let far = star(144)
            .iter()
            .map(|p| *p * 1000.0 + DVec2::new(1.0e7, -3.0e6))
            .collect();
        let polygons: [(&str, Vec<DVec2>); 5] = [
            ("star", star(144)),
            ("SPD gear face", spd_gear_face()),
            ("comb", comb(20)),
            ("zigzag", zigzag(61)),
            ("star far from the origin", far),
        ];
        for (name, points) in polygons {
            // The oracle: the lecture's count over every edge.
            let count = |p: DVec2| count_crossings(points.iter().copied(), p);
            let grid = InsideGrid::new(&points, count).unwrap();
            let bands = EdgeBands::new(points.clone());
            assert_eq!(bands.is_none(), name == "zigzag", "{name}: bands");
            let (mut inside, mut outside, mut mixed) = (0, 0, 0);
            for p in probes(&points, Some(&grid)) {
                let expected = count(p) % 2 == 1;
                match grid.inside(p) {
                    Some(answer) => {
                        assert_eq!(answer, expected, "{name}: {p}");
                        if answer {
                            inside += 1;
                        } else {
                            outside += 1;
                        }
                    }
                    None => mixed += 1,
                }
                if let Some(bands) = &bands {
                    assert_eq!(bands.inside(p), expected, "{name}: {p} through the bands");
                }
            }
            // Not vacuous: of some 23,000 probes, many of each answer.
            assert!(
                inside > 1000 && outside > 1000 && mixed > 1000,
                "{name}: {inside} inside, {outside} outside, {mixed} mixed"
            );
        }
    }

    #[test]
    fn a_gear_face_is_mostly_classified() {
        let face = spd_gear_face();
        let bands = EdgeBands::new(face.clone()).unwrap();
        let grid = bands.grid.as_ref().unwrap();
        let known: u32 = grid.known.iter().map(|row| row.count_ones()).sum();
        let inside: u32 = grid.inside.iter().map(|row| row.count_ones()).sum();
        // The face is a disc with 36 teeth: its edges run round the rim, a
        // band a few cells wide of the 64 x 64, so most cells (the hub's
        // inside and the box's corners outside) are clear of every edge.
        let share = known as f64 / (GRID * GRID) as f64;
        assert!(share > 0.75, "{known} of {} cells classified", GRID * GRID);
        assert!(
            inside > 1000 && known - inside > 400,
            "{inside} of {known} inside"
        );
        // Inside a classified cell only where the count says so.
        for row in 0..GRID {
            for column in 0..GRID {
                if grid.known[row] >> column & 1 == 1 {
                    let centre =
                        grid.corner + (DVec2::new(column as f64, row as f64) + 0.5) / grid.scale;
                    let odd = count_crossings(face.iter().copied(), centre) % 2 == 1;
                    assert_eq!(grid.inside[row] >> column & 1 == 1, odd, "{column}, {row}");
                }
            }
        }
    }
}
