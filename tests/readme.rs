//! The README's complete scene example must parse and render: docs cannot go stale.

use std::path::Path;

#[test]
fn readme_scene_example_is_valid() {
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md")).unwrap();
    let start = readme.find("```toml\n").expect("a toml example") + "```toml\n".len();
    let end = start + readme[start..].find("```").unwrap();
    let scene = raystep::scene::parse(Path::new("README.md"), &readme[start..end]).unwrap();
    assert_eq!(scene.objects.len(), 7);
    assert_eq!(scene.objects[4].name, "smooth card");
    assert_eq!(
        scene
            .materials
            .iter()
            .find(|m| m.name == "glass")
            .unwrap()
            .specular,
        Some(raystep::scene::SpecularModel::Phong)
    );
}
