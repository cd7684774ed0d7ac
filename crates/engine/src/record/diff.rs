//! What-if: one pixel recorded twice (before and after a change of the
//! settings or the scene) and what changed between the two trees: the
//! pixel's colour, the rays that appeared or disappeared, and each term of
//! each ray that moved. Rays are matched by their path from the primary ray
//! ("primary → reflected → transmitted"), as a student would name them.

use std::collections::HashMap;
use std::fmt::Write;

use super::numbers::color;
use super::ray_tree::{Node, NodeId, RayTree};
use super::shared_words::kind_name;
use raystep_model::math::Color;

/// A change smaller than this in every channel is not reported (well below
/// the 3-decimal print and half an 8-bit step).
const NOTICEABLE: f64 = 5e-4;

/// The differences of `after` from `before` (the same pixel), in words; one
/// line saying nothing changed when nothing did.
pub fn diff(before: &RayTree, after: &RayTree) -> String {
    let mut out = String::new();
    let (b, a) = (before.color(), after.color());
    let _ = writeln!(
        out,
        "Pixel ({}, {}): colour {} -> {} (rgb8 {:?} -> {:?}).",
        after.pixel.0,
        after.pixel.1,
        color(b),
        color(a),
        before.rgb8(),
        after.rgb8()
    );
    let paths_before = paths(before);
    let paths_after = paths(after);
    // Matched through a map of the paths (a path names one ray in a
    // tree): linear, where a search of the list per ray took minutes on
    // trees of 65,536 rays.
    let (ids_before, ids_after) = (by_path(&paths_before), by_path(&paths_after));
    let mut lines = Vec::new();
    for (path, id) in &paths_before {
        match ids_after.get(path.as_str()) {
            None => lines.push(format!(
                "  the {path} ray is gone (it brought {})",
                color(before.nodes[*id].color)
            )),
            Some(other) => node_changes(&mut lines, path, &before.nodes[*id], &after.nodes[*other]),
        }
    }
    for (path, id) in &paths_after {
        if !ids_before.contains_key(path.as_str()) {
            lines.push(format!(
                "  a new {path} ray (it brings {})",
                color(after.nodes[*id].color)
            ));
        }
    }
    if lines.is_empty() {
        out.push_str("  nothing else changed: the same rays with the same terms.\n");
    }
    for line in lines {
        let _ = writeln!(out, "{line}");
    }
    out
}

/// Every ray's path from the primary ray, in tree order.
fn paths(tree: &RayTree) -> Vec<(String, NodeId)> {
    let mut out = Vec::new();
    let mut stack = vec![(kind_name(tree.root().kind).to_string(), 0)];
    while let Some((path, id)) = stack.pop() {
        let children: Vec<NodeId> = tree.children(id).collect();
        for &child in children.iter().rev() {
            stack.push((
                format!("{path} → {}", kind_name(tree.nodes[child].kind)),
                child,
            ));
        }
        out.push((path, id));
    }
    out
}

/// Each ray by its path (a path names one ray: a ray has at most one
/// reflected and one transmitted child).
fn by_path(paths: &[(String, NodeId)]) -> HashMap<&str, NodeId> {
    (paths.iter()).map(|(p, id)| (p.as_str(), *id)).collect()
}

/// The terms of one ray that moved between `before` and `after`.
fn node_changes(lines: &mut Vec<String>, path: &str, before: &Node, after: &Node) {
    let mut changed = Vec::new();
    let object = |n: &Node| n.hit.as_ref().map(|h| h.object.clone());
    if object(before) != object(after) {
        let name = |o: Option<String>| o.unwrap_or_else(|| "nothing (a miss)".into());
        changed.push(format!(
            "hits {} -> {}",
            name(object(before)),
            name(object(after))
        ));
    }
    let mut term = |what: String, b: Color, a: Color| {
        if (a - b).abs().max_element() >= NOTICEABLE {
            changed.push(format!("{what} {} -> {}", color(b), color(a)));
        }
    };
    term("ambient".into(), before.ambient, after.ambient);
    for light in &before.lights {
        let other = after
            .lights
            .iter()
            .find(|l| l.light_index == light.light_index);
        let (d, s) = other.map_or((Color::ZERO, Color::ZERO), |l| (l.diffuse, l.specular));
        term(format!("diffuse from {}", light.light), light.diffuse, d);
        term(format!("specular from {}", light.light), light.specular, s);
    }
    term("colour".into(), before.color, after.color);
    let tir = |n: &Node| n.tir();
    if tir(before) != tir(after) {
        changed.push(if tir(after) {
            "now total internal reflection".into()
        } else {
            "no longer total internal reflection".into()
        });
    }
    if !changed.is_empty() {
        lines.push(format!("  {path} ray: {}", changed.join("; ")));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::record_pixel;
    use crate::scene::builtin::load_file_or_builtin;

    #[test]
    fn the_same_tree_changes_nothing() {
        let scene = load_file_or_builtin(None).unwrap();
        let tree = record_pixel(&scene, &scene.settings, 80, 60);
        let text = diff(&tree, &tree);
        assert!(text.contains("nothing else changed"), "{text}");
    }

    #[test]
    fn a_lower_depth_removes_the_deepest_rays_and_says_so() {
        // The built-in scene's centre pixel has rays at depth 3 (its
        // max_depth); at max_depth 2 those are gone and their parents'
        // colours change.
        let scene = load_file_or_builtin(None).unwrap();
        let mut shallow = scene.settings;
        shallow.max_depth = 2;
        let before = record_pixel(&scene, &scene.settings, 80, 60);
        let after = record_pixel(&scene, &shallow, 80, 60);
        let gone = before.nodes.iter().filter(|n| n.depth == 3).count();
        assert!(gone > 0);
        let text = diff(&before, &after);
        assert_eq!(text.matches("ray is gone").count(), gone, "{text}");
        assert!(!text.contains("a new"), "{text}");
    }
}
