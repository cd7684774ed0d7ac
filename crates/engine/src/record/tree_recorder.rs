//! The recorder that builds a pixel's ray tree and event list from the
//! tracer's callbacks. It never computes a term itself: every number it holds
//! is the one the tracer used, so a tree cannot disagree with the image.

use crate::render::viewport;
use crate::scene::{Scene, Settings};
use crate::trace::{
    Blocker, ChildTerm, DepthLimit, LightTerm, NotCast, RayKind, Recorder, Refraction, Rules,
    SurfaceHit, trace,
};
use std::sync::Arc;

use glam::DVec3;
use raystep_accel::Cost;
use raystep_model::math::{Color, EPS, Interval, Ray};
use raystep_model::object::{Object, ObjectName};
use raystep_model::shapes::{
    Aabb, CrossingFigure, Patch, Polygon, PolygonWorking, Shape, Sphere, SphereWorking, Working,
};

use super::ray_tree::{
    BlockerRecord, ClosestApproach, Event, EventKind, HitRecord, LightRecord, MaterialFactors,
    NearMiss, Node, NodeId, RayTree, ShadowRecord,
};

/// Near misses are looked for in scenes up to this size, where they teach;
/// in benchmark scenes the scan would cost more than the whole pixel.
pub const NEAR_MISS_SCENE_LIMIT: usize = 2000;

/// Builds a `RayTree` from the tracer's callbacks.
pub struct TreeRecorder<'a> {
    scene: &'a Scene,
    /// The settings traced with, kept in the tree for its readers (the
    /// depth limit, the mistakes that decide its bytes, the rules the
    /// explainers word).
    settings: Settings,
    /// The settings' I_a, kept on each hit for its ambient term's factors.
    ambient_light: Color,
    nodes: Vec<Node>,
    events: Vec<Event>,
    /// The node of the ray being traced, innermost last.
    stack: Vec<NodeId>,
    /// Blockers of the shadow ray being traced, in the order found.
    blockers: Vec<Blocker>,
    /// The shadow ray being traced: its light, ray and length.
    shadow_ray: Option<(usize, Ray, Option<f64>)>,
}

/// Records image pixel (x, y) of `scene` traced with `settings`: the same
/// `trace` of the same primary ray the render makes for that pixel.
pub fn record_pixel(scene: &Scene, settings: &Settings, x: u32, y: u32) -> RayTree {
    let ray = viewport(scene, settings, (scene.width, scene.height)).primary_ray(x, y);
    let mut recorder = TreeRecorder::new(scene, settings);
    trace(scene, settings, &ray, &mut recorder);
    recorder.into_tree((x, y))
}

impl<'a> TreeRecorder<'a> {
    pub fn new(scene: &'a Scene, settings: &Settings) -> Self {
        Self {
            scene,
            settings: *settings,
            ambient_light: settings.ambient,
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
            max_depth: self.settings.max_depth,
            mistakes: self.settings.mistakes,
            settings: self.settings,
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
    const RECORDS_DEPTH_LIMIT: bool = true;

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
            tint: None,
            hit: None,
            near_misses: Vec::new(),
            cost: Cost::default(),
            ambient: Color::ZERO,
            emission: Color::ZERO,
            lights: Vec::new(),
            refraction: None,
            reflected: None,
            transmitted: None,
            not_cast: Vec::new(),
            depth_limit: None,
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
        let material = scene.material_of(hit.object);
        let i_a = self.ambient_light;
        let node = self.node();
        let ray = Ray::new(node.origin, node.direction);
        node.cost = cost;
        node.near_misses = near_misses(scene, &ray, hit.t, Some(hit.object));
        let working = object.shape.working(&ray, Interval::in_front());
        node.hit = Some(HitRecord {
            object: object.name.to_string(),
            object_index: hit.object,
            kind: object.shape.kind(),
            material: material.name.clone(),
            t: hit.t,
            point: hit.point,
            geometric_normal: hit.geometric_normal,
            normal: hit.normal,
            entering: hit.entering,
            crossing_figure: crossing_figure(&object.shape, &ray, &working),
            working,
            factors: MaterialFactors {
                o_d: material.color,
                ka: material.ka,
                kd: material.kd,
                ks: material.ks,
                n: material.shininess,
                kt: material.kt,
                ior: material.ior,
                ambient: material.ambient,
                specular_color: material.specular_color.unwrap_or(Color::ONE),
            },
            i_a,
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
        node.near_misses = near_misses(
            scene,
            &Ray::new(node.origin, node.direction),
            f64::INFINITY,
            None,
        );
        self.push_event(EventKind::Miss { tested: cost });
    }

    fn ambient(&mut self, term: Color) {
        self.node().ambient = term;
        self.push_event(EventKind::Ambient { term });
    }

    fn emission(&mut self, term: Color) {
        self.node().emission = term;
        self.push_event(EventKind::Emission { term });
    }

    fn shadow_cast(&mut self, light: usize, ray: &Ray, distance: Option<f64>) {
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
                    .map(|b| {
                        let working = scene.objects[b.object]
                            .shape
                            .working(&ray, Interval::in_front());
                        BlockerRecord {
                            object: scene.objects[b.object].name.to_string(),
                            object_index: b.object,
                            t: b.t,
                            kt: b.kt,
                            root: BlockerRecord::root_of(&working, b.t),
                            working,
                        }
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
        let coefficients =
            *Rules::<true>::new(&self.settings).light_attenuation(&scene.lights[term.light]);
        let profile = self.settings.profile;
        self.node().lights.push(LightRecord {
            light: scene.lights[term.light].name.clone(),
            light_index: term.light,
            i_p: scene.lights[term.light].color,
            directional: scene.lights[term.light].is_directional(),
            to_light: term.to_light,
            distance: term.distance,
            n_dot_l: term.n_dot_l,
            faces_away: term.faces_away,
            at_point: term.at_point,
            shadow,
            f_att: term.f_att,
            coefficients,
            clamped: profile.clamps_attenuation(),
            lit_from_behind: term.faces_away
                && !term.at_point
                && !profile.light_behind_adds_nothing(),
            specular_model: term.specular_model,
            specular_cosine: term.specular_cosine,
            diffuse: term.diffuse,
            specular: term.specular,
        });
        self.push_event(EventKind::Light {
            light: term.light,
            faces_away: term.faces_away,
            at_point: term.at_point,
            s,
            diffuse: term.diffuse,
            specular: term.specular,
        });
    }

    fn refraction(&mut self, refraction: &Refraction) {
        let node = self.node();
        node.refraction = Some(*refraction);
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
        self.nodes[child].tint = term.tint;
        self.nodes[child].contribution = term.contribution;
        self.push_event(EventKind::ChildReturned {
            child,
            kind: term.kind,
            contribution: term.contribution,
        });
    }

    fn not_cast(&mut self, ray: &NotCast) {
        self.node().not_cast.push(*ray);
        self.push_event(EventKind::NotCast(*ray));
    }

    fn depth_limit(&mut self, limit: &DepthLimit) {
        self.node().depth_limit = Some(*limit);
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

/// Objects the ray went past although it came near, each with its working:
/// polygons and patches whose plane the ray meets in front of `before`,
/// within the polygon's bounding box, but whose crossing test puts the point
/// outside (a concave notch, or just past an edge); spheres whose bounding
/// box the ray crosses in front of `before` but whose quadratic has no real
/// roots, or only roots more than EPS behind the origin (MODEL §3). The
/// object `hit`'s own surface is left out (`same_surface`).
fn near_misses(scene: &Scene, ray: &Ray, before: f64, hit: Option<usize>) -> Vec<NearMiss> {
    if scene.objects.len() > NEAR_MISS_SCENE_LIMIT {
        return Vec::new();
    }
    let range = Interval::new(EPS, before);
    let hit = hit.map(|h| &scene.objects[h]);
    let mut found = Vec::new();
    for (index, object) in scene.objects.iter().enumerate() {
        if hit.is_some_and(|h| same_surface(h, object)) {
            continue;
        }
        // Each candidate solved once; a patch's fan is located only when
        // its polygon was missed.
        let working = match &object.shape {
            Shape::Polygon(p) => {
                let w = p.solve(ray, range);
                polygon_missed(p, ray, &w).then_some(Working::Polygon(w))
            }
            Shape::Patch(p) => polygon_missed(&p.polygon, ray, &p.polygon.solve(ray, range))
                .then(|| object.shape.working(ray, range)),
            Shape::Sphere(s) => {
                let w = s.solve(ray, range);
                sphere_missed(&s.bounds(), ray, range, &w).then_some(Working::Sphere(w))
            }
            Shape::Ellipsoid(e) => {
                let w = e.working(ray, range);
                sphere_missed(&e.bounds(), ray, range, &w.quadratic)
                    .then(|| Working::Ellipsoid(Box::new(w)))
            }
            _ => None,
        };
        let Some(working) = working else {
            continue;
        };
        found.push(NearMiss {
            object: object.name.to_string(),
            object_index: index,
            crossing_figure: crossing_figure(&object.shape, ray, &working),
            closest_approach: match (&object.shape, &working) {
                (Shape::Sphere(s), _) => Some(closest_approach(s, ray)),
                // In the sphere's own space, where the ellipsoid is a sphere.
                (Shape::Ellipsoid(e), Working::Ellipsoid(w)) => Some(closest_approach(
                    &e.sphere,
                    &Ray::new(w.object_origin, w.object_direction),
                )),
                _ => None,
            },
            working,
        });
    }
    found
}

/// Whether `other` is a piece of the surface `hit` lies on, so that a ray
/// hitting `hit` near an edge did not go past it: a triangle of the same
/// mesh (one mesh file as the scene placed it: its triangles share their
/// names) with a corner in common, or a patch that shares a corner and its
/// normal there with the patch hit (NFF's `pp` patches, which name no mesh,
/// are pieces of a smooth surface). The ray crosses such a neighbour's
/// plane just before it hits wherever the surface is convex (MODEL §3).
fn same_surface(hit: &Object, other: &Object) -> bool {
    if same_mesh(&hit.name, &other.name) {
        let (Some(a), Some(b)) = (corners(&hit.shape), corners(&other.shape)) else {
            return false;
        };
        return a.iter().any(|v| b.contains(v));
    }
    let (Shape::Patch(a), Shape::Patch(b)) = (&hit.shape, &other.shape) else {
        return false;
    };
    smooth_corners(a).any(|corner| smooth_corners(b).any(|other| other == corner))
}

/// A patch's corners, each with its normal.
fn smooth_corners(patch: &Patch) -> impl Iterator<Item = (&DVec3, &DVec3)> {
    patch.polygon.vertices.iter().zip(&patch.normals)
}

/// Both triangles of one placed mesh.
fn same_mesh(a: &ObjectName, b: &ObjectName) -> bool {
    match (a, b) {
        (ObjectName::MeshTriangle { names: a, .. }, ObjectName::MeshTriangle { names: b, .. }) => {
            Arc::ptr_eq(a, b)
        }
        _ => false,
    }
}

/// A polygon's or patch's corners.
fn corners(shape: &Shape) -> Option<&[DVec3]> {
    match shape {
        Shape::Polygon(p) => Some(&p.vertices),
        Shape::Patch(p) => Some(&p.polygon.vertices),
        _ => None,
    }
}

fn polygon_missed(polygon: &Polygon, ray: &Ray, working: &PolygonWorking) -> bool {
    let in_box = working
        .plane
        .hit_t()
        .is_some_and(|t| polygon.bounds().contains(ray.at(t)));
    in_box && working.crossing.is_some_and(|c| !c.inside)
}

/// No real roots, or both roots more than EPS behind the origin (the roots
/// do not depend on the range `working` was solved in). Roots beyond
/// `range` (behind the hit) are not a miss: the sphere is hidden. Nor is a
/// root within EPS of the origin: that is the sphere a secondary ray
/// leaves from, not one it passes by. An ellipsoid's roots are its
/// own-space sphere's, at the same t.
fn sphere_missed(bounds: &Aabb, ray: &Ray, range: Interval, working: &SphereWorking) -> bool {
    let passed = working.t1.is_none_or(|t1| t1 < -EPS);
    passed && bounds.crossed_by(ray, range)
}

fn closest_approach(sphere: &Sphere, ray: &Ray) -> ClosestApproach {
    let oc = ray.origin - sphere.center;
    let t = -ray.direction.dot(oc) / ray.direction.length_squared();
    ClosestApproach {
        t,
        distance: (oc + t * ray.direction).length(),
        radius: sphere.radius,
    }
}

/// The crossing test edge by edge, where `working` reached it.
fn crossing_figure(shape: &Shape, ray: &Ray, working: &Working) -> Option<CrossingFigure> {
    let (polygon, plane) = match (shape, working) {
        (Shape::Polygon(p), Working::Polygon(w)) => (p, w),
        (Shape::Patch(p), Working::Patch(w)) => (&p.polygon, &w.polygon),
        _ => return None,
    };
    plane.crossing?;
    let t = plane.plane.hit_t()?;
    Some(polygon.crossing_figure(ray.at(t)))
}
