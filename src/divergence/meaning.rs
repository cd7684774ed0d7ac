//! What our number means: the formula of docs/MODEL.md that produced it,
//! with our numbers in it, so that a student sees which line of their own
//! code to read.

use glam::DVec3;

use super::moment::Field;
use super::ours::OurRays;
use crate::math::EPS;
use crate::raylog::Step;
use crate::record::{LightFate, LightRecord, Node};
use crate::scene::{Scene, SpecularModel};
use crate::shapes::Working;

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
            .map_or_else(Vec::new, |parent| reflected_direction(parent, node)),
        (Field::Dir, Some(Step::Transmitted)) => ours
            .source(ray)
            .map_or_else(Vec::new, |parent| transmitted_direction(parent, node)),
        (Field::Weight, _) => weight(ours, node),
        (Field::Hit | Field::T | Field::Point, _) => hit(scene, node),
        (Field::Normal, _) => normal(node),
        (Field::S, _) => ours.light(ray).map_or_else(Vec::new, shadow_factor),
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

fn primary_direction(scene: &Scene, ours: &OurRays) -> Vec<String> {
    let (x, y) = ours.tree.pixel;
    let (w, h) = (scene.width as f64, scene.height as f64);
    let fov = scene.camera.fov;
    let s = (fov.to_radians() / 2.0).tan();
    let px = (2.0 * (x as f64 + 0.5) / w - 1.0) * s * (w / h);
    let py = (1.0 - 2.0 * (y as f64 + 0.5) / h) * s;
    let frame = scene.camera.frame();
    let d = (frame.forward + px * frame.right + py * frame.true_up).normalize();
    vec![
        format!(
            "MODEL §2: s = tan(fov / 2) = tan({}° / 2) = {}",
            fine(fov),
            fine(s)
        ),
        format!(
            "px = (2 (x + 0.5) / W − 1) s (W / H) = (2 × {} / {w} − 1) × {} × {} = {}",
            x as f64 + 0.5,
            fine(s),
            fine(w / h),
            fine(px)
        ),
        format!(
            "py = (1 − 2 (y + 0.5) / H) s = (1 − 2 × {} / {h}) × {} = {}",
            y as f64 + 0.5,
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
    let position = scene.lights[light.light_index].position;
    vec![format!(
        "MODEL §4: L = normalize(P_L − p) = normalize({} − {}) = {}, d_L = {}",
        fine3(position),
        fine3(p),
        fine3(light.to_light),
        fine(light.distance)
    )]
}

fn reflected_direction(parent: &Node, child: &Node) -> Vec<String> {
    let Some(hit) = &parent.hit else {
        return Vec::new();
    };
    let (d, n) = (parent.direction, hit.normal);
    vec![
        format!(
            "MODEL §5: R = d − 2 (d·N) N, with d = {} and N = {} (facing the ray): d·N = {}",
            fine3(d),
            fine3(n),
            fine(d.dot(n))
        ),
        format!("R = {}", fine3(child.direction)),
    ]
}

fn transmitted_direction(parent: &Node, child: &Node) -> Vec<String> {
    let (Some(hit), Some(r)) = (&parent.hit, parent.refraction) else {
        return Vec::new();
    };
    let ior = hit.factors.ior;
    let eta = if hit.entering {
        format!("1 / ior = 1 / {} = {} (entering)", fine(ior), fine(r.eta))
    } else {
        format!("ior / 1 = {} (leaving)", fine(r.eta))
    };
    vec![
        format!(
            "MODEL §5: cos_i = −d·N = {}, with d = {} and N = {} (facing the ray)",
            fine(r.cos_i),
            fine3(parent.direction),
            fine3(hit.normal)
        ),
        format!("η = {eta}"),
        format!("k = 1 − η² (1 − cos_i²) = {}", fine(r.k)),
        format!("T = η d + (η cos_i − √k) N = {}", fine3(child.direction)),
    ]
}

fn weight(ours: &OurRays, node: &Node) -> Vec<String> {
    let mut factors = Vec::new();
    let mut at = Some(node);
    while let Some(n) = at {
        if n.parent.is_some() {
            factors.push(fine(n.weight));
        }
        at = n.parent.map(|p| &ours.tree.nodes[p]);
    }
    factors.push("1".into());
    factors.reverse();
    vec![format!(
        "MODEL §5: the product of the weights along the path from the primary ray (1): {}",
        factors.join(" × ")
    )]
}

fn hit(scene: &Scene, node: &Node) -> Vec<String> {
    let Some(hit) = &node.hit else {
        return vec![format!(
            "MODEL §3: ours hit nothing: no object meets the ray at t > EPS = {EPS:e}; it returns the background"
        )];
    };
    let mut lines = vec![format!(
        "MODEL §3: the nearest hit with t > EPS = {EPS:e} is object {} ({}, a {}) at t = {}",
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
    vec![
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
    ]
}

fn shadow_factor(light: &LightRecord) -> Vec<String> {
    let fate = LightFate::of(light);
    let shadow = match fate {
        LightFate::AtPoint | LightFate::FacesAway | LightFate::NotCast => return Vec::new(),
        LightFate::Lit(shadow)
        | LightFate::Crossed(shadow)
        | LightFate::PartlyBlocked(shadow)
        | LightFate::Blocked(shadow) => shadow,
    };
    let mut lines = vec![format!(
        "MODEL §4: S = the product of k_t over every crossing with EPS < t < d_L = {}",
        fine(light.distance)
    )];
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
