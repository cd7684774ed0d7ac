//! The events anywhere in a pixel's ray tree that shaped its colour, each
//! with how much it mattered: `explain` lists them, largest first, after
//! the primary hit's story, so that total internal reflection three rays
//! down is told as plainly as a shadow on the first hit.

use super::numbers::{color, num, root};
use super::ray_tree::{LightRecord, MaterialFactors, Node, NodeId, RayTree};
use super::shared_words::{cosine_name, kind_name, not_cast_reason};
use raystep_model::math::Color;

/// One event and how much it matters to the pixel: the mean over the three
/// channels of the colour it added or took away, after the weights and
/// attenuations of every ray above it (for a ray never cast, the most it
/// could have added: its weight times the path's).
#[derive(Clone, Debug, PartialEq)]
pub struct Shaping {
    pub matters: f64,
    pub node: NodeId,
    pub text: String,
}

/// Every shaping event of the tree, largest first; ties in tree order.
pub fn shaping_events(tree: &RayTree) -> Vec<Shaping> {
    let mut events = Vec::new();
    for id in 0..tree.nodes.len() {
        let node = &tree.nodes[id];
        let reach = reach(tree, id);
        let Some(hit) = &node.hit else {
            if id != 0 {
                events.push(miss(tree, id, reach));
            }
            continue;
        };
        // At the depth limit TIR is told with the reflected ray it does not cast.
        if node.tir() && !node.at_depth_limit() {
            events.push(tir(tree, id, reach, &hit.object));
        }
        for light in &node.lights {
            if let Some(event) = blocked(tree, id, reach, light, &hit.factors) {
                events.push(event);
            }
        }
        events.extend(depth_cut(tree, id, reach));
        for ray in &node.not_cast {
            let matters = reach * ray.weight;
            events.push(Shaping {
                matters,
                node: id,
                text: format!(
                    "at {} the {} ray (weight {}) is not cast: {}; it could have added up to {} \
                     to each channel.",
                    place(tree, id),
                    kind_name(ray.kind),
                    num(ray.weight),
                    not_cast_reason(ray),
                    num(matters)
                ),
            });
        }
    }
    events.extend(clamped(tree.color()));
    events.sort_by(|a, b| b.matters.total_cmp(&a.matters));
    events
}

/// The most a node's colour is scaled by in the pixel, in any channel: the
/// product of weight x attenuation of the node and every ray above it.
pub fn reach(tree: &RayTree, id: NodeId) -> f64 {
    super::tree_words::path_factor(tree, id).max_element()
}

fn mean(c: Color) -> f64 {
    (c.x + c.y + c.z) / 3.0
}

/// "r3 (primary → transmitted → reflected, depth 3)": a ray and its path.
pub fn place(tree: &RayTree, id: NodeId) -> String {
    let mut kinds = Vec::new();
    let mut at = Some(id);
    while let Some(node) = at.map(|i| &tree.nodes[i]) {
        kinds.push(kind_name(node.kind));
        at = node.parent;
    }
    kinds.reverse();
    format!(
        "r{id} ({}, depth {})",
        kinds.join(" → "),
        tree.nodes[id].depth
    )
}

fn miss(tree: &RayTree, id: NodeId, reach: f64) -> Shaping {
    let node = &tree.nodes[id];
    // Channel by channel: a profile may weigh a ray by a colour (MODEL §11).
    let adds = super::tree_words::path_factor(tree, id) * node.color;
    let tinted = std::iter::successors(Some(id), |&n| tree.nodes[n].parent)
        .any(|n| tree.nodes[n].tint.is_some());
    Shaping {
        matters: if tinted {
            mean(adds)
        } else {
            reach * mean(node.color)
        },
        node: id,
        text: format!(
            "{} misses everything: the background {} adds {} to the pixel.",
            place(tree, id),
            color(node.color),
            color(adds)
        ),
    }
}

fn tir(tree: &RayTree, id: NodeId, reach: f64, object: &str) -> Shaping {
    let node = &tree.nodes[id];
    let k = node.refraction.map_or(0.0, |r| r.k);
    let kt = node.hit.as_ref().map_or(0.0, |h| h.factors.kt);
    let reflected = node.reflected.map(|c| &tree.nodes[c]);
    // The part of the reflected ray's weight that k_t moved to it.
    let moved = match reflected {
        Some(r) if r.weight > 0.0 => (r.weight - ks(node)).max(0.0) / r.weight * r.contribution,
        _ => Color::ZERO,
    };
    let carried = match (node.reflected, reflected) {
        (Some(c), Some(r)) => format!(
            "moves to the reflected ray r{c} (weight {}), whose k_t share adds {} to the pixel",
            num(r.weight),
            color(reach * moved)
        ),
        _ => "is lost: no reflected ray carries it".into(),
    };
    Shaping {
        matters: reach * mean(moved),
        node: id,
        text: format!(
            "total internal reflection at {} on {object}: k = {} < 0, no transmitted ray; \
             k_t = {} {carried}.",
            place(tree, id),
            num(k),
            num(kt)
        ),
    }
}

fn ks(node: &Node) -> f64 {
    node.hit.as_ref().map_or(0.0, |h| h.factors.ks)
}

/// A light with S < 1: what it would have added unblocked, less what it did.
fn blocked(
    tree: &RayTree,
    id: NodeId,
    reach: f64,
    light: &LightRecord,
    f: &MaterialFactors,
) -> Option<Shaping> {
    let shadow = light.shadow.as_ref().filter(|s| s.s < 1.0)?;
    let highlight = if f.ks == 0.0 {
        0.0
    } else {
        light.specular_cosine.max(0.0).powf(f.n)
    };
    let unblocked = light.f_att * light.i_p * (f.kd * light.n_dot_l * f.o_d + f.ks * highlight);
    let lost = reach * (1.0 - shadow.s) * unblocked;
    let by: Vec<String> = shadow
        .blockers
        .iter()
        .map(|b| {
            let which = b.root.map(|r| format!(", root {r}")).unwrap_or_default();
            format!(
                "{} ({}{which}, k_t = {})",
                b.object,
                root("t", b.t),
                num(b.kt)
            )
        })
        .collect();
    // With k_s = 0 the light only ever gave a diffuse term.
    let terms = if f.ks == 0.0 {
        format!("its diffuse term with N·L = {}", num(light.n_dot_l))
    } else {
        format!(
            "diffuse with N·L = {}, specular with {} = {}",
            num(light.n_dot_l),
            cosine_name(light.specular_model),
            num(light.specular_cosine)
        )
    };
    let how = if shadow.s == 0.0 {
        "blocked"
    } else {
        "partly blocked"
    };
    Some(Shaping {
        matters: mean(lost),
        node: id,
        text: format!(
            "{} is {how} at {} by {}: S = {}; unblocked it would add {} more to the pixel \
             ({terms}).",
            light.light,
            place(tree, id),
            by.join(", "),
            num(shadow.s),
            color(lost)
        ),
    })
}

/// A hit whose material reflects or transmits at the depth limit: the rays
/// it would have spawned are not cast (MODEL §5).
fn depth_cut(tree: &RayTree, id: NodeId, reach: f64) -> Vec<Shaping> {
    let node = &tree.nodes[id];
    // TIR is told here, with the ray it does not cast: on which object.
    let tir = match &node.hit {
        Some(hit) if node.tir() => format!(
            ", the one ray of a total internal reflection on {}",
            hit.object
        ),
        _ => String::new(),
    };
    node.depth_cut()
        .map(|(kind, weight)| Shaping {
            matters: reach * weight,
            node: id,
            text: format!(
                "at {} the depth limit (max_depth {}) stops its {} ray (weight {}){}: it could \
                 have added up to {} to each channel.",
                place(tree, id),
                tree.max_depth,
                kind_name(kind),
                num(weight),
                tir,
                num(reach * weight)
            ),
        })
        .collect()
}

fn clamped(c: Color) -> Vec<Shaping> {
    let mut events = Vec::new();
    for (name, value) in [("red", c.x), ("green", c.y), ("blue", c.z)] {
        let (kept, stored) = if value > 1.0 {
            (1.0, "255 (clamped)")
        } else if value < 0.0 {
            (0.0, "0 (clamped)")
        } else {
            continue;
        };
        events.push(Shaping {
            matters: (value - kept).abs() / 3.0,
            node: 0,
            text: format!(
                "the {name} channel is {} before clamping: it is stored as {stored}.",
                num(value)
            ),
        });
    }
    events
}
