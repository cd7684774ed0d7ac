//! The recorder that builds a pixel's ray tree and event list from the
//! tracer's callbacks. It never computes a term itself: every number it holds
//! is the one the tracer used, so a tree cannot disagree with the image.

use glam::DVec3;
use serde::Serialize;
use serde_json::Value;

use crate::accel::Cost;
use crate::math::{Color, Interval, Ray};
use crate::scene::{Scene, SpecularModel};
use crate::shapes::{Shape, Working};
use crate::trace::{
    Blocker, ChildTerm, LightTerm, RayKind, Recorder, Refraction, SurfaceHit, trace_pixel,
};

pub type NodeId = usize;

/// One shading ray (primary, reflected or transmitted) and all it computed.
#[derive(Clone, Debug, Serialize)]
pub struct Node {
    #[serde(skip)]
    pub parent: Option<NodeId>,
    pub kind: RayKind,
    pub depth: u32,
    pub origin: DVec3,
    pub direction: DVec3,
    /// The factor this ray's colour is scaled by in its parent (1 for the primary ray).
    pub weight: f64,
    /// Distance attenuation applied in the parent (1 for a miss and for the primary ray).
    pub attenuation: f64,
    pub hit: Option<HitRecord>,
    /// Polygons whose plane the ray met before its hit (or at all, on a miss)
    /// but whose crossing test said outside: why the ray went past them.
    pub near_misses: Vec<NearMiss>,
    /// What the closest-hit query tested.
    pub cost: Cost,
    pub ambient: Color,
    pub lights: Vec<LightRecord>,
    pub refraction: Option<Refraction>,
    pub tir: bool,
    pub reflected: Option<NodeId>,
    pub transmitted: Option<NodeId>,
    /// The colour this ray returns, the sum of its stored terms.
    pub color: Color,
    /// weight * attenuation * color: what it adds to its parent.
    pub contribution: Color,
}

#[derive(Clone, Debug, Serialize)]
pub struct HitRecord {
    pub object: String,
    /// 0-based, in file order.
    pub object_index: usize,
    pub kind: &'static str,
    pub material: String,
    pub t: f64,
    pub point: DVec3,
    /// N_g.
    pub normal: DVec3,
    /// N, facing the ray.
    pub shading_normal: DVec3,
    pub entering: bool,
    /// The intersection worked the way the course notes teach it.
    pub working: Working,
}

#[derive(Clone, Debug, Serialize)]
pub struct NearMiss {
    pub object: String,
    pub object_index: usize,
    pub working: Working,
}

/// Near misses are looked for in scenes up to this size, where they teach;
/// in benchmark scenes the scan would cost more than the whole pixel.
pub const NEAR_MISS_SCENE_LIMIT: usize = 2000;

#[derive(Clone, Debug, Serialize)]
pub struct LightRecord {
    pub light: String,
    pub light_index: usize,
    pub to_light: DVec3,
    pub distance: f64,
    pub n_dot_l: f64,
    pub faces_away: bool,
    pub shadow: Option<ShadowRecord>,
    pub f_att: f64,
    pub specular_model: SpecularModel,
    /// N·H with Blinn, R·V with Phong, before clamping.
    pub specular_cosine: f64,
    pub diffuse: Color,
    pub specular: Color,
}

#[derive(Clone, Debug, Serialize)]
pub struct ShadowRecord {
    pub origin: DVec3,
    pub direction: DVec3,
    pub distance: f64,
    /// Every crossing of the segment, nearest first.
    pub blockers: Vec<BlockerRecord>,
    pub s: f64,
    pub cost: Cost,
}

#[derive(Clone, Debug, Serialize)]
pub struct BlockerRecord {
    pub object: String,
    pub object_index: usize,
    pub t: f64,
    pub kt: f64,
}

/// One step of the trace, in the order the tracer performed it.
#[derive(Clone, Debug, Serialize)]
pub struct Event {
    /// The node (shading ray) the step belongs to.
    pub node: NodeId,
    #[serde(flatten)]
    pub kind: EventKind,
}

#[derive(Clone, Debug, Serialize)]
#[serde(tag = "event", rename_all = "snake_case")]
pub enum EventKind {
    RayCast {
        kind: RayKind,
        depth: u32,
    },
    Hit {
        object: usize,
        t: f64,
        tested: Cost,
    },
    Miss {
        tested: Cost,
    },
    Ambient {
        term: Color,
    },
    ShadowCast {
        light: usize,
    },
    Blocker {
        light: usize,
        object: usize,
        t: f64,
        kt: f64,
    },
    Light {
        light: usize,
        faces_away: bool,
        s: Option<f64>,
        diffuse: Color,
        specular: Color,
    },
    Refraction {
        tir: bool,
    },
    ChildReturned {
        child: NodeId,
        kind: RayKind,
        contribution: Color,
    },
    RayDone {
        color: Color,
    },
}

/// A pixel's recording: the tree (node 0 is the primary ray) and its events.
#[derive(Clone, Debug)]
pub struct RayTree {
    pub pixel: (u32, u32),
    /// The scene's max_depth when recorded.
    pub max_depth: Option<u32>,
    pub nodes: Vec<Node>,
    pub events: Vec<Event>,
}

/// Builds a `RayTree` from the tracer's callbacks.
pub struct TreeRecorder<'a> {
    scene: &'a Scene,
    nodes: Vec<Node>,
    events: Vec<Event>,
    /// The node of the ray being traced, innermost last.
    stack: Vec<NodeId>,
    /// Blockers of the shadow ray being traced, in the order found.
    blockers: Vec<Blocker>,
    /// The shadow ray being traced: its light, ray and length.
    shadow_ray: Option<(usize, Ray, f64)>,
}

/// Records pixel (x, y): the same `trace_pixel` call the render makes.
pub fn record_pixel(scene: &Scene, x: u32, y: u32) -> RayTree {
    let viewport = scene.camera.viewport(scene.width, scene.height);
    let mut recorder = TreeRecorder::new(scene);
    trace_pixel(scene, &viewport, x, y, &mut recorder);
    recorder.into_tree((x, y))
}

impl<'a> TreeRecorder<'a> {
    pub fn new(scene: &'a Scene) -> Self {
        Self {
            scene,
            nodes: Vec::new(),
            events: Vec::new(),
            stack: Vec::new(),
            blockers: Vec::new(),
            shadow_ray: None,
        }
    }

    /// The finished recording, labelled with the pixel it belongs to.
    pub fn into_tree(self, pixel: (u32, u32)) -> RayTree {
        RayTree {
            pixel,
            max_depth: Some(self.scene.settings.max_depth),
            nodes: self.nodes,
            events: self.events,
        }
    }

    fn current(&self) -> NodeId {
        *self.stack.last().expect("a callback outside any ray")
    }

    fn node(&mut self) -> &mut Node {
        let id = self.current();
        &mut self.nodes[id]
    }

    fn push_event(&mut self, kind: EventKind) {
        let node = self.current();
        self.events.push(Event { node, kind });
    }
}

impl Recorder for TreeRecorder<'_> {
    const RECORDS_ALL_BLOCKERS: bool = true;

    fn ray_cast(&mut self, kind: RayKind, depth: u32, ray: &Ray, weight: f64) {
        let parent = self.stack.last().copied();
        let id = self.nodes.len();
        self.nodes.push(Node {
            parent,
            kind,
            depth,
            origin: ray.origin,
            direction: ray.direction,
            weight,
            attenuation: 1.0,
            hit: None,
            near_misses: Vec::new(),
            cost: Cost::default(),
            ambient: Color::ZERO,
            lights: Vec::new(),
            refraction: None,
            tir: false,
            reflected: None,
            transmitted: None,
            color: Color::ZERO,
            contribution: Color::ZERO,
        });
        if let Some(parent) = parent {
            match kind {
                RayKind::Reflected => self.nodes[parent].reflected = Some(id),
                RayKind::Transmitted => self.nodes[parent].transmitted = Some(id),
                RayKind::Primary => {}
            }
        }
        self.stack.push(id);
        self.push_event(EventKind::RayCast { kind, depth });
    }

    fn hit(&mut self, hit: &SurfaceHit, cost: Cost) {
        let scene = self.scene;
        let object = &scene.objects[hit.object];
        let node = self.node();
        let ray = Ray::new(node.origin, node.direction);
        node.cost = cost;
        node.near_misses = near_misses(scene, &ray, hit.t);
        node.hit = Some(HitRecord {
            object: object.name.clone(),
            object_index: hit.object,
            kind: object.shape.kind(),
            material: scene.materials[object.material].name.clone(),
            t: hit.t,
            point: hit.point,
            normal: hit.geometric_normal,
            shading_normal: hit.normal,
            entering: hit.entering,
            working: object.shape.working(&ray, Interval::in_front()),
        });
        self.push_event(EventKind::Hit {
            object: hit.object,
            t: hit.t,
            tested: cost,
        });
    }

    fn miss(&mut self, _background: Color, cost: Cost) {
        let scene = self.scene;
        let node = self.node();
        node.cost = cost;
        node.near_misses =
            near_misses(scene, &Ray::new(node.origin, node.direction), f64::INFINITY);
        self.push_event(EventKind::Miss { tested: cost });
    }

    fn ambient(&mut self, term: Color) {
        self.node().ambient = term;
        self.push_event(EventKind::Ambient { term });
    }

    fn shadow_cast(&mut self, light: usize, ray: &Ray, distance: f64) {
        self.blockers.clear();
        self.shadow_ray = Some((light, *ray, distance));
        self.push_event(EventKind::ShadowCast { light });
    }

    fn blocker(&mut self, blocker: &Blocker) {
        self.blockers.push(*blocker);
        let Some((light, _, _)) = self.shadow_ray else {
            return;
        };
        self.push_event(EventKind::Blocker {
            light,
            object: blocker.object,
            t: blocker.t,
            kt: blocker.kt,
        });
    }

    fn light(&mut self, term: &LightTerm) {
        let scene = self.scene;
        let shadow = match (term.shadow, self.shadow_ray.take()) {
            (Some(outcome), Some((_, ray, distance))) => {
                let mut blockers: Vec<BlockerRecord> = self
                    .blockers
                    .iter()
                    .map(|b| BlockerRecord {
                        object: scene.objects[b.object].name.clone(),
                        object_index: b.object,
                        t: b.t,
                        kt: b.kt,
                    })
                    .collect();
                blockers.sort_by(|a, b| {
                    a.t.total_cmp(&b.t)
                        .then(a.object_index.cmp(&b.object_index))
                });
                Some(ShadowRecord {
                    origin: ray.origin,
                    direction: ray.direction,
                    distance,
                    blockers,
                    s: outcome.s,
                    cost: outcome.cost,
                })
            }
            _ => None,
        };
        let s = shadow.as_ref().map(|s| s.s);
        self.node().lights.push(LightRecord {
            light: scene.lights[term.light].name.clone(),
            light_index: term.light,
            to_light: term.to_light,
            distance: term.distance,
            n_dot_l: term.n_dot_l,
            faces_away: term.faces_away,
            shadow,
            f_att: term.f_att,
            specular_model: term.specular_model,
            specular_cosine: term.specular_cosine,
            diffuse: term.diffuse,
            specular: term.specular,
        });
        self.push_event(EventKind::Light {
            light: term.light,
            faces_away: term.faces_away,
            s,
            diffuse: term.diffuse,
            specular: term.specular,
        });
    }

    fn refraction(&mut self, refraction: &Refraction) {
        let node = self.node();
        node.refraction = Some(*refraction);
        node.tir = refraction.tir;
        self.push_event(EventKind::Refraction {
            tir: refraction.tir,
        });
    }

    fn child(&mut self, term: &ChildTerm) {
        let parent = self.current();
        let child = match term.kind {
            RayKind::Reflected => self.nodes[parent].reflected,
            RayKind::Transmitted => self.nodes[parent].transmitted,
            RayKind::Primary => None,
        };
        let Some(child) = child else { return };
        self.nodes[child].attenuation = term.attenuation;
        self.nodes[child].contribution = term.contribution;
        self.push_event(EventKind::ChildReturned {
            child,
            kind: term.kind,
            contribution: term.contribution,
        });
    }

    fn ray_done(&mut self, color: Color) {
        let node = self.node();
        node.color = color;
        if node.parent.is_none() {
            node.contribution = color;
        }
        self.push_event(EventKind::RayDone { color });
        self.stack.pop();
    }
}

/// Polygons and patches whose plane the ray meets in front of `before`,
/// within the polygon's bounding box, but whose crossing test puts the point
/// outside: a concave notch, or just past an edge.
fn near_misses(scene: &Scene, ray: &Ray, before: f64) -> Vec<NearMiss> {
    if scene.objects.len() > NEAR_MISS_SCENE_LIMIT {
        return Vec::new();
    }
    let range = Interval::new(crate::math::EPS, before);
    let mut found = Vec::new();
    for (index, object) in scene.objects.iter().enumerate() {
        let polygon = match &object.shape {
            Shape::Polygon(p) => p,
            Shape::Patch(p) => &p.polygon,
            _ => continue,
        };
        let working = polygon.solve(ray, range);
        let in_box = working
            .plane
            .hit_t()
            .is_some_and(|t| polygon.bounds().contains(ray.at(t)));
        if in_box && working.crossing.is_some_and(|c| !c.inside) {
            found.push(NearMiss {
                object: object.name.clone(),
                object_index: index,
                working: object.shape.working(ray, range),
            });
        }
    }
    found
}

impl RayTree {
    pub fn root(&self) -> &Node {
        &self.nodes[0]
    }

    /// The pixel's colour before clamping.
    pub fn color(&self) -> Color {
        self.root().color
    }

    pub fn children(&self, id: NodeId) -> impl Iterator<Item = NodeId> + '_ {
        let node = &self.nodes[id];
        node.reflected.into_iter().chain(node.transmitted)
    }

    /// The sum of a node's stored terms, in the tracer's order; equals its colour.
    pub fn sum_of_terms(&self, id: NodeId) -> Color {
        let node = &self.nodes[id];
        let mut sum = node.ambient;
        for light in &node.lights {
            sum += light.diffuse + light.specular;
        }
        for child in self.children(id) {
            sum += self.nodes[child].contribution;
        }
        if node.hit.is_none() { node.color } else { sum }
    }

    /// The tree as nested JSON, children inside their parents, with the events.
    pub fn to_json(&self) -> Value {
        serde_json::json!({
            "pixel": [self.pixel.0, self.pixel.1],
            "color": self.color(),
            "rgb8": crate::math::to_rgb8(self.color()),
            "tree": self.node_json(0),
            "events": self.events,
        })
    }

    fn node_json(&self, id: NodeId) -> Value {
        let node = &self.nodes[id];
        let mut value = serde_json::to_value(node).unwrap_or(Value::Null);
        value["reflected"] = node.reflected.map_or(Value::Null, |c| self.node_json(c));
        value["transmitted"] = node.transmitted.map_or(Value::Null, |c| self.node_json(c));
        value["id"] = id.into();
        value
    }
}
