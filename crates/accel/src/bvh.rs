//! Building the hierarchy: top-down, splitting each node where the surface
//! area heuristic (SAH) estimates the cheapest traversal, with the candidate
//! planes taken between 32 bins of the primitives' centroids along each of
//! the three axes.
//!
//! The SAH estimates the cost of a split as one node visit plus, for each
//! child, the chance a ray through the parent also crosses the child (the
//! ratio of their surface areas) times the primitives it holds. A node stays a
//! leaf when that is no cheaper than testing all its primitives.

use glam::DVec3;

use raystep_model::shapes::Aabb;

// Measured with the node and primitive counts of `render --stats` on the SPD
// scenes (deterministic, unlike timings here): trying all three axes instead
// of the widest cut the nodes per closest-hit ray by 5-20 % (balls 37 -> 32,
// gears 30 -> 24); 32 bins instead of 16 helped teapot (27 -> 25); a
// traversal cost of 0.5 instead of 1 trades a few % more nodes for 10-45 %
// fewer primitive tests (rings 5.9 -> 4.2), which pays where primitives are
// cones and many-sided polygons. Leaves of at most 4 were within noise.

/// Centroid bins per split.
const BINS: usize = 32;
/// The cost of visiting one node, relative to testing one primitive.
const TRAVERSAL_COST: f64 = 0.5;
/// A leaf never holds more, whatever the SAH says.
pub(super) const MAX_LEAF: usize = 8;
/// Below this depth the SAH chooses the split; deeper, the primitives are
/// halved at their median, so the depth stays below `MAX_DEPTH`. Primitives
/// whose centroids coincide are halved too (by file order).
const SAH_DEPTH: usize = 32;
/// No path from the root is longer: the traversal stack holds this many nodes.
pub(super) const MAX_DEPTH: usize = SAH_DEPTH + 33;

/// Each box is widened by this fraction of its largest coordinate (plus a
/// scene-wide floor), so that a hit point a primitive computes with rounding
/// error just outside its exact box is still inside the node's box.
const RELATIVE_PADDING: f64 = 1.0 / (1u64 << 22) as f64;
const SCENE_PADDING: f64 = 1.0 / (1u64 << 30) as f64;

/// A node of the binary tree as built: a box and what is under it, a range
/// of primitives (a leaf, `count > 0`) or two children (`count == 0`): the
/// first right after this node in the array, the second at `offset`.
#[derive(Clone, Copy, Debug)]
pub(super) struct BuildNode {
    pub(crate) bounds: Aabb,
    /// Leaf: the first position in the primitive index array; interior: the second child.
    pub(crate) offset: u32,
    /// Leaf: how many primitives (at least 1); interior: 0.
    pub(crate) count: u16,
}

impl BuildNode {
    pub(crate) fn is_leaf(&self) -> bool {
        self.count > 0
    }
}

/// A bounded object as the build sees it.
#[derive(Clone, Copy, Debug)]
pub(super) struct PrimitiveRef {
    pub(crate) bounds: Aabb,
    pub(crate) centroid: DVec3,
    pub(crate) object: u32,
}

impl PrimitiveRef {
    pub(crate) fn new(object: u32, bounds: Aabb) -> PrimitiveRef {
        PrimitiveRef {
            bounds,
            centroid: bounds.centroid(),
            object,
        }
    }
}

/// The hierarchy: nodes in depth-first order (the root first) and the
/// objects of the leaves, each leaf's run in file order.
pub(super) struct Bvh {
    pub(crate) nodes: Vec<BuildNode>,
    pub(crate) objects: Vec<u32>,
}

pub(super) fn build(mut primitives: Vec<PrimitiveRef>) -> Bvh {
    let mut builder = Builder {
        nodes: Vec::with_capacity(primitives.len() / 2 + 1),
        floor_padding: SCENE_PADDING * largest_coordinate(&bounds_of(&primitives)),
    };
    if !primitives.is_empty() {
        builder.subdivide(&mut primitives, 0, 0);
    }
    Bvh {
        nodes: builder.nodes,
        objects: primitives.iter().map(|p| p.object).collect(),
    }
}

struct Builder {
    nodes: Vec<BuildNode>,
    floor_padding: f64,
}

impl Builder {
    /// Appends the subtree over `primitives`, which start at `first` in the
    /// final primitive order, and reorders them so each leaf's run is contiguous.
    fn subdivide(&mut self, primitives: &mut [PrimitiveRef], first: usize, depth: usize) {
        let bounds = self.padded(bounds_of(primitives));
        let Some(middle) = split(primitives, &bounds, depth) else {
            primitives.sort_unstable_by_key(|p| p.object);
            self.nodes.push(BuildNode {
                bounds,
                offset: first as u32,
                count: primitives.len() as u16,
            });
            return;
        };
        let index = self.nodes.len();
        self.nodes.push(BuildNode {
            bounds,
            offset: 0,
            count: 0,
        });
        let (left, right) = primitives.split_at_mut(middle);
        self.subdivide(left, first, depth + 1);
        self.nodes[index].offset = self.nodes.len() as u32;
        self.subdivide(right, first + middle, depth + 1);
    }

    fn padded(&self, bounds: Aabb) -> Aabb {
        let padding =
            DVec3::splat(RELATIVE_PADDING * largest_coordinate(&bounds) + self.floor_padding);
        Aabb::new(bounds.min - padding, bounds.max + padding)
    }
}

fn bounds_of(primitives: &[PrimitiveRef]) -> Aabb {
    primitives
        .iter()
        .fold(Aabb::EMPTY, |b, p| b.union(&p.bounds))
}

fn largest_coordinate(bounds: &Aabb) -> f64 {
    if bounds.min.x > bounds.max.x {
        0.0
    } else {
        bounds.min.abs().max(bounds.max.abs()).max_element()
    }
}

pub(super) fn surface_area(bounds: &Aabb) -> f64 {
    let e = bounds.max - bounds.min;
    2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
}

/// Where to split: how many primitives (now reordered) go to the first
/// child. `None` makes a leaf.
fn split(primitives: &mut [PrimitiveRef], bounds: &Aabb, depth: usize) -> Option<usize> {
    let n = primitives.len();
    if n == 1 {
        return None;
    }
    let centroids = primitives.iter().fold(Aabb::EMPTY, |b, p| {
        b.union(&Aabb::new(p.centroid, p.centroid))
    });
    let extent = centroids.max - centroids.min;
    // Every axis is tried; on equal costs the first. An axis whose centroids
    // all coincide (or spread beyond the f64 range) cannot be binned.
    let mut best: Option<(f64, usize, usize)> = None;
    if depth < SAH_DEPTH {
        for axis in 0..3 {
            if !(extent[axis] > 0.0 && extent[axis].is_finite()) {
                continue;
            }
            if let Some((cost, plane)) = best_plane(primitives, bounds, &centroids, axis)
                && best.is_none_or(|(c, _, _)| cost < c)
            {
                best = Some((cost, plane, axis));
            }
        }
    }
    let axis = best.map_or(extent.max_position(), |(_, _, axis)| axis);
    match best {
        Some((cost, _, _)) if n <= MAX_LEAF && cost >= n as f64 => None,
        Some((_, plane, _)) => {
            let scale = BINS as f64 / extent[axis];
            let middle = partition(primitives, |p| {
                bin(p.centroid[axis], centroids.min[axis], scale) < plane
            });
            Some(middle)
        }
        None if n <= MAX_LEAF => None,
        None => Some(median_split(primitives, axis)),
    }
}

fn bin(centroid: f64, min: f64, scale: f64) -> usize {
    (((centroid - min) * scale) as usize).min(BINS - 1)
}

/// The cheapest plane between bins along `axis`: its SAH cost, in units of
/// one primitive test, and the first bin on its far side.
fn best_plane(
    primitives: &[PrimitiveRef],
    bounds: &Aabb,
    centroids: &Aabb,
    axis: usize,
) -> Option<(f64, usize)> {
    let mut counts = [0usize; BINS];
    let mut boxes = [Aabb::EMPTY; BINS];
    let scale = BINS as f64 / (centroids.max[axis] - centroids.min[axis]);
    for p in primitives {
        let b = bin(p.centroid[axis], centroids.min[axis], scale);
        counts[b] += 1;
        boxes[b] = boxes[b].union(&p.bounds);
    }
    // below[i]: area times count of bins 0..i, swept from the left.
    let mut below = [0.0; BINS];
    let (mut count, mut b) = (0, Aabb::EMPTY);
    for i in 1..BINS {
        count += counts[i - 1];
        b = b.union(&boxes[i - 1]);
        below[i] = if count > 0 {
            surface_area(&b) * count as f64
        } else {
            0.0
        };
    }
    let (mut count, mut b) = (0, Aabb::EMPTY);
    let mut best: Option<(f64, usize)> = None;
    let parent_area = surface_area(bounds);
    for i in (1..BINS).rev() {
        count += counts[i];
        b = b.union(&boxes[i]);
        if count == 0 || count == primitives.len() {
            continue;
        }
        let cost = TRAVERSAL_COST + (below[i] + surface_area(&b) * count as f64) / parent_area;
        if best.is_none_or(|(c, _)| cost < c) {
            best = Some((cost, i));
        }
    }
    best
}

/// Puts the primitives of smaller centroids first, ties by object index, and
/// returns the half's size.
fn median_split(primitives: &mut [PrimitiveRef], axis: usize) -> usize {
    let middle = primitives.len() / 2;
    primitives.select_nth_unstable_by(middle, |a, b| {
        a.centroid[axis]
            .total_cmp(&b.centroid[axis])
            .then(a.object.cmp(&b.object))
    });
    middle
}

/// Moves the primitives that satisfy `first` to the front; returns how many.
fn partition(primitives: &mut [PrimitiveRef], first: impl Fn(&PrimitiveRef) -> bool) -> usize {
    let mut middle = 0;
    for i in 0..primitives.len() {
        if first(&primitives[i]) {
            primitives.swap(i, middle);
            middle += 1;
        }
    }
    middle
}
