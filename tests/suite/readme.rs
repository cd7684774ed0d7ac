//! README must match the code: the scene example parses and renders, and
//! the key table lists every row of the keymap. Docs cannot go stale.

use std::path::Path;

#[test]
fn readme_scene_example_is_valid() {
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md")).unwrap();
    let start = readme.find("```toml\n").expect("a toml example") + "```toml\n".len();
    let end = start + readme[start..].find("```").unwrap();
    let scene = raystep_engine::scene::parse(Path::new("README.md"), &readme[start..end]).unwrap();
    assert_eq!(scene.objects.len(), 7);
    assert_eq!(scene.objects[4].name, "smooth card");
    assert_eq!(
        scene
            .materials
            .iter()
            .find(|m| m.name == "glass")
            .unwrap()
            .specular,
        Some(raystep_engine::scene::SpecularModel::Phong)
    );
}

/// The keys column of README's key table, row by row, backticks and commas dropped.
fn readme_key_rows() -> Vec<String> {
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md")).unwrap();
    let start = readme
        .find("| keys | what they do |")
        .expect("the key table");
    readme[start..]
        .lines()
        .skip(2)
        .take_while(|line| line.starts_with('|'))
        .map(|line| {
            let keys = line.split('|').nth(1).unwrap().replace(['`', ','], " ");
            keys.split_whitespace().collect::<Vec<_>>().join(" ")
        })
        .collect()
}

#[test]
fn readme_key_table_lists_every_row_of_the_keymap() {
    let table: Vec<String> = raystep::tui::keymap::rows().map(|r| r.keys()).collect();
    assert_eq!(
        readme_key_rows(),
        table,
        "README's keys, in the help's order"
    );
    // Spot check by hand: the keys the README used to leave out.
    for keys in ["PageUp PageDown", "g Home e End", "Enter Space", "Ctrl+C"] {
        assert!(table.iter().any(|k| k == keys), "{keys}");
    }
}
