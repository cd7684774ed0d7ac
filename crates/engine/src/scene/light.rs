//! A light of MODEL §4: a point light at a position, or a directional light
//! infinitely far away along a direction (the sun of a scene, CSE 167's
//! `directional`). Where a light's terms need its place, they ask `to` for
//! L and d_L at a point, so the two kinds differ in one `match`.

use glam::DVec3;

use raystep_model::math::Color;

#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    pub name: String,
    pub kind: LightKind,
    /// I_p.
    pub color: Color,
    /// This light's (c1, c2, c3) of f_att, in place of the scene's
    /// `light_attenuation` (TOML `attenuation`, CSE 167's per light); a
    /// directional light is never attenuated.
    pub attenuation: Option<[f64; 3]>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightKind {
    /// P_L: L = normalize(P_L - p), d_L = |P_L - p|.
    Point { position: DVec3 },
    /// The unit direction *to* the light, the same at every point: L is it,
    /// there is no d_L (the shadow ray has no end) and no attenuation.
    Directional { direction: DVec3 },
}

impl Light {
    pub fn point(name: impl Into<String>, position: DVec3, color: Color) -> Light {
        Light {
            name: name.into(),
            kind: LightKind::Point { position },
            color,
            attenuation: None,
        }
    }

    /// A directional light towards `direction`, normalised here (divided by
    /// its length, as a point light's L is: (3, 0, 4) gives (0.6, 0, 0.8)
    /// exactly); `None` when it has no direction (zero, or too small or
    /// large to normalise).
    pub fn directional(name: impl Into<String>, direction: DVec3, color: Color) -> Option<Light> {
        let length = direction.length();
        if !(length > 0.0 && length.is_finite()) {
            return None;
        }
        let direction = direction / length;
        Some(Light {
            name: name.into(),
            kind: LightKind::Directional { direction },
            color,
            attenuation: None,
        })
    }

    /// P_L for a point light; `None` for a directional one, which has none.
    pub fn position(&self) -> Option<DVec3> {
        match self.kind {
            LightKind::Point { position } => Some(position),
            LightKind::Directional { .. } => None,
        }
    }

    pub fn is_directional(&self) -> bool {
        matches!(self.kind, LightKind::Directional { .. })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_direction_is_normalised_and_a_zero_one_refused() {
        // (3, 0, 4) has length 5: its unit direction is (0.6, 0, 0.8).
        let sun = Light::directional("sun", DVec3::new(3.0, 0.0, 4.0), Color::ONE).unwrap();
        let direction = DVec3::new(0.6, 0.0, 0.8);
        assert_eq!(sun.kind, LightKind::Directional { direction });
        assert_eq!(sun.position(), None);
        assert!(Light::directional("none", DVec3::ZERO, Color::ONE).is_none());
        // 1e-200 squared underflows to 0: no length to divide by.
        assert!(Light::directional("tiny", DVec3::splat(1e-200), Color::ONE).is_none());
    }
}
