//! The `inspect` text of a recording: each ray's typed lines (the debugger's
//! details pane shows the same) and the indented tree for terminals (80
//! columns). Numbers are written as `numbers.rs` writes them.

use std::fmt::Write;

use super::ellipsoid_words;
use super::fate::LightFate;
use super::lines::{About, Line};
use super::numbers::{color, count, num, precise, root, vector};
use super::ray_tree::{
    BlockerRecord, HitRecord, LightRecord, MaterialFactors, NearMiss, Node, NodeId, RayTree,
    ShadowRecord,
};
use super::shared_words::{
    attenuation_formula, cosine_name, directional_words, kind_name, not_cast_line, ray_header,
};
use crate::trace::RayKind;
use raystep_model::math::Color;
use raystep_model::math::EPS;
use raystep_model::mistakes::{Mistake, Mistakes};
use raystep_model::shapes::{
    ConeWorking, CrossingFigure, PolygonWorking, RootChoice, SphereWorking, Working,
};

/// The intersection worked as in the course notes, a line per step.
pub(crate) fn working_lines(working: &Working) -> Vec<String> {
    match working {
        Working::Sphere(w) => {
            let mut lines = vec![format!(
                "sphere: A = {}, B = {}, C = {}, discriminant B^2 - 4AC = {}",
                num(w.a),
                num(w.b),
                num(w.c),
                num(w.discriminant)
            )];
            lines.push(roots_line(w));
            lines
        }
        Working::Ellipsoid(w) => {
            let mut lines = ellipsoid_words::quadratic_lines(w);
            lines.push(roots_line(&w.quadratic));
            lines.extend(ellipsoid_words::normal_line(w));
            lines
        }
        Working::Plane(w) => vec![plane_line(w)],
        Working::Polygon(w) => polygon_lines(w),
        Working::Patch(w) => {
            let mut lines = polygon_lines(&w.polygon);
            if let (Some(i), Some(b)) = (w.fan_triangle, w.barycentric) {
                lines.push(format!(
                    "normal interpolated on fan triangle (v0, v{i}, v{}) with weights ({}, {}, {})",
                    i + 1,
                    num(b[0]),
                    num(b[1]),
                    num(b[2])
                ));
            }
            lines
        }
        Working::Cone(w) => cone_lines(w),
    }
}

/// A quadratic's roots and which the ray took, and why (sphere, ellipsoid).
fn roots_line(w: &SphereWorking) -> String {
    if let (Some(t0), Some(t1)) = (w.t0, w.t1) {
        let why = match w.choice {
            RootChoice::NearerRoot => "took t0: the nearer root is in front".to_string(),
            RootChoice::FartherRoot => {
                "took t1: t0 is not beyond EPS, the ray starts on or inside the sphere".to_string()
            }
            RootChoice::BothBehind => "both roots are behind the ray".to_string(),
            RootChoice::NoRealRoots => String::new(),
        };
        format!("roots {}, {}: {why}", root("t0", t0), root("t1", t1))
    } else {
        "negative discriminant: no real roots, no hit".into()
    }
}

fn plane_line(w: &raystep_model::shapes::PlaneWorking) -> String {
    if w.parallel {
        return format!("plane: v_d = P_n·d = {}: parallel, no hit", num(w.v_d));
    }
    let facing = if w.faces_away {
        "faces away, hit from behind"
    } else {
        "faces the ray"
    };
    let t = w.t.map(num).unwrap_or_default();
    let behind = if w.behind {
        ", behind the ray: no hit"
    } else {
        ""
    };
    format!(
        "plane: v_d = P_n·d = {} ({facing}), v_0 = -(P_n·o + D) = {}, t = v_0 / v_d = {t}{behind}",
        num(w.v_d),
        num(w.v_0)
    )
}

fn polygon_lines(w: &PolygonWorking) -> Vec<String> {
    let mut lines = vec![format!("1. the polygon's {}", plane_line(&w.plane))];
    if let Some(test) = &w.crossing {
        let [u, v] = test.projected_point;
        lines.push(format!(
            "2. drop {:?}: {} at (U, V) = ({}, {}); {} of +U: {}",
            test.dropped_axis,
            point_name(test.inside),
            num(u),
            num(v),
            count(test.crossings, "edge crossing", "edge crossings"),
            if test.inside {
                "odd, inside"
            } else {
                "even, outside"
            }
        ));
    }
    lines
}

/// What the crossing test tests: the hit point, or for a polygon passed by
/// the point where the ray meets its plane.
fn point_name(inside: bool) -> &'static str {
    if inside { "hit point" } else { "plane point" }
}

/// The crossing test edge by edge: the edges that reach V = 0, where, and
/// whether they count (MODEL §3).
pub(crate) fn crossing_lines(figure: &CrossingFigure) -> Vec<String> {
    let (_, u, v) = figure.axes();
    let corners: Vec<String> = figure
        .vertices
        .iter()
        .map(|[x, y]| format!("({}, {})", num(*x), num(*y)))
        .collect();
    let mut lines = vec![format!(
        "   U = {u}, V = {v}; vertices from the {}: {}",
        point_name(figure.inside()),
        corners.join(" ")
    )];
    let mut apart = 0u32;
    for edge in &figure.edges {
        let Some(at) = edge.u.filter(|_| edge.straddles) else {
            apart += 1;
            continue;
        };
        let verdict = if edge.counts {
            format!("crosses +U at U = {} (counts)", num(at))
        } else {
            format!(
                "crosses V = 0 at U = {}, left of the point (does not count)",
                num(at)
            )
        };
        lines.push(format!("   edge {}→{}: {verdict}", edge.from, edge.to));
    }
    if apart > 0 {
        let edges = count(apart, "other edge stays", "other edges stay");
        lines.push(format!("   {edges} on one side of V = 0"));
    }
    lines
}

/// A near miss's working, with why the ray went past: a sphere's closest
/// approach, a polygon's crossing test edge by edge.
fn near_miss_lines(near: &NearMiss) -> Vec<String> {
    let mut lines = working_lines(&near.working);
    if let Some(figure) = &near.crossing_figure {
        lines.extend(crossing_lines(figure));
    }
    if let (Some((w, space)), Some(c)) = (sphere_quadratic(&near.working), near.closest_approach) {
        lines.pop(); // the working's own verdict, said more fully here
        lines.push(if w.choice == RootChoice::NoRealRoots {
            format!(
                "negative discriminant, no real roots: the ray passes the sphere by: its line \
                 comes within {} of the centre{space} (at t = {}), more than the radius {}",
                num(c.distance),
                num(c.t),
                num(c.radius)
            )
        } else {
            format!(
                "roots {}, {}: both behind the origin, the sphere is behind the ray",
                root("t0", w.t0.unwrap_or(0.0)),
                root("t1", w.t1.unwrap_or(0.0))
            )
        });
    }
    lines
}

/// A sphere's quadratic, or an ellipsoid's in the sphere's own space, with
/// the words that say where its distances are measured.
pub(crate) fn sphere_quadratic(working: &Working) -> Option<(&SphereWorking, &'static str)> {
    match working {
        Working::Sphere(w) => Some((w, "")),
        Working::Ellipsoid(w) => Some((&w.quadratic, " in the sphere's own space")),
        _ => None,
    }
}

fn cone_lines(w: &ConeWorking) -> Vec<String> {
    let mut lines = vec![format!(
        "quadratic: A = {}, B = {}, C = {}, discriminant = {}",
        num(w.a),
        num(w.b),
        num(w.c),
        num(w.discriminant)
    )];
    let at = |name: &str, t: Option<f64>, s: Option<f64>, ok: bool| match (t, s) {
        (Some(t), Some(s)) => format!(
            "{} at height {} of {}: {}",
            root(name, t),
            num(s),
            num(w.height),
            if ok {
                "on the surface"
            } else {
                "rejected (behind, or beyond an end)"
            }
        ),
        _ => format!("{name}: none"),
    };
    if w.t0.is_some() {
        lines.push(at("t0", w.t0, w.s0, w.on_surface[0]));
        lines.push(at("t1", w.t1, w.s1, w.on_surface[1]));
    } else {
        lines.push("no real roots: no hit".into());
    }
    lines
}

/// What one light did at a hit: its fate, then each term with its factors
/// (MODEL §4), so that a student can check the formula by hand.
pub(crate) fn light_lines(
    light: &LightRecord,
    factors: &MaterialFactors,
    mistakes: Mistakes,
) -> Vec<Line> {
    // Under two-sided-diffuse the recorded cosine is |N·L| (MODEL §8): say so.
    let n_dot_l = if mistakes.contains(Mistake::TwoSidedDiffuse) {
        "|N·L|"
    } else {
        "N·L"
    };
    let about = Some(About::Light(light.light_index));
    let crossings = |s: &ShadowRecord, how: &str| {
        let names: Vec<String> = s
            .blockers
            .iter()
            .map(|b| format!("{} ({}, k_t = {})", b.object, root("t", b.t), num(b.kt)))
            .collect();
        (
            s.s,
            format!("S = {}, {how} by {}", num(s.s), names.join("; ")),
        )
    };
    let (s, shadow) = match LightFate::of(light) {
        LightFate::AtPoint => {
            return vec![Line::text(
                about,
                format!(
                    "{}: at the point (distance {} < EPS = {}): no direction, no shadow ray, adds nothing",
                    light.light,
                    precise(light.distance.unwrap_or_default()),
                    precise(EPS)
                ),
            )];
        }
        LightFate::FacesAway => {
            return vec![Line::text(
                about,
                format!(
                    "{}: faces away (N·L = {}), no shadow ray, adds nothing",
                    light.light,
                    num(light.n_dot_l)
                ),
            )];
        }
        LightFate::NotCast => (1.0, "S = 1 (shadows off)".to_string()),
        LightFate::Lit(_) => (1.0, "S = 1 (nothing in the way)".to_string()),
        LightFate::Crossed(s) | LightFate::PartlyBlocked(s) => crossings(s, "partly blocked"),
        LightFate::Blocked(s) => crossings(s, "blocked"),
    };
    let cosine = cosine_name(light.specular_model);
    let lead = format!("    = {} · {} · ", num(s), precise(light.f_att));
    let mut lines = vec![Line::text(
        about,
        format!(
            "{}: {n_dot_l} = {}, {shadow}",
            light.light,
            num(light.n_dot_l)
        ),
    )];
    // Each blocking object once, with all its crossings (a ball twice).
    let blockers: &[BlockerRecord] = light.shadow.as_ref().map_or(&[], |s| &s.blockers);
    for (i, b) in blockers.iter().enumerate() {
        if blockers[..i]
            .iter()
            .any(|o| o.object_index == b.object_index)
        {
            continue;
        }
        let crossings: Vec<String> = blockers
            .iter()
            .filter(|o| o.object_index == b.object_index)
            .map(|o| {
                let which = o.root.map(|r| format!(" (root {r})")).unwrap_or_default();
                format!("{}{which}", root("t", o.t))
            })
            .collect();
        lines.push(Line::text(
            about,
            format!("  {} crossed at {}:", b.object, crossings.join(" and ")),
        ));
        lines.extend(indented(about, indented_strings(blocker_lines(&b.working))));
    }
    // A light behind the surface that the profile still counts (cse167)
    // lights it through (N·L)₊, which is 0 there (MODEL §11).
    let (n_dot_l, cosine_value) = if light.lit_from_behind {
        (format!("({n_dot_l})₊"), highlight_base(light.n_dot_l))
    } else {
        (format!("({n_dot_l})"), num(light.n_dot_l))
    };
    let tinted = factors.specular_color != Color::ONE;
    let (o_s, o_s_value) = if tinted {
        (" · O_s", format!(" · {}", color(factors.specular_color)))
    } else {
        ("", String::new())
    };
    lines.extend([
        Line::text(
            about,
            format!(
                "  {}{}, {cosine} = {}",
                directional_words(light).map_or(String::new(), |w| format!("{w}: ")),
                f_att_words(light),
                num(light.specular_cosine)
            ),
        ),
        Line::text(
            about,
            format!("  diffuse = S · f_att · I_p · k_d · O_d · {n_dot_l}"),
        ),
        Line::text(about, lead.clone())
            .color(light.i_p)
            .then(format!(" · {} · ", num(factors.kd)))
            .color(factors.o_d)
            .then(format!(" · {cosine_value} = "))
            .color(light.diffuse),
        Line::text(
            about,
            format!("  specular = S · f_att · I_p · k_s{o_s} · ({cosine})^n"),
        ),
        Line::text(about, lead)
            .color(light.i_p)
            .then(format!(
                " · {}{o_s_value} · {}^{} = ",
                num(factors.ks),
                highlight_base(light.specular_cosine),
                num(factors.n)
            ))
            .color(light.specular),
    ]);
    lines
}

/// "f_att = 0.25": with its formula where the profile does not clamp it
/// (cse167, MODEL §11), "f_att = 1 / (0 + 0 d + 1 d²) = 4, d = 0.5, no
/// clamp".
fn f_att_words(light: &LightRecord) -> String {
    let Some(distance) = light.distance.filter(|_| !light.clamped) else {
        return format!("f_att = {}", precise(light.f_att));
    };
    format!(
        "f_att = {} = {}, d = {}, no clamp",
        attenuation_formula(light),
        precise(light.f_att),
        num(distance)
    )
}

/// A blocker's intersection working: as for a hit, but a sphere's roots
/// without the closest-hit choice (a shadow ray counts every crossing).
fn blocker_lines(working: &Working) -> Vec<String> {
    match working {
        Working::Sphere(w) => {
            let mut lines = working_lines(working);
            if let (Some(t0), Some(t1)) = (w.t0, w.t1) {
                lines.truncate(1);
                lines.push(format!("roots {}, {}", root("t0", t0), root("t1", t1)));
            }
            lines
        }
        Working::Ellipsoid(w) => {
            let mut lines = ellipsoid_words::quadratic_lines(w);
            if let (Some(t0), Some(t1)) = (w.quadratic.t0, w.quadratic.t1) {
                lines.push(format!("roots {}, {}", root("t0", t0), root("t1", t1)));
            } else {
                lines.push(roots_line(&w.quadratic));
            }
            lines
        }
        _ => working_lines(working),
    }
}

fn indented_strings(lines: Vec<String>) -> Vec<String> {
    lines.into_iter().map(|l| format!("  {l}")).collect()
}

/// The highlight's cosine as the formula raises it: clamped at 0 (MODEL §4).
fn highlight_base(cosine: f64) -> String {
    if cosine < 0.0 {
        format!("max(0, {})", num(cosine))
    } else {
        num(cosine)
    }
}

/// The ambient term with its factors: I_a · k_a · O_d (MODEL §1), or the
/// material's own ambient colour, as it is.
fn ambient_line(tree: &RayTree, node: &Node, hit: &HitRecord) -> Line {
    let f = &hit.factors;
    if let Some(own) = f.ambient {
        let line = Line::text(
            Some(About::Ambient),
            "ambient = the material's own ambient colour, added as it is: ",
        )
        .color(own);
        return match node.ambient == own {
            true => line,
            false => line.then(" (off: 0)"),
        };
    }
    let line = Line::text(Some(About::Ambient), "ambient = I_a · k_a · O_d = ")
        .color(hit.i_a)
        .then(format!(" · {} · ", num(f.ka)))
        .color(f.o_d)
        .then(" = ")
        .color(node.ambient);
    if tree.mistakes.contains(Mistake::NoAmbient) {
        line.then(" (0 under the no-ambient mistake)")
    } else {
        line
    }
}

/// Whether a ray's lines list its child rays: the debugger does, the text
/// tree prints them as branches below instead.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Children {
    Listed,
    Omitted,
}

/// The lines describing one node: how it was cast, what it met, its terms
/// and its colour.
pub fn node_lines(tree: &RayTree, id: NodeId, children: Children) -> Vec<Line> {
    let node = &tree.nodes[id];
    let mut lines = vec![Line::text(
        Some(About::Cast),
        format!(
            "from {} along {}",
            vector(node.origin),
            vector(node.direction)
        ),
    )];
    for near in &node.near_misses {
        lines.push(Line::text(
            None,
            format!("passed by {} (#{}):", near.object, near.object_index),
        ));
        lines.extend(indented(None, near_miss_lines(near)));
    }
    let Some(hit) = &node.hit else {
        lines.push(
            Line::text(
                Some(About::Miss),
                format!(
                    "missed everything ({} tested): background ",
                    count(node.cost.primitives, "primitive", "primitives")
                ),
            )
            .color(node.color),
        );
        return lines;
    };
    lines.extend(hit_lines(node, hit));
    lines.push(ambient_line(tree, node, hit));
    if node.emission != Color::ZERO {
        lines.push(
            Line::text(Some(About::Emission), "emission E = ")
                .color(node.emission)
                .then(", added as it is"),
        );
    }
    for light in &node.lights {
        lines.extend(light_lines(light, &hit.factors, tree.mistakes));
    }
    lines.extend(secondary_lines(tree, id));
    if children == Children::Listed {
        lines.extend(tree.children(id).map(|c| child_line(tree, c)));
    }
    // The text tree prints child rays as branches below this ray's lines.
    let below = children == Children::Omitted && tree.children(id).next().is_some();
    lines.push(
        Line::text(Some(About::Colour), "colour ")
            .color(node.color)
            .then(if below {
                " = sum of the terms above and of the rays below"
            } else {
                " = sum of the terms above"
            }),
    );
    if node.kind != RayKind::Primary {
        lines.push(child_term(tree, id));
    }
    lines
}

fn indented(about: Option<About>, lines: Vec<String>) -> impl Iterator<Item = Line> {
    lines
        .into_iter()
        .map(move |l| Line::text(about, format!("  {l}")))
}

/// The hit, where, its normals, the intersection working and its cost.
fn hit_lines(node: &Node, hit: &HitRecord) -> Vec<Line> {
    let about = Some(About::Hit);
    let side = if hit.entering {
        "front side"
    } else {
        "back side (normal flipped)"
    };
    let mut lines = vec![
        Line::text(
            about,
            format!(
                "hit {} ({} #{}{}) at t = {}, {side}",
                hit.object,
                hit.kind,
                hit.object_index,
                hit.material_note(),
                num(hit.t)
            ),
        ),
        Line::text(about, format!("  point {}", vector(hit.point))),
        Line::text(
            about,
            format!(
                "  N_g {} N {}",
                vector(hit.geometric_normal),
                vector(hit.normal)
            ),
        ),
    ];
    lines.extend(indented(about, working_lines(&hit.working)));
    if let Some(figure) = &hit.crossing_figure {
        lines.extend(indented(about, crossing_lines(figure)));
    }
    lines.push(Line::text(
        about,
        format!(
            "  tested {}, {}",
            count(node.cost.nodes, "node", "nodes"),
            count(node.cost.primitives, "primitive", "primitives")
        ),
    ));
    lines
}

/// Refraction, the rays a rule kept from being cast, and the depth limit.
fn secondary_lines(tree: &RayTree, id: NodeId) -> Vec<Line> {
    let node = &tree.nodes[id];
    let mut lines = Vec::new();
    if let Some(r) = &node.refraction {
        // At the depth limit (recorded on TIR only) no ray is cast; the line
        // below says so.
        let outcome = match (r.tir, node.at_depth_limit()) {
            (true, false) => "total internal reflection: kt goes to the reflected ray",
            (true, true) => "total internal reflection: no transmitted ray",
            (false, _) => "transmitted",
        };
        lines.push(Line::text(
            Some(About::Refraction),
            format!(
                "refraction: cos_i = {}, eta = {}, k = {}: {outcome}",
                num(r.cos_i),
                num(r.eta),
                num(r.k)
            ),
        ));
    }
    lines.extend(
        node.not_cast
            .iter()
            .map(|ray| Line::text(Some(About::NotCast(ray.kind)), not_cast_line(ray))),
    );
    if node.at_depth_limit() {
        let limit = if node.depth >= tree.max_depth {
            "max_depth"
        } else {
            "max_depth - 1, the limit under depth-off-by-one"
        };
        lines.push(Line::text(
            None,
            format!("no secondary rays: depth {} is {limit}", node.depth),
        ));
    }
    lines
}

/// The formula of a child ray's term (MODEL §1): "reflected = k_s · att ·
/// I_r" ((k_s + k_t) on TIR) or "transmitted = k_t · att · I_t", and the
/// symbol of its returned colour.
pub(crate) fn child_formula(tree: &RayTree, child: NodeId) -> String {
    let node = &tree.nodes[child];
    let parent = node.parent.map(|p| &tree.nodes[p]);
    match node.kind {
        RayKind::Transmitted => "transmitted = k_t · att · I_t".into(),
        _ if node.tint.is_some() => "reflected = k_s · O_s · att · I_r".into(),
        _ if parent.is_some_and(Node::tir) && node.weight != ks_of(parent) => {
            "reflected = (k_s + k_t) · att · I_r (TIR)".into()
        }
        _ => "reflected = k_s · att · I_r".into(),
    }
}

fn ks_of(node: Option<&Node>) -> f64 {
    node.and_then(|n| n.hit.as_ref())
        .map_or(0.0, |h| h.factors.ks)
}

/// A child ray's term with its numbers, as the child's own lines end.
fn child_term(tree: &RayTree, id: NodeId) -> Line {
    let node = &tree.nodes[id];
    let tint = node
        .tint
        .map(|t| format!("{} · ", color(t)))
        .unwrap_or_default();
    Line::text(
        None,
        format!(
            "{} = {} · {tint}{} · ",
            child_formula(tree, id),
            num(node.weight),
            num(node.attenuation)
        ),
    )
    .color(node.color)
    .then(" = ")
    .color(node.contribution)
}

/// What a child ray adds, as its parent lists it.
fn child_line(tree: &RayTree, child: NodeId) -> Line {
    let node = &tree.nodes[child];
    Line::text(
        Some(About::Child(child)),
        format!("{} ray r{child} adds ", kind_name(node.kind)),
    )
    .color(node.contribution)
}

/// The text form fits an 80-column terminal.
const WIDTH: usize = 80;

/// The whole recording as an indented tree, like `cargo tree`.
pub fn text(tree: &RayTree) -> String {
    let c = tree.color();
    let [r, g, b] = tree.rgb8();
    let mut out = format!(
        "pixel ({}, {}): colour {} -> rgb8 ({r}, {g}, {b})\n",
        tree.pixel.0,
        tree.pixel.1,
        color(c)
    );
    if !tree.settings.profile.is_lecture() {
        let _ = writeln!(out, "profile: {} (MODEL §11)", tree.settings.profile.name());
    }
    if !tree.mistakes.is_empty() {
        let _ = writeln!(out, "traced with the mistakes: {}", tree.mistakes);
    }
    write_node(&mut out, tree, 0, "");
    out
}

fn write_node(out: &mut String, tree: &RayTree, id: NodeId, prefix: &str) {
    let _ = writeln!(out, "{}", ray_header(&tree.nodes[id]));
    let children: Vec<NodeId> = tree.children(id).collect();
    let body = if children.is_empty() { "  " } else { "│ " };
    let room = WIDTH.saturating_sub(prefix.chars().count() + 2);
    for line in node_lines(tree, id, Children::Omitted) {
        for row in line.wrap(room, 0) {
            let _ = writeln!(out, "{prefix}{body}{}", row.text());
        }
    }
    for (i, child) in children.iter().enumerate() {
        let last = i + 1 == children.len();
        let _ = write!(out, "{prefix}{}", if last { "└─ " } else { "├─ " });
        let next = format!("{prefix}{}", if last { "   " } else { "│  " });
        write_node(out, tree, *child, &next);
    }
}
