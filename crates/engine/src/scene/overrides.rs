//! What-if from the command line: `--set KEY=VALUE` changes one setting or
//! one material's number after the scene is read, with the same ranges as
//! the file (`limits.rs`), e.g. `settings.max_depth=2` or
//! `materials.glass.ior=1.0`.

use glam::DVec3;

use super::error::{MAX_MESSAGE_CHARS, bounded};
use super::limits::{self, Bounds};
use super::toml_format::MAX_DEPTH_LIMIT;
use super::{MAX_RAYS_LIMIT, Scene, SpecularModel};

/// Applies `KEY=VALUE` to `scene`, or says why it cannot, in at most
/// `MAX_MESSAGE_CHARS` characters as a scene error would (a 100 KB value is
/// not echoed whole).
pub fn apply(scene: &mut Scene, assignment: &str) -> Result<(), String> {
    applied(scene, assignment).map_err(|why| bounded(why, MAX_MESSAGE_CHARS))
}

fn applied(scene: &mut Scene, assignment: &str) -> Result<(), String> {
    let not_key_value = || format!("`{assignment}` is not KEY=VALUE, e.g. settings.max_depth=2");
    let equals = *outside_quotes(assignment, '=', true)
        .map_err(|_| not_key_value())?
        .first()
        .ok_or_else(not_key_value)?;
    let (key, value) = (assignment[..equals].trim(), assignment[equals + 1..].trim());
    let bad = |why: String| format!("--set {key}={value}: {why}");
    let parts = key_parts(key).map_err(bad)?;
    let parts: Vec<&str> = parts.iter().map(String::as_str).collect();
    match parts.as_slice() {
        ["settings", name] => setting(scene, name, value).map_err(bad),
        ["materials", material, name] => {
            let names: Vec<&str> = scene.materials.iter().map(|m| m.name.as_str()).collect();
            let index = names.iter().position(|n| n == material).ok_or_else(|| {
                bad(format!(
                    "no material {material:?}; the scene has {}",
                    names.join(", ")
                ))
            })?;
            material_number(&mut scene.materials[index], name, value).map_err(bad)
        }
        _ => Err(bad(
            "the key must be settings.NAME or materials.MATERIAL.NAME".into(),
        )),
    }
}

/// Byte offsets of `sep` in `text` outside TOML's quotes (`"..."` with
/// backslash escapes, `'...'` literal), only the first if `first`; a quote
/// left open is an error.
fn outside_quotes(text: &str, sep: char, first: bool) -> Result<Vec<usize>, String> {
    let mut found = Vec::new();
    let (mut quote, mut escaped) = (None, false);
    for (i, c) in text.char_indices() {
        match quote {
            Some('"') if escaped => escaped = false,
            Some('"') if c == '\\' => escaped = true,
            Some(q) if c == q => quote = None,
            Some(_) => {}
            None if c == '"' || c == '\'' => quote = Some(c),
            None if c == sep => {
                found.push(i);
                if first {
                    return Ok(found);
                }
            }
            None => {}
        }
    }
    match quote {
        Some(q) => Err(format!("the quote {q} in `{text}` is not closed")),
        None => Ok(found),
    }
}

/// A key's parts between its dots. A material whose name holds `.` or `=`
/// is reached as TOML reaches it, quoted: `materials."a.b".kd` (read by the
/// TOML reader, so `"\u001b"` means ESC as in the scene); else a part is
/// taken as written, spaces and all (`materials.red paint.kd`).
fn key_parts(key: &str) -> Result<Vec<String>, String> {
    let dots = outside_quotes(key, '.', false)?;
    let starts = std::iter::once(0).chain(dots.iter().map(|d| d + 1));
    let ends = dots.iter().copied().chain(std::iter::once(key.len()));
    starts
        .zip(ends)
        .map(|(start, end)| key_part(key[start..end].trim()))
        .collect()
}

fn key_part(part: &str) -> Result<String, String> {
    if !part.starts_with(['"', '\'']) {
        return Ok(part.to_owned());
    }
    let not_quoted = || format!("{part} is not a quoted TOML key, e.g. \"a.b\"");
    let table: toml::Table = toml::from_str(&format!("{part} = 0")).map_err(|_| not_quoted())?;
    match table.iter().next() {
        Some((name, toml::Value::Integer(0))) if table.len() == 1 => Ok(name.clone()),
        _ => Err(not_quoted()),
    }
}

/// A whole number from 1 to `limit`; -3 is out of range, not "not whole".
fn whole(value: &str, name: &str, limit: u32) -> Result<u32, String> {
    let range = || format!("{name} must be between 1 and {limit}, got {}", value.trim());
    match value.trim().parse::<i64>() {
        Ok(n) => u32::try_from(n)
            .ok()
            .filter(|n| (1..=limit).contains(n))
            .ok_or_else(range),
        Err(_) => Err(format!("{name} is a whole number, e.g. {}", limit.min(3))),
    }
}

fn setting(scene: &mut Scene, name: &str, value: &str) -> Result<(), String> {
    let s = &mut scene.settings;
    match name {
        "max_depth" => {
            s.max_depth = whole(value, "max_depth", MAX_DEPTH_LIMIT)?;
        }
        "max_rays" => {
            s.max_rays = whole(value, "max_rays", MAX_RAYS_LIMIT)?;
        }
        "min_weight" => s.min_weight = number(value, limits::WEIGHT)?,
        "specular" => {
            s.specular = match value {
                "blinn" => SpecularModel::Blinn,
                "phong" => SpecularModel::Phong,
                _ => return Err("specular is blinn or phong".into()),
            }
        }
        "ambient" => s.ambient = vector(value, limits::COLOR)?,
        "background" => s.background = vector(value, limits::COLOR)?,
        "light_attenuation" => s.light_attenuation = vector(value, limits::ATTENUATION)?.into(),
        "ray_attenuation" => s.ray_attenuation = vector(value, limits::ATTENUATION)?.into(),
        _ => {
            return Err(
                "settings are max_depth, max_rays, min_weight, specular, ambient, \
                 background, light_attenuation, ray_attenuation"
                    .into(),
            );
        }
    }
    Ok(())
}

fn material_number(material: &mut super::Material, name: &str, value: &str) -> Result<(), String> {
    match name {
        "kd" => material.kd = number(value, limits::COEFFICIENT)?,
        "ks" => material.ks = number(value, limits::COEFFICIENT)?,
        "ka" => material.ka = number(value, limits::COEFFICIENT)?,
        "kt" => material.kt = number(value, limits::TRANSMISSION)?,
        "n" => material.shininess = number(value, limits::SHININESS)?,
        "ior" => material.ior = number(value, limits::IOR)?,
        "color" => material.color = vector(value, limits::COLOR)?,
        _ => return Err("a material's numbers are kd, ks, ka, kt, n, ior, color".into()),
    }
    Ok(())
}

fn number(value: &str, bounds: Bounds) -> Result<f64, String> {
    let x: f64 = value
        .parse()
        .map_err(|_| format!("`{value}` is not a number"))?;
    bounds.check(x)?;
    Ok(x)
}

/// `[r, g, b]`, `r,g,b`, or one number for all three.
fn vector(value: &str, bounds: Bounds) -> Result<DVec3, String> {
    let inner = match (value.strip_prefix('['), value.ends_with(']')) {
        (Some(opened), true) => &opened[..opened.len() - 1],
        (Some(_), false) => return Err(format!("`{value}` has no closing ]")),
        (None, true) => return Err(format!("`{value}` has no opening [")),
        (None, false) => value,
    };
    let parts: Vec<&str> = inner.split(',').map(str::trim).collect();
    let numbers = parts
        .iter()
        .map(|p| number(p, bounds))
        .collect::<Result<Vec<f64>, String>>()?;
    match numbers.as_slice() {
        [x] => Ok(DVec3::splat(*x)),
        [x, y, z] => Ok(DVec3::new(*x, *y, *z)),
        _ => Err(format!("`{value}` is not one number or three")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::builtin::load_file_or_builtin;

    #[test]
    fn settings_and_materials_change_within_their_ranges() {
        let mut scene = load_file_or_builtin(None).unwrap();
        apply(&mut scene, "settings.max_depth=2").unwrap();
        assert_eq!(scene.settings.max_depth, 2);
        apply(&mut scene, "settings.ambient=[0.1, 0.2, 0.3]").unwrap();
        assert_eq!(scene.settings.ambient, DVec3::new(0.1, 0.2, 0.3));
        let glass = scene.materials[0].name.clone();
        apply(&mut scene, &format!("materials.{glass}.ior=1.0")).unwrap();
        assert_eq!(scene.materials[0].ior, 1.0);
        for (bad, says) in [
            ("settings.max_depth=0", "between 1 and 64"),
            // A negative number is a whole number out of range, not "not whole".
            (
                "settings.max_depth=-3",
                "max_depth must be between 1 and 64, got -3",
            ),
            ("settings.max_rays=2.5", "max_rays is a whole number"),
            ("materials.nowhere.kd=1", "no material \"nowhere\""),
            ("settings.colour=1", "settings are"),
            ("max_depth 2", "not KEY=VALUE"),
            ("settings.specular=cook", "blinn or phong"),
        ] {
            let error = apply(&mut scene, bad).unwrap_err();
            assert!(error.contains(says), "{bad}: {error}");
        }
        // The brackets come in pairs; a 100,000-character value is echoed
        // in at most MAX_MESSAGE_CHARS (400) characters.
        let error = apply(&mut scene, "settings.ambient=[0.1, 0.2").unwrap_err();
        assert!(error.ends_with("`[0.1, 0.2` has no closing ]"), "{error}");
        let long = format!("settings.ambient={}", "x".repeat(100_000));
        let error = apply(&mut scene, &long).unwrap_err();
        assert!(error.chars().count() <= MAX_MESSAGE_CHARS + 1, "{error}");
        assert!(error.ends_with("` is not a number"), "{error}");
        let error = apply(&mut scene, &format!("materials.{glass}.ior=20")).unwrap_err();
        assert!(error.contains("must be between 0.1 and 10"), "{error}");
    }

    #[test]
    fn a_quoted_key_part_is_read_as_toml_reads_it() {
        // Dots and equals signs inside quotes do not split; TOML's escapes
        // hold inside "...", not inside '...'.
        assert_eq!(
            key_parts(r#"materials."a.b".kd"#).unwrap(),
            ["materials", "a.b", "kd"]
        );
        assert_eq!(
            key_parts("materials.'x=y'.kd").unwrap(),
            ["materials", "x=y", "kd"]
        );
        assert_eq!(
            key_parts(r#"materials."\u001b".kd"#).unwrap(),
            ["materials", "\u{1b}", "kd"]
        );
        assert_eq!(
            key_parts(r"materials.'\u001b'.kd").unwrap(),
            ["materials", r"\u001b", "kd"]
        );
        // A bare part is taken as written, spaces and all.
        assert_eq!(
            key_parts("materials.red paint.kd").unwrap(),
            ["materials", "red paint", "kd"]
        );
        assert!(
            key_parts(r#"materials."a.kd"#)
                .unwrap_err()
                .contains("not closed")
        );
        assert!(
            key_parts(r#"materials."a"b.kd"#)
                .unwrap_err()
                .contains("not a quoted")
        );
        assert_eq!(outside_quotes(r#""a=b".kd=1=2"#, '=', true).unwrap(), [8]);
    }
}
