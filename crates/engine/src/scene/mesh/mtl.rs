//! An MTL material onto the model's material (MODEL §4 "MTL materials"): the
//! table there is this file's contract, rule by rule and warning by warning.

use glam::DVec3;

use crate::scene::Material;
use crate::scene::limits::{COEFFICIENT, COLOR, IOR, SHININESS, TRANSMISSION};
use raystep_model::math::Color;

/// I_p of the point light an emitter becomes is its Ke times this.
pub(crate) const EMITTER_INTENSITY: f64 = 1.0;

/// The fields of one `newmtl` that the model reads.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Read {
    pub(crate) name: String,
    pub(crate) diffuse: Option<DVec3>,
    pub(crate) ambient: Option<DVec3>,
    pub(crate) specular: Option<DVec3>,
    pub(crate) emission: Option<DVec3>,
    pub(crate) shininess: Option<f64>,
    pub(crate) ior: Option<f64>,
    /// `d`, opacity.
    pub(crate) dissolve: Option<f64>,
    /// `Tr`, transparency (1 - d), as Wavefront's own tools write it.
    pub(crate) transparency: Option<f64>,
    /// `Tf`, the transmission filter colour.
    pub(crate) filter: Option<DVec3>,
    pub(crate) illum: Option<u8>,
    /// The `map_*`, `bump`, `disp`, `decal` and `refl` statements, by keyword.
    pub(crate) maps: Vec<String>,
    /// What reading kept from the file's own numbers, as `to_model` words
    /// its warnings (an emission clamped).
    pub(crate) warnings: Vec<String>,
}

impl Read {
    pub(crate) fn from_tobj(m: &tobj::Material) -> Self {
        let v = |a: Option<[f64; 3]>| a.map(DVec3::from_array);
        let number = |key: &str| {
            m.unknown_param
                .get(key)
                .and_then(|t| t.split_whitespace().next()?.parse::<f64>().ok())
        };
        let (emission, warnings) = emission(v(m.emissive));
        let filter = m.unknown_param.get("Tf").and_then(|t| {
            let mut it = t.split_whitespace().map(|w| w.parse::<f64>().ok());
            let r = it.next()??;
            // One number is a grey filter; three are a colour.
            match (it.next().flatten(), it.next().flatten()) {
                (Some(g), Some(b)) => Some(DVec3::new(r, g, b)),
                _ => Some(DVec3::splat(r)),
            }
        });
        let mut maps: Vec<String> = [
            ("map_Ka", &m.ambient_texture),
            ("map_Kd", &m.diffuse_texture),
            ("map_Ks", &m.specular_texture),
            ("map_Bump", &m.normal_texture),
            ("map_Ns", &m.shininess_texture),
            ("map_d", &m.dissolve_texture),
        ]
        .into_iter()
        .filter(|(_, t)| t.is_some())
        .map(|(k, _)| k.to_string())
        .collect();
        let mut others: Vec<String> = m
            .unknown_param
            .keys()
            .filter(|k| {
                k.starts_with("map_") || ["disp", "decal", "refl", "bump"].contains(&k.as_str())
            })
            .cloned()
            .collect();
        others.sort();
        maps.extend(others);
        Self {
            name: m.name.clone(),
            diffuse: v(m.diffuse),
            ambient: v(m.ambient),
            specular: v(m.specular),
            emission,
            shininess: m.shininess,
            ior: m.optical_density,
            dissolve: m.dissolve,
            transparency: number("Tr"),
            filter,
            illum: m.illumination_model,
            maps,
            warnings,
        }
    }
}

/// `Ke` within the range of a colour, channel by channel (an infinite Ke
/// gave NaN pixels, a Ke of -1e308 a light that darkens), with a warning;
/// `None` when no channel is above 0 (no emitter).
fn emission(ke: Option<DVec3>) -> (Option<DVec3>, Vec<String>) {
    let Some(ke) = ke else {
        return (None, Vec::new());
    };
    let channel = |c: f64| {
        if c.is_nan() {
            COLOR.min
        } else {
            c.clamp(COLOR.min, COLOR.max)
        }
    };
    let kept = DVec3::new(channel(ke.x), channel(ke.y), channel(ke.z));
    let warnings = if kept == ke {
        Vec::new()
    } else {
        vec![format!(
            "Ke {ke} is outside {}..{}: {kept} is used",
            COLOR.min, COLOR.max
        )]
    };
    (Some(kept).filter(|e| e.max_element() > 0.0), warnings)
}

/// Which of the model's secondary rays an `illum` level asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Illum {
    pub(crate) highlights: bool,
    pub(crate) reflects: bool,
    pub(crate) transmits: bool,
}

/// MTL's illumination levels (Wavefront's table) as the model can follow them.
pub(crate) fn illum(level: u8) -> Option<Illum> {
    let (highlights, reflects, transmits) = match level {
        0 | 1 => (false, false, false),
        2 => (true, false, false),
        3 | 5 | 8 => (true, true, false),
        4 | 6 | 7 | 9 => (true, true, true),
        _ => return None,
    };
    Some(Illum {
        highlights,
        reflects,
        transmits,
    })
}

fn mean(c: DVec3) -> f64 {
    (c.x + c.y + c.z) / 3.0
}

fn is_grey(c: DVec3) -> bool {
    c.x == c.y && c.y == c.z
}

/// The model's material for an MTL material, and a warning for each rule
/// that could not keep what the MTL says.
pub(crate) fn to_model(m: &Read) -> (Material, Vec<String>) {
    let mut warnings = m.warnings.clone();
    let mut clamp = |what: &str, value: f64, min: f64, max: f64| -> f64 {
        if value.is_finite() && (min..=max).contains(&value) {
            value
        } else {
            let kept = if value.is_nan() {
                min
            } else {
                value.clamp(min, max)
            };
            warnings.push(format!(
                "{what} {value} is outside {min}..{max}: {kept} is used"
            ));
            kept
        }
    };
    let diffuse = m.diffuse.unwrap_or(Color::ONE);
    let color = DVec3::new(
        clamp("Kd red", diffuse.x, COLOR.min, COLOR.max),
        clamp("Kd green", diffuse.y, COLOR.min, COLOR.max),
        clamp("Kd blue", diffuse.z, COLOR.min, COLOR.max),
    );
    let ka = match m.ambient {
        Some(a) => clamp("Ka (mean)", mean(a), COEFFICIENT.min, COEFFICIENT.max),
        None => 1.0,
    };
    let mut ks = match m.specular {
        Some(s) => clamp("Ks (mean)", mean(s), COEFFICIENT.min, COEFFICIENT.max),
        None => 0.0,
    };
    let shininess = match m.shininess {
        Some(n) => clamp("Ns", n, SHININESS.min, SHININESS.max),
        None => 20.0,
    };
    let ior = match m.ior {
        Some(n) => clamp("Ni", n, IOR.min, IOR.max),
        None => 1.0,
    };
    let mut kt = match (m.dissolve, m.transparency, m.filter) {
        (Some(d), _, _) => 1.0 - clamp("d", d, TRANSMISSION.min, TRANSMISSION.max),
        (None, Some(tr), _) => clamp("Tr", tr, TRANSMISSION.min, TRANSMISSION.max),
        (None, None, Some(tf)) => clamp("Tf (mean)", mean(tf), TRANSMISSION.min, TRANSMISSION.max),
        (None, None, None) => 0.0,
    };
    if let Some(a) = m.ambient
        && !is_grey(a)
    {
        warnings.push(format!(
            "Ka {a} is coloured: the model's k_a is one number, their mean {ka} is used"
        ));
    }
    if let Some(s) = m.specular
        && !is_grey(s)
    {
        warnings.push(format!(
            "Ks {s} is coloured: the model's k_s is one number, their mean {ks} is used"
        ));
    }
    if let Some(tf) = m.filter
        && !is_grey(tf)
    {
        warnings.push(format!(
            "Tf {tf} is coloured: the model's k_t is one number (the transmitted light is not filtered)"
        ));
    }
    let level = m.illum.unwrap_or(2);
    let rays = illum(level).unwrap_or_else(|| {
        warnings.push(format!(
            "illum {level} is not a level the model follows (0 to 9): read as 2 (highlights, no reflection)"
        ));
        illum(2).expect("level 2 is in the table")
    });
    if level == 0 {
        warnings.push("illum 0 (colour only, no lighting) is read as 1 (diffuse)".into());
    }
    if !rays.highlights && ks > 0.0 {
        warnings.push(format!(
            "illum {level} has no highlights: Ks is not used (k_s = 0)"
        ));
        ks = 0.0;
    }
    if !rays.transmits && kt > 0.0 {
        warnings.push(format!(
            "illum {level} does not transmit: d/Tr/Tf is not used (k_t = 0)"
        ));
        kt = 0.0;
    }
    if !m.maps.is_empty() {
        warnings.push(format!(
            "{} ignored: raystep has no textures",
            m.maps.join(", ")
        ));
    }
    let material = Material {
        name: m.name.clone(),
        color,
        kd: 1.0,
        ks,
        shininess,
        kt,
        ior,
        ka,
        specular: None,
        reflects: rays.reflects,
        ..Material::default_white()
    };
    (material, warnings)
}
