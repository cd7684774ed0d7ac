//! TOML scenes are read one `[[object]]` section at a time (crates/engine/src/scene/toml_sections.rs):
//! the scene read that way is the scene the whole file describes, and errors
//! in any section still name the file's own line and column.

use std::path::Path;

use raystep_engine::scene::{SceneError, parse};

const HEAD: &str = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n\
[materials.a]\nkd = 1\n[materials.b]\nkd = 0.5\n";

fn fails(text: &str) -> String {
    let error: SceneError = parse(Path::new("s.toml"), text).expect_err("an error");
    error.to_string()
}

#[test]
fn sections_read_the_scene_the_whole_file_describes() {
    // The first object's sphere is a sub-table; the light sits between objects.
    let cut = format!(
        "{HEAD}[[object]]\nname = \"first\"\nmaterial = \"a\"\n[object.sphere]\ncenter = [1, 2, 3]\nradius = 1\n\
         [[light]]\nposition = [0, 5, 5]\n\
         [[object]]\nmaterial = \"b\"\nsphere = {{ center = [0, 0, 0], radius = 2 }}\n"
    );
    // The same scene, but `[object.sphere]` comes after `[[light]]` (it still
    // extends the last object): this file is not cut, the whole is read at once.
    let whole = format!(
        "{HEAD}[[object]]\nname = \"first\"\nmaterial = \"a\"\n\
         [[light]]\nposition = [0, 5, 5]\n\
         [object.sphere]\ncenter = [1, 2, 3]\nradius = 1\n\
         [[object]]\nmaterial = \"b\"\nsphere = {{ center = [0, 0, 0], radius = 2 }}\n"
    );
    let cut = parse(Path::new("cut.toml"), &cut).unwrap();
    let whole = parse(Path::new("whole.toml"), &whole).unwrap();
    assert_eq!(cut.objects, whole.objects);
    assert_eq!(cut.lights, whole.lights);
    let names: Vec<String> = cut.objects.iter().map(|o| o.name.to_string()).collect();
    assert_eq!(names, ["first", "sphere 1"]);
    assert_eq!(
        cut.objects.iter().map(|o| o.material).collect::<Vec<_>>(),
        [0, 1]
    );
}

#[test]
fn an_error_in_a_later_section_names_the_files_line_and_column() {
    // HEAD is 7 lines; each object 3 more: the third object's sphere is on
    // line 7 + 3 * 3 = 16; the range check points at the radius, after
    // "sphere = { center = [0, 0, 0], radius = " (40 characters): column 41.
    let sphere = |r: &str| {
        format!("[[object]]\nmaterial = \"a\"\nsphere = {{ center = [0, 0, 0], radius = {r} }}\n")
    };
    let text = format!("{HEAD}{}{}{}", sphere("1"), sphere("2"), sphere("-1"));
    let message = fails(&text);
    assert!(message.starts_with("s.toml:16:41: "), "{message}");
    assert!(message.contains("16 | sphere = {"), "{message}");
    // A syntax error in the second section (line 13): the value after
    // "sphere = { center = [0, 0, 0], radius = " (40 characters) is missing,
    // and the reader stops at the `}` after one more space, column 42.
    let text = format!("{HEAD}{}{}", sphere("1"), sphere(""));
    let message = fails(&text);
    assert!(message.starts_with("s.toml:13:42: "), "{message}");
}

#[test]
fn a_given_name_may_not_repeat_any_earlier_name() {
    let named = |name: &str| {
        format!(
            "[[object]]\nname = \"{name}\"\nmaterial = \"a\"\nsphere = {{ center = [0, 0, 0], radius = 1 }}\n"
        )
    };
    let unnamed = "[[object]]\nmaterial = \"a\"\nsphere = { center = [0, 0, 0], radius = 1 }\n";
    // The unnamed sphere at index 0 is "sphere 0": the name on line 12 clashes.
    let message = fails(&format!("{HEAD}{unnamed}{}", named("sphere 0")));
    assert!(
        message.starts_with("s.toml:12:8: object name `sphere 0` is used twice"),
        "{message}"
    );
    // "sphere 1" would be object 1's default name, but object 1 is named "x".
    let text = format!("{HEAD}{unnamed}{}{}", named("x"), named("sphere 1"));
    assert!(parse(Path::new("s.toml"), &text).is_ok());
    let message = fails(&format!("{HEAD}{}{}", named("x"), named("x")));
    assert!(
        message.starts_with("s.toml:13:8: object name `x` is used twice"),
        "{message}"
    );
}

#[test]
fn objects_written_both_as_an_array_and_as_tables_are_refused() {
    let text = format!(
        "object = []\n{HEAD}[[object]]\nmaterial = \"a\"\nsphere = {{ center = [0, 0, 0], radius = 1 }}\n"
    );
    // The whole file is read then, and TOML's own message points at the
    // first `[[object]]` (line 9, after "[[").
    let message = fails(&text);
    assert!(
        message.starts_with("s.toml:9:3: duplicate key"),
        "{message}"
    );
}
