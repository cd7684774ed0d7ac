//! raystep's own tree as a ray log (`inspect --format raylog`): one line
//! per ray cast, primary, reflected, transmitted and shadow, in the order
//! the tracer cast them, with numbers that read back to the same bits.

use std::fmt::Write;

use glam::DVec3;

use super::logged_ray::{Hit, LoggedRay};
use super::path::{RayPath, Step};
use raystep_engine::record::{EventKind, NodeId, RayTree};
use raystep_engine::trace::RayKind;

/// The recorded rays of `tree` as log records, in the order they were cast.
pub fn rays_of(tree: &RayTree) -> Vec<LoggedRay> {
    rays_with_nodes(tree)
        .into_iter()
        .map(|(ray, _)| ray)
        .collect()
}

/// The recorded rays of `tree` in the order they were cast, each with the
/// node it belongs to: its own, or for a shadow ray the node whose hit cast it.
pub fn rays_with_nodes(tree: &RayTree) -> Vec<(LoggedRay, NodeId)> {
    // A node is recorded when cast, so its parent comes before it.
    let mut paths: Vec<RayPath> = Vec::with_capacity(tree.nodes.len());
    let mut weights: Vec<DVec3> = Vec::with_capacity(tree.nodes.len());
    for node in &tree.nodes {
        let (path, weight) = match node.parent {
            None => (RayPath::primary(), DVec3::ONE),
            Some(parent) => {
                let step = match node.kind {
                    RayKind::Transmitted => Step::Transmitted,
                    _ => Step::Reflected,
                };
                // The tracer's own product, in its order (parent's, then
                // this one's, then the colour a profile weighs it by).
                let own = weights[parent] * node.weight;
                let weight = node.tint.map_or(own, |tint| own * tint);
                (paths[parent].child(step), weight)
            }
        };
        paths.push(path);
        weights.push(weight);
    }
    let mut rays = Vec::new();
    for event in &tree.events {
        let node = &tree.nodes[event.node];
        match event.kind {
            EventKind::RayCast { .. } => {
                let mut ray = LoggedRay::new(tree.pixel, paths[event.node].clone());
                ray.origin = Some(node.origin);
                ray.dir = Some(node.direction);
                ray.weight = Some(weights[event.node]);
                ray.color = Some(node.color);
                ray.hit = Some(Hit::Miss);
                if let Some(hit) = &node.hit {
                    ray.hit = Some(Hit::Object(hit.object_index));
                    ray.t = Some(hit.t);
                    ray.point = Some(hit.point);
                    ray.normal = Some(hit.normal);
                    ray.ambient = Some(node.ambient);
                    ray.diffuse = Some(node.lights.iter().map(|l| l.diffuse).collect());
                    ray.specular = Some(node.lights.iter().map(|l| l.specular).collect());
                }
                rays.push((ray, event.node));
            }
            EventKind::ShadowCast { light } => {
                let shadow = node
                    .lights
                    .iter()
                    .find(|l| l.light_index == light)
                    .and_then(|l| l.shadow.as_ref());
                let path = paths[event.node].child(Step::Shadow(light));
                let mut ray = LoggedRay::new(tree.pixel, path);
                if let Some(shadow) = shadow {
                    ray.origin = Some(shadow.origin);
                    ray.dir = Some(shadow.direction);
                    ray.s = Some(shadow.s);
                }
                rays.push((ray, event.node));
            }
            _ => {}
        }
    }
    rays
}

/// The log of `tree`: one line per ray, each ending in a newline.
pub fn raylog(tree: &RayTree) -> String {
    rays_of(tree)
        .iter()
        .map(|ray| line_of(ray) + "\n")
        .collect()
}

/// `ray` as one JSON object on one line, keys in docs/RAYLOG.md's order,
/// the fields it lacks left out.
pub(crate) fn line_of(ray: &LoggedRay) -> String {
    let mut line = format!(
        "{{\"pixel\": [{}, {}], \"path\": \"{}\"",
        ray.pixel.0, ray.pixel.1, ray.path
    );
    let mut key = |name: &str, value: String| {
        let _ = write!(line, ", \"{name}\": {value}");
    };
    if let Some(v) = ray.origin {
        key("origin", vector(v));
    }
    if let Some(v) = ray.dir {
        key("dir", vector(v));
    }
    if let Some(hit) = ray.hit {
        key(
            "hit",
            match hit {
                Hit::Object(i) => i.to_string(),
                Hit::Miss => "null".to_string(),
            },
        );
    }
    if let Some(t) = ray.t {
        key("t", number(t));
    }
    if let Some(v) = ray.point {
        key("point", vector(v));
    }
    if let Some(v) = ray.normal {
        key("normal", vector(v));
    }
    if let Some(v) = ray.color {
        key("color", vector(v));
    }
    if let Some(v) = ray.ambient {
        key("ambient", vector(v));
    }
    if let Some(vs) = &ray.diffuse {
        key("diffuse", vectors(vs));
    }
    if let Some(vs) = &ray.specular {
        key("specular", vectors(vs));
    }
    if let Some(s) = ray.s {
        key("S", number(s));
    }
    if let Some(w) = ray.weight {
        // A number, as every tracer logs it, unless a colour weighs it.
        key(
            "weight",
            super::uniform(w).map_or_else(|| vector(w), number),
        );
    }
    line.push('}');
    line
}

/// Rust's shortest form that reads back to the same bits (`-0.0` keeps its
/// sign, 1e-20 its exponent); NaN and infinities as Python's json writes them.
fn number(x: f64) -> String {
    if x.is_nan() {
        "NaN".to_string()
    } else if x.is_infinite() {
        if x > 0.0 { "Infinity" } else { "-Infinity" }.to_string()
    } else {
        format!("{x:?}")
    }
}

fn vector(v: DVec3) -> String {
    format!("[{}, {}, {}]", number(v.x), number(v.y), number(v.z))
}

fn vectors(vs: &[DVec3]) -> String {
    let inner: Vec<String> = vs.iter().map(|&v| vector(v)).collect();
    format!("[{}]", inner.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_print_in_their_shortest_exact_form() {
        for (x, text) in [
            (1.0, "1.0"),
            (-0.0, "-0.0"),
            (0.1, "0.1"),
            (1e-20, "1e-20"),
            (f64::NAN, "NaN"),
            (f64::NEG_INFINITY, "-Infinity"),
        ] {
            assert_eq!(number(x), text);
        }
    }

    #[test]
    fn a_line_has_only_the_fields_the_ray_has() {
        let mut ray = LoggedRay::new((3, 4), RayPath::primary().child(Step::Shadow(1)));
        ray.s = Some(0.5);
        ray.hit = Some(Hit::Miss);
        assert_eq!(
            line_of(&ray),
            r#"{"pixel": [3, 4], "path": "P/S1", "hit": null, "S": 0.5}"#
        );
    }
}
