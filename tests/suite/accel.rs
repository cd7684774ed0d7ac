//! The hierarchy answers exactly as testing every object in file order does
//! (`accel::brute`): the same nearest object and the same t to the bit, the
//! same crossings, and the first object in the file on a tie (MODEL §3).

use std::ops::ControlFlow;
use std::time::Instant;

use glam::{DMat4, DVec3};
use raystep_accel::{Accel, Candidate, Cost, brute};
use raystep_engine::scene::Object;
use raystep_engine::trace::NoRecorder;
use raystep_model::math::{EPS, Interval, Ray};
use raystep_model::shapes::{Cone, Patch, Plane, Polygon, Shape, Sphere, placed_sphere};

const SPD: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/spd");

/// xorshift64*: a few lines, seeded, the same sequence everywhere.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    fn point(&mut self, half: f64) -> DVec3 {
        DVec3::new(
            self.range(-half, half),
            self.range(-half, half),
            self.range(-half, half),
        )
    }

    fn direction(&mut self) -> DVec3 {
        loop {
            let d = self.point(1.0);
            if d.length_squared() > 1e-6 && d.length_squared() <= 1.0 {
                return d.normalize();
            }
        }
    }
}

fn object(shape: Shape) -> Object {
    Object {
        name: "".into(),
        shape,
        material: 0,
    }
}

fn triangle(rng: &mut Rng, center: DVec3, size: f64) -> Option<Polygon> {
    Polygon::new((0..3).map(|_| center + rng.point(size)).collect()).ok()
}

/// Where a scene lies: the cube `center +- half`.
#[derive(Clone, Copy, Debug)]
struct Frame {
    center: DVec3,
    half: f64,
}

const UNIT: Frame = Frame {
    center: DVec3::ZERO,
    half: 10.0,
};

impl Frame {
    fn point(&self, rng: &mut Rng) -> DVec3 {
        self.center + rng.point(self.half)
    }

    /// A length that is `length` in a frame of half side 10.
    fn scaled(&self, length: f64) -> f64 {
        length * self.half / 10.0
    }
}

/// Spheres, triangles, patches, cones and cylinders scattered in the frame
/// (some overlapping, some tiny, a few exact copies), and two planes.
fn random_scene(rng: &mut Rng, count: usize, frame: Frame) -> Vec<Object> {
    let mut objects = Vec::with_capacity(count + 2);
    let floor = frame.center - DVec3::Y * frame.scaled(11.0);
    objects.push(object(Shape::Plane(Plane::new(DVec3::Y, floor).unwrap())));
    while objects.len() < count {
        let center = frame.point(rng);
        let size = frame.scaled(if rng.below(10) == 0 {
            4.0
        } else {
            rng.range(0.01, 1.0)
        });
        let shape = match rng.below(5) {
            0 => Shape::Sphere(Sphere::new(center, size).unwrap()),
            1 | 2 => match triangle(rng, center, size) {
                Some(p) => Shape::Polygon(p),
                None => continue,
            },
            3 => {
                let vertices: Vec<DVec3> = (0..3).map(|_| center + rng.point(size)).collect();
                let normals = (0..3).map(|_| rng.direction()).collect();
                match Patch::new(vertices, normals) {
                    Ok(p) => Shape::Patch(p),
                    Err(_) => continue,
                }
            }
            _ => {
                let apex = center + rng.direction() * frame.scaled(rng.range(0.1, 3.0));
                let apex_radius = if rng.below(2) == 0 {
                    size
                } else {
                    rng.range(0.0, size)
                };
                Shape::Cone(Box::new(
                    Cone::new(center, size, apex, apex_radius).unwrap(),
                ))
            }
        };
        objects.push(object(shape));
        // Now and then an exact copy of something earlier: a tie at equal t.
        if rng.below(20) == 0 {
            let earlier = rng.below(objects.len());
            objects.push(object(objects[earlier].shape.clone()));
        }
    }
    let far = frame.center + DVec3::splat(frame.scaled(13.0));
    objects.push(object(Shape::Plane(
        Plane::new(DVec3::new(1.0, 1.0, 0.5), far).unwrap(),
    )));
    objects
}

/// Spheres stretched, squashed, turned and mirrored (MODEL §3), some long
/// and thin, so that a box too small for its ellipsoid loses hits.
fn ellipsoid_scene(rng: &mut Rng, count: usize) -> Vec<Object> {
    (0..count)
        .map(|_| {
            let scale = DVec3::new(
                rng.range(0.05, 3.0),
                rng.range(0.05, 3.0),
                rng.range(0.05, 3.0),
            ) * if rng.below(4) == 0 { -1.0 } else { 1.0 };
            let turn = DMat4::from_axis_angle(rng.direction(), rng.range(0.0, 6.3));
            let m = DMat4::from_translation(UNIT.point(rng)) * turn * DMat4::from_scale(scale);
            object(placed_sphere(rng.point(0.5), rng.range(0.1, 1.0), m).unwrap())
        })
        .collect()
}

/// Axis-aligned unit squares on an integer grid, many coplanar and some
/// repeated: rays with integer origins along the axes run exactly along box
/// faces, and hits on coplanar squares tie bit for bit.
fn grid_scene(rng: &mut Rng, count: usize) -> Vec<Object> {
    let mut objects = Vec::with_capacity(count);
    while objects.len() < count {
        let corner = DVec3::new(
            rng.below(8) as f64,
            rng.below(8) as f64,
            rng.below(8) as f64,
        );
        let (u, v) = match rng.below(3) {
            0 => (DVec3::X, DVec3::Y),
            1 => (DVec3::Y, DVec3::Z),
            _ => (DVec3::Z, DVec3::X),
        };
        let scale = 1.0 + rng.below(3) as f64;
        let square = vec![
            corner,
            corner + u * scale,
            corner + (u + v) * scale,
            corner + v * scale,
        ];
        objects.push(object(Shape::Polygon(Polygon::new(square).unwrap())));
    }
    objects
}

/// Rays of every kind: from outside and inside the scene, towards objects,
/// along the axes (with +0 and -0 components), unnormalized, and starting
/// on a surface as secondary rays do.
fn random_ray(rng: &mut Rng, objects: &[Object], frame: Frame) -> Ray {
    let origin = match rng.below(3) {
        0 => frame.center + rng.point(frame.half * 1.5),
        _ => frame.point(rng),
    };
    // On a grid of 10 steps across the frame: integers in the grid scene.
    let integer = |rng: &mut Rng| {
        let step = DVec3::new(
            rng.below(10) as f64,
            rng.below(10) as f64,
            rng.below(10) as f64,
        );
        frame.center + (step - DVec3::splat(5.0)) * frame.scaled(2.0)
    };
    match rng.below(6) {
        0 => Ray::new(origin, rng.direction()),
        1 => {
            let target = objects[rng.below(objects.len())]
                .shape
                .bounds()
                .map_or(DVec3::ZERO, |b| b.centroid());
            Ray::new(origin, target - origin)
        }
        2 => {
            let mut direction = DVec3::ZERO;
            let axis = rng.below(3);
            direction[axis] = if rng.below(2) == 0 { 1.0 } else { -1.0 };
            if rng.below(2) == 0 {
                direction[(axis + 1) % 3] = -0.0;
            }
            let origin = if rng.below(2) == 0 {
                integer(rng)
            } else {
                origin
            };
            Ray::new(origin, direction)
        }
        3 => Ray::new(
            integer(rng) + DVec3::splat(frame.scaled(1.0)),
            rng.direction() * rng.range(0.1, 3.0),
        ),
        _ => {
            // A secondary ray from the nearest hit of another ray.
            let first = Ray::new(origin, rng.direction());
            let hit = brute::closest(objects, &first, Interval::in_front(), &mut Cost::default());
            match hit {
                Some(hit) => Ray::new(first.at(hit.t), rng.direction()),
                None => first,
            }
        }
    }
}

/// `n`, times `ACCEL_STRESS` when set:
/// `ACCEL_STRESS=100 cargo test --release --test suite accel::`.
fn rays(n: usize) -> usize {
    let stress = std::env::var("ACCEL_STRESS").ok();
    n * stress.and_then(|s| s.parse().ok()).unwrap_or(1)
}

fn same(a: Option<Candidate>, b: Option<Candidate>) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => a.object == b.object && a.t.to_bits() == b.t.to_bits(),
        (None, None) => true,
        _ => false,
    }
}

fn all_crossings(
    query: impl FnOnce(&mut dyn FnMut(usize, f64) -> ControlFlow<()>),
) -> Vec<(usize, u64)> {
    let mut found = Vec::new();
    query(&mut |object, t| {
        found.push((object, t.to_bits()));
        ControlFlow::Continue(())
    });
    found
}

/// The scenes every property is checked on, with the frame rays are cast in.
fn scenes() -> Vec<(&'static str, Vec<Object>, Frame)> {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let far = Frame {
        center: DVec3::new(1000.0, -2000.0, 500.0),
        half: 10.0,
    };
    let tiny = Frame {
        center: DVec3::new(0.3, 0.0, -0.1),
        half: 0.05,
    };
    let huge = Frame {
        center: DVec3::ZERO,
        half: 1e4,
    };
    let grid = Frame {
        center: DVec3::splat(5.0),
        half: 5.0,
    };
    let small = Frame {
        center: DVec3::ZERO,
        half: 2.0,
    };
    let sphere = Shape::Sphere(Sphere::new(DVec3::ZERO, 1.0).unwrap());
    let plane = Shape::Plane(Plane::new(DVec3::Z, DVec3::ZERO).unwrap());
    vec![
        ("random 2000", random_scene(&mut rng, 2000, UNIT), UNIT),
        ("random 60", random_scene(&mut rng, 60, UNIT), UNIT),
        ("far from the origin", random_scene(&mut rng, 500, far), far),
        ("tiny", random_scene(&mut rng, 500, tiny), tiny),
        ("huge", random_scene(&mut rng, 500, huge), huge),
        ("grid 400", grid_scene(&mut rng, 400), grid),
        ("single sphere", vec![object(sphere)], small),
        ("plane only", vec![object(plane)], small),
        ("ellipsoids 300", ellipsoid_scene(&mut rng, 300), UNIT),
    ]
}

#[test]
fn closest_equals_brute_force_bit_for_bit() {
    let mut rng = Rng(12345);
    for (name, objects, frame) in scenes() {
        let accel = Accel::build(&objects);
        let (mut bvh_cost, mut brute_cost, mut hits) = (Cost::default(), Cost::default(), 0);
        for i in 0..rays(6000) {
            let ray = random_ray(&mut rng, &objects, frame);
            let range = if i % 4 == 0 {
                Interval::new(EPS, rng.range(0.0, 3.0 * frame.half))
            } else {
                Interval::in_front()
            };
            let expected = brute::closest(&objects, &ray, range, &mut brute_cost);
            let got = accel.closest(&objects, &ray, range, &mut bvh_cost);
            assert!(
                same(got, expected),
                "{name}: ray {ray:?} {range:?}: {got:?} != {expected:?}"
            );
            hits += usize::from(expected.is_some());
        }
        assert!(
            hits > 300,
            "{name}: only {hits} rays hit: the test shows little"
        );
        if objects.len() > 1000 {
            assert!(
                bvh_cost.primitives * 10 < brute_cost.primitives,
                "{name}: {bvh_cost:?} vs {brute_cost:?}"
            );
        }
    }
}

#[test]
fn crossings_equal_brute_force_as_a_multiset() {
    let mut rng = Rng(777);
    for (name, objects, frame) in scenes() {
        let accel = Accel::build(&objects);
        for _ in 0..rays(4000) {
            let ray = random_ray(&mut rng, &objects, frame);
            let segment = Interval::new(EPS, rng.range(0.0, 4.0 * frame.half));
            let mut expected = all_crossings(|v| {
                brute::crossings(&objects, &ray, segment, &mut Cost::default(), v)
            });
            let got = all_crossings(|v| {
                accel.crossings(&objects, &ray, segment, &mut Cost::default(), v)
            });
            // The order is the tree's, but the same on every call.
            let again = all_crossings(|v| {
                accel.crossings(&objects, &ray, segment, &mut Cost::default(), v)
            });
            assert_eq!(got, again, "{name}: order changed between calls");
            let mut got = got;
            got.sort_unstable();
            expected.sort_unstable();
            assert_eq!(got, expected, "{name}: ray {ray:?} {segment:?}");
        }
    }
}

#[test]
fn any_crossing_agrees_with_the_closest_hit() {
    let mut rng = Rng(4242);
    for (name, objects, frame) in scenes() {
        let accel = Accel::build(&objects);
        for _ in 0..rays(4000) {
            let ray = random_ray(&mut rng, &objects, frame);
            let end = rng.range(0.0, 3.0 * frame.half);
            let mut calls = 0;
            accel.crossings(
                &objects,
                &ray,
                Interval::new(EPS, end),
                &mut Cost::default(),
                |_, t| {
                    assert!(EPS < t && t < end);
                    calls += 1;
                    ControlFlow::Break(())
                },
            );
            assert!(calls <= 1, "{name}: visit was called after it broke");
            let nearest = accel.closest(&objects, &ray, Interval::in_front(), &mut Cost::default());
            let blocked = nearest.is_some_and(|c| c.t < end);
            assert_eq!(
                calls == 1,
                blocked,
                "{name}: ray {ray:?} to {end}: nearest {nearest:?}"
            );
        }
    }
}

#[test]
fn tie_goes_to_the_first_object_in_the_file() {
    let square = |z: f64| {
        let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        Polygon::new(corners.iter().map(|[x, y]| DVec3::new(*x, *y, z)).collect()).unwrap()
    };
    let down = Ray::new(DVec3::new(0.5, 0.5, 5.0), DVec3::NEG_Z);
    // Two identical coincident polygons.
    let pair = vec![
        object(Shape::Polygon(square(0.0))),
        object(Shape::Polygon(square(0.0))),
    ];
    let hit = Accel::build(&pair).closest(&pair, &down, Interval::in_front(), &mut Cost::default());
    assert_eq!(hit, Some(Candidate { object: 0, t: 5.0 }));

    // Forty copies among other objects: they cannot be told apart, so they
    // land in several leaves, visited in tree order; still the first wins.
    let mut rng = Rng(99);
    let mut objects = random_scene(&mut rng, 300, UNIT);
    objects.retain(|o| {
        o.shape
            .bounds()
            .is_none_or(|b| b.max.z < -3.5 || b.min.z > 5.5)
    });
    let first_copy = objects.len();
    for i in 0..40 {
        objects.push(object(Shape::Polygon(square(0.0))));
        objects.push(object(Shape::Sphere(
            Sphere::new(DVec3::new(i as f64, 20.0, 0.0), 0.5).unwrap(),
        )));
    }
    let accel = Accel::build(&objects);
    // Rays running either way along each axis visit the leaves in both orders.
    let rays = [
        down,
        Ray::new(DVec3::new(0.5, 0.5, 5.0), DVec3::new(-0.0, -0.0, -1.0)),
        Ray::new(DVec3::new(0.6, 0.4, 5.0), DVec3::new(-0.01, 0.02, -1.0)),
        Ray::new(DVec3::new(0.25, 0.75, -3.0), DVec3::new(0.0, 0.0, 2.0)),
        Ray::new(DVec3::new(0.25, 0.75, -3.0), DVec3::new(0.03, -0.02, 2.0)),
    ];
    for ray in rays {
        let hit = accel
            .closest(&objects, &ray, Interval::in_front(), &mut Cost::default())
            .unwrap();
        assert_eq!(hit.object, first_copy, "{ray:?}");
        assert!(same(
            Some(hit),
            brute::closest(&objects, &ray, Interval::in_front(), &mut Cost::default())
        ));
    }
    // Every copy is a crossing of a shadow segment through them.
    let crossings = all_crossings(|v| {
        accel.crossings(
            &objects,
            &down,
            Interval::new(EPS, 10.0),
            &mut Cost::default(),
            v,
        )
    });
    assert_eq!(
        crossings
            .iter()
            .filter(|(_, t)| f64::from_bits(*t) == 5.0)
            .count(),
        40
    );
}

#[test]
fn cost_counts_nodes_and_primitives() {
    let mut rng = Rng(5);
    let objects = random_scene(&mut rng, 2000, UNIT);
    let accel = Accel::build(&objects);
    // A ray far away from everything: the two planes and the boxes of the
    // first node are tested. For 2000 objects the root and its children are
    // interior, so the first node holds four grandchildren of the root.
    let away = Ray::new(DVec3::new(100.0, 100.0, 100.0), DVec3::X);
    let mut cost = Cost::default();
    accel.closest(&objects, &away, Interval::in_front(), &mut cost);
    assert_eq!(
        cost,
        Cost {
            nodes: 4,
            primitives: 2
        }
    );
    let mut cost = Cost::default();
    brute::closest(&objects, &away, Interval::in_front(), &mut cost);
    assert_eq!(
        cost,
        Cost {
            nodes: 0,
            primitives: objects.len() as u32
        }
    );
    // A ray through the scene visits nodes and tests some, not all, primitives.
    let mut cost = Cost::default();
    accel.closest(
        &objects,
        &Ray::new(DVec3::new(-30.0, 0.1, 0.2), DVec3::X),
        Interval::in_front(),
        &mut cost,
    );
    assert!(
        cost.nodes > 1 && cost.primitives > 2 && (cost.primitives as usize) < objects.len() / 4,
        "{cost:?}"
    );
}

#[test]
fn empty_scene_has_no_hits() {
    let accel = Accel::build(&[]);
    let ray = Ray::new(DVec3::ZERO, DVec3::X);
    let mut cost = Cost::default();
    assert_eq!(
        accel.closest(&[], &ray, Interval::in_front(), &mut cost),
        None
    );
    accel.crossings(&[], &ray, Interval::in_front(), &mut cost, |_, _| {
        panic!("no crossings")
    });
    assert_eq!(cost, Cost::default());
}

/// Timings, not a pass/fail test:
/// `cargo test --release --test suite accel:: -- --ignored --nocapture`.
/// Per scene: the build, closest-hit queries towards random objects (and the
/// brute force on a tenth of them), and a 256 x 256 render of the SPD scenes.
#[test]
#[ignore]
fn timings() {
    let mut rng = Rng(2024);
    let mut triangles = Vec::new();
    while triangles.len() < 10_000 {
        let center = rng.point(10.0);
        if let Some(p) = triangle(&mut rng, center, 0.3) {
            triangles.push(object(Shape::Polygon(p)));
        }
    }
    let mut rng = Rng(7);
    let (_, accel) = time_build(&triangles);
    time_queries("10k random triangles", &triangles, &accel, &mut rng);
    for name in [
        "balls", "gears", "mount", "rings", "teapot", "tetra", "tree",
    ] {
        let path = std::path::Path::new(SPD).join(format!("{name}.nff"));
        let description = match raystep_engine::scene::load(&path) {
            Ok(description) => description,
            Err(e) => {
                println!("{name}: skipped ({e})");
                continue;
            }
        };
        let (_, accel) = time_build(&description.objects);
        time_queries(name, &description.objects, &accel, &mut rng);
        let scene = description;
        let viewport = scene.camera.viewport(256, 256);
        let start = Instant::now();
        for y in 0..256 {
            for x in 0..256 {
                let color = raystep_engine::trace::trace(
                    &scene,
                    &scene.settings,
                    &viewport.primary_ray(x, y),
                    &mut NoRecorder,
                );
                std::hint::black_box(color);
            }
        }
        println!("{:>22}  render 256 x 256 in {:.1?}", "", start.elapsed());
    }
}

fn time_build(objects: &[Object]) -> (std::time::Duration, Accel) {
    let runs = 10;
    let start = Instant::now();
    for _ in 0..runs {
        std::hint::black_box(Accel::build(objects));
    }
    (start.elapsed() / runs, Accel::build(objects))
}

fn time_queries(name: &str, objects: &[Object], accel: &Accel, rng: &mut Rng) {
    let (build, _) = time_build(objects);
    // From 50 units away towards random objects, as primary rays go.
    let rays: Vec<Ray> = (0..20_000)
        .map(|_| {
            let target = objects[rng.below(objects.len())]
                .shape
                .bounds()
                .map_or(DVec3::ZERO, |b| b.centroid());
            let origin = target + rng.direction() * 50.0;
            Ray::new(origin, (target - origin).normalize())
        })
        .collect();
    let mut cost = Cost::default();
    let start = Instant::now();
    for ray in &rays {
        std::hint::black_box(accel.closest(objects, ray, Interval::in_front(), &mut cost));
    }
    let per_ray = start.elapsed() / rays.len() as u32;
    let some = &rays[..rays.len() / 10];
    let start = Instant::now();
    for ray in some {
        let hit = brute::closest(objects, ray, Interval::in_front(), &mut Cost::default());
        std::hint::black_box(hit);
    }
    let brute_per_ray = start.elapsed() / some.len() as u32;
    println!(
        "{name:>22}: {} objects, {accel:?}, build {build:.2?}, closest {per_ray:.2?}/ray \
         (brute {brute_per_ray:.2?}), {:.1} nodes + {:.1} primitives/ray",
        objects.len(),
        cost.nodes as f64 / rays.len() as f64,
        cost.primitives as f64 / rays.len() as f64,
    );
}

/// A plain render traces its primary rays in packets of eight
/// (`Accel::closest_each`); a render with `--stats` counts each query's cost
/// and so keeps the per-ray query, the oracle here. Their images must be
/// the same bytes, with the AVX copy and with the SSE2 copy
/// (`RAYSTEP_NO_AVX=1`), at a width that is a multiple of eight and at one
/// that leaves a row's last pixels outside any packet, and with a pixel
/// mistake (which moves every primary ray).
#[test]
fn plain_renders_in_packets_equal_per_ray_renders() {
    use std::process::Command;
    let dir = tempfile::tempdir().unwrap();
    let scenes = [
        "balls", "gears", "mount", "rings", "teapot", "tetra", "tree",
    ]
    .map(|name| format!("{SPD}/{name}-small.nff"));
    let mut compared = 0;
    for scene in &scenes {
        for (size, mistake) in [("64x48", None), ("61x37", Some("pixel-corner"))] {
            let mut images = Vec::new();
            for no_avx in [false, true] {
                for stats in [false, true] {
                    let out = dir.path().join(format!("{}.png", images.len()));
                    let mut command = Command::new(env!("CARGO_BIN_EXE_raystep"));
                    command.args(["render", scene, "-o"]).arg(&out);
                    command.args(["--size", size, "--threads", "2"]);
                    if stats {
                        command.arg("--stats");
                    }
                    if let Some(mistake) = mistake {
                        command.args(["--mistake", mistake]);
                    }
                    if no_avx {
                        command.env("RAYSTEP_NO_AVX", "1");
                    } else {
                        command.env_remove("RAYSTEP_NO_AVX");
                    }
                    let output = command.output().unwrap();
                    assert!(output.status.success(), "{scene}: {output:?}");
                    images.push(std::fs::read(&out).unwrap());
                }
            }
            for (i, image) in images.iter().enumerate() {
                assert!(image == &images[0], "{scene} {size}: image {i} differs");
            }
            compared += images.len();
        }
    }
    assert_eq!(compared, 7 * 2 * 4);
}
