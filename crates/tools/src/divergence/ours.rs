//! raystep's own rays of a pixel, as a ray log holds them, each tied to
//! the node of the recording it came from, found by path.

use std::collections::HashMap;

use crate::raylog::{LoggedRay, RayPath, Step, rays_with_nodes};
use raystep_engine::record::{LightRecord, Node, NodeId, RayTree, record_pixel};
use raystep_engine::render::viewport;
use raystep_engine::scene::{Scene, Settings};
use raystep_engine::trace::Rules;
use raystep_model::camera::Viewport;

/// Up to this many rays, a path is found by looking at each: cheaper than
/// hashing it, and most pixels have a handful of rays.
const SMALL_TREE: usize = 32;

/// One pixel's recording and its rays in the order they were cast.
pub struct OurRays {
    pub(crate) tree: RayTree,
    rays: Vec<LoggedRay>,
    nodes: Vec<NodeId>,
    by_path: HashMap<RayPath, usize>,
}

impl OurRays {
    /// Records pixel (x, y) of `scene` with `settings`.
    pub(crate) fn record(scene: &Scene, settings: &Settings, (x, y): (u32, u32)) -> Self {
        Self::of(record_pixel(scene, settings, x, y))
    }

    pub fn of(tree: RayTree) -> Self {
        let (rays, nodes): (Vec<LoggedRay>, Vec<NodeId>) =
            rays_with_nodes(&tree).into_iter().unzip();
        let by_path = if rays.len() > SMALL_TREE {
            rays.iter()
                .enumerate()
                .map(|(i, ray)| (ray.path.clone(), i))
                .collect()
        } else {
            HashMap::new()
        };
        Self {
            tree,
            rays,
            nodes,
            by_path,
        }
    }

    /// The rules ours was traced by: the recorded settings, with their
    /// mistakes (MODEL §8). An explainer words these, never the model's
    /// rules written again.
    pub(crate) fn rules(&self) -> Rules<'_, true> {
        Rules::new(&self.tree.settings)
    }

    /// Which primary ray each pixel got when ours was traced: the camera
    /// with the recorded settings' pixel mistakes, as the render asks.
    pub(crate) fn viewport(&self, scene: &Scene) -> Viewport {
        viewport(scene, &self.tree.settings, (scene.width, scene.height))
    }

    /// The rays in the order they were cast.
    pub(crate) fn rays(&self) -> &[LoggedRay] {
        &self.rays
    }

    pub(crate) fn find(&self, path: &RayPath) -> Option<usize> {
        if self.rays.len() <= SMALL_TREE {
            return self.rays.iter().position(|ray| ray.path == *path);
        }
        self.by_path.get(path).copied()
    }

    /// The node a ray belongs to: its own, or for a shadow ray the node
    /// whose hit cast it.
    pub(crate) fn node(&self, ray: usize) -> &Node {
        &self.tree.nodes[self.nodes[ray]]
    }

    /// The node whose hit a ray leaves from: a shadow ray's caster, a
    /// secondary ray's parent; none for the primary ray.
    pub(crate) fn source(&self, ray: usize) -> Option<&Node> {
        let node = self.node(ray);
        if self.rays[ray].path.is_shadow() {
            Some(node)
        } else {
            node.parent.map(|parent| &self.tree.nodes[parent])
        }
    }

    /// A shadow ray's light record, on its caster's hit.
    pub(crate) fn light(&self, ray: usize) -> Option<&LightRecord> {
        let Some(Step::Shadow(light)) = self.rays[ray].path.steps.last() else {
            return None;
        };
        self.node(ray)
            .lights
            .iter()
            .find(|l| l.light_index == *light)
    }

    /// The node of the shading ray at `path` (not a shadow ray), if ours
    /// cast it.
    pub(crate) fn node_at(&self, path: &RayPath) -> Option<&Node> {
        let ray = self.find(path)?;
        (!path.is_shadow()).then(|| self.node(ray))
    }
}
