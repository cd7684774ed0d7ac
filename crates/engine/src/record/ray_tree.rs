//! A pixel's recording: the ray tree with every term, and the events in the
//! order the tracer performed them. `tree_recorder.rs` fills it in.

use glam::DVec3;
use serde::Serialize;
use serde_json::Value;

use crate::scene::{Settings, SpecularModel};
use crate::trace::{DepthLimit, NotCast, RayKind, Refraction, SurfaceHit};
use raystep_accel::Cost;
use raystep_model::math::Color;
use raystep_model::mistakes::Mistakes;
use raystep_model::shapes::{CrossingFigure, Working};

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
    /// A colour the profile weighs the ray by besides `weight`: a cse167
    /// mirror ray's specular colour S (MODEL §11); absent when none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tint: Option<Color>,
    pub hit: Option<HitRecord>,
    /// Polygons whose plane the ray met before its hit (or at all, on a miss)
    /// but whose crossing test said outside: why the ray went past them.
    pub near_misses: Vec<NearMiss>,
    /// What the closest-hit query tested.
    pub cost: Cost,
    pub ambient: Color,
    /// The material's emission E, added as it is; absent when black.
    #[serde(skip_serializing_if = "is_black")]
    pub emission: Color,
    pub lights: Vec<LightRecord>,
    pub refraction: Option<Refraction>,
    pub reflected: Option<NodeId>,
    pub transmitted: Option<NodeId>,
    /// Secondary rays a rule kept from being cast (MODEL §5); absent when none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub not_cast: Vec<NotCast>,
    /// At a hit the depth limit kept from spawning, the rays it cut (MODEL
    /// §5), as the tracer reported them; absent elsewhere.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) depth_limit: Option<DepthLimit>,
    /// The colour this ray returns, the sum of its stored terms.
    pub color: Color,
    /// weight * attenuation * color: what it adds to its parent.
    pub contribution: Color,
}

impl Node {
    /// Whether the ray's refraction was total internal reflection.
    pub fn tir(&self) -> bool {
        self.refraction.is_some_and(|r| r.tir)
    }

    /// Whether the ray hit at the depth limit, where nothing is spawned:
    /// max_depth, or one less under `depth-off-by-one` (MODEL §5, §8).
    pub fn at_depth_limit(&self) -> bool {
        self.depth_limit.is_some()
    }

    /// The secondary rays the depth limit kept this ray's hit from
    /// spawning, by kind and weight; none below the limit, where every ray
    /// is cast or recorded as not cast.
    pub fn depth_cut(&self) -> impl Iterator<Item = (RayKind, f64)> {
        self.depth_limit.into_iter().flat_map(|limit| limit.cut())
    }
}

#[derive(Clone, Debug, Serialize)]
pub struct HitRecord {
    pub object: String,
    /// 0-based, in file order.
    pub object_index: usize,
    pub kind: &'static str,
    pub(crate) material: String,
    pub t: f64,
    pub point: DVec3,
    /// N_g.
    pub geometric_normal: DVec3,
    /// N: N_g turned to the side the ray meets (MODEL §3: a patch's side is
    /// its plane's), as in the tracer's `SurfaceHit`.
    pub normal: DVec3,
    pub entering: bool,
    /// The intersection worked the way the course notes teach it.
    pub working: Working,
    /// A polygon's or patch's crossing test edge by edge; absent for others.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub crossing_figure: Option<CrossingFigure>,
    /// The material's numbers the terms were computed with (MODEL §4, §5).
    pub factors: MaterialFactors,
    /// I_a, the scene's ambient light (the ambient term is I_a k_a O_d).
    pub i_a: Color,
}

impl HitRecord {
    /// The hit as the tracer held it, for the questions of `trace::Rules`
    /// (which normal lights it, which one Snell's law uses).
    pub fn surface_hit(&self) -> SurfaceHit {
        SurfaceHit {
            object: self.object_index,
            t: self.t,
            point: self.point,
            geometric_normal: self.geometric_normal,
            normal: self.normal,
            entering: self.entering,
        }
    }

    /// ", material white" to follow the object's kind, or nothing when the
    /// name already says it (a mesh triangle's "(material white)").
    pub(crate) fn material_note(&self) -> String {
        if self
            .object
            .ends_with(&format!("(material {})", self.material))
        {
            String::new()
        } else {
            format!(", material {}", self.material)
        }
    }
}

/// A material's coefficients as the course notes name them, so that every
/// term of a hit can be checked by hand from the recording alone.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct MaterialFactors {
    /// O_d, the diffuse colour.
    pub o_d: Color,
    pub ka: f64,
    pub kd: f64,
    pub ks: f64,
    /// The specular exponent.
    pub n: f64,
    pub kt: f64,
    pub ior: f64,
    /// The material's own ambient colour, the ambient term as it is in
    /// place of I_a k_a O_d (MODEL §1); absent when it has none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ambient: Option<Color>,
    /// The specular term's colour S; absent when white.
    #[serde(skip_serializing_if = "is_white")]
    pub specular_color: Color,
}

#[derive(Clone, Debug, Serialize)]
pub struct NearMiss {
    pub object: String,
    pub object_index: usize,
    pub working: Working,
    /// A polygon's or patch's crossing test edge by edge; absent for others.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub crossing_figure: Option<CrossingFigure>,
    /// A sphere's: how close the ray's line comes to its centre.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub closest_approach: Option<ClosestApproach>,
}

/// The point of the ray's line nearest a sphere's centre, t = -B / (2A).
/// The discriminant is 4A^2 (r^2 - distance^2): negative exactly when
/// `distance > radius`, the ray passing the sphere by.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct ClosestApproach {
    pub t: f64,
    pub distance: f64,
    pub radius: f64,
}

#[derive(Clone, Debug, Serialize)]
pub struct LightRecord {
    pub light: String,
    pub light_index: usize,
    /// I_p, the light's colour.
    pub i_p: Color,
    /// A directional light (MODEL §4): L is its direction, it has no
    /// `distance` and is not attenuated; absent for a point light.
    #[serde(skip_serializing_if = "is_false")]
    pub directional: bool,
    pub to_light: DVec3,
    /// d_L; absent for a directional light, which is infinitely far.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub distance: Option<f64>,
    pub n_dot_l: f64,
    pub faces_away: bool,
    /// The light is within EPS of the point (MODEL §4); absent when not.
    #[serde(skip_serializing_if = "is_false")]
    pub at_point: bool,
    pub shadow: Option<ShadowRecord>,
    pub f_att: f64,
    /// The (c1, c2, c3) f_att was computed with (the light's own, else
    /// the scene's, as the mistakes in force left them), and whether it
    /// was clamped to 1 (the profile's rule, MODEL §11): for the words.
    #[serde(skip)]
    pub(crate) coefficients: [f64; 3],
    #[serde(skip)]
    pub(crate) clamped: bool,
    /// N·L <= 0, yet the profile casts the shadow ray and adds the
    /// highlight (cse167, MODEL §11): the light is not left out.
    #[serde(skip_serializing_if = "is_false")]
    pub lit_from_behind: bool,
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
    /// The segment's end, d_L; absent towards a directional light, where
    /// the segment has no end.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) distance: Option<f64>,
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
    /// Which root of the quadratic this crossing is ("t0" or "t1"), for a
    /// sphere, cylinder or cone; absent for a plane or polygon (one root).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) root: Option<&'static str>,
    /// The shadow ray's intersection with the blocker, worked as for a hit.
    pub(crate) working: Working,
}

impl BlockerRecord {
    /// Which of the working's two roots is nearer to `t`, if it has two.
    pub(crate) fn root_of(working: &Working, t: f64) -> Option<&'static str> {
        let (nearer, _) = working.nearer_root(t)?;
        Some(["t0", "t1"][nearer])
    }
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
    /// A material's emission E, added as it is (only when not black).
    Emission {
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
        #[serde(skip_serializing_if = "is_false")]
        at_point: bool,
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
    /// A secondary ray a rule kept from being cast.
    NotCast(NotCast),
    RayDone {
        color: Color,
    },
}

impl EventKind {
    /// The light this event is about, if any: its shadow ray, a blocker
    /// of it, or its terms.
    pub fn light(&self) -> Option<usize> {
        match self {
            EventKind::ShadowCast { light }
            | EventKind::Blocker { light, .. }
            | EventKind::Light { light, .. } => Some(*light),
            _ => None,
        }
    }
}

fn is_false(value: &bool) -> bool {
    !value
}

/// A pixel's recording: the tree (node 0 is the primary ray) and its events.
#[derive(Clone, Debug)]
pub struct RayTree {
    pub pixel: (u32, u32),
    /// The scene's max_depth when recorded.
    pub(crate) max_depth: u32,
    /// The mistakes traced with (MODEL §8); they decide the pixel's bytes too.
    pub mistakes: Mistakes,
    /// Every setting traced with (the mistakes and max_depth above among
    /// them): the rules an explainer words are `Rules` of these.
    pub settings: Settings,
    pub nodes: Vec<Node>,
    pub events: Vec<Event>,
}

impl RayTree {
    pub fn root(&self) -> &Node {
        &self.nodes[0]
    }

    /// The pixel's colour before clamping.
    pub fn color(&self) -> Color {
        self.root().color
    }

    /// The pixel's bytes, as the render stores them with the same mistakes.
    pub fn rgb8(&self) -> [u8; 3] {
        self.mistakes.rgb8(self.color())
    }

    pub fn children(&self, id: NodeId) -> impl Iterator<Item = NodeId> + '_ {
        let node = &self.nodes[id];
        node.reflected.into_iter().chain(node.transmitted)
    }

    /// The sum of a hit node's stored terms, in the tracer's order; equals
    /// its colour. `None` for a miss: it has no terms, its colour is the
    /// background.
    pub fn sum_of_terms(&self, id: NodeId) -> Option<Color> {
        let node = &self.nodes[id];
        node.hit.as_ref()?;
        let mut sum = node.ambient;
        if node.emission != Color::ZERO {
            sum += node.emission;
        }
        for light in &node.lights {
            sum += light.diffuse + light.specular;
        }
        for child in self.children(id) {
            sum += self.nodes[child].contribution;
        }
        Some(sum)
    }

    /// Ok if every number of the recording is finite; else names the first
    /// that is not. JSON writes NaN and infinity as `null`, so the JSON
    /// output calls this first rather than hide them.
    pub fn check_finite(&self) -> Result<(), super::NonFinite> {
        super::check_finite("nodes", &self.nodes)?;
        super::check_finite("events", &self.events)
    }

    /// The tree as nested JSON, children inside their parents, with the events.
    /// With a `mistakes` key, the list of their names, only when there are some.
    pub fn to_json(&self) -> Value {
        let mut json = serde_json::json!({
            "pixel": [self.pixel.0, self.pixel.1],
            "color": self.color(),
            "rgb8": self.rgb8(),
            "tree": self.node_json(0),
            "events": self.events,
        });
        if !self.mistakes.is_empty() {
            json["mistakes"] = serde_json::to_value(self.mistakes).unwrap_or(Value::Null);
        }
        // Which equation the numbers follow, where it is not the lecture's
        // (MODEL §11); a lecture tree's JSON reads as it always did.
        if !self.settings.profile.is_lecture() {
            json["profile"] = self.settings.profile.name().into();
        }
        json
    }

    fn node_json(&self, id: NodeId) -> Value {
        let node = &self.nodes[id];
        let mut value = serde_json::to_value(node).unwrap_or(Value::Null);
        value["reflected"] = node.reflected.map_or(Value::Null, |c| self.node_json(c));
        value["transmitted"] = node.transmitted.map_or(Value::Null, |c| self.node_json(c));
        value["id"] = id.into();
        // Derived, not stored: the JSON keeps its `tir` key beside `refraction`.
        value["tir"] = node.tir().into();
        value
    }
}

fn is_black(color: &Color) -> bool {
    *color == Color::ZERO
}

fn is_white(color: &Color) -> bool {
    *color == Color::ONE
}
