//! Every number of a parsed TOML scene within its range (`scene::limits`),
//! refused at its own line and column with its key, before anything is built.

use super::Source;
use super::schema::{FileDef, MaterialDef, Number, ObjectDef, SettingsDef, Vec3, vec3};
use crate::scene::limits::{
    ATTENUATION, Bounds, COEFFICIENT, COLOR, COORDINATE, IOR, SHININESS, SIZE, TRANSMISSION,
    WEIGHT, check_cone_length, check_cone_radius, show,
};
use crate::scene::{SceneError, check_fov};

/// Checks everything but the objects, which `object` checks one at a time as
/// they are read; the first number out of range is the error.
pub(super) fn file(source: &Source, file: &FileDef) -> Result<(), SceneError> {
    let camera = file.camera.get_ref();
    vector(source, "camera.eye", &camera.eye, COORDINATE)?;
    vector(source, "camera.look_at", &camera.look_at, COORDINATE)?;
    optional_vector(source, "camera.up", &camera.up, COORDINATE)?;
    if let Some(fov) = &camera.fov {
        check_fov(fov.get_ref().0).map_err(|m| source.error(fov.span(), m))?;
    }
    settings(source, &file.settings)?;
    for (name, def) in &file.materials {
        material(source, &format!("materials.{name}"), def.get_ref())?;
    }
    for (i, def) in file.lights.iter().enumerate() {
        let light = def.get_ref();
        optional_vector(
            source,
            &format!("light[{i}].position"),
            &light.position,
            COORDINATE,
        )?;
        if let Some(direction) = &light.direction {
            let key = format!("light[{i}].direction");
            vector(source, &key, direction.get_ref(), COORDINATE)?;
        }
        optional_vector(source, &format!("light[{i}].color"), &light.color, COLOR)?;
        if let Some(attenuation) = &light.attenuation {
            let key = format!("light[{i}].attenuation");
            vector(source, &key, attenuation.get_ref(), ATTENUATION)?;
        }
    }
    Ok(())
}

fn settings(source: &Source, s: &SettingsDef) -> Result<(), SceneError> {
    optional_vector(source, "settings.background", &s.background, COLOR)?;
    optional_vector(source, "settings.ambient", &s.ambient, COLOR)?;
    let light = &s.light_attenuation;
    optional_vector(source, "settings.light_attenuation", light, ATTENUATION)?;
    let ray = &s.ray_attenuation;
    optional_vector(source, "settings.ray_attenuation", ray, ATTENUATION)?;
    if let Some(weight) = &s.min_weight {
        number(source, "settings.min_weight", weight, WEIGHT)?;
    }
    Ok(())
}

fn material(source: &Source, key: &str, m: &MaterialDef) -> Result<(), SceneError> {
    optional_vector(source, &format!("{key}.color"), &m.color, COLOR)?;
    optional_vector(source, &format!("{key}.ambient"), &m.ambient, COLOR)?;
    optional_vector(source, &format!("{key}.emission"), &m.emission, COLOR)?;
    let specular = &m.specular_color;
    optional_vector(source, &format!("{key}.specular_color"), specular, COLOR)?;
    for (name, value, bounds) in [
        ("kd", &m.kd, COEFFICIENT),
        ("ks", &m.ks, COEFFICIENT),
        ("ka", &m.ka, COEFFICIENT),
        ("n", &m.n, SHININESS),
        ("kt", &m.kt, TRANSMISSION),
        ("ior", &m.ior, IOR),
    ] {
        if let Some(value) = value {
            number(source, &format!("{key}.{name}"), value, bounds)?;
        }
    }
    Ok(())
}

pub(super) fn object(source: &Source, key: &str, o: &ObjectDef) -> Result<(), SceneError> {
    if let Some(m) = &o.mesh {
        let (key, d) = (format!("{key}.mesh"), m.get_ref());
        if let Some(scale) = &d.scale {
            number(source, &format!("{key}.scale"), scale, SIZE)?;
        }
        optional_vector(source, &format!("{key}.rotate"), &d.rotate, COORDINATE)?;
        optional_vector(
            source,
            &format!("{key}.translate"),
            &d.translate,
            COORDINATE,
        )?;
    }
    if let Some(s) = &o.sphere {
        let (key, d) = (format!("{key}.sphere"), s.get_ref());
        vector(source, &format!("{key}.center"), &d.center, COORDINATE)?;
        number(source, &format!("{key}.radius"), &d.radius, SIZE)?;
        if let Some(scale) = &d.scale {
            sphere_scale(source, &format!("{key}.scale"), scale)?;
        }
        optional_vector(source, &format!("{key}.rotate"), &d.rotate, COORDINATE)?;
    }
    if let Some(s) = &o.plane {
        let (key, d) = (format!("{key}.plane"), s.get_ref());
        vector(source, &format!("{key}.normal"), &d.normal, COORDINATE)?;
        vector(source, &format!("{key}.point"), &d.point, COORDINATE)?;
    }
    if let Some(s) = &o.polygon {
        vectors(
            source,
            &format!("{key}.polygon.vertices"),
            &s.get_ref().vertices,
        )?;
    }
    if let Some(s) = &o.patch {
        let (key, d) = (format!("{key}.patch"), s.get_ref());
        vectors(source, &format!("{key}.vertices"), &d.vertices)?;
        vectors(source, &format!("{key}.normals"), &d.normals)?;
    }
    if let Some(s) = &o.cylinder {
        let (key, d) = (format!("{key}.cylinder"), s.get_ref());
        cone_end(source, &format!("{key}.base"), &d.base, None)?;
        cone_end(source, &format!("{key}.apex"), &d.apex, None)?;
        number(source, &format!("{key}.radius"), &d.radius, SIZE)?;
        cone_length(source, &key, s.span(), &d.base, &d.apex)?;
    }
    if let Some(s) = &o.cone {
        let (key, d) = (format!("{key}.cone"), s.get_ref());
        cone_end(
            source,
            &format!("{key}.base"),
            &d.base,
            Some(&d.base_radius),
        )?;
        cone_end(
            source,
            &format!("{key}.apex"),
            &d.apex,
            Some(&d.apex_radius),
        )?;
        cone_length(source, &key, s.span(), &d.base, &d.apex)?;
    }
    Ok(())
}

/// An ellipsoid's scale factors: each a size; a zero one is named as what
/// it is, a flattened sphere with no M⁻¹ (MODEL §3).
fn sphere_scale(source: &Source, key: &str, scale: &Vec3) -> Result<(), SceneError> {
    for (i, n) in scale.0.iter().enumerate() {
        if n.get_ref().0 == 0.0 {
            return Err(source.error(
                n.span(),
                format!(
                    "`{key}[{i}]` is 0: a zero scale flattens the sphere and its transform has \
                     no inverse; a scale factor {}",
                    SIZE.check(0.0).unwrap_err()
                ),
            ));
        }
        number(source, &format!("{key}[{i}]"), n, SIZE)?;
    }
    Ok(())
}

/// A cone's end point and, for a cone, its radius (`key` is the point's key,
/// the radius's is `key` + `_radius`).
fn cone_end(
    source: &Source,
    key: &str,
    point: &Vec3,
    radius: Option<&Number>,
) -> Result<(), SceneError> {
    vector(source, key, point, COORDINATE)?;
    let Some(radius) = radius else {
        return Ok(());
    };
    let value = radius.get_ref().0;
    check_cone_radius(value).map_err(|reason| {
        source.error(
            radius.span(),
            format!("`{key}_radius` {reason}, got {}", show(value)),
        )
    })
}

fn cone_length(
    source: &Source,
    key: &str,
    span: std::ops::Range<usize>,
    base: &Vec3,
    apex: &Vec3,
) -> Result<(), SceneError> {
    check_cone_length(vec3(base), vec3(apex))
        .map_err(|reason| source.error(span, format!("`{key}`: {reason}")))
}

fn number(source: &Source, key: &str, n: &Number, bounds: Bounds) -> Result<(), SceneError> {
    let value = n.get_ref().0;
    bounds
        .check(value)
        .map_err(|reason| source.error(n.span(), format!("`{key}` {reason}, got {}", show(value))))
}

fn vector(source: &Source, key: &str, v: &Vec3, bounds: Bounds) -> Result<(), SceneError> {
    for (i, n) in v.0.iter().enumerate() {
        number(source, &format!("{key}[{i}]"), n, bounds)?;
    }
    Ok(())
}

fn optional_vector(
    source: &Source,
    key: &str,
    v: &Option<Vec3>,
    bounds: Bounds,
) -> Result<(), SceneError> {
    v.as_ref()
        .map_or(Ok(()), |v| vector(source, key, v, bounds))
}

fn vectors(source: &Source, key: &str, list: &[Vec3]) -> Result<(), SceneError> {
    for (i, v) in list.iter().enumerate() {
        vector(source, &format!("{key}[{i}]"), v, COORDINATE)?;
    }
    Ok(())
}
