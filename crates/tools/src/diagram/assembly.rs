//! The ray diagram assembled once, for both media: from a pixel's
//! recording, on one plane, at one point of the step-through, every ray,
//! mark, outline, label anchor and legend row either medium draws. The SVG
//! figure (`svg/`) and the debugger's diagram pane only draw a `Diagram`;
//! neither decides what it holds.

use std::collections::{HashMap, HashSet};

use glam::{DVec2, DVec3};

use super::outline::{Outline, outline};
use super::projection::{DiagramPlane, Projection};
use super::rays::{BlockerMark, Progress, Segment, Stroke, light_place, miss_length, ray_segments};
use raystep_engine::record::{EventKind, NearMiss, Node, NodeId, RayTree};
use raystep_engine::scene::Scene;
use raystep_model::shapes::Shape;

/// Scenes with more objects give no context outlines: only what the
/// pixel's rays meet or pass by.
const MAX_CONTEXT: usize = 300;

/// One pixel's ray diagram, projected onto its plane.
#[derive(Clone, Debug)]
pub struct Diagram {
    pub(crate) pixel: (u32, u32),
    pub(crate) plane: DiagramPlane,
    /// Every ray and normal, coloured by kind and by the step-through.
    pub segments: Vec<Segment>,
    /// Where a shadow ray's blocker stops it.
    pub blockers: Vec<BlockerMark>,
    pub eye: DVec2,
    pub lights: Vec<LightMark>,
    /// Each hit, in the order the tracer recorded them.
    pub(crate) hits: Vec<HitMark>,
    /// Polygons and spheres a ray passed by.
    pub passed: Vec<PassedMark>,
    /// From a hit to a light that faces away from it (no shadow ray).
    pub faces_away: Vec<FacesAway>,
    /// The objects met, then those passed by, then (in small scenes) the
    /// rest for context, each in object order.
    pub objects: Vec<ObjectOutline>,
    /// Which shadow rays are drawn.
    pub(crate) shadows: Shadows,
}

/// Which shadow rays a diagram draws (`diagram --shadows`): a slide about
/// the reflections need not be crowded by every hit's shadow rays.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Shadows {
    /// Every hit's shadow rays and lights facing away.
    #[default]
    All,
    /// Only those of the primary ray's hit.
    Primary,
    /// None: no shadow ray, blocker or line to a light facing away.
    None,
}

#[derive(Clone, Debug, PartialEq)]
pub struct LightMark {
    /// The light's name as the scene gives it.
    pub(crate) name: String,
    pub at: DVec2,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct HitMark {
    pub(crate) object: usize,
    pub(crate) at: DVec2,
}

/// The objects this pixel's rays meet: hit by a ray or blocking a shadow
/// ray, sorted.
fn involved_objects(tree: &RayTree) -> Vec<usize> {
    let mut objects: Vec<usize> = tree
        .events
        .iter()
        .filter_map(|e| match e.kind {
            EventKind::Hit { object, .. } | EventKind::Blocker { object, .. } => Some(object),
            _ => None,
        })
        .collect();
    objects.sort_unstable();
    objects.dedup();
    objects
}

/// Where a ray passed an object by: where it crosses a polygon's plane, or
/// comes nearest a sphere's centre.
#[derive(Clone, Debug, PartialEq)]
pub struct PassedMark {
    pub(crate) object: usize,
    pub(crate) name: String,
    pub at: DVec2,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FacesAway {
    pub hit: DVec2,
    pub light: DVec2,
    /// The node whose hit it is.
    pub(crate) node: NodeId,
}

/// Why an object is in the diagram.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// A ray hits it or it blocks a shadow ray.
    Met,
    /// A ray passed it by, and none meets it.
    PassedBy,
    /// Neither: drawn only to show where the rest of the scene is.
    Context,
}

#[derive(Clone, Debug, PartialEq)]
pub struct ObjectOutline {
    pub object: usize,
    pub(crate) name: String,
    pub(crate) role: Role,
    pub shapes: Vec<Outline>,
    /// Where rays hit it, in the order they were recorded.
    pub(crate) hits: Vec<DVec2>,
}

/// What a label names, for the medium's colour and wording.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Named {
    Eye,
    Light,
    Object(usize),
    /// The index of its mark in `Diagram::passed`.
    PassedBy(usize),
}

/// Where a label belongs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Anchor<'a> {
    /// At a mark.
    Point(DVec2),
    /// Beside an object's outline; `hits` are where rays hit the object
    /// (a plane's line is named at one of them). Where exactly on the
    /// outline depends on the medium's room: its text runs right of its
    /// start, over cells or in a frame.
    Outline {
        outline: &'a Outline,
        hits: &'a [DVec2],
    },
}

#[derive(Clone, Debug, PartialEq)]
pub struct Label<'a> {
    pub named: Named,
    pub text: String,
    pub anchor: Anchor<'a>,
}

/// A row of the legend: each kind of ray and mark the diagram can hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LegendRow {
    Primary,
    Reflected,
    Transmitted,
    ShadowLit,
    ShadowBlocked,
    /// Only when a shadow ray is partly blocked.
    ShadowPartial,
    Normal,
    Hit,
    /// Only when a ray passed an object by.
    PassedBy,
    /// Only when a light faces away from a hit.
    FacesAway,
}

impl Diagram {
    /// The diagram of `tree` (recorded in `scene`) on `plane`, with the
    /// step-through at `progress`.
    pub fn new(scene: &Scene, tree: &RayTree, plane: DiagramPlane, progress: Progress) -> Diagram {
        let projection = Projection::new(plane, scene, tree);
        let p = |v| projection.project(v);
        let (segments, blockers) = ray_segments(tree, scene, &projection, progress);
        // A directional light is drawn along its L from the primary ray's
        // hit (or the eye), where that hit's shadow ray to it ends.
        let reach = miss_length(tree, scene);
        let first = (tree.root().hit.as_ref()).map_or(tree.root().origin, |h| h.point);
        let mut diagram = Diagram {
            pixel: tree.pixel,
            plane,
            segments,
            blockers,
            eye: p(tree.root().origin),
            lights: (scene.lights.iter())
                .map(|l| LightMark {
                    name: if l.is_directional() {
                        format!("{} (directional)", l.name)
                    } else {
                        l.name.clone()
                    },
                    at: p(light_place(l, first, reach)),
                })
                .collect(),
            hits: Vec::new(),
            passed: Vec::new(),
            faces_away: Vec::new(),
            objects: Vec::new(),
            shadows: Shadows::All,
        };
        for (id, node) in tree.nodes.iter().enumerate() {
            for near in &node.near_misses {
                let shape = scene.objects.get(near.object_index).map(|o| &o.shape);
                if let Some(at) = passed_point(node, near, shape) {
                    diagram.passed.push(PassedMark {
                        object: near.object_index,
                        name: near.object.clone(),
                        at: p(at),
                    });
                }
            }
            let Some(hit) = &node.hit else { continue };
            diagram.hits.push(HitMark {
                object: hit.object_index,
                at: p(hit.point),
            });
            for light in node.lights.iter().filter(|l| l.faces_away) {
                if let Some(l) = scene.lights.get(light.light_index) {
                    diagram.faces_away.push(FacesAway {
                        hit: p(hit.point),
                        light: p(light_place(l, hit.point, reach)),
                        node: id,
                    });
                }
            }
        }
        let met = involved_objects(tree);
        let passed = passed_objects(tree, &met);
        let context: Vec<usize> = if scene.objects.len() <= MAX_CONTEXT {
            (0..scene.objects.len())
                .filter(|o| met.binary_search(o).is_err() && passed.binary_search(o).is_err())
                .collect()
        } else {
            Vec::new()
        };
        let roles = (met.iter().map(|&o| (o, Role::Met)))
            .chain(passed.iter().map(|&o| (o, Role::PassedBy)))
            .chain(context.iter().map(|&o| (o, Role::Context)));
        // Each object's hits in one pass, in the order they were recorded.
        let mut hits: HashMap<usize, Vec<DVec2>> = HashMap::new();
        for h in &diagram.hits {
            hits.entry(h.object).or_default().push(h.at);
        }
        diagram.objects = roles
            .filter_map(|(object, role)| {
                let o = scene.objects.get(object)?;
                Some(ObjectOutline {
                    object,
                    name: o.name.to_string(),
                    role,
                    shapes: outline(&o.shape, &projection),
                    hits: hits.remove(&object).unwrap_or_default(),
                })
            })
            .collect();
        diagram
    }

    /// The diagram with only `shadows`' shadow rays, their blockers and
    /// lines to lights facing away; an object only a left-out shadow ray
    /// met is no longer met (passed by, or context).
    pub fn with_shadows(mut self, shadows: Shadows) -> Diagram {
        let kept = |node: NodeId| match shadows {
            Shadows::All => true,
            Shadows::Primary => node == 0,
            Shadows::None => false,
        };
        self.shadows = shadows;
        (self.segments).retain(|s| s.shadow_of.is_none_or(kept));
        self.blockers.retain(|b| kept(b.shadow_of));
        self.faces_away.retain(|f| kept(f.node));
        let passed: HashSet<usize> = self.passed.iter().map(|m| m.object).collect();
        let blocking: HashSet<usize> = self.blockers.iter().map(|b| b.object).collect();
        for object in self.objects.iter_mut().filter(|o| o.role == Role::Met) {
            if object.hits.is_empty() && !blocking.contains(&object.object) {
                object.role = if passed.contains(&object.object) {
                    Role::PassedBy
                } else {
                    Role::Context
                };
            }
        }
        self
    }

    /// The points a view must hold to show the whole diagram: every ray's
    /// ends, the eye, the lights, the passed-by marks and the outlines of
    /// the objects met or passed by (not the context).
    pub fn extent(&self) -> Vec<DVec2> {
        let mut points: Vec<DVec2> = (self.segments.iter())
            .flat_map(|s| [s.from, s.to])
            .collect();
        points.push(self.eye);
        points.extend(self.lights.iter().map(|l| l.at));
        points.extend(self.passed.iter().map(|m| m.at));
        for object in self.objects.iter().filter(|o| o.role != Role::Context) {
            points.extend(object.shapes.iter().flat_map(Outline::points));
        }
        points
    }

    /// Whether the rays (primary, reflected, transmitted) all lie on one
    /// line in this plane, at least two of them: they lie in one plane
    /// seen edge-on (seven-rays' centre pixel from the side, where every
    /// ray lies in the horizontal plane through the eye), so the figure
    /// cannot show them apart. Within a thousandth of the figure's extent.
    pub(crate) fn rays_edge_on(&self) -> bool {
        let rays: Vec<&Segment> = (self.segments.iter())
            .filter(|s| {
                matches!(
                    s.stroke,
                    Stroke::Primary | Stroke::Reflected | Stroke::Transmitted
                )
            })
            .collect();
        let Some(primary) = rays.first() else {
            return false;
        };
        let along = (primary.to - primary.from).normalize_or_zero();
        let points = self.extent();
        let (lo, hi) = points.iter().fold((points[0], points[0]), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
        let tolerance = 1e-3 * (hi - lo).length();
        let off_line = |p: DVec2| (p - primary.from).perp_dot(along).abs();
        rays.len() > 1
            && along != DVec2::ZERO
            && (rays.iter()).all(|s| off_line(s.from) <= tolerance && off_line(s.to) <= tolerance)
    }

    /// The names, most important first: the eye, the lights, the objects
    /// met (each at its first outline), the passed-by marks.
    pub fn labels(&self) -> Vec<Label<'_>> {
        let mut labels = vec![Label {
            named: Named::Eye,
            text: "eye".to_string(),
            anchor: Anchor::Point(self.eye),
        }];
        labels.extend(self.lights.iter().map(|l| Label {
            named: Named::Light,
            text: l.name.clone(),
            anchor: Anchor::Point(l.at),
        }));
        for object in self.objects.iter().filter(|o| o.role == Role::Met) {
            let Some(outline) = object.shapes.first() else {
                continue;
            };
            labels.push(Label {
                named: Named::Object(object.object),
                text: object.name.to_string(),
                anchor: Anchor::Outline {
                    outline,
                    hits: &object.hits,
                },
            });
        }
        let met: HashSet<usize> = (self.objects.iter())
            .filter(|o| o.role == Role::Met)
            .map(|o| o.object)
            .collect();
        labels.extend(self.passed.iter().enumerate().map(|(i, m)| Label {
            named: Named::PassedBy(i),
            // An object named at its outline already: "passed by" alone.
            text: if met.contains(&m.object) {
                "passed by".to_string()
            } else {
                format!("{}: passed by", m.name)
            },
            anchor: Anchor::Point(m.at),
        }));
        labels
    }

    /// The legend's rows, in order; the optional ones only when the
    /// diagram holds one.
    pub fn legend(&self) -> Vec<LegendRow> {
        use LegendRow::*;
        let partial = (self.segments.iter()).any(|s| s.stroke == Stroke::ShadowPartial);
        let mut rows = vec![Primary, Reflected, Transmitted];
        if self.shadows != Shadows::None {
            rows.extend([ShadowLit, ShadowBlocked]);
        }
        rows.extend(partial.then_some(ShadowPartial));
        rows.extend([Normal, Hit]);
        rows.extend((!self.passed.is_empty()).then_some(PassedBy));
        rows.extend((!self.faces_away.is_empty()).then_some(FacesAway));
        rows
    }
}

/// Where a ray passed an object by: where it crosses a polygon's plane,
/// or its point nearest a sphere's centre (o + t d, t = -B / 2A).
fn passed_point(node: &Node, near: &NearMiss, shape: Option<&Shape>) -> Option<DVec3> {
    let plane = match shape {
        Some(Shape::Polygon(polygon)) => &polygon.plane,
        Some(Shape::Patch(patch)) => &patch.polygon.plane,
        _ => {
            let closest = near.closest_approach?;
            return Some(node.origin + node.direction * closest.t);
        }
    };
    // n·(o + t d) + d0 = 0 (MODEL §1's plane/ray).
    let t = -(plane.normal.dot(node.origin) + plane.d) / plane.normal.dot(node.direction);
    t.is_finite().then(|| node.origin + node.direction * t)
}

/// The polygons and spheres a ray passed by that no ray met (`met`
/// sorted), sorted.
fn passed_objects(tree: &RayTree, met: &[usize]) -> Vec<usize> {
    let mut passed: Vec<usize> = (tree.nodes.iter())
        .flat_map(|n| n.near_misses.iter())
        .filter(|n| n.crossing_figure.is_some() || n.closest_approach.is_some())
        .map(|n| n.object_index)
        .filter(|o| met.binary_search(o).is_err())
        .collect();
    passed.sort_unstable();
    passed.dedup();
    passed
}

#[cfg(test)]
mod tests {
    use super::*;
    use raystep_engine::test_scenes::{PEBBLE, centre_pixel, pebble};

    fn close(a: DVec2, b: DVec2) -> bool {
        (a - b).length() < 1e-9
    }

    #[test]
    fn the_diagram_holds_every_mark_once() {
        // From above: the plane through the hit (0, 0, 1), the camera's
        // right (x) to the right, its forward (-z) up: (x, y, z) lands at
        // (x, 1 - z).
        let (scene, tree) = pebble();
        let d = Diagram::new(&scene, &tree, DiagramPlane::Top, Progress::done(&tree));
        assert!(close(d.eye, DVec2::new(0.0, -9.0)), "{}", d.eye);
        let lights: Vec<_> = d.lights.iter().map(|l| (l.name.as_str(), l.at)).collect();
        assert_eq!(
            lights,
            [
                ("lamp", DVec2::new(5.0, -9.0)),
                ("back", DVec2::new(0.0, 11.0))
            ]
        );
        assert_eq!(
            d.hits,
            [HitMark {
                object: 0,
                at: DVec2::ZERO
            }]
        );
        // The primary ray passes the pebble by: its line comes within
        // |(0.9, 0.9)| = 1.27 > 1 of the centre, nearest at (0, 0, 4):
        // (0, -3). One ray, one ring.
        assert_eq!(d.passed.len(), 1, "{:?}", d.passed);
        assert_eq!(
            (d.passed[0].object, d.passed[0].name.as_str()),
            (1, "pebble")
        );
        assert!(close(d.passed[0].at, DVec2::new(0.0, -3.0)));
        // "back" lies behind the hit: N·L = (0, 0, 1)·(0, 0, -1) < 0, no
        // shadow ray, a dotted line from the hit to it.
        assert_eq!(
            d.faces_away,
            [FacesAway {
                hit: DVec2::ZERO,
                light: DVec2::new(0.0, 11.0),
                node: 0,
            }]
        );
        let roles: Vec<_> = d.objects.iter().map(|o| (o.object, o.role)).collect();
        assert_eq!(roles, [(0, Role::Met), (1, Role::PassedBy)]);
        let labels: Vec<_> = d.labels().into_iter().map(|l| (l.named, l.text)).collect();
        let named = |n, t: &str| (n, t.to_string());
        assert_eq!(
            labels,
            [
                named(Named::Eye, "eye"),
                named(Named::Light, "lamp"),
                named(Named::Light, "back"),
                named(Named::Object(0), "ball"),
                named(Named::PassedBy(0), "pebble: passed by"),
            ]
        );
        // Every row but the partly blocked shadow ray's (none here).
        let all = [
            LegendRow::Primary,
            LegendRow::Reflected,
            LegendRow::Transmitted,
            LegendRow::ShadowLit,
            LegendRow::ShadowBlocked,
            LegendRow::Normal,
            LegendRow::Hit,
            LegendRow::PassedBy,
            LegendRow::FacesAway,
        ];
        assert_eq!(d.legend(), all);
    }

    #[test]
    fn the_extent_holds_what_was_met_or_passed_by_not_the_context() {
        // The pebble's ring and circle are in the extent; with the ray
        // kept off it (the pebble moved far aside), it is context only
        // and its circle (x up to 101) is not.
        let (scene, tree) = pebble();
        let d = Diagram::new(&scene, &tree, DiagramPlane::Top, Progress::done(&tree));
        let right = |d: &Diagram| d.extent().iter().fold(f64::MIN, |a, p| a.max(p.x));
        // The pebble's circle's box corner: (0.9, -3) + (1, 1).
        let corner = DVec2::new(1.9, -2.0);
        assert!(d.extent().iter().any(|p| close(*p, corner)));
        assert!(d.extent().contains(&d.passed[0].at));
        // The lamp at x 5 is the furthest right.
        assert_eq!(right(&d), 5.0);
        let far = PEBBLE.replace("[0.9, 0.9, 4]", "[100, 0, 4]");
        let (scene, tree) = centre_pixel("far.toml", &far);
        let d = Diagram::new(&scene, &tree, DiagramPlane::Top, Progress::done(&tree));
        assert!(d.passed.is_empty());
        assert_eq!(d.objects[1].role, Role::Context);
        assert_eq!(right(&d), 5.0);
        assert!(!d.legend().contains(&LegendRow::PassedBy));
    }
}
