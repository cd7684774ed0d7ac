//! STL, ASCII or binary, with `stl_io`. STL triangles carry a facet normal
//! but no vertex normals: every triangle is flat (its normal comes from its
//! vertices' order, as an OBJ face's does; the stored one is not used).
//! `stl_io`'s errors carry no line: a bad ASCII STL is named by file only.

use std::io::Cursor;
use std::path::Path;

use glam::DVec3;

use super::{Loaded, Triangle, read_file};
use crate::scene::SceneError;
use crate::scene::limits::COORDINATE;

pub(super) fn load(path: &Path) -> Result<Loaded, SceneError> {
    let bytes = read_file(path, "mesh file").map_err(SceneError::plain)?;
    parse(path, &bytes)
}

pub(super) fn parse(path: &Path, bytes: &[u8]) -> Result<Loaded, SceneError> {
    let fail = |what: String| SceneError::plain(format!("{}: {what}", path.display()));
    check_binary_length(bytes).map_err(fail)?;
    let mut cursor = Cursor::new(bytes);
    let reader = stl_io::create_stl_reader(&mut cursor)
        .map_err(|e| fail(format!("not a readable STL file: {e}")))?;
    let stem = path
        .file_stem()
        .map_or("mesh".into(), |s| s.to_string_lossy().into_owned());
    let mut loaded = Loaded {
        groups: vec![stem],
        ..Loaded::default()
    };
    for (index, triangle) in reader.enumerate() {
        let triangle =
            triangle.map_err(|e| fail(format!("triangle {index} cannot be read: {e}")))?;
        let vertices = triangle
            .vertices
            .map(|v| DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64));
        for v in &vertices {
            if let Some(c) = v.to_array().into_iter().find(|c| !c.is_finite()) {
                return Err(fail(format!(
                    "triangle {index}: numbers must be finite, got {c}"
                )));
            }
            if v.to_array().iter().any(|c| COORDINATE.check(*c).is_err()) {
                return Err(fail(format!(
                    "triangle {index}: vertex {v} is outside the model's bounds ({}..{})",
                    COORDINATE.min, COORDINATE.max
                )));
            }
        }
        loaded.triangles.push(Triangle {
            vertices,
            normals: None,
            group: 0,
            material: None,
        });
    }
    Ok(loaded)
}

/// A binary STL (one that does not start with `solid`) is an 80-byte header,
/// a triangle count and 50 bytes per triangle: a file shorter than its count
/// says is truncated (said here, with both lengths, before any is read).
fn check_binary_length(bytes: &[u8]) -> Result<(), String> {
    if bytes.starts_with(b"solid") && !looks_binary(bytes) {
        return Ok(());
    }
    if bytes.len() < 84 {
        return Err(format!(
            "a binary STL starts with 84 bytes (header and triangle count); the file has {}",
            bytes.len()
        ));
    }
    let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
    let expected = 84 + 50 * count;
    if (bytes.len() as u64) < expected {
        return Err(format!(
            "truncated binary STL: {count} triangles need {expected} bytes, the file has {}",
            bytes.len()
        ));
    }
    Ok(())
}

/// Some binary STLs begin their header with `solid` too: such a file's
/// length matches its triangle count exactly.
fn looks_binary(bytes: &[u8]) -> bool {
    bytes.len() >= 84 && {
        let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
        bytes.len() as u64 == 84 + 50 * count
    }
}
