//! The Whitted tracer, written once for rendering and recording (MODEL §3-§6):
//! nearest hit or background; ambient; each light with its shadow ray; then
//! reflection and transmission while the depth allows. The settings'
//! switches and the classic mistakes of MODEL §8 enter only through `Rules`.

use std::ops::ControlFlow;

use glam::DVec3;

use super::recorder::{
    Blocker, ChildTerm, DepthLimit, LightTerm, NotCast, PruneRule, RayKind, Recorder, Refraction,
    ShadowOutcome, SurfaceHit,
};
use super::rules::Rules;
use crate::scene::{Light, LightKind, Material, Scene, Settings, SpecularModel};
use raystep_accel::{Candidate, Cost, ShadowCache};
use raystep_model::math::{Color, EPS, Ray, attenuation};

/// What a ray brings back: its colour and, if it hit, how far it went.
#[derive(Clone, Copy, Debug)]
struct Traced {
    color: Color,
    distance: Option<f64>,
}

/// The colour, unclamped, that the primary ray `ray` brings back from
/// `scene` traced with `settings` (the scene's own, or the debugger's).
pub fn trace<R: Recorder>(scene: &Scene, settings: &Settings, ray: &Ray, rec: &mut R) -> Color {
    let mut cache = ShadowCache::default();
    trace_in_row(scene, settings, ray, Nearest::ToFind, &mut cache, rec)
}

/// A primary ray's nearest hit as the tracer is handed it: still to be
/// found by the scene's query, or already found by a walk over a row's
/// rays together (`Accel::closest_each`, which gives what `closest` gives
/// over `hit_range(RayKind::Primary)`, without counting its cost).
///
/// `Found` borrows the walk's answer: one pointer to hand over per pixel
/// rather than a candidate copied in and out (tetra's misses notice).
#[derive(Clone, Copy, Debug)]
pub enum Nearest<'a> {
    ToFind,
    Found(&'a Option<Candidate>),
}

/// `trace` for a render that goes along a row with one shadow cache and
/// may have found the row's nearest hits already: the colour is the same,
/// only the queries get cheaper.
pub fn trace_in_row<R: Recorder>(
    scene: &Scene,
    settings: &Settings,
    ray: &Ray,
    nearest: Nearest<'_>,
    cache: &mut ShadowCache,
    rec: &mut R,
) -> Color {
    // Two tracers: the model's, where every rule is a constant, and one that
    // asks the set; the common case pays nothing for the mistakes.
    if settings.mistakes.is_empty() {
        Tracer::<R, false>::new(scene, settings, cache, rec).primary(ray, nearest)
    } else {
        Tracer::<R, true>::new(scene, settings, cache, rec).primary(ray, nearest)
    }
}

/// One pixel's trace in progress: the scene, its settings and the rules they
/// make (with the settings' mistakes if `MISTAKES`), the row's shadow cache,
/// the recorder, and how many rays the pixel's tree holds so far.
struct Tracer<'a, R, const MISTAKES: bool> {
    scene: &'a Scene,
    settings: &'a Settings,
    rules: Rules<'a, MISTAKES>,
    cache: &'a mut ShadowCache,
    rec: &'a mut R,
    rays: u32,
}

impl<'a, R: Recorder, const MISTAKES: bool> Tracer<'a, R, MISTAKES> {
    fn new(
        scene: &'a Scene,
        settings: &'a Settings,
        cache: &'a mut ShadowCache,
        rec: &'a mut R,
    ) -> Self {
        Tracer {
            scene,
            settings,
            rules: Rules::new(settings),
            cache,
            rec,
            rays: 0,
        }
    }

    fn primary(&mut self, ray: &Ray, nearest: Nearest<'_>) -> Color {
        self.trace(ray, RayKind::Primary, nearest, 1, 1.0, 1.0)
            .color
    }

    /// `path_weight` is the ray's accumulated weight: the product of the
    /// weights from the primary ray (1) down to this ray.
    // Inlined so that a primary ray found by its row's walk goes straight
    // to `finish`, as cheap as when the walk had its own door.
    #[inline(always)]
    fn trace(
        &mut self,
        ray: &Ray,
        kind: RayKind,
        nearest: Nearest<'_>,
        depth: u32,
        weight: f64,
        path_weight: f64,
    ) -> Traced {
        let scene = self.scene;
        self.rays += 1;
        self.rec.ray_cast(kind, depth, ray, weight);
        let mut cost = Cost::default();
        let found = match nearest {
            Nearest::Found(found) => *found,
            Nearest::ToFind => {
                let range = self.rules.hit_range(kind);
                scene.accel.closest(&scene.objects, ray, range, &mut cost)
            }
        };
        self.finish(ray, found, cost, depth, path_weight)
    }

    /// The rest of `trace` once the nearest hit is known: the background,
    /// or the hit shaded.
    #[inline(never)]
    fn finish(
        &mut self,
        ray: &Ray,
        found: Option<Candidate>,
        cost: Cost,
        depth: u32,
        path_weight: f64,
    ) -> Traced {
        let scene = self.scene;
        let Some(candidate) = found else {
            let background = self.settings.background;
            self.rec.miss(background, cost);
            self.rec.ray_done(background);
            return Traced {
                color: background,
                distance: None,
            };
        };
        let hit = surface_hit(scene, ray, candidate);
        self.rec.hit(&hit, cost);
        let color = self.shade(ray, &hit, depth, path_weight);
        self.rec.ray_done(color);
        Traced {
            color,
            distance: Some(hit.t),
        }
    }

    /// I = ambient + sum_i (diffuse_i + specular_i) + reflected + transmitted.
    fn shade(&mut self, ray: &Ray, hit: &SurfaceHit, depth: u32, path_weight: f64) -> Color {
        let scene = self.scene;
        let settings = self.settings;
        let material = scene.material_of(hit.object);
        let ambient = match material.ambient {
            _ if !self.rules.ambient() => Color::ZERO,
            Some(own) => own,
            None => settings.ambient * material.color * material.ka,
        };
        self.rec.ambient(ambient);
        let mut color = ambient;
        if let Some(emission) = material.emission {
            self.rec.emission(emission);
            color += emission;
        }
        let to_viewer = -ray.direction;
        let normal = self.rules.lighting_normal(hit);
        for (index, light) in scene.lights.iter().enumerate() {
            let term = self.light_term(hit.point, normal, material, to_viewer, (index, light));
            self.rec.light(&term);
            color += term.diffuse + term.specular;
        }
        color = self.rules.local_color(color);
        if depth < self.rules.spawn_below_depth() {
            color = self.secondary_rays(ray, hit, material, (depth, path_weight), color);
        } else if R::RECORDS_DEPTH_LIMIT {
            self.depth_limit(ray, hit, material);
        }
        color
    }

    /// Reports a hit the depth limit keeps from spawning, with the rays it
    /// would have cast, for the recording only: Snell's law is kept on TIR,
    /// where the ray not cast is one reflected ray, not a reflected and a
    /// transmitted one (MODEL §5). No colour depends on it, so a render
    /// (`NoRecorder`) skips it at compile time.
    #[cold]
    #[inline(never)]
    fn depth_limit(&mut self, ray: &Ray, hit: &SurfaceHit, material: &Material) {
        let spawn = self.spawn(ray, hit, material);
        if let Some(refraction) = spawn.refraction.filter(|r| r.tir) {
            self.rec.refraction(&refraction);
        }
        let transmits = spawn.refraction.is_some_and(|r| r.direction.is_some());
        self.rec.depth_limit(&DepthLimit {
            reflected: spawn.reflected_weight,
            transmitted: if transmits { material.kt } else { 0.0 },
        });
    }

    /// What a hit spawns, once, for the rays cast and for those the depth
    /// limit cuts: Snell's law if the material transmits, and the reflected
    /// ray's weight, k_s (+ k_t on TIR).
    #[inline]
    fn spawn(&self, ray: &Ray, hit: &SurfaceHit, material: &Material) -> Spawn {
        let refraction = self.rules.transmits(material).then(|| {
            refract(
                ray.direction,
                self.rules.refraction_normal(hit),
                self.rules.eta(hit.entering, material.ior),
            )
        });
        let tir = refraction.is_some_and(|r| r.tir);
        let reflected_weight = self.rules.mirror_weight(material)
            + if tir && self.rules.tir_adds_kt() {
                material.kt
            } else {
                0.0
            };
        Spawn {
            refraction,
            reflected_weight,
        }
    }

    /// Light `index`'s diffuse and specular terms at `point`, lit on the side
    /// of `normal` (`Rules::lighting_normal`).
    fn light_term(
        &mut self,
        point: DVec3,
        normal: DVec3,
        material: &Material,
        to_viewer: DVec3,
        (index, light): (usize, &Light),
    ) -> LightTerm {
        // A directional light's L is the same everywhere: it has no d_L, its
        // shadow ray no end and it is never attenuated (MODEL §4).
        let (to_light, distance, l, f_att) = match light.kind {
            LightKind::Point { position } => {
                let offset = position - point;
                let distance = offset.length();
                let to_light = offset / distance;
                let l = self.rules.lighting_direction(offset, to_light);
                let f_att = self.rules.f_att(light, distance);
                (to_light, Some(distance), l, f_att)
            }
            LightKind::Directional { direction } => (direction, None, direction, 1.0),
        };
        let n_dot_l = self.rules.light_cosine(normal.dot(l));
        let mut term = LightTerm {
            light: index,
            to_light: l,
            distance,
            n_dot_l,
            faces_away: n_dot_l <= 0.0,
            at_point: false,
            shadow: None,
            f_att,
            specular_model: self.rules.specular_model(material),
            specular_cosine: 0.0,
            diffuse: Color::ZERO,
            specular: Color::ZERO,
        };
        // A light within EPS of the point has no usable direction (at 0, L and
        // N·L are NaN) and no shadow segment: it adds nothing (MODEL §4).
        if distance.is_some_and(|d| d < EPS) {
            return at_point(term);
        }
        if term.faces_away && self.rules.light_behind_adds_nothing() {
            return term;
        }
        if self.rules.shadows() {
            term.shadow = Some(self.shadow_ray(point, to_light, distance, index));
        }
        let s = term.shadow.map_or(1.0, |shadow| shadow.s);
        term.specular_cosine = match term.specular_model {
            SpecularModel::Blinn => normal.dot(self.rules.half_vector(l, to_viewer)),
            SpecularModel::Phong => (2.0 * n_dot_l * normal - l).dot(to_viewer),
        };
        let strength = s * term.f_att;
        // powf is slow, slower still when it underflows (a shininess of 100000
        // in the SPD tree); where the product is zero anyway it is skipped,
        // giving the same bits (the highlight is finite and at least 0).
        let highlight = if strength * material.ks == 0.0 {
            0.0
        } else {
            term.specular_cosine.max(0.0).powf(material.shininess)
        };
        // (N·L)₊ = 0 for a light the profile counts from behind for its
        // highlight (MODEL §11); N·L is above 0 everywhere else here.
        if !term.faces_away {
            term.diffuse = light.color * material.color * (strength * material.kd * n_dot_l);
        }
        term.specular = light.color * (strength * material.ks * highlight);
        if let Some(o_s) = material.specular_color {
            term.specular *= o_s;
        }
        term
    }

    /// S_i: the product of k_t over every crossing of the segment to the
    /// light (`distance` away; `None`, a directional light, without end);
    /// an opaque crossing settles S_i = 0 and ends the walk, unless the
    /// recorder lists every blocker.
    fn shadow_ray(
        &mut self,
        point: DVec3,
        to_light: DVec3,
        distance: Option<f64>,
        light: usize,
    ) -> ShadowOutcome {
        let scene = self.scene;
        let ray = Ray::new(point, to_light);
        self.rec.shadow_cast(light, &ray, distance);
        let mut outcome = ShadowOutcome {
            s: 1.0,
            crossings: 0,
            cost: Cost::default(),
        };
        let rec = &mut *self.rec;
        let opaque = self.rules.opaque_shadows();
        let mut visit = |object, t| {
            let kt = if opaque {
                0.0
            } else {
                scene.material_of(object).kt
            };
            outcome.s *= kt;
            outcome.crossings += 1;
            rec.blocker(&Blocker { object, t, kt });
            if kt == 0.0 && !R::RECORDS_ALL_BLOCKERS {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        };
        // The row's cache only makes the query cheaper; a recording walks
        // the whole segment.
        let cache = (!R::RECORDS_ALL_BLOCKERS).then_some(&mut *self.cache);
        let segment = self.rules.shadow_segment(distance);
        scene.accel.shadow_crossings(
            &scene.objects,
            &ray,
            segment,
            light,
            cache,
            &mut outcome.cost,
            &mut visit,
        );
        outcome
    }

    /// Adds the reflected and transmitted rays, each through `trace_child`, to
    /// the local colour, one after the other (the order of MODEL §6's sum).
    fn secondary_rays(
        &mut self,
        ray: &Ray,
        hit: &SurfaceHit,
        material: &Material,
        parent: (u32, f64),
        local: Color,
    ) -> Color {
        let Spawn {
            refraction,
            reflected_weight,
        } = self.spawn(ray, hit, material);
        if let Some(refraction) = &refraction {
            self.rec.refraction(refraction);
        }
        let mut color = local;
        if reflected_weight > 0.0 {
            let mirrored = ray.direction - 2.0 * ray.direction.dot(hit.normal) * hit.normal;
            let child = (
                RayKind::Reflected,
                self.rules.reflected(mirrored),
                reflected_weight,
            );
            color += self.trace_child(hit, child, self.rules.mirror_tint(material), parent);
        }
        if let Some(direction) = refraction.and_then(|r| r.direction) {
            let child = (RayKind::Transmitted, direction, material.kt);
            color += self.trace_child(hit, child, None, parent);
        }
        color
    }

    /// Records a secondary ray that MODEL §5's rules keep from being cast:
    /// the weight cutoff if it applies, else the budget. Out of the way of
    /// the rays that are cast.
    #[cold]
    #[inline(never)]
    fn not_cast(&mut self, kind: RayKind, weight: f64, path_weight: f64) {
        let settings = self.settings;
        let rule = if path_weight < settings.min_weight {
            PruneRule::MinWeight {
                min_weight: settings.min_weight,
            }
        } else {
            PruneRule::MaxRays {
                max_rays: settings.max_rays,
            }
        };
        self.rec.not_cast(&NotCast {
            kind,
            weight,
            path_weight,
            rule,
        });
    }

    /// Traces a secondary ray (kind, direction, weight) from the hit of a ray
    /// of (depth, accumulated weight) `parent`, and scales what it returns by
    /// its weight (and `tint`, a colour the profile weighs it by) and its
    /// distance attenuation; a ray a rule prunes adds nothing.
    fn trace_child(
        &mut self,
        hit: &SurfaceHit,
        (kind, direction, weight): (RayKind, DVec3, f64),
        tint: Option<Color>,
        (depth, parent_weight): (u32, f64),
    ) -> Color {
        let path_weight = parent_weight * weight;
        let settings = self.settings;
        if path_weight < settings.min_weight || self.rays >= settings.max_rays {
            self.not_cast(kind, weight, path_weight);
            return Color::ZERO;
        }
        let ray = Ray::new(hit.point, direction);
        let traced = self.trace(&ray, kind, Nearest::ToFind, depth + 1, weight, path_weight);
        let attenuation = traced
            .distance
            .map_or(1.0, |t| attenuation(self.settings.ray_attenuation, t));
        let contribution = match tint {
            None => traced.color * (weight * attenuation),
            Some(tint) => traced.color * tint * (weight * attenuation),
        };
        self.rec.child(&ChildTerm {
            kind,
            attenuation,
            tint,
            contribution,
        });
        contribution
    }
}

/// What a hit spawns (`Tracer::spawn`).
struct Spawn {
    refraction: Option<Refraction>,
    reflected_weight: f64,
}

/// A light within EPS of the point, recorded like one that faces away, with
/// L = 0 and N·L = 0 in place of what the division by ~0 gave.
#[cold]
fn at_point(term: LightTerm) -> LightTerm {
    LightTerm {
        to_light: DVec3::ZERO,
        n_dot_l: 0.0,
        faces_away: true,
        at_point: true,
        ..term
    }
}

fn surface_hit(scene: &Scene, ray: &Ray, candidate: Candidate) -> SurfaceHit {
    let point = ray.at(candidate.t);
    let (geometric_normal, patch_plane) = scene.normals(candidate.object, point);
    // A patch's blended normal may face away from a ray that meets its
    // front near a silhouette: the side is its plane's, turned to the
    // blended normal's side (as pbrt does), and N follows it (MODEL §3).
    let side = match patch_plane {
        Some(plane) if plane.dot(geometric_normal) < 0.0 => -plane,
        Some(plane) => plane,
        None => geometric_normal,
    };
    let entering = side.dot(ray.direction) < 0.0;
    SurfaceHit {
        object: candidate.object,
        t: candidate.t,
        point,
        geometric_normal,
        normal: if entering {
            geometric_normal
        } else {
            -geometric_normal
        },
        entering,
    }
}

/// Snell's law with N facing the incoming ray (`Rules::refraction_normal`)
/// and the ratio `eta` (`Rules::eta`).
pub fn refract(direction: DVec3, normal: DVec3, eta: f64) -> Refraction {
    let cos_i = -direction.dot(normal);
    let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    let tir = k < 0.0;
    let direction = (!tir).then(|| eta * direction + (eta * cos_i - k.sqrt()) * normal);
    Refraction {
        cos_i,
        eta,
        k,
        tir,
        direction,
    }
}
