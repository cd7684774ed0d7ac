//! Which illumination equation a scene means (issue 42). The lecture's model
//! (MODEL §1-§6) is one course's; UCSD's CSE 167 (and its edX course
//! CSE167x) hands out scenes whose equation differs from it in a few
//! places. A profile names the variant, so that raystep traces a scene as
//! its course means it without bending the lecture's model: every
//! difference is one question here, asked by `trace::Rules`, and written in
//! MODEL §11.

use serde::{Deserialize, Serialize};

use raystep_model::mistakes::{ActsOn, Mistake};

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Profile {
    /// The lecture's model, MODEL §1-§6 (the default).
    #[default]
    Lecture,
    /// CSE 167's: I = A + E + Σ V L / (c0 + c1 d + c2 d²) [D (N·L)₊ +
    /// S (N·H)₊^s] + S I_R, MODEL §11.
    Cse167,
}

impl Profile {
    pub const ALL: [Profile; 2] = [Profile::Lecture, Profile::Cse167];

    /// As a scene names it (`profile = "cse167"`).
    pub fn name(self) -> &'static str {
        match self {
            Profile::Lecture => "lecture",
            Profile::Cse167 => "cse167",
        }
    }

    /// What a reader is told of the profile a pixel is traced with; nothing
    /// for the lecture's, the model every page assumes.
    pub fn words(self) -> Option<&'static str> {
        match self {
            Profile::Lecture => None,
            Profile::Cse167 => Some(
                "It is traced with the cse167 profile, CSE 167's equation (MODEL §11): \
                 ambient and emission added as they are, f_att not clamped, a light behind \
                 the surface still casts its shadow ray and adds its highlight, the mirror \
                 ray weighted by k_s O_s, and no refraction.",
            ),
        }
    }

    pub fn is_lecture(&self) -> bool {
        *self == Profile::Lecture
    }

    /// Whether a light behind the surface (N·L <= 0) adds nothing and casts
    /// no shadow ray (the lecture), or still casts its shadow ray and adds
    /// its highlight, the diffuse term taking (N·L)₊ (CSE 167: the specular
    /// term has no N·L > 0 condition).
    pub(crate) fn light_behind_adds_nothing(self) -> bool {
        self == Profile::Lecture
    }

    /// Whether f_att is min(1, 1 / (c1 + c2 d + c3 d²)) (the lecture) or
    /// the quotient as it is (CSE 167: no clamp).
    pub(crate) fn clamps_attenuation(self) -> bool {
        self == Profile::Lecture
    }

    /// Whether the mirror ray's weight k_s is multiplied by the material's
    /// specular colour S (CSE 167: the mirror ray adds S ∘ I_R).
    pub(crate) fn mirror_takes_specular_colour(self) -> bool {
        self == Profile::Cse167
    }

    /// Whether a material with k_t > 0 refracts (CSE 167's tracer casts no
    /// transmitted ray, and its shadows are 0 or 1).
    pub fn refracts(self) -> bool {
        self == Profile::Lecture
    }

    /// Whether the debugger's menu, the page's, `--mistake` and `compare`
    /// offer `mistake` under this profile: not when the profile has nothing
    /// for it to change (MODEL §11). Under cse167 that is the three that act
    /// on refraction (eta-inverted, tir-dropped, refraction-outward-normal):
    /// no transmitted ray is cast. Every other mistake still means something
    /// there: opaque-shadows because S_i is still the product of the
    /// crossings' k_t (a TOML scene may give k_t); two-sided-diffuse because
    /// the course's diffuse term takes (N·L)₊, not |N·L|; clamp-before-adding
    /// because S ∘ I_R is still added after the local colour;
    /// phong-not-blinn because the course's highlight is Blinn's N·H;
    /// inverse-square and no-light-attenuation because its lights are
    /// attenuated by the scene's (c0, c1, c2); the rest act on shadow rays,
    /// the mirror ray, the camera or the bytes, which it shares with the
    /// lecture.
    pub fn offers(self, mistake: Mistake) -> bool {
        match mistake.acts_on() {
            ActsOn::Refraction => self.refracts(),
            ActsOn::ShadowRays
            | ActsOn::TransparentShadows
            | ActsOn::LightAttenuation
            | ActsOn::Ambient
            | ActsOn::Highlights
            | ActsOn::SecondaryRays
            | ActsOn::Lights
            | ActsOn::ShadowOrSecondaryRays
            | ActsOn::AnyScene => true,
        }
    }

    /// The mistakes this profile offers (`offers`), in catalogue order.
    pub fn offered_mistakes(self) -> impl Iterator<Item = Mistake> {
        Mistake::ALL.into_iter().filter(move |&m| self.offers(m))
    }

    /// Why `mistake` is not offered under this profile, in words that
    /// follow the mistake's name ("has no meaning under the cse167 profile:
    /// it has no refraction (MODEL §11)"), as every refusal says it; `None`
    /// when it is offered.
    pub fn why_not_offered(self, mistake: Mistake) -> Option<String> {
        if self.offers(mistake) {
            return None;
        }
        let why = match mistake.acts_on() {
            ActsOn::Refraction => "it has no refraction (MODEL §11)",
            _ => "it has nothing for it to change (MODEL §11)",
        };
        Some(format!(
            "has no meaning under the {} profile: {why}",
            self.name()
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cse167_offers_every_mistake_but_the_three_of_refraction() {
        // MODEL §11: cse167 casts no transmitted ray, so the mistakes of
        // Snell's law, TIR and the leaving normal cannot change a pixel.
        let refraction = [
            Mistake::EtaInverted,
            Mistake::TirDropped,
            Mistake::RefractionOutwardNormal,
        ];
        let offered: Vec<Mistake> = Profile::Cse167.offered_mistakes().collect();
        assert_eq!(offered.len(), Mistake::ALL.len() - 3);
        for mistake in Mistake::ALL {
            assert_eq!(
                Profile::Cse167.offers(mistake),
                !refraction.contains(&mistake),
                "{mistake}"
            );
        }
        assert_eq!(
            Profile::Cse167
                .why_not_offered(Mistake::TirDropped)
                .as_deref(),
            Some("has no meaning under the cse167 profile: it has no refraction (MODEL §11)")
        );
        assert_eq!(
            Profile::Cse167.why_not_offered(Mistake::OpaqueShadows),
            None
        );
    }

    #[test]
    fn the_lecture_offers_the_whole_catalogue() {
        let offered: Vec<Mistake> = Profile::Lecture.offered_mistakes().collect();
        assert_eq!(offered, Mistake::ALL);
    }
}
