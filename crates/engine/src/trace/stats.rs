//! The ray counts of MODEL §7, gathered by a recorder.

use serde::Serialize;

use super::recorder::{LightTerm, NotCast, RayKind, Recorder, SurfaceHit};
use raystep_accel::Cost;
use raystep_model::math::{Color, Ray};

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct RayStats {
    pub primary: u64,
    pub(crate) primary_hit: u64,
    /// Reflected rays, TIR included.
    pub reflected: u64,
    pub transmitted: u64,
    /// Secondary rays not cast: below `min_weight` or over `max_rays`.
    pub not_cast: u64,
    /// Shadow rays cast (lights facing away cast none).
    pub(crate) shadow: u64,
    /// Shadow rays with at least one crossing, transparent or not.
    pub(crate) shadow_blocked: u64,
    /// Shadow rays fully blocked (S = 0).
    pub shadow_opaque: u64,
    /// What the closest-hit queries of all primary, reflected and transmitted
    /// rays tested: bounding-volume nodes and primitives.
    pub closest_nodes: u64,
    pub closest_primitives: u64,
    /// What the shadow queries tested.
    pub shadow_nodes: u64,
    pub shadow_primitives: u64,
    #[serde(skip)]
    depth: u32,
}

impl RayStats {
    pub fn add(&mut self, other: &RayStats) {
        self.primary += other.primary;
        self.primary_hit += other.primary_hit;
        self.reflected += other.reflected;
        self.transmitted += other.transmitted;
        self.not_cast += other.not_cast;
        self.shadow += other.shadow;
        self.shadow_blocked += other.shadow_blocked;
        self.shadow_opaque += other.shadow_opaque;
        self.closest_nodes += other.closest_nodes;
        self.closest_primitives += other.closest_primitives;
        self.shadow_nodes += other.shadow_nodes;
        self.shadow_primitives += other.shadow_primitives;
    }
}

impl RayStats {
    fn closest(&mut self, cost: Cost) {
        self.closest_nodes += u64::from(cost.nodes);
        self.closest_primitives += u64::from(cost.primitives);
    }
}

impl Recorder for RayStats {
    #[inline]
    fn ray_cast(&mut self, kind: RayKind, depth: u32, _ray: &Ray, _weight: f64) {
        self.depth = depth;
        match kind {
            RayKind::Primary => self.primary += 1,
            RayKind::Reflected => self.reflected += 1,
            RayKind::Transmitted => self.transmitted += 1,
        }
    }

    #[inline]
    fn hit(&mut self, _hit: &SurfaceHit, cost: Cost) {
        if self.depth == 1 {
            self.primary_hit += 1;
        }
        self.closest(cost);
    }

    #[inline]
    fn miss(&mut self, _background: Color, cost: Cost) {
        self.closest(cost);
    }

    #[inline]
    fn not_cast(&mut self, _ray: &NotCast) {
        self.not_cast += 1;
    }

    #[inline]
    fn light(&mut self, term: &LightTerm) {
        if let Some(shadow) = term.shadow {
            self.shadow += 1;
            self.shadow_blocked += u64::from(shadow.crossings > 0);
            self.shadow_opaque += u64::from(shadow.s == 0.0);
            self.shadow_nodes += u64::from(shadow.cost.nodes);
            self.shadow_primitives += u64::from(shadow.cost.primitives);
        }
    }
}
