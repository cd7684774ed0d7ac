//! The few numbers and choices of MODEL §3-§6 that a setting's switch or a
//! classic mistake changes (MODEL §8), each asked as a question (is the
//! ambient term added? which normal lights the hit? which segment does a
//! shadow ray test?) so that the tracer reads like the lecture rather than
//! checking switches and mistakes. With `MISTAKES` false (an empty set) every
//! mistake's answer is the model's and compiles to it; otherwise each
//! question is one bit test of the settings' set.

use glam::DVec3;

use super::recorder::{RayKind, SurfaceHit};
use crate::scene::{Light, Material, Settings, SpecularModel};
use raystep_model::math::Color;
use raystep_model::math::{EPS, Interval};
use raystep_model::mistakes::Mistake;

/// The rules a pixel is traced by: the settings' model, with their mistakes
/// when `MISTAKES`.
#[derive(Clone, Copy, Debug)]
pub struct Rules<'a, const MISTAKES: bool> {
    settings: &'a Settings,
}

impl<'a, const MISTAKES: bool> Rules<'a, MISTAKES> {
    pub fn new(settings: &'a Settings) -> Rules<'a, MISTAKES> {
        Rules { settings }
    }

    #[inline]
    fn has(&self, mistake: Mistake) -> bool {
        MISTAKES && self.settings.mistakes.contains(mistake)
    }

    /// Whether the ambient term is added: the switch, unless `no-ambient`.
    #[inline]
    pub fn ambient(&self) -> bool {
        self.settings.switches.ambient && !self.has(Mistake::NoAmbient)
    }

    /// Whether a light that faces the point casts a shadow ray: the switch
    /// (off, every light is unblocked, S = 1).
    #[inline]
    pub fn shadows(&self) -> bool {
        self.settings.switches.shadows
    }

    /// The mirror weight of the reflected ray: k_s, or 0 with reflection
    /// switched off or for a material that does not reflect (`reflect =
    /// false`; a TIR's k_t still moves to it).
    #[inline]
    pub(crate) fn mirror_weight(&self, material: &Material) -> f64 {
        if self.settings.switches.reflection && material.reflects {
            material.ks
        } else {
            0.0
        }
    }

    /// Whether the material refracts: k_t > 0 with transmission switched
    /// on, in a profile that refracts (not cse167's, MODEL §11).
    #[inline]
    pub fn transmits(&self, material: &Material) -> bool {
        material.kt > 0.0 && self.settings.switches.transmission && self.settings.profile.refracts()
    }

    /// What the mirror ray's colour is multiplied by besides its weight:
    /// the material's specular colour S under the cse167 profile (S ∘ I_R,
    /// MODEL §11), else nothing (`None`: white).
    #[inline]
    pub(crate) fn mirror_tint(&self, material: &Material) -> Option<Color> {
        self.settings
            .profile
            .mirror_takes_specular_colour()
            .then(|| material.specular_color.unwrap_or(Color::ONE))
    }

    /// Whether a light behind the surface (N·L <= 0) adds nothing and
    /// casts no shadow ray: the lecture's rule; under the cse167 profile
    /// it still casts one and adds its highlight (MODEL §11).
    #[inline]
    pub(crate) fn light_behind_adds_nothing(&self) -> bool {
        self.settings.profile.light_behind_adds_nothing()
    }

    /// Hits at a depth below this spawn secondary rays: max_depth, or one
    /// fewer under `depth-off-by-one`.
    #[inline]
    pub fn spawn_below_depth(&self) -> u32 {
        let max_depth = self.settings.max_depth;
        if self.has(Mistake::DepthOffByOne) {
            max_depth.saturating_sub(1)
        } else {
            max_depth
        }
    }

    /// (c1, c2, c3) of `light`'s f_att: its own, else the scene's; (1, 0,
    /// 0), so f_att = 1, under `no-light-attenuation`; else (0, 0, 1),
    /// f_att = min(1, 1 / d²), under `inverse-square`.
    #[inline]
    pub fn light_attenuation(&self, light: &'a Light) -> &'a [f64; 3] {
        if self.has(Mistake::NoLightAttenuation) {
            &[1.0, 0.0, 0.0]
        } else if self.has(Mistake::InverseSquare) {
            &[0.0, 0.0, 1.0]
        } else {
            (light.attenuation.as_ref()).unwrap_or(&self.settings.light_attenuation)
        }
    }

    /// f_att of `light` at `distance`: min(1, 1 / (c1 + c2 d + c3 d²)),
    /// without the min under a profile that does not clamp (cse167: then
    /// at most the largest finite number), 1 where the quotient has no
    /// positive denominator (MODEL §4, §11).
    #[inline]
    pub fn f_att(&self, light: &'a Light, distance: f64) -> f64 {
        let [c1, c2, c3] = *self.light_attenuation(light);
        let denominator = c1 + c2 * distance + c3 * distance * distance;
        let most = if self.settings.profile.clamps_attenuation() {
            1.0
        } else {
            f64::MAX
        };
        if denominator <= 0.0 {
            1.0
        } else {
            (1.0 / denominator).min(most)
        }
    }

    /// The material's specular model, else the scene's; Phong for every
    /// material under `phong-not-blinn`.
    #[inline]
    pub fn specular_model(&self, material: &Material) -> SpecularModel {
        if self.has(Mistake::PhongNotBlinn) {
            SpecularModel::Phong
        } else {
            material.specular.unwrap_or(self.settings.specular)
        }
    }

    /// The normal that diffuse, specular and the faces-away test use: N,
    /// facing the ray (MODEL §3), or N_g under `no-normal-flip`. Reflection
    /// and refraction always use N.
    #[inline]
    pub(crate) fn lighting_normal(&self, hit: &SurfaceHit) -> DVec3 {
        if self.has(Mistake::NoNormalFlip) {
            hit.geometric_normal
        } else {
            hit.normal
        }
    }

    /// The hits a ray of `kind` accepts: (EPS, inf); a reflected or
    /// transmitted ray's start at 0 under `no-epsilon`.
    #[inline]
    pub fn hit_range(&self, kind: RayKind) -> Interval {
        if kind != RayKind::Primary && self.has(Mistake::NoEpsilon) {
            Interval::new(0.0, f64::INFINITY)
        } else {
            Interval::in_front()
        }
    }

    /// The shadow segment towards a light `distance` away: (EPS, d_L), or
    /// (EPS, inf) to a directional light (`None`); it starts at 0 under
    /// `shadow-acne` or `no-epsilon` and has no end under
    /// `shadows-past-light`.
    #[inline]
    pub fn shadow_segment(&self, distance: Option<f64>) -> Interval {
        let start = if self.has(Mistake::ShadowAcne) || self.has(Mistake::NoEpsilon) {
            0.0
        } else {
            EPS
        };
        let end = match distance {
            Some(d) if !self.has(Mistake::ShadowsPastLight) => d,
            _ => f64::INFINITY,
        };
        Interval::new(start, end)
    }

    /// Every shadow crossing counts as k_t = 0 (`opaque-shadows`).
    #[inline]
    pub(crate) fn opaque_shadows(&self) -> bool {
        self.has(Mistake::OpaqueShadows)
    }

    /// Snell's eta: 1 / ior entering, ior leaving (MODEL §5); the other way
    /// round under `eta-inverted`.
    #[inline]
    pub fn eta(&self, entering: bool, ior: f64) -> f64 {
        if entering != self.has(Mistake::EtaInverted) {
            1.0 / ior
        } else {
            ior
        }
    }

    /// At TIR k_t moves to the reflected ray, unless `tir-dropped`.
    #[inline]
    pub fn tir_adds_kt(&self) -> bool {
        !self.has(Mistake::TirDropped)
    }

    /// L as a light's terms use it (N·L, H, Phong's R): `to_light`, unit
    /// length, or `offset` = P_L - p under `light-not-normalised`. The
    /// shadow ray always goes along the unit L.
    #[inline]
    pub(crate) fn lighting_direction(&self, offset: DVec3, to_light: DVec3) -> DVec3 {
        if self.has(Mistake::LightNotNormalised) {
            offset
        } else {
            to_light
        }
    }

    /// N·L as a light's terms and its faces-away test use it: `n_dot_l`, or
    /// |N·L| under `two-sided-diffuse`, so a light behind the surface lights
    /// it too.
    #[inline]
    pub(crate) fn light_cosine(&self, n_dot_l: f64) -> f64 {
        if self.has(Mistake::TwoSidedDiffuse) {
            n_dot_l.abs()
        } else {
            n_dot_l
        }
    }

    /// Blinn's H = normalize(L + V). L + V = 0 only where a mistake counts
    /// a light straight behind the point as seen: H is 0 there, not NaN
    /// (MODEL §4). The model's tracer never meets it and skips the test.
    #[inline]
    pub(crate) fn half_vector(&self, l: DVec3, to_viewer: DVec3) -> DVec3 {
        if MISTAKES {
            (l + to_viewer).normalize_or_zero()
        } else {
            (l + to_viewer).normalize()
        }
    }

    /// The reflected direction `mirrored` (R = d - 2 (d·N) N), or -R under
    /// `reflection-sign`.
    #[inline]
    pub fn reflected(&self, mirrored: DVec3) -> DVec3 {
        if self.has(Mistake::ReflectionSign) {
            -mirrored
        } else {
            mirrored
        }
    }

    /// The normal Snell's law uses, in cos_i and in T: N, facing the ray,
    /// or N_g under `refraction-outward-normal` (they differ only leaving).
    #[inline]
    pub fn refraction_normal(&self, hit: &SurfaceHit) -> DVec3 {
        if self.has(Mistake::RefractionOutwardNormal) {
            hit.geometric_normal
        } else {
            hit.normal
        }
    }

    /// The local colour (ambient and the lights' terms) as the secondary
    /// rays' terms are added to it: `local`, or each channel at most 1
    /// under `clamp-before-adding`.
    #[inline]
    pub(crate) fn local_color(&self, local: Color) -> Color {
        if self.has(Mistake::ClampBeforeAdding) {
            local.min(Color::ONE)
        } else {
            local
        }
    }
}
