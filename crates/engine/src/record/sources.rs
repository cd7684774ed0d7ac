//! Where a pixel's colour comes from: each ray's own share of it. A hit's
//! local terms (ambient + diffuse + specular, MODEL §6) and a miss's
//! background, times the weight x attenuation of every ray on the path to
//! it, sum over the tree to the pixel's colour (before clamping), since a
//! node's colour is its local terms plus its children's contributions.

use super::ray_tree::{NodeId, RayTree};
use super::tree_words::path_factor;
use raystep_model::math::Color;

/// One ray's own part of the pixel: what its surface (or the background,
/// for a miss) adds after every weight and attenuation above it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Source {
    pub(crate) node: NodeId,
    /// The object hit, `None` for the background.
    pub(crate) object: Option<String>,
    pub(crate) color: Color,
}

/// Every ray's own part, largest brightness (sum of channels) first; ties
/// in tree order. The colours sum to the pixel's colour before clamping.
pub(crate) fn sources(tree: &RayTree) -> Vec<Source> {
    let mut all: Vec<Source> = tree
        .nodes
        .iter()
        .enumerate()
        .map(|(id, node)| {
            let local = match &node.hit {
                Some(_) => {
                    let lights = node.lights.iter().map(|l| l.diffuse + l.specular);
                    lights.fold(node.ambient + node.emission, |sum, term| sum + term)
                }
                None => node.color,
            };
            Source {
                node: id,
                object: node.hit.as_ref().map(|h| h.object.clone()),
                color: path_factor(tree, id) * local,
            }
        })
        .collect();
    all.sort_by(|a, b| brightness(b.color).total_cmp(&brightness(a.color)));
    all
}

/// The brightness used to compare parts: the sum of the three channels.
pub(crate) fn brightness(c: Color) -> f64 {
    c.x + c.y + c.z
}
