use std::path::Path;

use glam::DVec3;

use super::mtl::{self, Read};
use super::*;

fn obj(text: &str) -> Result<Loaded, SceneError> {
    obj::parse(Path::new("t.obj"), text.as_bytes(), &|_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
}

#[test]
fn a_quad_is_two_triangles_of_its_group() {
    let loaded = obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\ng wall\nf 1 2 3 4\n").unwrap();
    assert_eq!(loaded.triangles.len(), 2);
    assert_eq!(loaded.groups, ["wall"]);
    // Fan triangulation: (1 2 3) and (1 3 4).
    assert_eq!(loaded.triangles[1].vertices[2], DVec3::new(0.0, 1.0, 0.0));
    assert!(loaded.triangles[0].normals.is_none());
}

#[test]
fn a_face_index_out_of_range_is_named_at_its_line_and_column() {
    let e = obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 9\n").unwrap_err();
    let at = e.location.as_ref().unwrap();
    assert_eq!((at.line, at.column), (4, 7));
    assert!(
        e.message.contains("index 9 is out of range: 3 `v`"),
        "{}",
        e.message
    );
}

#[test]
fn placement_scales_then_rotates_then_translates() {
    // (1, 0, 0) scaled by 2 is (2, 0, 0); 90° about z takes it to (0, 2, 0);
    // moved by (0, 0, 5): (0, 2, 5).
    let p = Placement {
        scale: 2.0,
        rotate: DVec3::new(0.0, 0.0, 90.0),
        translate: DVec3::new(0.0, 0.0, 5.0),
    };
    let q = p.rotation() * (DVec3::X * p.scale) + p.translate;
    assert!((q - DVec3::new(0.0, 2.0, 5.0)).length() < 1e-12, "{q}");
}

#[test]
fn illum_2_highlights_without_a_mirror() {
    let read = Read {
        name: "m".into(),
        specular: Some(DVec3::splat(0.5)),
        illum: Some(2),
        ..Read::default()
    };
    let (m, warnings) = mtl::to_model(&read);
    assert_eq!((m.ks, m.reflects), (0.5, false));
    assert!(warnings.is_empty(), "{warnings:?}");
}

#[test]
fn a_face_without_vn_stays_flat_in_a_file_that_has_normals() {
    // tobj gives the second face's corners a made-up normal (the first
    // `vn`, here +x); that face has none of its own, so it is flat.
    let loaded = obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 1 0 0\n\
                      f 1//1 2//1 3//1\nf 1 2 4 3\n")
    .unwrap();
    assert_eq!(loaded.triangles.len(), 3);
    assert!(loaded.triangles[0].normals.is_some());
    assert!(loaded.triangles[1].normals.is_none());
    assert!(loaded.triangles[2].normals.is_none());
}
