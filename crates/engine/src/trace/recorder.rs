//! The recorder: the tracer drives and calls back, like ripgrep's `Sink`.
//! Every method has an empty `#[inline]` default, so the render's
//! `NoRecorder` compiles away; the debugger's recorder builds the ray tree and
//! the event list from the same calls, in the order they happen.

use glam::DVec3;
use serde::Serialize;

use crate::scene::SpecularModel;
use raystep_accel::Cost;
use raystep_model::math::{Color, Ray};

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RayKind {
    Primary,
    Reflected,
    Transmitted,
}

/// The surface a ray hit, expanded from the winning candidate only.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceHit {
    pub object: usize,
    pub(crate) t: f64,
    pub(crate) point: DVec3,
    /// N_g, unit length (for a patch, the interpolated normal).
    pub(crate) geometric_normal: DVec3,
    /// N: N_g turned to face the incoming ray (N·d <= 0), unit length.
    pub(crate) normal: DVec3,
    /// N_g·d < 0: the ray arrives on the front side.
    pub(crate) entering: bool,
}

/// One crossing of a shadow ray's segment.
#[derive(Clone, Copy, Debug)]
pub struct Blocker {
    pub(crate) object: usize,
    pub(crate) t: f64,
    pub(crate) kt: f64,
}

/// The result of one shadow ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ShadowOutcome {
    /// S_i: the product of k_t over the crossings.
    pub(crate) s: f64,
    /// How many crossings were found (the render stops at the first opaque one).
    pub(crate) crossings: u32,
    pub(crate) cost: Cost,
}

/// Everything one light contributes at a hit (MODEL §4).
#[derive(Clone, Copy, Debug)]
pub struct LightTerm {
    pub(crate) light: usize,
    /// L, unit length (P_L - p under `light-not-normalised`).
    pub(crate) to_light: DVec3,
    /// d_L; `None` for a directional light, which is infinitely far.
    pub(crate) distance: Option<f64>,
    pub(crate) n_dot_l: f64,
    /// N·L <= 0: no shadow ray, no contribution.
    pub(crate) faces_away: bool,
    /// The light is closer to the point than EPS: L is undefined, so it is
    /// recorded as L = 0, N·L = 0, facing away (MODEL §4).
    pub(crate) at_point: bool,
    /// The shadow ray's result; `None` when none was cast (faces away, or shadows off).
    pub(crate) shadow: Option<ShadowOutcome>,
    pub(crate) f_att: f64,
    /// Which specular model this material used: Blinn's N·H or Phong's R·V.
    pub(crate) specular_model: SpecularModel,
    /// N·H (Blinn) or R·V (Phong), before clamping to 0.
    pub(crate) specular_cosine: f64,
    pub(crate) diffuse: Color,
    pub(crate) specular: Color,
}

/// Snell's law at a transparent surface (MODEL §5).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Refraction {
    pub cos_i: f64,
    pub eta: f64,
    /// 1 - eta^2 (1 - cos_i^2); negative means total internal reflection.
    pub k: f64,
    pub tir: bool,
    /// The transmitted direction, unless TIR.
    pub direction: Option<DVec3>,
}

/// A secondary ray's returned colour and what it adds to its parent.
#[derive(Clone, Copy, Debug)]
pub struct ChildTerm {
    pub(crate) kind: RayKind,
    /// Distance attenuation; 1 for a miss.
    pub(crate) attenuation: f64,
    /// A colour the profile weighs the ray by besides its weight: the
    /// specular colour S of a cse167 mirror ray (MODEL §11).
    pub(crate) tint: Option<Color>,
    /// weight * attenuation * color (∘ tint): the term added to the parent.
    pub(crate) contribution: Color,
}

/// Why a secondary ray was not cast (MODEL §5).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "rule", rename_all = "snake_case")]
pub enum PruneRule {
    /// Its accumulated weight is below the scene's `min_weight`.
    MinWeight { min_weight: f64 },
    /// The pixel's tree already holds `max_rays` rays.
    MaxRays { max_rays: u32 },
}

/// A secondary ray that was not cast, and why.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct NotCast {
    pub kind: RayKind,
    /// The factor it would have been scaled by in its parent (k_s, k_t, k_s + k_t).
    pub weight: f64,
    /// The product of the weights from the primary ray down, this one included.
    pub path_weight: f64,
    #[serde(flatten)]
    pub rule: PruneRule,
}

/// A hit the depth limit keeps from spawning (MODEL §5), with the weights
/// of the secondary rays it would have cast: k_s and k_t, or on total
/// internal reflection one reflected ray of k_s + k_t (k_s under
/// `tir-dropped`); 0 for a ray it would not have cast either way (its
/// material, or its switch off).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct DepthLimit {
    pub(crate) reflected: f64,
    pub(crate) transmitted: f64,
}

impl DepthLimit {
    /// The rays the limit cut, by kind and weight: those of weight above 0.
    pub(crate) fn cut(self) -> impl Iterator<Item = (RayKind, f64)> {
        [
            (RayKind::Reflected, self.reflected),
            (RayKind::Transmitted, self.transmitted),
        ]
        .into_iter()
        .filter(|(_, weight)| *weight > 0.0)
    }
}

/// Callbacks in execution order. For one ray: `ray_cast`, then `hit` or `miss`;
/// after a hit `ambient`, per light `shadow_cast` and its `blocker`s then
/// `light`, then `refraction`, each child's whole subtree followed by `child`
/// (or, for a child that is not cast, `not_cast`); last `ray_done`. At a hit
/// the depth limit keeps from spawning, and only if `RECORDS_DEPTH_LIMIT`,
/// `refraction` (on TIR only) and `depth_limit` come in place of the children.
pub trait Recorder {
    /// When true, shadow queries report every blocker instead of stopping at
    /// the first opaque one. S is the same either way.
    const RECORDS_ALL_BLOCKERS: bool = false;
    /// When true, a hit the depth limit keeps from spawning is reported
    /// (`depth_limit`, and `refraction` if it is TIR), though no colour
    /// depends on it; a render skips that work at compile time.
    const RECORDS_DEPTH_LIMIT: bool = false;

    #[inline]
    fn ray_cast(&mut self, _kind: RayKind, _depth: u32, _ray: &Ray, _weight: f64) {}
    #[inline]
    fn hit(&mut self, _hit: &SurfaceHit, _cost: Cost) {}
    #[inline]
    fn miss(&mut self, _background: Color, _cost: Cost) {}
    #[inline]
    fn ambient(&mut self, _term: Color) {}
    /// A material's emission E, added as it is (after `ambient`, only
    /// when some channel is above 0).
    #[inline]
    fn emission(&mut self, _term: Color) {}
    #[inline]
    fn shadow_cast(&mut self, _light: usize, _ray: &Ray, _distance: Option<f64>) {}
    #[inline]
    fn blocker(&mut self, _blocker: &Blocker) {}
    #[inline]
    fn light(&mut self, _term: &LightTerm) {}
    #[inline]
    fn refraction(&mut self, _refraction: &Refraction) {}
    #[inline]
    fn child(&mut self, _term: &ChildTerm) {}
    #[inline]
    fn not_cast(&mut self, _ray: &NotCast) {}
    #[inline]
    fn depth_limit(&mut self, _limit: &DepthLimit) {}
    #[inline]
    fn ray_done(&mut self, _color: Color) {}
}

/// Records nothing: what a full render passes.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoRecorder;

impl Recorder for NoRecorder {}
