//! The few numbers and choices of MODEL §3-§6 that a classic mistake changes
//! (MODEL §8), settled once per pixel from the settings, so that the tracer
//! reads like the lecture and asks a question (which normal lights the hit?
//! which segment does the shadow ray test?) rather than checking mistakes.
//! With no mistakes every rule is the model's, computed the same way.

use glam::DVec3;

use super::recorder::SurfaceHit;
use crate::math::{EPS, Interval};
use crate::mistakes::Mistake;
use crate::scene::{Settings, SpecularModel};

/// The rules one pixel is traced by.
#[derive(Clone, Copy, Debug)]
pub(super) struct Rules {
    /// Hits at depth < this spawn secondary rays: max_depth, or one fewer.
    pub spawn_below_depth: u32,
    /// Whether the ambient term is added (the switch, and no `no-ambient`).
    pub ambient: bool,
    /// (c1, c2, c3) of f_att; (1, 0, 0), no attenuation, under `no-light-attenuation`.
    pub light_attenuation: [f64; 3],
    /// Phong for every material under `phong-not-blinn`.
    pub forced_specular: Option<SpecularModel>,
    /// Where a shadow segment starts: EPS, or 0 under `shadow-acne`.
    shadow_start: f64,
    /// Crossings beyond the light block too (`shadows-past-light`).
    shadow_past_light: bool,
    /// Every crossing counts as k_t = 0 (`opaque-shadows`).
    pub opaque_shadows: bool,
    /// Lighting uses N_g unflipped (`no-normal-flip`).
    unflipped_lighting: bool,
    /// eta = ior entering, 1 / ior leaving (`eta-inverted`).
    eta_inverted: bool,
    /// At TIR k_t moves to the reflected ray (not under `tir-dropped`).
    pub tir_adds_kt: bool,
}

impl Rules {
    pub fn new(settings: &Settings) -> Rules {
        let mistakes = settings.mistakes;
        let has = |mistake| mistakes.contains(mistake);
        if mistakes.is_empty() {
            return Rules::model(settings);
        }
        Rules {
            spawn_below_depth: if has(Mistake::DepthOffByOne) {
                settings.max_depth.saturating_sub(1)
            } else {
                settings.max_depth
            },
            ambient: settings.switches.ambient && !has(Mistake::NoAmbient),
            light_attenuation: if has(Mistake::NoLightAttenuation) {
                [1.0, 0.0, 0.0]
            } else {
                settings.light_attenuation
            },
            forced_specular: has(Mistake::PhongNotBlinn).then_some(SpecularModel::Phong),
            shadow_start: if has(Mistake::ShadowAcne) { 0.0 } else { EPS },
            shadow_past_light: has(Mistake::ShadowsPastLight),
            opaque_shadows: has(Mistake::OpaqueShadows),
            unflipped_lighting: has(Mistake::NoNormalFlip),
            eta_inverted: has(Mistake::EtaInverted),
            tir_adds_kt: !has(Mistake::TirDropped),
        }
    }

    /// MODEL §3-§6 as written.
    fn model(settings: &Settings) -> Rules {
        Rules {
            spawn_below_depth: settings.max_depth,
            ambient: settings.switches.ambient,
            light_attenuation: settings.light_attenuation,
            forced_specular: None,
            shadow_start: EPS,
            shadow_past_light: false,
            opaque_shadows: false,
            unflipped_lighting: false,
            eta_inverted: false,
            tir_adds_kt: true,
        }
    }

    /// The normal that diffuse, specular and the faces-away test use: N,
    /// facing the ray (MODEL §3). Reflection and refraction always use N.
    #[inline]
    pub fn lighting_normal(&self, hit: &SurfaceHit) -> DVec3 {
        if self.unflipped_lighting {
            hit.geometric_normal
        } else {
            hit.normal
        }
    }

    /// The shadow segment towards a light `distance` away: (EPS, d_L).
    #[inline]
    pub fn shadow_segment(&self, distance: f64) -> Interval {
        let end = if self.shadow_past_light {
            f64::INFINITY
        } else {
            distance
        };
        Interval::new(self.shadow_start, end)
    }

    /// Snell's eta: 1 / ior entering, ior leaving (MODEL §5).
    #[inline]
    pub fn eta(&self, entering: bool, ior: f64) -> f64 {
        if entering != self.eta_inverted {
            1.0 / ior
        } else {
            ior
        }
    }
}
