//! What our number means: the formula of docs/MODEL.md that produced it,
//! with our numbers in it, so that a student sees which line of their own
//! code to read.

use glam::DVec3;

use super::moment::Field;
use super::ours::OurRays;
use crate::raylog::Step;
use raystep_engine::record::{LightFate, LightRecord, Node, weight_words};
use raystep_engine::scene::{Scene, SpecularModel};
use raystep_model::math::EPS;
use raystep_model::mistakes::Mistake;
use raystep_model::shapes::Working;

/// A number to six decimals (fine enough to see a difference of 1e-4),
/// without trailing zeros; tiny and huge ones in exponent form.
pub(crate) fn fine(x: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if x != 0.0 && (x.abs() >= 1e7 || x.abs() < 1e-5) {
        return format!("{x:.4e}");
    }
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

pub(crate) fn fine3(v: DVec3) -> String {
    format!("({}, {}, {})", fine(v.x), fine(v.y), fine(v.z))
}

/// The lines that say how ours came to be, for `field` of ray `ray`.
pub(crate) fn meaning(scene: &Scene, ours: &OurRays, ray: usize, field: Field) -> Vec<String> {
    let logged = &ours.rays()[ray];
    let node = ours.node(ray);
    match (field, logged.path.steps.last()) {
        (Field::Origin, None) => vec![format!(
            "MODEL §2: a primary ray starts at the eye, E = {}",
            fine3(logged.origin.unwrap_or_default())
        )],
        (Field::Origin, Some(Step::Shadow(_))) => vec![format!(
            "MODEL §4: a shadow ray starts at the hit point p = {} (the segment (EPS, d_L) keeps it off its surface)",
            fine3(logged.origin.unwrap_or_default())
        )],
        (Field::Origin, Some(_)) => vec![format!(
            "MODEL §5: a secondary ray starts exactly at its parent's hit point p = {}",
            fine3(logged.origin.unwrap_or_default())
        )],
        (Field::Dir, None) => primary_direction(scene, ours),
        (Field::Dir, Some(Step::Shadow(_))) => ours.light(ray).map_or_else(Vec::new, |light| {
            shadow_direction(scene, light, logged.origin.unwrap_or_default())
        }),
        (Field::Dir, Some(Step::Reflected)) => ours
            .source(ray)
            .map_or_else(Vec::new, |parent| reflected_direction(ours, parent, node)),
        (Field::Dir, Some(Step::Transmitted)) => ours
            .source(ray)
            .map_or_else(Vec::new, |parent| transmitted_direction(ours, parent, node)),
        (Field::Weight, _) => weight(ours, node),
        (Field::Hit | Field::T | Field::Point, _) => hit(scene, ours, node),
        (Field::Normal, _) => normal(node),
        (Field::S, _) => ours
            .light(ray)
            .map_or_else(Vec::new, |light| shadow_factor(ours, light)),
        (Field::Ambient, _) => ambient(node),
        (Field::Diffuse(i), _) => light_of(node, i).map_or_else(Vec::new, |l| diffuse(node, l)),
        (Field::Specular(i), _) => light_of(node, i).map_or_else(Vec::new, |l| specular(node, l)),
        (Field::Color, _) => colour(ours, node),
        (Field::Ray, _) => Vec::new(),
    }
}

fn light_of(node: &Node, i: usize) -> Option<&LightRecord> {
    node.lights.iter().find(|l| l.light_index == i)
}

/// The camera's working for our primary ray, every number the engine's:
/// the viewport the recording was traced with (its pixel mistakes in
/// force, MODEL §8) and the direction it recorded.
fn primary_direction(scene: &Scene, ours: &OurRays) -> Vec<String> {
    let (x, y) = ours.tree.pixel;
    let viewport = ours.viewport(scene);
    let (w, h) = (scene.width as f64, scene.height as f64);
    let fov = scene.camera.fov;
    let s = viewport.half_height();
    let (px, py) = viewport.plane_offsets(x, y);
    let frame = viewport.frame();
    let d = ours.tree.root().direction;
    let mistakes = ours.tree.mistakes;
    let corner = viewport.pixel_offset() == 0.0;
    let row = viewport.traced_row(y);
    let s_line = if mistakes.contains(Mistake::FovFullAngle) {
        format!(
            "MODEL §2 under fov-full-angle (§8): s = tan(fov) = tan({}°) = {}",
            fine(fov),
            fine(s)
        )
    } else {
        format!(
            "MODEL §2: s = tan(fov / 2) = tan({}° / 2) = {}",
            fine(fov),
            fine(s)
        )
    };
    let corner_note = "through the pixel's top-left corner under pixel-corner (§8)";
    let x_term = if corner { "x" } else { "(x + 0.5)" };
    let y_name = if viewport.flips_rows() { "y'" } else { "y" };
    let y_term = if corner {
        y_name.to_string()
    } else {
        format!("({y_name} + 0.5)")
    };
    // What a mistake changed in each formula, said between it and its numbers.
    let noted = |notes: Vec<String>| {
        if notes.is_empty() {
            String::new()
        } else {
            format!(", {},", notes.join("; "))
        }
    };
    let px_note = noted(
        corner
            .then(|| corner_note.to_string())
            .into_iter()
            .collect(),
    );
    let py_note = noted(
        (viewport.flips_rows().then(|| {
            format!("y' = H − 1 − y = {row}, the row traced for image row {y} under flipped-y (§8)")
        }))
        .into_iter()
        .chain(corner.then(|| corner_note.to_string()))
        .collect(),
    );
    let offset = viewport.pixel_offset();
    vec![
        s_line,
        format!(
            "px = (2 {x_term} / W − 1) s (W / H){px_note} = (2 × {} / {w} − 1) × {} × {} = {}",
            x as f64 + offset,
            fine(s),
            fine(w / h),
            fine(px)
        ),
        format!(
            "py = (1 − 2 {y_term} / H) s{py_note} = (1 − 2 × {} / {h}) × {} = {}",
            row as f64 + offset,
            fine(s),
            fine(py)
        ),
        format!(
            "D = normalize(f + px r + py u), f = {}, r = {}, u = {}: D = {}",
            fine3(frame.forward),
            fine3(frame.right),
            fine3(frame.true_up),
            fine3(d)
        ),
    ]
}

fn shadow_direction(scene: &Scene, light: &LightRecord, p: DVec3) -> Vec<String> {
    match (scene.lights[light.light_index].position(), light.distance) {
        (Some(position), Some(distance)) => vec![format!(
            "MODEL §4: L = normalize(P_L − p) = normalize({} − {}) = {}, d_L = {}",
            fine3(position),
            fine3(p),
            fine3(light.to_light),
            fine(distance)
        )],
        _ => vec![format!(
            "MODEL §4: light {} is directional: L = {} at every point (its direction, \
             normalised), with no d_L",
            light.light_index,
            fine3(light.to_light)
        )],
    }
}

fn reflected_direction(ours: &OurRays, parent: &Node, child: &Node) -> Vec<String> {
    let Some(hit) = &parent.hit else {
        return Vec::new();
    };
    let (d, n) = (parent.direction, hit.normal);
    let formula = if ours.tree.mistakes.contains(Mistake::ReflectionSign) {
        "MODEL §5 under reflection-sign (§8): R = 2 (d·N) N − d"
    } else {
        "MODEL §5: R = d − 2 (d·N) N"
    };
    vec![
        format!(
            "{formula}, with d = {} and N = {} (facing the ray): d·N = {}",
            fine3(d),
            fine3(n),
            fine(d.dot(n))
        ),
        format!("R = {}", fine3(child.direction)),
    ]
}

/// Snell's law as ours applied it: η, cos_i and k as the tracer recorded
/// them, with the normal the rules in force gave it (MODEL §5, §8).
fn transmitted_direction(ours: &OurRays, parent: &Node, child: &Node) -> Vec<String> {
    let (Some(hit), Some(r)) = (&parent.hit, parent.refraction) else {
        return Vec::new();
    };
    let ior = hit.factors.ior;
    let side = if hit.entering { "entering" } else { "leaving" };
    let inverted = ours.tree.mistakes.contains(Mistake::EtaInverted);
    let under = if inverted {
        ", under eta-inverted, MODEL §8"
    } else {
        ""
    };
    let eta = if hit.entering != inverted {
        format!(
            "1 / ior = 1 / {} = {} ({side}{under})",
            fine(ior),
            fine(r.eta)
        )
    } else {
        format!("ior / 1 = {} ({side}{under})", fine(r.eta))
    };
    let n = ours.rules().refraction_normal(&hit.surface_hit());
    let which = if n == hit.normal {
        "(facing the ray)".to_string()
    } else {
        "(N_g, the outward normal, under refraction-outward-normal, MODEL §8)".to_string()
    };
    vec![
        format!(
            "MODEL §5: cos_i = −d·N = {}, with d = {} and N = {} {which}",
            fine(r.cos_i),
            fine3(parent.direction),
            fine3(n)
        ),
        format!("η = {eta}"),
        format!("k = 1 − η² (1 − cos_i²) = {}", fine(r.k)),
        format!("T = η d + (η cos_i − √k) N = {}", fine3(child.direction)),
    ]
}

fn weight(ours: &OurRays, node: &Node) -> Vec<String> {
    let (mut factors, mut tinted) = (Vec::new(), false);
    let mut at = Some(node);
    while let Some(n) = at {
        if n.parent.is_some() {
            tinted |= n.tint.is_some();
            factors.push(match n.tint {
                Some(_) => format!("({})", weight_words(n)),
                None => fine(n.weight),
            });
        }
        at = n.parent.map(|p| &ours.tree.nodes[p]);
    }
    factors.push("1".into());
    factors.reverse();
    // cse167 weighs a mirror ray by k_s O_s, a colour: the product is
    // taken per channel.
    let rule = if tinted {
        "MODEL §5 and §11: the product of the weights along the path from the primary ray (1), a mirror ray's k_s O_s per channel"
    } else {
        "MODEL §5: the product of the weights along the path from the primary ray (1)"
    };
    vec![format!("{rule}: {}", factors.join(" × "))]
}

fn hit(scene: &Scene, ours: &OurRays, node: &Node) -> Vec<String> {
    // The distances the ray accepted, as the rules in force gave them.
    let start = ours.rules().hit_range(node.kind).min();
    let above = if start == EPS {
        format!("EPS = {EPS:e}")
    } else {
        format!("{} (no-epsilon, MODEL §8)", fine(start))
    };
    let Some(hit) = &node.hit else {
        return vec![format!(
            "MODEL §3: ours hit nothing: no object meets the ray at t > {above}; it returns the background"
        )];
    };
    let mut lines = vec![format!(
        "MODEL §3: the nearest hit with t > {above} is object {} ({}, a {}) at t = {}",
        hit.object_index,
        scene.object_name(hit.object_index),
        hit.kind,
        fine(hit.t)
    )];
    if let Working::Sphere(w) = &hit.working {
        lines.push(format!(
            "|o + t d − c|² = r²: A = {}, B = {}, C = {}, discriminant = {}, roots {} and {}",
            fine(w.a),
            fine(w.b),
            fine(w.c),
            fine(w.discriminant),
            w.t0.map_or("none".into(), fine),
            w.t1.map_or("none".into(), fine)
        ));
    }
    if let Working::Ellipsoid(w) = &hit.working {
        let q = &w.quadratic;
        lines.push(format!(
            "MODEL §3: an ellipsoid, a sphere under a transform M, is solved in the sphere's own space: \
             o' = M⁻¹ o = {}, d' = M⁻¹ d = {} (not renormalised, so t is the same), c = {}, r = {}",
            fine3(w.object_origin),
            fine3(w.object_direction),
            fine3(w.object_center),
            fine(w.object_radius)
        ));
        lines.push(format!(
            "|o' + t d' − c|² = r²: A = {}, B = {}, C = {}, discriminant = {}, roots {} and {}",
            fine(q.a),
            fine(q.b),
            fine(q.c),
            fine(q.discriminant),
            q.t0.map_or("none".into(), fine),
            q.t1.map_or("none".into(), fine)
        ));
    }
    lines.push(format!(
        "p = o + t d = {} + {} × {} = {}",
        fine3(node.origin),
        fine(hit.t),
        fine3(node.direction),
        fine3(hit.point)
    ));
    lines
}

fn normal(node: &Node) -> Vec<String> {
    let Some(hit) = &node.hit else {
        return Vec::new();
    };
    let flipped = !hit.entering;
    let mut lines = Vec::new();
    if let Working::Ellipsoid(w) = &hit.working
        && let (Some(p), Some(n)) = (w.object_point, w.object_normal)
    {
        lines.push(format!(
            "MODEL §3: an ellipsoid's normal comes from the inverse transpose: p' = M⁻¹ p = {}, \
             (p' − c)/r = {}, N_g = normalize(M⁻ᵀ (p' − c)/r); not (p − M c)/|p − M c|",
            fine3(p),
            fine3(n)
        ));
    }
    lines.extend([
        format!(
            "MODEL §3: N_g = {} (the {}'s geometric normal), d·N_g = {}",
            fine3(hit.geometric_normal),
            hit.kind,
            fine(node.direction.dot(hit.geometric_normal))
        ),
        format!(
            "N is N_g turned to face the ray (N·d ≤ 0): N = {}{}",
            if flipped { "−N_g = " } else { "N_g = " },
            fine3(hit.normal)
        ),
    ]);
    lines
}

fn shadow_factor(ours: &OurRays, light: &LightRecord) -> Vec<String> {
    let fate = LightFate::of(light);
    let shadow = match fate {
        LightFate::AtPoint | LightFate::FacesAway | LightFate::NotCast => return Vec::new(),
        LightFate::Lit(shadow)
        | LightFate::Crossed(shadow)
        | LightFate::PartlyBlocked(shadow)
        | LightFate::Blocked(shadow) => shadow,
    };
    // The segment the rules in force gave the shadow ray.
    let segment = ours.rules().shadow_segment(light.distance);
    let end = light
        .distance
        .map_or("∞ (a directional light)".to_string(), |d| {
            format!("d_L = {}", fine(d))
        });
    let model_end = light.distance.unwrap_or(f64::INFINITY);
    let mut lines = vec![if segment.min() == EPS && segment.max() == model_end {
        format!("MODEL §4: S = the product of k_t over every crossing with EPS < t < {end}")
    } else {
        let names: Vec<&str> = [
            Mistake::ShadowAcne,
            Mistake::NoEpsilon,
            Mistake::ShadowsPastLight,
        ]
        .into_iter()
        .filter(|&m| ours.tree.mistakes.contains(m))
        .map(Mistake::name)
        .collect();
        format!(
            "MODEL §4 under {} (§8): S = the product of k_t over every crossing with {} < t < {} ({end})",
            names.join(" and "),
            fine(segment.min()),
            fine(segment.max()),
        )
    }];
    if let LightFate::Lit(_) = fate {
        lines.push("nothing crosses the segment: S = 1".into());
    } else {
        let crossings: Vec<String> = shadow
            .blockers
            .iter()
            .map(|b| format!("{} at t = {} (k_t = {})", b.object, fine(b.t), fine(b.kt)))
            .collect();
        lines.push(format!("{}: S = {}", crossings.join(", "), fine(shadow.s)));
    }
    lines
}

fn ambient(node: &Node) -> Vec<String> {
    let Some(hit) = &node.hit else {
        return Vec::new();
    };
    let f = hit.factors;
    vec![format!(
        "MODEL §4: ambient = I_a k_a O_d = {} × {} × {} = {}",
        fine3(hit.i_a),
        fine(f.ka),
        fine3(f.o_d),
        fine3(node.ambient)
    )]
}

fn diffuse(node: &Node, light: &LightRecord) -> Vec<String> {
    let Some(hit) = &node.hit else {
        return Vec::new();
    };
    let fate = LightFate::of(light);
    if fate.adds_nothing() {
        return vec![format!(
            "MODEL §4: light {} is behind the surface (N·L = {} ≤ 0): it adds nothing",
            light.light_index,
            fine(light.n_dot_l)
        )];
    }
    let s = fate.s();
    let f = hit.factors;
    vec![format!(
        "MODEL §4: diffuse = S f_att I_p k_d O_d (N·L) = {} × {} × {} × {} × {} × {} = {}",
        fine(s),
        fine(light.f_att),
        fine3(light.i_p),
        fine(f.kd),
        fine3(f.o_d),
        fine(light.n_dot_l),
        fine3(light.diffuse)
    )]
}

fn specular(node: &Node, light: &LightRecord) -> Vec<String> {
    let Some(hit) = &node.hit else {
        return Vec::new();
    };
    let fate = LightFate::of(light);
    if fate.adds_nothing() {
        return diffuse(node, light);
    }
    let s = fate.s();
    let f = hit.factors;
    let cosine = match light.specular_model {
        SpecularModel::Blinn => "N·H, H = normalize(L + V)",
        SpecularModel::Phong => "R·V, R = 2 (N·L) N − L",
    };
    vec![format!(
        "MODEL §4: specular = S f_att I_p k_s max(0, {cosine})^n = {} × {} × {} × {} × max(0, {})^{} = {}",
        fine(s),
        fine(light.f_att),
        fine3(light.i_p),
        fine(f.ks),
        fine(light.specular_cosine),
        fine(f.n),
        fine3(light.specular)
    )]
}

fn colour(ours: &OurRays, node: &Node) -> Vec<String> {
    if node.hit.is_none() {
        return vec![format!(
            "MODEL §5: a ray that hits nothing returns the background colour {}",
            fine3(node.color)
        )];
    }
    let mut parts = vec![format!("ambient {}", fine3(node.ambient))];
    for light in &node.lights {
        parts.push(format!(
            "light {} {}",
            light.light_index,
            fine3(light.diffuse + light.specular)
        ));
    }
    for (name, child) in [
        ("reflected", node.reflected),
        ("transmitted", node.transmitted),
    ] {
        if let Some(child) = child {
            let c = &ours.tree.nodes[child];
            parts.push(format!(
                "{name} {} (its colour {} × weight {} × attenuation {})",
                fine3(c.contribution),
                fine3(c.color),
                fine(c.weight),
                fine(c.attenuation)
            ));
        }
    }
    vec![
        "MODEL §6: I = ambient + Σ (diffuse_i + specular_i) + reflected + transmitted".into(),
        format!("= {} = {}", parts.join(" + "), fine3(node.color)),
    ]
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::raylog::RayPath;
    use raystep_engine::scene::Settings;
    use raystep_model::mistakes::Mistakes;

    /// `scene` recorded at `pixel` with `mistakes` on.
    fn ours_under(
        scene: &Scene,
        mistakes: impl IntoIterator<Item = Mistake>,
        pixel: (u32, u32),
    ) -> OurRays {
        let settings = Settings {
            mistakes: Mistakes::from_iter(mistakes),
            ..scene.settings
        };
        OurRays::record(scene, &settings, pixel)
    }

    /// A 4 x 2 image with a 60° field of view from the origin down −z
    /// (f = (0, 0, −1), r = (1, 0, 0), u = (0, 1, 0) by MODEL §2's cross
    /// products), a wall at z = −10 for the rays to meet.
    const WIDE: &str = r#"
        [camera]
        eye = [0, 0, 0]
        look_at = [0, 0, -1]
        up = [0, 1, 0]
        fov = 60
        [image]
        width = 4
        height = 2
        [materials.wall]
        kd = 1
        [[object]]
        material = "wall"
        plane = { normal = [0, 0, 1], point = [0, 0, -10] }
    "#;

    #[test]
    fn the_primary_working_is_the_cameras_under_each_camera_mistake() {
        let scene = raystep_engine::scene::parse(Path::new("wide.toml"), WIDE).unwrap();
        // Each camera mistake alone, and the two pixel ones together.
        let cases: [&[Mistake]; 5] = [
            &[],
            &[Mistake::PixelCorner],
            &[Mistake::FlippedY],
            &[Mistake::FovFullAngle],
            &[Mistake::PixelCorner, Mistake::FlippedY],
        ];
        for mistake in cases {
            let ours = ours_under(&scene, mistake.iter().copied(), (1, 0));
            let lines = meaning(&scene, &ours, 0, Field::Dir);
            let text = lines.join("\n");
            // s by MODEL §2 (tan 30° = 1/√3), or §8's fov-full-angle (tan 60° = √3).
            let s = if mistake.contains(&Mistake::FovFullAngle) {
                3f64.sqrt()
            } else {
                1.0 / 3f64.sqrt()
            };
            // px and py of the ray the engine traced, read off its recorded
            // direction D: px = D·r / D·f, py = D·u / D·f.
            let d = ours.tree.root().direction;
            let (px, py) = (d.x / -d.z, d.y / -d.z);
            assert!(
                lines[0].ends_with(&format!("= {}", fine(s))),
                "{mistake:?}:\n{text}"
            );
            assert!(
                lines[1].ends_with(&format!("= {}", fine(px))),
                "{mistake:?}:\n{text}"
            );
            assert!(
                lines[2].ends_with(&format!("= {}", fine(py))),
                "{mistake:?}:\n{text}"
            );
            assert!(lines[3].ends_with(&fine3(d)), "{mistake:?}:\n{text}");
            // The numbers put into the formula are the pixel's as traced:
            // x + 0.5 = 1.5 and row 0 + 0.5, or the corner 1 and 0, or row
            // H − 1 − 0 = 1 under flipped-y.
            let corner = mistake.contains(&Mistake::PixelCorner);
            let row = if mistake.contains(&Mistake::FlippedY) {
                1.0
            } else {
                0.0
            };
            let offset = if corner { 0.0 } else { 0.5 };
            let (x_in, y_in) = (format!("{}", 1.0 + offset), format!("{}", row + offset));
            assert!(!text.contains(",,"), "{text}");
            assert!(
                lines[1].contains(&format!("(2 × {x_in} / 4 − 1)")),
                "{text}"
            );
            assert!(
                lines[2].contains(&format!("(1 − 2 × {y_in} / 2)")),
                "{text}"
            );
        }
    }

    /// A water ball (ior 4/3, k_t = 1) of radius 1 at the origin; the only
    /// pixel's ray runs down −z at height 0.3 and enters at
    /// p = (0, 0.3, √0.91): cos_i = √0.91, so even η = 4/3 (eta-inverted)
    /// refracts, k = 1 − (16/9)(0.09) = 0.84.
    const WATER_BALL: &str = r#"
        [camera]
        eye = [0, 0.3, 5]
        look_at = [0, 0.3, 0]
        [image]
        width = 1
        height = 1
        [materials.water]
        kd = 0
        kt = 1
        ior = 1.3333333333333333
        [[object]]
        material = "water"
        sphere = { center = [0, 0, 0], radius = 1 }
    "#;

    #[test]
    fn the_refraction_working_is_the_tracers_under_each_refraction_mistake() {
        let scene = raystep_engine::scene::parse(Path::new("water.toml"), WATER_BALL).unwrap();
        let refraction_mistakes = [Mistake::EtaInverted, Mistake::RefractionOutwardNormal];
        for mistake in [None].into_iter().chain(refraction_mistakes.map(Some)) {
            let ours = ours_under(&scene, mistake, (0, 0));
            for path in ["P/T", "P/T/T"] {
                let ray = ours.find(&RayPath::parse(path, 0).unwrap()).unwrap();
                let lines = meaning(&scene, &ours, ray, Field::Dir);
                let text = lines.join("\n");
                let parent = ours.source(ray).unwrap();
                let hit = parent.hit.as_ref().unwrap();
                let refraction = parent.refraction.unwrap();
                // η by MODEL §5 (1/ior entering, ior leaving), the other way
                // round under eta-inverted (§8); the line must say the
                // formula that gives it, and the tracer's η.
                let entering = path == "P/T";
                let inverted = mistake == Some(Mistake::EtaInverted);
                let (formula, eta) = if entering != inverted {
                    ("1 / ior = 1 / 1.333333 = ", 0.75)
                } else {
                    ("ior / 1 = ", 4.0 / 3.0)
                };
                assert!((refraction.eta - eta).abs() < 1e-12, "{mistake:?} {path}");
                assert!(
                    lines[1].contains(&format!("{formula}{}", fine(eta))),
                    "{mistake:?} {path}:\n{text}"
                );
                // The normal shown is the one cos_i = −d·N was taken with:
                // N facing the ray, or N_g (the hit point itself, on a unit
                // ball at the origin) under refraction-outward-normal (§8).
                let n = if mistake == Some(Mistake::RefractionOutwardNormal) {
                    hit.point
                } else {
                    hit.normal
                };
                let cos_i = -parent.direction.dot(n);
                assert!(
                    (cos_i - refraction.cos_i).abs() < 1e-12,
                    "{mistake:?} {path}"
                );
                assert!(
                    lines[0].contains(&format!("cos_i = −d·N = {}", fine(cos_i)))
                        && lines[0].contains(&format!("N = {}", fine3(n))),
                    "{mistake:?} {path}:\n{text}"
                );
                assert!(
                    lines[3].ends_with(&fine3(ours.node(ray).direction)),
                    "{text}"
                );
            }
        }
    }
}
