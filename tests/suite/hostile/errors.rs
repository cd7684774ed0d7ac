//! Errors that say what and where (issue 41, section 4): a student's file
//! that raystep cannot read is named with its line and column and what is
//! wrong there, never "face parse error" alone; what Notepad writes (a
//! byte-order mark) and what most OBJ readers take (a comment after a face)
//! are read; a mesh that draws nothing is never a silent empty render; a
//! binary STL whose header starts with `solid` is read as binary; and an
//! assignment's scene that is a FIFO, a folder or a device is said to be one.

use std::fs;
use std::path::Path;
use std::process::Command;

use super::files::{mkfifo, refused as refused_run, run};
use crate::support::{raystep, stderr, stdout};

/// Writes `files` (name, contents) into a fresh folder.
fn folder(files: &[(&str, &[u8])]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (name, contents) in files {
        fs::write(dir.path().join(name), contents).unwrap();
    }
    dir
}

/// `raystep render scene --size 24x18` run in `dir` (so that messages name
/// files as the test does): its exit code, standard error and the PNG's
/// bytes (empty when none was written).
fn render(dir: &Path, scene: &str) -> (Option<i32>, String, Vec<u8>) {
    let out = format!("{scene}.png");
    let output = Command::new(env!("CARGO_BIN_EXE_raystep"))
        .args(["render", scene, "-o", &out, "--size", "24x18"])
        .current_dir(dir)
        .output()
        .expect("raystep runs");
    let png = fs::read(dir.join(&out)).unwrap_or_default();
    (output.status.code(), stderr(&output), png)
}

/// `files` rendered as `scene` is refused: exit 1, no image, and standard
/// error starts `error: ` + `expected` (the file, its line and column, and
/// the words), with no panic.
fn refused(files: &[(&str, &[u8])], scene: &str, expected: &str) {
    let dir = folder(files);
    let (code, err, png) = render(dir.path(), scene);
    assert_eq!(code, Some(1), "{scene}: {err}");
    assert!(
        err.starts_with(&format!("error: {expected}")),
        "expected `error: {expected}` in:\n{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    assert!(png.is_empty());
}

/// The same image from two sets of files, each rendered without a warning.
fn same_image(a: &[(&str, &[u8])], b: &[(&str, &[u8])], scene: &str) {
    let (a, b) = (folder(a), folder(b));
    let (code_a, err_a, png_a) = render(a.path(), scene);
    let (code_b, err_b, png_b) = render(b.path(), scene);
    assert_eq!((code_a, code_b), (Some(0), Some(0)), "{err_a}\n{err_b}");
    assert_eq!((err_a.as_str(), err_b.as_str()), ("", ""));
    assert!(!png_a.is_empty() && png_a == png_b, "the two images differ");
}

const TRIANGLE: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
const BOM: &str = "\u{feff}";

#[test]
fn an_obj_its_mtl_and_a_ray_log_with_a_byte_order_mark_are_read() {
    // Notepad and PowerShell 5 write EF BB BF first. main read the OBJ's
    // first line as the keyword "\u{feff}v", unknown, so `f 1 2 3` had 2
    // vertices before it ("index 3 is out of range"); an MTL's first
    // `newmtl` was lost the same way (a warning, and white faces); and a
    // ray log's first line was "not JSON".
    let obj = format!("mtllib m.mtl\n{TRIANGLE}usemtl red\nf 1 2 3\n");
    let mtl = "newmtl red\nKd 1 0 0\n";
    let (obj_bom, mtl_bom) = (format!("{BOM}{obj}"), format!("{BOM}{mtl}"));
    same_image(
        &[("m.obj", obj.as_bytes()), ("m.mtl", mtl.as_bytes())],
        &[("m.obj", obj_bom.as_bytes()), ("m.mtl", mtl_bom.as_bytes())],
        "m.obj",
    );

    // raystep's own log of one pixel, compared with and without the mark:
    // the same report, word for word.
    let dir = tempfile::tempdir().unwrap();
    let scene = "scenes/seven-rays.toml";
    let logged = raystep(&["inspect", scene, "--pixel", "80,60", "--format", "raylog"]);
    assert!(logged.status.success(), "{}", stderr(&logged));
    // One name in two folders: the report names the log.
    let (plain_log, marked_log) = (
        dir.path().join("rays.jsonl"),
        dir.path().join("m/rays.jsonl"),
    );
    fs::create_dir(dir.path().join("m")).unwrap();
    fs::write(&plain_log, &logged.stdout).unwrap();
    fs::write(&marked_log, [BOM.as_bytes(), &logged.stdout].concat()).unwrap();
    let compare = |log: &Path| raystep(&["compare", scene, "--rays", log.to_str().unwrap()]);
    let (plain, marked) = (compare(&plain_log), compare(&marked_log));
    assert!(plain.status.success(), "{}", stderr(&plain));
    assert!(
        stdout(&plain).contains("Every logged ray matches."),
        "{}",
        stdout(&plain)
    );
    assert_eq!(
        marked.status.code(),
        plain.status.code(),
        "{}",
        stderr(&marked)
    );
    let names = |p: &Path| p.to_str().unwrap().to_owned();
    assert_eq!(
        stdout(&marked),
        stdout(&plain).replace(&names(&plain_log), &names(&marked_log))
    );
    assert_eq!(stderr(&marked), stderr(&plain));
}

#[test]
fn what_tobj_refused_without_a_line_is_named_at_its_line_and_column() {
    // main said "m.obj: color parse error (too many or too few
    // components)" for the first two, "face vertex color index out of
    // bounds" for the third, and "position parse error" for the fourth:
    // no line. A `v` takes x y z and then nothing, a weight w (1 number)
    // or a colour r g b (3): 5 and 7 numbers are neither; the extra
    // numbers start at column 9 ("v 1 2 3 " is 8 characters).
    let cases: &[(&str, &str)] = &[
        (
            "v 1 2 3 4 5\nf 1 2 3\n",
            "m.obj:4:9: `v` takes x y z, then a weight w or a colour r g b: this one has 5 numbers",
        ),
        (
            "v 1 2 3 4 5 6 7\nf 1 2 3\n",
            "m.obj:4:9: `v` takes x y z, then a weight w or a colour r g b: this one has 7 numbers",
        ),
        // A `\` ending a line: Wavefront's line continuation, read by
        // neither tobj nor raystep; said at the backslash (column 9).
        (
            "v 1 2 3 \\\nf 1 2 3\n",
            "m.obj:4:9: a `\\` line continuation is not read",
        ),
    ];
    for (line, expected) in cases {
        let obj = format!("{TRIANGLE}{line}");
        refused(&[("m.obj", obj.as_bytes())], "m.obj", expected);
    }
    // Colours on the first vertex only: line 2's `v` is the first without.
    refused(
        &[("m.obj", b"v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")],
        "m.obj",
        "m.obj:2:1: vertex colours on some vertices only: this `v` has none, the first `v` (line 1) has one",
    );
    // An MTL tobj refuses (illum is read as a byte) falls back to white,
    // as a missing MTL does, with a warning naming the MTL's line 2.
    let obj = format!("mtllib m.mtl\n{TRIANGLE}usemtl a\nf 1 2 3\n");
    let dir = folder(&[
        ("m.obj", obj.as_bytes()),
        ("m.mtl", b"newmtl a\nillum 99999999999999999999\n"),
    ]);
    let (code, err, _) = render(dir.path(), "m.obj");
    assert_eq!(code, Some(0), "{err}");
    assert!(
        err.contains("m.mtl:2: material parse error in `illum 99999999999999999999`"),
        "{err}"
    );
}

#[test]
fn a_vertex_weight_of_zero_nan_tiny_or_infinite_is_refused_at_its_column() {
    // tobj divides x, y and z by w. main: w = 0 was "scaling (w) by zero"
    // with no line; NaN made a NaN vertex, refused only once placed and by
    // triangle; 1e-300 put x at 1e300, refused the same way; infinity put
    // the vertex at the origin and rendered. The weight is column 9.
    let cases: &[(&str, &str)] = &[
        ("0", "m.obj:1:9: vertex weight w is 0"),
        ("nan", "m.obj:1:9: numbers must be finite, got nan"),
        (
            "1e-300",
            "m.obj:1:9: vertex weight w = 1e-300 puts the vertex out of bounds: \
             x/w, y/w and z/w must be between -10000 and 10000",
        ),
        ("inf", "m.obj:1:9: numbers must be finite, got inf"),
    ];
    for (w, expected) in cases {
        let obj = format!("v 1 0 0 {w}\nv 1 1 0\nv 0 1 0\nf 1 2 3\n");
        refused(&[("m.obj", obj.as_bytes())], "m.obj", expected);
    }
    // A weight that keeps the vertex in bounds is read: (2 0 0) / 2 is
    // (1 0 0), the same triangle as written plainly.
    let weighted = "v 2 0 0 2\nv 1 1 0\nv 0 1 0\nf 1 2 3\n";
    let plain = "v 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\n";
    same_image(
        &[("m.obj", weighted.as_bytes())],
        &[("m.obj", plain.as_bytes())],
        "m.obj",
    );
}

/// A scene of one mesh, `file`, and a small sphere, so that it renders
/// something whatever the mesh holds.
fn scene_with(file: &str) -> String {
    format!(
        "[camera]\neye = [0.3, 0.3, 3]\nlook_at = [0.3, 0.3, 0]\n\
         [materials.m]\ncolor = [1, 1, 1]\n[[light]]\nposition = [1, 2, 3]\n\
         [[object]]\nmesh = {{ file = \"{file}\" }}\n\
         [[object]]\nmaterial = \"m\"\nsphere = {{ center = [2, 2, -1], radius = 0.1 }}\n"
    )
}

#[test]
fn a_normal_of_no_direction_is_refused_at_its_line_not_called_collinear() {
    // main made such a face's patch fail and counted it among "degenerate
    // triangle(s) skipped (their vertices are collinear)", which they are
    // not; in a scene the render went on without the triangle. 1e300 ... is
    // finite but its length overflows; 1e-200's squares underflow to 0.
    let cases: &[(&str, &str)] = &[
        ("vn 0 0 0", "has no direction: its length is 0"),
        ("vn 1e-200 0 0", "has no direction: its length is 0"),
        ("vn 1e300 1e300 0", "is too long: its length overflows"),
    ];
    let scene = scene_with("m.obj");
    for (vn, words) in cases {
        let obj = format!("{TRIANGLE}{vn}\nf 1//1 2//1 3//1\n");
        refused(
            &[("m.obj", obj.as_bytes()), ("s.toml", scene.as_bytes())],
            "s.toml",
            &format!("m.obj:4:1: this normal {words}"),
        );
    }
}

#[test]
fn a_comment_after_a_face_or_a_vertex_is_read_as_a_comment() {
    // main: "m.obj: face parse error", no line (tobj read `#` and `tri` as
    // two more corners). Blender, Assimp and tinyobjloader read `#` to the
    // end of a line as a comment wherever it starts, and so does raystep's
    // own pass over the lines: the same triangle as without the comments.
    let commented = "v 0 0 0\nv 1 0 0 # right\nv 0 1 0\t# top\nvn 0 0 1 # up\n\
                     f 1//1 2//1 3//1 # tri\n";
    let plain = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n";
    same_image(
        &[("m.obj", commented.as_bytes())],
        &[("m.obj", plain.as_bytes())],
        "m.obj",
    );
}

/// One ASCII STL facet of the triangle (0 0 0) (1 0 0) (0 1 0), with
/// `vertex` lines as given.
fn ascii_stl(second_vertex: &str) -> String {
    format!(
        "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n{second_vertex}\n\
         vertex 0 1 0\nendloop\nendfacet\nendsolid t\n"
    )
}

#[test]
fn an_ascii_stl_is_refused_at_the_line_and_column_of_what_is_wrong() {
    // main: "g.stl: triangle 0 cannot be read: invalid float literal", no
    // line. Line 5 is the second `vertex`; `zz` starts at column 10.
    let cases: &[(&str, &str)] = &[
        ("vertex 1 zz 0", "g.stl:5:10: `zz` is not a number"),
        (
            "vertex 1 0 1e39",
            "g.stl:5:12: numbers must be finite, got 1e39",
        ),
        (
            "vertex 1 0",
            "g.stl:5:1: expected `vertex x y z`, got `vertex 1 0`",
        ),
    ];
    for (line, expected) in cases {
        let stl = ascii_stl(line);
        refused(&[("g.stl", stl.as_bytes())], "g.stl", expected);
    }
    // Cut short after its first vertex: line 5 is where the file ends.
    refused(
        &[(
            "g.stl",
            b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n",
        )],
        "g.stl",
        "g.stl:5:1: the file ends inside a facet: expected `vertex x y z`",
    );
}

#[test]
fn a_mesh_that_is_not_utf_8_is_refused_at_the_bad_byte() {
    // Line 2 of each; the byte 0xFF after `v 1 ` (column 5) and after
    // `vertex 1 ` (column 10). The OBJ's message named its line only, the
    // STL's too, until both used the scene reader's check.
    refused(
        &[("u.obj", b"v 0 0 0\nv 1 \xff 0\nv 0 1 0\nf 1 2 3\n")],
        "u.obj",
        "u.obj:2:5: invalid UTF-8 (byte 0xFF): OBJ files must be UTF-8 text",
    );
    let mut bytes = ascii_stl("vertex 1 X 0").into_bytes();
    let bad = bytes.iter().position(|&b| b == b'X').unwrap();
    bytes[bad] = 0xFF;
    refused(
        &[("u.stl", &bytes)],
        "u.stl",
        "u.stl:5:10: invalid UTF-8 (byte 0xFF): ASCII STL files must be UTF-8 text",
    );
}

#[test]
fn a_mesh_that_gives_no_triangle_is_refused_in_a_scene_too() {
    // main rendered the scene without the mesh, silently: an ASCII STL
    // saved as .obj (tobj knows none of its keywords), an OBJ of comments,
    // vertices and no faces, and faces whose vertices are all on a line.
    // Refused rather than warned about: a reference image rendered
    // without the mesh would look finished, and a warning scrolls by in
    // an autograder's log.
    let scene = scene_with("m.obj");
    let stl = ascii_stl("vertex 1 0 0");
    let cases: &[(&[u8], &str)] = &[
        (
            stl.as_bytes(),
            "m.obj:1:1: this is an ASCII STL (it starts with `solid`), not an OBJ: name it .stl",
        ),
        (
            b"# exported by hand\n# nothing yet\n",
            "s.toml:9:17: m.obj: the mesh has no triangles to show: it has 0 `v` line(s) and no `f` line",
        ),
        (
            TRIANGLE.as_bytes(),
            "s.toml:9:17: m.obj: the mesh has no triangles to show: it has 3 `v` line(s) and no `f` line",
        ),
        (
            b"v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 3 2 1\n",
            "s.toml:9:17: m.obj: the mesh has no triangles to show: \
             all 2 are degenerate (their vertices are collinear)",
        ),
    ];
    for (obj, expected) in cases {
        refused(
            &[("m.obj", obj), ("s.toml", scene.as_bytes())],
            "s.toml",
            expected,
        );
    }
}

/// A binary STL: an 80-byte `header` (padded with spaces), the triangle
/// count `count`, then `triangles` as (normal, three vertices), each with
/// its 2 attribute bytes.
fn binary_stl(header: &str, count: u32, triangles: &[[[f32; 3]; 4]]) -> Vec<u8> {
    let mut bytes = format!("{header:<80}").into_bytes();
    bytes.extend(count.to_le_bytes());
    for triangle in triangles {
        for c in triangle.iter().flatten() {
            bytes.extend(c.to_le_bytes());
        }
        bytes.extend([0, 0]);
    }
    bytes
}

#[test]
fn a_binary_stl_whose_header_starts_with_solid_is_read_as_binary() {
    // Exporters write "solid NAME" into the binary header, some with a
    // line break after it. main (stl_io) took a file whose first line is
    // text starting "solid " for ASCII and refused this one ("stream did
    // not contain valid UTF-8"). Its length, 84 + 50 x 1 = 134, is what
    // its count says: binary. The same triangle as in ASCII.
    let triangle = [[0., 0., 1.], [0., 0., 0.], [1., 0., 0.], [0., 1., 0.]];
    let binary = binary_stl("solid part\n", 1, &[triangle]);
    assert_eq!(binary.len(), 134);
    let ascii = ascii_stl("vertex 1 0 0");
    same_image(
        &[("t.stl", &binary)],
        &[("t.stl", ascii.as_bytes())],
        "t.stl",
    );
    // Two triangles promised, one given: 84 + 50 x 2 = 184 bytes needed,
    // 134 there. main read it as ASCII too, or with another header as a
    // binary whose "triangle 1 cannot be read: failed to fill whole
    // buffer"; it is binary by its NUL bytes (a float 0 is four of them),
    // and said to be cut short.
    let truncated = binary_stl("solid part\n", 2, &[triangle]);
    refused(
        &[("t.stl", &truncated)],
        "t.stl",
        "t.stl: truncated binary STL: 2 triangles need 184 bytes, the file has 134",
    );
}

#[test]
fn an_assignment_scene_that_is_a_fifo_a_folder_or_a_device_says_so() {
    // main checked the scene with `is_file` and said "no scene file" of
    // each, though each is there. Judged from its metadata, as every other
    // input is: the FIFO is never opened (a blocking open would wait for a
    // writer), and `run` fails the test if raystep hangs.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    mkfifo(&d.join("fifo.toml"));
    fs::create_dir(d.join("folder.toml")).unwrap();
    fs::create_dir(d.join("ada")).unwrap();
    let cases = [
        (
            "fifo.toml",
            "it is a FIFO (a named pipe), not a regular file",
        ),
        ("folder.toml", "it is a directory, not a regular file"),
        ("/dev/null", "it is a character device, not a regular file"),
    ];
    for (file, why) in cases {
        fs::write(
            d.join("a.toml"),
            format!(
                "title = \"t\"\n[[scene]]\nfile = \"{file}\"\nsubmit = \"s.png\"\npoints = 1\n"
            ),
        )
        .unwrap();
        // `file = "` is 8 characters: the value starts at column 8.
        refused_run(
            &run(d, &["grade", "a.toml", "--submission", "ada"]),
            &format!("a.toml:3:8: cannot read the scene file {file}: {why}"),
        );
    }
}
