//! Polygonal patch: a polygon with a normal at every vertex. It is intersected
//! exactly like a polygon; its normal is interpolated (MODEL §3).

use glam::{DVec2, DVec3};
use serde::Serialize;

use crate::math::exceeds;

use super::GeometryError;
use super::polygon::{Axis, Polygon, PolygonWorking};

#[derive(Clone, Debug, PartialEq)]
pub struct Patch {
    pub polygon: Polygon,
    /// One unit normal per vertex (boxed, as the polygon's vertices).
    pub normals: Box<[DVec3]>,
}

/// Where in the fan a hit landed and how its normal was blended.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PatchWorking {
    pub polygon: PolygonWorking,
    /// The fan triangle (v0, v_i, v_i+1) that holds the hit: i.
    pub fan_triangle: Option<usize>,
    /// Barycentric weights of v0, v_i, v_i+1.
    pub barycentric: Option<[f64; 3]>,
}

impl Patch {
    pub fn new(vertices: Vec<DVec3>, normals: Vec<DVec3>) -> Result<Self, GeometryError> {
        if normals.len() != vertices.len() {
            return Err(GeometryError(format!(
                "a patch needs one normal per vertex: {} vertices, {} normals",
                vertices.len(),
                normals.len()
            )));
        }
        let polygon = Polygon::new(vertices)?;
        let mut unit = Vec::with_capacity(normals.len());
        for (i, n) in normals.iter().enumerate() {
            let length = n.length();
            if !exceeds(length, 0.0) || !length.is_finite() {
                return Err(GeometryError(format!("vertex normal {i} is zero")));
            }
            unit.push(*n / length);
        }
        Ok(Self {
            polygon,
            normals: unit.into_boxed_slice(),
        })
    }

    /// The fan triangle holding `point` and the point's barycentric weights in it.
    pub(crate) fn locate(&self, point: DVec3) -> (usize, [f64; 3]) {
        let projected = |i: usize| self.polygon.dropped.project(self.polygon.vertices[i]);
        locate(
            self.polygon.vertices.len(),
            projected,
            self.polygon.dropped,
            point,
        )
    }

    /// The interpolated unit normal at a point of the patch.
    pub(crate) fn normal_at(&self, point: DVec3) -> DVec3 {
        let projected = |i: usize| self.polygon.dropped.project(self.polygon.vertices[i]);
        blended_normal(
            self.polygon.vertices.len(),
            projected,
            self.polygon.dropped,
            &self.normals,
            self.polygon.plane.normal,
            point,
        )
    }
}

/// The fan triangle holding `point` and the point's barycentric weights in it,
/// computed in the polygon's projected 2-D plane (`projected(i)`, vertex i
/// of `n` with `dropped` left out). A point on no triangle (it can only be off by
/// rounding) takes the triangle it is least outside of.
fn locate(
    n: usize,
    projected: impl Fn(usize) -> DVec2,
    dropped: Axis,
    point: DVec3,
) -> (usize, [f64; 3]) {
    let p = dropped.project(point);
    let mut best = (1, [1.0, 0.0, 0.0], f64::NEG_INFINITY);
    let a = projected(0);
    for i in 1..n - 1 {
        let (b, c) = (projected(i), projected(i + 1));
        let area = (b - a).perp_dot(c - a);
        if area == 0.0 {
            continue;
        }
        let wb = (p - a).perp_dot(c - a) / area;
        let wc = (b - a).perp_dot(p - a) / area;
        let weights = [1.0 - wb - wc, wb, wc];
        let worst = weights[0].min(wb).min(wc);
        if worst >= 0.0 {
            return (i, weights);
        }
        if worst > best.2 {
            best = (i, weights, worst);
        }
    }
    (best.0, best.1)
}

/// The vertex normals blended at `point` with its weights in the fan
/// triangle holding it, normalized; `flat` (the polygon's normal) where the
/// blend vanishes.
pub fn blended_normal(
    n: usize,
    projected: impl Fn(usize) -> DVec2,
    dropped: Axis,
    normals: &[DVec3],
    flat: DVec3,
    point: DVec3,
) -> DVec3 {
    let (i, [w0, wi, wj]) = locate(n, projected, dropped, point);
    let blended = w0 * normals[0] + wi * normals[i] + wj * normals[i + 1];
    let length = blended.length();
    if length > 0.0 { blended / length } else { flat }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_is_interpolated_barycentrically() {
        // Triangle (0,0,0) (1,0,0) (0,1,0) with normals z, x, y.
        let patch = Patch::new(
            vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            vec![DVec3::Z, DVec3::X, DVec3::Y],
        )
        .unwrap();
        // At (0.25, 0.25): weights v0 = 0.5, v1 = 0.25, v2 = 0.25;
        // blend (0.25, 0.25, 0.5), length sqrt(0.375).
        let (i, w) = patch.locate(DVec3::new(0.25, 0.25, 0.0));
        assert_eq!(i, 1);
        assert!((w[0] - 0.5).abs() < 1e-12 && (w[1] - 0.25).abs() < 1e-12);
        let n = patch.normal_at(DVec3::new(0.25, 0.25, 0.0));
        let expected = DVec3::new(0.25, 0.25, 0.5) / 0.375f64.sqrt();
        assert!((n - expected).length() < 1e-12);
    }

    #[test]
    fn quad_patch_picks_the_second_fan_triangle() {
        // Square fan: triangles (v0,v1,v2) and (v0,v2,v3). (0.2, 0.8) lies in the second.
        let v = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
        let patch = Patch::new(v, vec![DVec3::Z; 4]).unwrap();
        assert_eq!(patch.locate(DVec3::new(0.2, 0.8, 0.0)).0, 2);
        assert_eq!(patch.locate(DVec3::new(0.8, 0.2, 0.0)).0, 1);
    }

    #[test]
    fn zero_vertex_normal_is_rejected() {
        let v = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
        assert!(Patch::new(v, vec![DVec3::Z, DVec3::ZERO, DVec3::Z]).is_err());
    }
}
