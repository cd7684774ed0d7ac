//! Every SPD scene in `scenes/spd/` loads through `raystep_engine::scene::load`,
//! with the primitive and light counts of the table in `spd/README.md`.

use std::collections::BTreeMap;
use std::path::Path;
use std::time::Instant;

use raystep_engine::scene::load;

const SPD: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/spd");

/// One row of the README's table: spheres, polygons, patches, cylinders,
/// cones, total objects, lights.
struct Expected {
    file: &'static str,
    spheres: usize,
    polygons: usize,
    patches: usize,
    cylinders: usize,
    cones: usize,
    total: usize,
    lights: usize,
}

/// A row written compactly: the kind counts, then total and lights.
const fn row(
    file: &'static str,
    [spheres, polygons, patches, cylinders, cones]: [usize; 5],
    total: usize,
    lights: usize,
) -> Expected {
    Expected {
        file,
        spheres,
        polygons,
        patches,
        cylinders,
        cones,
        total,
        lights,
    }
}

const TABLE: [Expected; 14] = [
    row("balls.nff", [7381, 1, 0, 0, 0], 7382, 3),
    row("gears.nff", [0, 9345, 0, 0, 0], 9345, 5),
    row("mount.nff", [4, 8192, 0, 0, 0], 8196, 1),
    row("rings.nff", [4200, 1, 0, 4200, 0], 8401, 3),
    row("teapot.nff", [0, 144, 9120, 0, 0], 9264, 2),
    row("tetra.nff", [0, 4096, 0, 0, 0], 4096, 1),
    row("tree.nff", [4095, 1, 0, 0, 4095], 8191, 7),
    row("balls-small.nff", [10, 1, 0, 0, 0], 11, 3),
    row("gears-small.nff", [0, 147, 0, 0, 0], 147, 5),
    row("mount-small.nff", [4, 8, 0, 0, 0], 12, 1),
    row("rings-small.nff", [30, 1, 0, 30, 0], 61, 3),
    row("teapot-small.nff", [0, 4, 240, 0, 0], 244, 2),
    row("tetra-small.nff", [0, 4, 0, 0, 0], 4, 1),
    row("tree-small.nff", [3, 1, 0, 0, 3], 7, 7),
];

#[test]
fn every_spd_scene_loads_with_the_published_counts() {
    let mut files: Vec<_> = std::fs::read_dir(SPD)
        .unwrap_or_else(|e| panic!("cannot list {SPD}: {e}"))
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "nff"))
        .collect();
    files.sort();
    let names: Vec<String> = files
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    let mut expected_names: Vec<&str> = TABLE.iter().map(|row| row.file).collect();
    expected_names.sort();
    assert_eq!(
        names, expected_names,
        "the SPD directory and the README's table list different files"
    );

    let all = Instant::now();
    for expected in &TABLE {
        let path = Path::new(SPD).join(expected.file);
        let start = Instant::now();
        let scene = load(&path).unwrap_or_else(|e| panic!("{e}"));
        let elapsed = start.elapsed();

        let mut kinds = BTreeMap::<&str, usize>::new();
        for object in &scene.objects {
            *kinds.entry(object.shape.kind()).or_default() += 1;
        }
        let count = |kind: &str| kinds.get(kind).copied().unwrap_or(0);
        let file = expected.file;
        assert_eq!(count("sphere"), expected.spheres, "{file}: spheres");
        assert_eq!(count("polygon"), expected.polygons, "{file}: polygons");
        assert_eq!(count("patch"), expected.patches, "{file}: patches");
        assert_eq!(count("cylinder"), expected.cylinders, "{file}: cylinders");
        assert_eq!(count("cone"), expected.cones, "{file}: cones");
        assert_eq!(scene.objects.len(), expected.total, "{file}: objects");
        assert_eq!(scene.lights.len(), expected.lights, "{file}: lights");

        // Every file: 512 x 512, angle 45, plain lights sharing sqrt(n) / (2 n) grey.
        assert_eq!((scene.width, scene.height), (512, 512), "{file}");
        let fov = 2.0
            * (22.5f64.to_radians().tan() * 512.0 / 511.0)
                .atan()
                .to_degrees();
        assert!(
            (scene.camera.fov - fov).abs() < 1e-12,
            "{file}: fov {}",
            scene.camera.fov
        );
        let n = expected.lights as f64;
        let grey = n.sqrt() / (2.0 * n);
        assert_eq!(
            scene.settings.ambient,
            glam::DVec3::splat(grey),
            "{file}: ambient"
        );
        assert!(
            scene
                .lights
                .iter()
                .all(|l| l.color == glam::DVec3::splat(grey)),
            "{file}: light colours"
        );

        // Names follow file order; every material index is valid.
        for (i, object) in scene.objects.iter().enumerate() {
            assert_eq!(
                object.name,
                format!("{} {i}", object.shape.kind()),
                "{file}"
            );
            assert!(
                object.material < scene.materials.len(),
                "{file}: {}",
                object.name
            );
        }
        eprintln!(
            "{file:>18}: {:>5} objects in {:>8.2?}",
            scene.objects.len(),
            elapsed
        );
    }
    eprintln!("all SPD files loaded in {:.2?}", all.elapsed());
}

#[test]
fn spd_materials_as_described() {
    // gears: the transmitting gears are Kd 0.2, Ks 0, T 0.8, ior 1.1.
    let gears = load(&Path::new(SPD).join("gears-small.nff")).unwrap();
    assert!(
        gears
            .materials
            .iter()
            .any(|m| m.kt == 0.8 && m.ior == 1.1 && m.kd == 0.2 && m.ks == 0.0)
    );
    // rings: one backdrop `f` and 840 ring `f` lines, each its own material;
    // nothing comes before the first `f`, so no default material.
    let rings = load(&Path::new(SPD).join("rings.nff")).unwrap();
    assert_eq!(rings.materials.len(), 841);
    assert!(rings.materials.iter().all(|m| m.name != "default"));
    // Opaque SPD materials carry ior 0, stored as 1.
    assert!(rings.materials.iter().all(|m| m.kt == 0.0 && m.ior == 1.0));
}
