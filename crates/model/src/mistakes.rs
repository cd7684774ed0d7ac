//! The classic mistakes of a student's Whitted tracer, each one a switch the
//! tracer reads (docs/MODEL.md §8 defines them). `raystep compare` renders a
//! scene under each to say which one a student's image looks like; the
//! debugger turns them on so a teacher can step through the ray that shows one.
//! Their names are fixed: graders and tools rely on them.

use std::fmt;

use serde::{Serialize, Serializer};

use crate::math::{Color, to_byte, to_rgb8};

/// One classic mistake.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Mistake {
    /// Shadow rays accept crossings at t > 0 instead of t > EPS.
    ShadowAcne,
    /// Diffuse, specular and the faces-away test use the outward normal N_g,
    /// not N turned to face the ray (reflection and refraction unchanged).
    NoNormalFlip,
    /// Snell's law with eta = n_t / n_i.
    EtaInverted,
    /// At total internal reflection k_t is not added to the reflected weight.
    TirDropped,
    /// Phong's R·V in place of Blinn's N·H.
    PhongNotBlinn,
    /// Any crossing blocks the light fully: k_t ignored.
    OpaqueShadows,
    /// Crossings beyond the light (t >= d_L) block it too.
    ShadowsPastLight,
    /// f_att = 1 for every light.
    NoLightAttenuation,
    /// One level fewer: rays of depth max_depth - 1 spawn no children.
    DepthOffByOne,
    /// The ambient term left out.
    NoAmbient,
    /// byte = floor(255c + 0.5) mod 256 instead of clamping.
    ByteWrap,
    /// byte = floor(255 c^(1/2.2) + 0.5), clamped.
    Gamma,
    /// Rows upside down.
    FlippedY,
    /// Primary rays through pixel corners (x, y) instead of centres.
    PixelCorner,
    /// Reflected and transmitted rays accept hits at t > 0, as shadow rays
    /// do under `ShadowAcne`.
    NoEpsilon,
    /// N·L and H with L = P_L - p, not normalised.
    LightNotNormalised,
    /// R = 2 (D·N) N - D, the reflected direction negated.
    ReflectionSign,
    /// Leaving, Snell's law with the outward N_g, not N facing the ray.
    RefractionOutwardNormal,
    /// |N·L|: lights behind the surface light it too.
    TwoSidedDiffuse,
    /// The local colour clamped to 1 before k_s I_r and k_t I_t are added.
    ClampBeforeAdding,
    /// f_att = min(1, 1 / d²) for every light, whatever the scene says.
    InverseSquare,
    /// The viewport's half-height tan(fov), not tan(fov / 2).
    FovFullAngle,
}

impl Mistake {
    /// The catalogue, in the order docs/MODEL.md lists it.
    pub const ALL: [Mistake; 22] = [
        Mistake::ShadowAcne,
        Mistake::NoNormalFlip,
        Mistake::EtaInverted,
        Mistake::TirDropped,
        Mistake::PhongNotBlinn,
        Mistake::OpaqueShadows,
        Mistake::ShadowsPastLight,
        Mistake::NoLightAttenuation,
        Mistake::DepthOffByOne,
        Mistake::NoAmbient,
        Mistake::ByteWrap,
        Mistake::Gamma,
        Mistake::FlippedY,
        Mistake::PixelCorner,
        Mistake::NoEpsilon,
        Mistake::LightNotNormalised,
        Mistake::ReflectionSign,
        Mistake::RefractionOutwardNormal,
        Mistake::TwoSidedDiffuse,
        Mistake::ClampBeforeAdding,
        Mistake::InverseSquare,
        Mistake::FovFullAngle,
    ];

    /// The fixed name, as the command line, JSON and MODEL.md write it.
    pub fn name(self) -> &'static str {
        match self {
            Mistake::ShadowAcne => "shadow-acne",
            Mistake::NoNormalFlip => "no-normal-flip",
            Mistake::EtaInverted => "eta-inverted",
            Mistake::TirDropped => "tir-dropped",
            Mistake::PhongNotBlinn => "phong-not-blinn",
            Mistake::OpaqueShadows => "opaque-shadows",
            Mistake::ShadowsPastLight => "shadows-past-light",
            Mistake::NoLightAttenuation => "no-light-attenuation",
            Mistake::DepthOffByOne => "depth-off-by-one",
            Mistake::NoAmbient => "no-ambient",
            Mistake::ByteWrap => "byte-wrap",
            Mistake::Gamma => "gamma",
            Mistake::FlippedY => "flipped-y",
            Mistake::PixelCorner => "pixel-corner",
            Mistake::NoEpsilon => "no-epsilon",
            Mistake::LightNotNormalised => "light-not-normalised",
            Mistake::ReflectionSign => "reflection-sign",
            Mistake::RefractionOutwardNormal => "refraction-outward-normal",
            Mistake::TwoSidedDiffuse => "two-sided-diffuse",
            Mistake::ClampBeforeAdding => "clamp-before-adding",
            Mistake::InverseSquare => "inverse-square",
            Mistake::FovFullAngle => "fov-full-angle",
        }
    }

    /// What a tracer with the mistake does, in a few words.
    pub fn summary(self) -> &'static str {
        match self {
            Mistake::ShadowAcne => "shadow rays hit their own surface (t > 0, not t > EPS)",
            Mistake::NoNormalFlip => "shading uses the outward normal on back faces",
            Mistake::EtaInverted => "Snell's law with n_t / n_i",
            Mistake::TirDropped => "k_t lost at total internal reflection",
            Mistake::PhongNotBlinn => "specular with R·V, not N·H",
            Mistake::OpaqueShadows => "transparent objects cast full shadows",
            Mistake::ShadowsPastLight => "objects beyond the light cast shadows",
            Mistake::NoLightAttenuation => "lights not attenuated with distance",
            Mistake::DepthOffByOne => "one reflection/refraction level too few",
            Mistake::NoAmbient => "no ambient term",
            Mistake::ByteWrap => "colours above 1 wrap around instead of clamping",
            Mistake::Gamma => "a gamma of 2.2 applied to the bytes",
            Mistake::FlippedY => "the image is upside down",
            Mistake::PixelCorner => "primary rays through pixel corners, not centres",
            Mistake::NoEpsilon => "every secondary ray hits its own surface (t > 0)",
            Mistake::LightNotNormalised => "N·L and H with L = P_L - p, not normalised",
            Mistake::ReflectionSign => "the reflected ray reversed: 2 (D·N) N - D",
            Mistake::RefractionOutwardNormal => "refraction leaving glass with the outward normal",
            Mistake::TwoSidedDiffuse => "|N·L|: lights behind a surface light it too",
            Mistake::ClampBeforeAdding => "the local colour clamped before reflections are added",
            Mistake::InverseSquare => "lights fall off as 1/d², whatever the scene says",
            Mistake::FovFullAngle => "tan(fov), not tan(fov / 2): a wider view",
        }
    }

    /// What the mistake acts on: a scene without it renders the same with
    /// the mistake, so `compare` need not render it (MODEL §8's "Touches").
    /// Every mistake answers here, beside its definition: a new one does not
    /// compile until it says what it can change.
    pub fn acts_on(self) -> ActsOn {
        match self {
            Mistake::ShadowAcne | Mistake::ShadowsPastLight => ActsOn::ShadowRays,
            Mistake::OpaqueShadows => ActsOn::TransparentShadows,
            Mistake::EtaInverted | Mistake::TirDropped => ActsOn::Refraction,
            Mistake::NoLightAttenuation => ActsOn::LightAttenuation,
            Mistake::NoAmbient => ActsOn::Ambient,
            Mistake::PhongNotBlinn => ActsOn::Highlights,
            Mistake::DepthOffByOne => ActsOn::SecondaryRays,
            Mistake::NoEpsilon => ActsOn::ShadowOrSecondaryRays,
            Mistake::ReflectionSign | Mistake::ClampBeforeAdding => ActsOn::SecondaryRays,
            Mistake::RefractionOutwardNormal => ActsOn::Refraction,
            Mistake::LightNotNormalised | Mistake::TwoSidedDiffuse | Mistake::InverseSquare => {
                ActsOn::Lights
            }
            Mistake::NoNormalFlip
            | Mistake::ByteWrap
            | Mistake::Gamma
            | Mistake::FlippedY
            | Mistake::PixelCorner
            | Mistake::FovFullAngle => ActsOn::AnyScene,
        }
    }

    /// Whether the mistake acts only on the bytes, after every ray is
    /// traced: no ray log can show it (docs/RAYLOG.md).
    pub fn acts_only_on_bytes(self) -> bool {
        match self {
            Mistake::ByteWrap | Mistake::Gamma => true,
            Mistake::ShadowAcne
            | Mistake::NoNormalFlip
            | Mistake::EtaInverted
            | Mistake::TirDropped
            | Mistake::PhongNotBlinn
            | Mistake::OpaqueShadows
            | Mistake::ShadowsPastLight
            | Mistake::NoLightAttenuation
            | Mistake::DepthOffByOne
            | Mistake::NoAmbient
            | Mistake::FlippedY
            | Mistake::PixelCorner
            | Mistake::NoEpsilon
            | Mistake::LightNotNormalised
            | Mistake::ReflectionSign
            | Mistake::RefractionOutwardNormal
            | Mistake::TwoSidedDiffuse
            | Mistake::ClampBeforeAdding
            | Mistake::InverseSquare
            | Mistake::FovFullAngle => false,
        }
    }

    fn bit(self) -> u32 {
        1 << self as u32
    }
}

/// What a scene must have for a mistake to change its image (`Mistake::acts_on`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ActsOn {
    /// Shadow rays: shadows switched on.
    ShadowRays,
    /// Shadow rays through a transparent material (k_t > 0).
    TransparentShadows,
    /// Refraction: transmission switched on and a material with k_t > 0.
    Refraction,
    /// Light attenuation other than (1, 0, 0).
    LightAttenuation,
    /// An ambient term: switched on, I_a not black, a material with k_a > 0.
    Ambient,
    /// Highlights: a material with k_s > 0.
    Highlights,
    /// Secondary rays: max_depth above 1, a material with k_s or k_t > 0.
    SecondaryRays,
    /// A light.
    Lights,
    /// Shadow rays (shadows switched on) or secondary rays.
    ShadowOrSecondaryRays,
    /// Any scene: the bytes, the rows, the primary rays or the normals.
    AnyScene,
}

impl fmt::Display for Mistake {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Serialize for Mistake {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

/// A set of mistakes; empty (the correct model) by default.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Mistakes(u32);

impl Mistakes {
    pub const NONE: Mistakes = Mistakes(0);

    pub fn contains(self, mistake: Mistake) -> bool {
        self.0 & mistake.bit() != 0
    }

    /// The set with `mistake` added.
    pub fn with(self, mistake: Mistake) -> Mistakes {
        Mistakes(self.0 | mistake.bit())
    }

    /// The set with `mistake` in it if it was not, out of it if it was.
    pub fn toggled(self, mistake: Mistake) -> Mistakes {
        Mistakes(self.0 ^ mistake.bit())
    }

    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// The mistakes in the set, in catalogue order.
    pub fn iter(self) -> impl Iterator<Item = Mistake> {
        Mistake::ALL.into_iter().filter(move |&m| self.contains(m))
    }

    /// A pixel's colour as the image stores it: MODEL §6's `to_rgb8`, or
    /// with `gamma` and `byte-wrap` their bytes (§8). The render, the term
    /// images and a recording's rgb8 all convert here, so they agree.
    #[inline]
    pub fn rgb8(self, color: Color) -> [u8; 3] {
        let bytes = Mistake::Gamma.bit() | Mistake::ByteWrap.bit();
        if self.0 & bytes == 0 {
            return to_rgb8(color);
        }
        color.to_array().map(|c| self.byte(c))
    }

    /// One channel under `gamma` and/or `byte-wrap`.
    #[cold]
    fn byte(self, channel: f64) -> u8 {
        let c = if self.contains(Mistake::Gamma) {
            // A negative channel has no real root; it counts as 0.
            channel.max(0.0).powf(1.0 / 2.2)
        } else {
            channel
        };
        if self.contains(Mistake::ByteWrap) {
            // The integer keeps its low 8 bits, as a C cast to unsigned char
            // does; the f64 to i64 cast saturates and takes NaN to 0.
            ((255.0 * c + 0.5).floor() as i64).rem_euclid(256) as u8
        } else {
            to_byte(c)
        }
    }
}

/// As the comma-separated list of their names.
impl fmt::Display for Mistakes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, mistake) in self.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            f.write_str(mistake.name())?;
        }
        Ok(())
    }
}

impl FromIterator<Mistake> for Mistakes {
    fn from_iter<I: IntoIterator<Item = Mistake>>(iter: I) -> Mistakes {
        iter.into_iter().fold(Mistakes::NONE, Mistakes::with)
    }
}

/// As the list of their names.
impl Serialize for Mistakes {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.iter())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_is_its_own_and_kebab_case() {
        let names: std::collections::BTreeSet<&str> =
            Mistake::ALL.iter().map(|m| m.name()).collect();
        assert_eq!(names.len(), Mistake::ALL.len());
        for name in names {
            assert!(
                name.chars().all(|c| c.is_ascii_lowercase() || c == '-'),
                "{name}"
            );
        }
    }

    #[test]
    fn a_set_holds_what_was_added_in_catalogue_order() {
        let set: Mistakes = [Mistake::PixelCorner, Mistake::ShadowAcne]
            .into_iter()
            .collect();
        assert!(set.contains(Mistake::ShadowAcne));
        assert!(!set.contains(Mistake::Gamma));
        assert_eq!(
            set.iter().collect::<Vec<_>>(),
            [Mistake::ShadowAcne, Mistake::PixelCorner]
        );
        assert!(
            set.toggled(Mistake::ShadowAcne)
                .toggled(Mistake::PixelCorner)
                .is_empty()
        );
    }
}
