//! The TOML scene file's schema: what serde reads, each table a struct
//! whose fields are the file's keys, with where each was written
//! (`Spanned`) so that a check can point at it. Reading only: the numbers'
//! ranges are checked in `bounds.rs`, the scene is built in
//! `toml_format.rs`.

use std::collections::BTreeMap;
use std::fmt;

use glam::DVec3;
use serde::Deserialize;
use toml::Spanned;

use crate::scene::{Profile, SpecularModel};

/// A number that must be finite: TOML allows `nan` and `inf`, scenes do not.
#[derive(Clone, Copy, Debug)]
pub(super) struct Finite(pub(super) f64);

impl<'de> Deserialize<'de> for Finite {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = f64::deserialize(deserializer)?;
        if value.is_finite() {
            Ok(Finite(value))
        } else {
            Err(serde::de::Error::custom(format!(
                "numbers must be finite, got {value}"
            )))
        }
    }
}

/// A finite number and where it is written, so that a range check can point at it.
pub(super) type Number = Spanned<Finite>;

pub(super) fn number(n: &Number) -> f64 {
    n.get_ref().0
}

/// Exactly three finite numbers, each with its place: a fourth element or a
/// missing third is an error, never dropped or defaulted.
#[derive(Clone, Debug)]
pub(super) struct Vec3(pub(super) [Number; 3]);

impl<'de> Deserialize<'de> for Vec3 {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_seq(Vec3Visitor)
    }
}

struct Vec3Visitor;

impl<'de> serde::de::Visitor<'de> for Vec3Visitor {
    type Value = Vec3;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("an array of three numbers")
    }

    fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Vec3, A::Error> {
        let mut values = Vec::with_capacity(3);
        while values.len() < 3 {
            match seq.next_element::<Number>()? {
                Some(value) => values.push(value),
                None => return Err(wrong_length(values.len())),
            }
        }
        // Count the extra elements, whatever they are, to say how many there were.
        let mut length = 3;
        while seq.next_element::<serde::de::IgnoredAny>()?.is_some() {
            length += 1;
        }
        match <[Number; 3]>::try_from(values) {
            Ok(values) if length == 3 => Ok(Vec3(values)),
            _ => Err(wrong_length(length)),
        }
    }
}

fn wrong_length<E: serde::de::Error>(length: usize) -> E {
    E::custom(format!(
        "expected an array of three numbers (x, y, z or red, green, blue), got {length}"
    ))
}

pub(super) fn vec3(v: &Vec3) -> DVec3 {
    DVec3::new(number(&v.0[0]), number(&v.0[1]), number(&v.0[2]))
}

pub(super) fn triple(v: &Vec3) -> [f64; 3] {
    vec3(v).to_array()
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileDef {
    pub(super) camera: Spanned<CameraDef>,
    pub(super) image: Option<Spanned<ImageDef>>,
    #[serde(default)]
    pub(super) settings: SettingsDef,
    #[serde(default)]
    pub(super) materials: BTreeMap<String, Spanned<MaterialDef>>,
    #[serde(default, rename = "light")]
    pub(super) lights: Vec<Spanned<LightDef>>,
    /// `None` when the file has no objects or they were cut out to be read
    /// one by one (`toml_sections`).
    #[serde(default, rename = "object")]
    pub(super) objects: Option<Vec<Spanned<ObjectDef>>>,
}

/// One `[[object]]` section read on its own.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ObjectSectionDef {
    #[serde(rename = "object")]
    pub(super) objects: Vec<Spanned<ObjectDef>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CameraDef {
    pub(super) eye: Vec3,
    pub(super) look_at: Vec3,
    pub(super) up: Option<Vec3>,
    pub(super) fov: Option<Number>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ImageDef {
    pub(super) width: u32,
    pub(super) height: u32,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct SettingsDef {
    pub(super) background: Option<Vec3>,
    pub(super) ambient: Option<Vec3>,
    pub(super) light_attenuation: Option<Vec3>,
    pub(super) ray_attenuation: Option<Vec3>,
    pub(super) max_depth: Option<Spanned<u32>>,
    pub(super) min_weight: Option<Spanned<Finite>>,
    pub(super) max_rays: Option<Spanned<u32>>,
    pub(super) specular: Option<SpecularModel>,
    /// Which equation the scene means (MODEL §11).
    pub(super) profile: Option<Profile>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MaterialDef {
    pub(super) color: Option<Vec3>,
    pub(super) kd: Option<Number>,
    pub(super) ks: Option<Number>,
    pub(super) n: Option<Number>,
    pub(super) kt: Option<Number>,
    pub(super) ior: Option<Number>,
    pub(super) ka: Option<Number>,
    pub(super) specular: Option<SpecularModel>,
    /// False: k_s gives highlights but no mirror-reflected ray (MODEL §5).
    pub(super) reflect: Option<bool>,
    /// The ambient term as it is, in place of k_a I_a O_d (MODEL §1).
    pub(super) ambient: Option<Vec3>,
    /// E, added as it is (MODEL §1).
    pub(super) emission: Option<Vec3>,
    /// The specular term's colour S (MODEL §4, §11).
    pub(super) specular_color: Option<Vec3>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct LightDef {
    pub(super) name: Option<String>,
    /// A point light's P_L; exactly one of `position` and `direction`.
    pub(super) position: Option<Vec3>,
    /// A directional light's direction *to* the light (normalised on load).
    pub(super) direction: Option<Spanned<Vec3>>,
    pub(super) color: Option<Vec3>,
    /// This light's (c1, c2, c3) of f_att, in place of the scene's.
    pub(super) attenuation: Option<Spanned<Vec3>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ObjectDef {
    pub(super) name: Option<Spanned<String>>,
    /// Required, except for a mesh (whose MTL gives its materials).
    pub(super) material: Option<Spanned<String>>,
    pub(super) mesh: Option<Spanned<MeshDef>>,
    pub(super) sphere: Option<Spanned<SphereDef>>,
    pub(super) plane: Option<Spanned<PlaneDef>>,
    pub(super) polygon: Option<Spanned<PolygonDef>>,
    pub(super) patch: Option<Spanned<PatchDef>>,
    pub(super) cylinder: Option<Spanned<CylinderDef>>,
    pub(super) cone: Option<Spanned<ConeDef>>,
}

/// `mesh = { file = "box.obj", scale = 2, rotate = [0, 30, 0], translate = [1, 0, 0] }`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MeshDef {
    pub(super) file: Spanned<String>,
    pub(super) scale: Option<Number>,
    /// Degrees about x, then y, then z.
    pub(super) rotate: Option<Vec3>,
    pub(super) translate: Option<Vec3>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SphereDef {
    pub(super) center: Vec3,
    pub(super) radius: Number,
    /// An ellipsoid (MODEL §3): the sphere's own x, y, z stretched by
    /// these factors, then `rotate`d about its centre.
    pub(super) scale: Option<Vec3>,
    /// Degrees about x, then y, then z, as a mesh's.
    pub(super) rotate: Option<Vec3>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PlaneDef {
    pub(super) normal: Vec3,
    pub(super) point: Vec3,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PolygonDef {
    pub(super) vertices: Vec<Vec3>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PatchDef {
    pub(super) vertices: Vec<Vec3>,
    pub(super) normals: Vec<Vec3>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CylinderDef {
    pub(super) base: Vec3,
    pub(super) apex: Vec3,
    pub(super) radius: Number,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ConeDef {
    pub(super) base: Vec3,
    pub(super) base_radius: Number,
    pub(super) apex: Vec3,
    pub(super) apex_radius: Number,
}
