//! "Why is this pixel this colour?", answered in plain words for a student,
//! from the recording alone.

use std::fmt::{self, Write};

use super::ellipsoid_words;
use super::fate::LightFate;
use super::lines::Line;
use super::numbers::{along, color, count, fraction, num};
use super::ray_tree::{LightRecord, NodeId, RayTree};
use super::shaping::{place, shaping_events};
use super::shared_words::{
    attenuation_formula, directional_words, kind_name, not_cast_reason, weight_words,
};
use super::sources::{brightness, sources};
use super::text::sphere_quadratic;
use crate::trace::{PruneRule, RayKind};
use raystep_model::math::{Color, EPS};
use raystep_model::shapes::{CrossingFigure, RootChoice, Working};

/// `explain` wraps its lines at 100 columns.
const WIDTH: usize = 100;

/// What a line of the story tells, so that a reader takes the parts it
/// needs (`compare`'s brief) by their type, never by their words.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Said {
    /// The pixel's colour and bytes.
    Pixel,
    /// The mistakes it is traced with.
    Mistakes,
    /// Something the primary ray passed by.
    NearMiss,
    /// What the primary ray hits, or that it misses.
    PrimaryRay,
    /// The crossing test that put a concave polygon's hit inside.
    Crossing,
    /// The heading of the primary ray's terms.
    TermsHeading,
    /// One of the primary ray's terms with its share, largest first (or the
    /// terms too small to show, or that every term is zero).
    Term,
    LightsHeading,
    /// What one light did at the primary hit.
    Light,
    /// Total internal reflection at the primary hit.
    Tir,
    /// A secondary ray of the primary ray and what it adds.
    Child,
    /// Secondary rays a rule kept from being cast.
    NotCast,
    /// The depth limit stopping the primary ray's secondary rays.
    DepthLimit,
    SourcesHeading,
    /// A ray whose own terms make a share of the pixel.
    Source,
    ShapedHeading,
    /// An event that shaped the colour, with how much it moved it.
    Shaped,
}

/// One line of the story: what it tells, its indentation, a leading number
/// its continuations hang past ("0.372", " 61.0%"), and its words.
#[derive(Clone, Debug, PartialEq)]
pub struct Told {
    pub said: Said,
    pub(crate) indent: usize,
    pub(crate) number: Option<String>,
    pub text: String,
}

impl Told {
    /// How far past the indentation a wrapped continuation starts: under
    /// the text after a leading number, else four.
    fn hang(&self) -> usize {
        self.number
            .as_ref()
            .map_or(4, |n| n.trim_start().chars().count() + 2)
    }
}

/// The line as `explain_unwrapped` prints it.
impl fmt::Display for Told {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", " ".repeat(self.indent))?;
        if let Some(number) = &self.number {
            write!(f, "{number}  ")?;
        }
        f.write_str(&self.text)
    }
}

/// The story as it is told, line by line.
#[derive(Default)]
struct Story(Vec<Told>);

impl Story {
    /// A sentence of its own.
    fn say(&mut self, said: Said, text: impl Into<String>) {
        self.push(said, 0, None, text.into());
    }

    /// An entry of a list, under its heading.
    fn item(&mut self, said: Said, text: impl Into<String>) {
        self.push(said, 2, None, text.into());
    }

    /// An entry of a list led by its number.
    fn ranked(&mut self, said: Said, number: String, text: String) {
        self.push(said, 2, Some(number), text);
    }

    fn push(&mut self, said: Said, indent: usize, number: Option<String>, text: String) {
        self.0.push(Told {
            said,
            indent,
            number,
            text,
        });
    }
}

/// The story wrapped for a terminal: each line broken at `WIDTH`, its
/// continuations hung under its text (`Told::hang`).
pub fn explain(tree: &RayTree) -> String {
    let mut out = String::new();
    for told in explain_lines(tree) {
        for row in Line::text(None, told.to_string()).wrap_hanging(WIDTH, 0, told.hang()) {
            let _ = writeln!(out, "{}", row.text());
        }
    }
    out
}

/// The story, one line per sentence or list entry (for tests that look for
/// a sentence on one line).
pub fn explain_unwrapped(tree: &RayTree) -> String {
    explain_lines(tree)
        .iter()
        .map(|told| format!("{told}\n"))
        .collect()
}

/// The story's lines, each with what it tells.
pub fn explain_lines(tree: &RayTree) -> Vec<Told> {
    let mut out = Story::default();
    let root = tree.root();
    let c = tree.color();
    let [r, g, b] = tree.rgb8();
    out.say(
        Said::Pixel,
        format!(
            "Pixel ({}, {}) has colour {} (stored as {r}, {g}, {b}).",
            tree.pixel.0,
            tree.pixel.1,
            color(c)
        ),
    );
    if let Some(words) = tree.settings.profile.words() {
        out.say(Said::Mistakes, words);
    }
    if !tree.mistakes.is_empty() {
        out.say(
            Said::Mistakes,
            format!(
                "It is traced with classic mistakes on purpose: {} (MODEL §8).",
                tree.mistakes
            ),
        );
    }
    write_near_misses(&mut out, tree);
    let Some(hit) = &root.hit else {
        out.say(
            Said::PrimaryRay,
            "Its primary ray hits nothing, so it shows the background colour.",
        );
        return out.0;
    };
    out.say(
        Said::PrimaryRay,
        format!(
            "Its primary ray hits {} ({}{}) at distance {}, on its {} side.",
            hit.object,
            hit.kind,
            hit.material_note(),
            num(hit.t),
            if hit.entering { "front" } else { "back" }
        ),
    );
    // An ellipsoid's hit is worked in the sphere's own space: say so.
    if let Some(words) = match &hit.working {
        Working::Ellipsoid(w) => ellipsoid_words::explained(w),
        _ => None,
    } {
        out.say(Said::PrimaryRay, words);
    }
    // A convex hit's single crossing is routine (it is in `inspect`); several
    // crossings mean a concave outline where the parity rule decided the hit.
    if let Some(figure) = hit.crossing_figure.as_ref().filter(|f| counted(f) > 1) {
        out.say(
            Said::Crossing,
            format!(
                "The crossing test puts the hit inside: {}, an odd number.",
                counted_edges(figure)
            ),
        );
    }
    write_shares(&mut out, tree, 0);
    out.say(Said::LightsHeading, "Lights:");
    for light in &root.lights {
        out.item(Said::Light, light_fate(light));
    }
    if root
        .lights
        .iter()
        .any(|l| l.light.contains("(Ke of material"))
    {
        // An MTL emitter became a point light (MODEL §4): say what is lost.
        out.item(
            Said::Light,
            "a Whitted tracer has no area lights: an MTL emitter (Ke) is one point light just off \
             its centre, so its shadows have hard edges.",
        );
    }
    if root.lights.is_empty() {
        out.item(
            Said::Light,
            "the scene has no lights: only ambient light and secondary rays add colour.",
        );
    }
    if root.tir() {
        out.say(
            Said::Tir,
            format!(
            "Total internal reflection on {}: the ray is inside a denser medium at too shallow an \
             angle, so no light is transmitted and k_t is added to the reflected ray's weight.",
            hit.object
        ));
    }
    for child in tree.children(0) {
        write_child(&mut out, tree, child);
    }
    write_not_cast(&mut out, tree);
    if root.at_depth_limit() {
        let but = if root.depth >= tree.max_depth {
            "so"
        } else {
            "and under depth-off-by-one"
        };
        out.say(
            Said::DepthLimit,
            format!(
                "No secondary rays: max_depth is {}, {but} the primary ray spawns none.",
                tree.max_depth
            ),
        );
    }
    write_sources(&mut out, tree);
    write_shaping(&mut out, tree);
    out.0
}

/// The rays whose own terms make most of the pixel: at most three, each
/// over 5% of its brightness, then what the rest add together.
fn write_sources(out: &mut Story, tree: &RayTree) {
    let total = brightness(tree.color());
    if total <= 0.0 {
        return;
    }
    let all = sources(tree);
    let share = |c: Color| 100.0 * brightness(c) / total;
    let top: Vec<_> = all
        .iter()
        .take(3)
        .filter(|s| share(s.color) > 5.0)
        .collect();
    out.say(
        Said::SourcesHeading,
        "Where the colour comes from: each surface's own ambient + diffuse + specular, times the \
         weights and attenuations of the rays leading to it, as a share of the brightness:",
    );
    for source in &top {
        let what = match &source.object {
            Some(object) => format!("{object}, hit by"),
            None => "the background, seen by".to_string(),
        };
        out.ranked(
            Said::Source,
            format!("{:>5.1}%", share(source.color)),
            format!(
                "{what} {}: adds {}",
                place(tree, source.node),
                color(source.color)
            ),
        );
    }
    let rest = &all[top.len()..];
    if !rest.is_empty() {
        let sum = rest.iter().fold(Color::ZERO, |sum, s| sum + s.color);
        let (rays, add) = match (rest.len(), top.is_empty()) {
            (1, true) => ("1 ray".to_string(), "adds"),
            (1, false) => ("1 other ray".to_string(), "adds"),
            (n, true) => (format!("{n} rays"), "add"),
            (n, false) => (format!("{n} other rays"), "add"),
        };
        // Rays that add nothing visible (their share prints as 0.0%, their
        // colour as (0.000, 0.000, 0.000)) are not worth a line.
        if share(sum) >= 0.05 || sum.abs().max_element() >= 0.0005 {
            out.ranked(
                Said::Source,
                format!("{:>5.1}%", share(sum)),
                format!("{rays} {add} {}", color(sum)),
            );
        }
    }
}

/// The events anywhere in the tree that shaped the colour, largest first.
fn write_shaping(out: &mut Story, tree: &RayTree) {
    let events = shaping_events(tree);
    if events.is_empty() {
        out.say(
            Said::ShapedHeading,
            "Nothing else shaped it: no shadow, no total internal reflection, no ray cut short \
             or lost to the background, no channel clamped.",
        );
        return;
    }
    out.say(
        Said::ShapedHeading,
        "What shaped the colour, at any depth of the tree, largest first; the number is how \
         much of a channel it moved in the pixel, on average:",
    );
    // An event that moved the pixel by less than 0.0005 prints as 0.000.
    let (visible, invisible): (Vec<_>, Vec<_>) =
        events.into_iter().partition(|e| e.matters >= 0.0005);
    for event in &visible {
        out.ranked(
            Said::Shaped,
            format!("{:.3}", event.matters),
            event.text.clone(),
        );
    }
    if !invisible.is_empty() {
        out.item(
            Said::Shaped,
            format!(
                "{} changed nothing visible (less than 0.0005 on average).",
                if visible.is_empty() {
                    count(invisible.len() as u64, "event", "events")
                } else {
                    count(invisible.len() as u64, "more event", "more events")
                }
            ),
        );
    }
}

/// Each term of the primary ray with its share of the total brightness.
fn write_shares(out: &mut Story, tree: &RayTree, id: NodeId) {
    let node = &tree.nodes[id];
    let ambient = match node.hit.as_ref().and_then(|h| h.factors.ambient) {
        Some(_) => "ambient (the material's own)",
        None => "ambient",
    };
    let mut terms: Vec<(String, Color)> = vec![(ambient.into(), node.ambient)];
    if node.emission != Color::ZERO {
        terms.push(("emission, added as it is".into(), node.emission));
    }
    for light in &node.lights {
        terms.push((format!("diffuse from {}", light.light), light.diffuse));
        terms.push((format!("specular from {}", light.light), light.specular));
    }
    for child in tree.children(id) {
        let child = &tree.nodes[child];
        terms.push((format!("{} ray", kind_name(child.kind)), child.contribution));
    }
    let total: f64 = terms.iter().map(|(_, c)| brightness(*c)).sum();
    terms.sort_by(|a, b| brightness(b.1).total_cmp(&brightness(a.1)));
    out.say(
        Said::TermsHeading,
        "Its colour is the sum of these terms (largest first, share of the brightness):",
    );
    // A term that prints as (0.000, 0.000, 0.000) is only named, in one line.
    let (shown, tiny): (Vec<_>, Vec<_>) = terms
        .iter()
        .filter(|(_, c)| brightness(*c) > 0.0)
        .partition(|(_, c)| c.max_element() >= 0.0005);
    for (name, term) in shown {
        let share = if total > 0.0 {
            100.0 * brightness(*term) / total
        } else {
            0.0
        };
        out.item(
            Said::Term,
            format!("{name:<28} {}  {share:>5.1}%", color(*term)),
        );
    }
    if !tiny.is_empty() {
        let names: Vec<&str> = tiny.iter().map(|(name, _)| name.as_str()).collect();
        let each = if names.len() == 1 { "" } else { "each " };
        out.item(
            Said::Term,
            format!("and {} ({each}under 0.0005)", names.join(", ")),
        );
    }
    if total <= 0.0 {
        out.item(Said::Term, "every term is zero: nothing lights this point.");
    }
}

fn light_fate(light: &LightRecord) -> String {
    let fate = LightFate::of(light);
    let shadow = match fate {
        LightFate::AtPoint => {
            return format!(
                "{}: sits on the point (distance {} < EPS = {}), so it has no direction; it adds nothing and no shadow ray is cast.",
                light.light,
                num(light.distance.unwrap_or_default()),
                num(EPS)
            );
        }
        LightFate::FacesAway => {
            return format!(
                "{}: behind the surface (N·L = {}), so it cannot light this point; no shadow ray is cast.",
                light.light,
                num(light.n_dot_l)
            );
        }
        LightFate::NotCast => {
            return format!(
                "{}: lit (shadows are switched off), N·L = {}.",
                light.light,
                num(light.n_dot_l)
            );
        }
        LightFate::Lit(shadow)
        | LightFate::Crossed(shadow)
        | LightFate::PartlyBlocked(shadow)
        | LightFate::Blocked(shadow) => shadow,
    };
    let distance = match (directional_words(light), light.distance) {
        (Some(words), _) => format!(" A {words}: its shadow ray has no end."),
        (None, Some(d)) if !light.clamped => format!(
            " At distance d = {} attenuation f_att = {} = {}, no clamp (the cse167 profile).",
            num(d),
            attenuation_formula(light),
            num(light.f_att)
        ),
        (None, Some(d)) if light.f_att < 1.0 => format!(
            " At distance {} attenuation f_att = {} lets {:.1}% of its light arrive.",
            num(d),
            num(light.f_att),
            100.0 * light.f_att
        ),
        (None, _) => String::new(),
    };
    let distance = if light.lit_from_behind {
        format!(
            "{distance} It is behind the surface (N·L = {}): the cse167 profile adds no diffuse light, (N·L)₊ = 0, but its highlight still counts.",
            num(light.n_dot_l)
        )
    } else {
        distance
    };
    if let LightFate::Lit(_) = fate {
        return format!(
            "{}: lit, nothing in the way (N·L = {}).{distance}",
            light.light,
            num(light.n_dot_l)
        );
    }
    // S = 0 names the opaque crossing that put the light out (k_t = 0);
    // a product of transparent ones that came to 0 is told as the others.
    if let LightFate::Blocked(_) = fate
        && let Some(opaque) = shadow.blockers.iter().find(|b| b.kt == 0.0)
    {
        let of = shadow.distance.map_or_else(
            || "towards a directional light, which is infinitely far".to_string(),
            |d| format!("of {} to the light", num(d)),
        );
        return format!(
            "{}: in shadow, blocked by {} (opaque) at distance {} along the shadow ray, {of}.",
            light.light,
            opaque.object,
            along(opaque.t),
        );
    }
    let mut through: Vec<String> = Vec::new();
    for b in &shadow.blockers {
        let crossings = shadow
            .blockers
            .iter()
            .filter(|o| o.object_index == b.object_index)
            .count();
        let entry = if crossings > 1 {
            format!(
                "{} (k_t = {}, crossed {crossings} times)",
                b.object,
                num(b.kt)
            )
        } else {
            format!("{} (k_t = {})", b.object, num(b.kt))
        };
        if !through.contains(&entry) {
            through.push(entry);
        }
    }
    format!(
        "{}: partly blocked through {}: S = {}, so it gives {:.1}% of its light.{distance}",
        light.light,
        through.join(", "),
        num(shadow.s),
        100.0 * shadow.s
    )
}

fn write_child(out: &mut Story, tree: &RayTree, id: NodeId) {
    let child = &tree.nodes[id];
    let kind = match child.kind {
        RayKind::Reflected => "Reflected",
        _ => "Transmitted",
    };
    let target = match &child.hit {
        Some(hit) => format!("hits {} at distance {}", hit.object, num(hit.t)),
        None => "hits nothing (background)".into(),
    };
    out.say(
        Said::Child,
        format!(
            "{kind} ray (weight {}): {target} and brings back {}; after attenuation {} it adds {}.",
            weight_words(child),
            color(child.color),
            num(child.attenuation),
            color(child.contribution)
        ),
    );
}

/// The primary ray's secondary rays that were not cast, and how many were
/// not cast deeper in the tree, by rule (MODEL §5).
fn write_not_cast(out: &mut Story, tree: &RayTree) {
    for ray in &tree.root().not_cast {
        out.say(
            Said::NotCast,
            format!(
                "The {} ray is not cast: {}; it adds nothing.",
                kind_name(ray.kind),
                not_cast_reason(ray)
            ),
        );
    }
    let deeper = tree.nodes[1..].iter().flat_map(|n| &n.not_cast);
    let (mut light, mut budget) = (None, None);
    let (mut lighter, mut over) = (0u64, 0u64);
    for ray in deeper {
        match ray.rule {
            PruneRule::MinWeight { min_weight } => {
                lighter += 1;
                light = Some(min_weight);
            }
            PruneRule::MaxRays { max_rays } => {
                over += 1;
                budget = Some(max_rays);
            }
        }
    }
    if let Some(min_weight) = light {
        out.say(
            Said::NotCast,
            format!(
                "Deeper in the tree {} not cast: {} below min_weight {}.",
                count(lighter, "secondary ray was", "secondary rays were"),
                if lighter == 1 {
                    "its accumulated weight was"
                } else {
                    "their accumulated weight was"
                },
                fraction(min_weight)
            ),
        );
    }
    if let Some(max_rays) = budget {
        out.say(
            Said::NotCast,
            format!(
                "Deeper in the tree {} not cast: the pixel's tree had reached max_rays = \
             {max_rays} rays.",
                count(over, "secondary ray was", "secondary rays were")
            ),
        );
    }
}

/// What the primary ray went past although it came near: polygons whose
/// plane it met within their bounds (the crossing test said outside), and
/// spheres whose box it crossed (no real roots, or both behind).
fn write_near_misses(out: &mut Story, tree: &RayTree) {
    for near in &tree.root().near_misses {
        if let Some(figure) = &near.crossing_figure {
            out.say(
                Said::NearMiss,
                format!(
                "On its way it passes through the plane of {} inside its bounding box, but the point \
                 is outside the polygon: {}, an even number.",
                near.object,
                counted_edges(figure)
            ));
        }
        if let (Some((w, space)), Some(c)) =
            (sphere_quadratic(&near.working), near.closest_approach)
        {
            let why = if w.choice == RootChoice::NoRealRoots {
                format!(
                    "its line comes within {} of the centre{space}, more than the radius {}: a negative \
                     discriminant, no real roots",
                    num(c.distance),
                    num(c.radius)
                )
            } else {
                "both roots of its quadratic lie behind the ray's origin".to_string()
            };
            // NFF spheres are already named "sphere 3", unnamed ellipsoids "ellipsoid 2".
            let kind = match near.working {
                Working::Ellipsoid(_) => "ellipsoid",
                _ => "sphere",
            };
            let name = if near.object.starts_with(kind) {
                near.object.clone()
            } else {
                format!("{kind} {}", near.object)
            };
            out.say(
                Said::NearMiss,
                format!(
                    "On its way it crosses the bounding box of {name} but passes it by: {why}."
                ),
            );
        }
    }
}

fn counted(figure: &CrossingFigure) -> usize {
    figure.edges.iter().filter(|e| e.counts).count()
}

/// "2 edge crossings of +U (edges 1→2 at U = 1.5 and 3→4 at U = 0.5)".
fn counted_edges(figure: &CrossingFigure) -> String {
    let edges: Vec<String> = figure
        .edges
        .iter()
        .filter(|e| e.counts)
        .map(|e| format!("{}→{} at U = {}", e.from, e.to, num(e.u.unwrap_or(0.0))))
        .collect();
    match edges.len() {
        0 => "no edge crosses +U".to_string(),
        1 => format!("1 edge crossing of +U (edge {})", edges[0]),
        n => format!("{n} edge crossings of +U (edges {})", edges.join(", ")),
    }
}
