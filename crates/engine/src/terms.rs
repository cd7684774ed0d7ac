//! Term images: the primary ray's illumination terms for every pixel, so a
//! whole image can be read term by term, plus the shadow factor, the number
//! of rays and the cost of the queries per pixel.

use std::sync::atomic::AtomicBool;

use image::RgbImage;

use crate::render::{PrimaryWalk, RowRecorder, trace_rows, viewport};
use crate::scene::{Scene, Settings};
use crate::trace::{
    Blocker, ChildTerm, DepthLimit, LightTerm, NotCast, RayKind, Recorder, Refraction, SurfaceHit,
    trace_in_row,
};
use raystep_accel::Cost;
use raystep_model::math::{Color, Ray, to_rgb8};
use raystep_model::mistakes::Mistakes;

/// One view of the per-pixel terms.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Term {
    Ambient,
    /// E, a material's emission (MODEL §11): written only for a scene
    /// with some, so it is not in `ALL` (see `Term::written_for`).
    Emission,
    Diffuse,
    Specular,
    Reflected,
    Transmitted,
    Shadow,
    Rays,
    Cost,
}

impl Term {
    /// The views of every scene (the debugger's `v` goes through these).
    pub const ALL: [Term; 8] = [
        Term::Ambient,
        Term::Diffuse,
        Term::Specular,
        Term::Reflected,
        Term::Transmitted,
        Term::Shadow,
        Term::Rays,
        Term::Cost,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Term::Ambient => "ambient",
            Term::Emission => "emission",
            Term::Diffuse => "diffuse",
            Term::Specular => "specular",
            Term::Reflected => "reflected",
            Term::Transmitted => "transmitted",
            Term::Shadow => "shadow",
            Term::Rays => "rays",
            Term::Cost => "cost",
        }
    }

    /// The views `render --terms` writes for `scene`: `ALL`, and the
    /// emission after the ambient when some material has one (so a scene
    /// without writes the files it always wrote).
    pub fn written_for(scene: &Scene) -> Vec<Term> {
        let emits = scene.materials.iter().any(|m| m.emission.is_some());
        let mut terms = Term::ALL.to_vec();
        if emits {
            terms.insert(1, Term::Emission);
        }
        terms
    }

    /// The file `render --terms DIR` writes this view to, inside DIR.
    pub fn file_name(self) -> String {
        format!("{}.png", self.name())
    }

    /// What the view shows, for legends.
    pub fn legend(self) -> &'static str {
        match self {
            Term::Ambient => {
                "ambient term of the primary hit: k_a I_a O_d, or the material's own ambient"
            }
            Term::Emission => "emission E of the primary hit, added as it is",
            Term::Diffuse => "sum over lights of the diffuse terms",
            Term::Specular => "sum over lights of the specular terms",
            Term::Reflected => {
                "what the reflected ray adds: k_s I_r (k_s O_s ∘ I_r under cse167, MODEL §11)"
            }
            Term::Transmitted => {
                "what the transmitted ray adds: k_t I_t (nothing under cse167, MODEL §11)"
            }
            Term::Shadow => {
                "mean S over the lights facing the hit: white lit, black shadowed; \
                 purple: no light faces the point; dark blue: background"
            }
            Term::Rays => "rays per pixel (all kinds, shadow rays too): dark few, bright many",
            Term::Cost => "nodes + primitives tested per pixel: dark cheap, bright expensive",
        }
    }
}

/// The terms of one pixel's primary ray.
#[derive(Clone, Copy, Debug, Default)]
pub struct PixelTerms {
    pub(crate) color: Color,
    pub ambient: Color,
    /// E at the primary hit (black where the material emits nothing).
    pub emission: Color,
    pub diffuse: Color,
    pub specular: Color,
    pub reflected: Color,
    pub transmitted: Color,
    /// Mean S over lights facing the hit; `None` on a miss or when none faces it.
    pub shadow: Option<f64>,
    /// Whether the primary ray hit something (`shadow.png` tells a miss
    /// from a point no light faces).
    pub(crate) hit: bool,
    pub rays: u32,
    pub cost: u32,
}

/// Gathers `PixelTerms` from the tracer's callbacks for one pixel.
#[derive(Default)]
struct TermsRecorder {
    terms: PixelTerms,
    depth: u32,
    shadow_sum: f64,
    shadow_count: u32,
}

impl Recorder for TermsRecorder {
    fn ray_cast(&mut self, _kind: RayKind, _depth: u32, _ray: &Ray, _weight: f64) {
        self.depth += 1;
        self.terms.rays += 1;
    }

    fn hit(&mut self, _hit: &SurfaceHit, cost: Cost) {
        self.terms.cost += cost.nodes + cost.primitives;
        if self.depth == 1 {
            self.terms.hit = true;
        }
    }

    fn miss(&mut self, _background: Color, cost: Cost) {
        self.terms.cost += cost.nodes + cost.primitives;
    }

    fn ambient(&mut self, term: Color) {
        if self.depth == 1 {
            self.terms.ambient = term;
        }
    }

    fn emission(&mut self, term: Color) {
        if self.depth == 1 {
            self.terms.emission = term;
        }
    }

    fn shadow_cast(&mut self, _light: usize, _ray: &Ray, _distance: Option<f64>) {
        self.terms.rays += 1;
    }

    fn light(&mut self, term: &LightTerm) {
        if let Some(shadow) = term.shadow {
            self.terms.cost += shadow.cost.nodes + shadow.cost.primitives;
        }
        if self.depth != 1 {
            return;
        }
        self.terms.diffuse += term.diffuse;
        self.terms.specular += term.specular;
        if !term.faces_away {
            self.shadow_sum += term.shadow.map_or(1.0, |s| s.s);
            self.shadow_count += 1;
        }
    }

    fn child(&mut self, term: &ChildTerm) {
        if self.depth != 1 {
            return;
        }
        match term.kind {
            RayKind::Reflected => self.terms.reflected += term.contribution,
            RayKind::Transmitted => self.terms.transmitted += term.contribution,
            RayKind::Primary => {}
        }
    }

    fn ray_done(&mut self, _color: Color) {
        self.depth -= 1;
    }
}

/// Every pixel's terms, row by row.
pub struct TermImages {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<PixelTerms>,
    /// The mistakes traced with: the colour image stores its bytes as the
    /// render does under them (`Mistakes::rgb8`).
    pub(crate) mistakes: Mistakes,
}

/// Traces every pixel with the terms recorder (the same `trace` as the
/// render), and `R` (`RayStats` for `--stats`) follows the same trace.
pub fn render_terms<R: RowRecorder>(
    scene: &Scene,
    settings: &Settings,
    row_done: &(dyn Fn() + Sync),
) -> (TermImages, R) {
    render_terms_unless(scene, settings, row_done, &AtomicBool::new(false))
        .expect("a render nobody can cancel finishes")
}

/// `render_terms` unless `cancel` is set, looked at before each row (as
/// `render::render_unless` does); `None` when cancelled.
pub fn render_terms_unless<R: RowRecorder>(
    scene: &Scene,
    settings: &Settings,
    row_done: &(dyn Fn() + Sync),
    cancel: &AtomicBool,
) -> Option<(TermImages, R)> {
    let size = (scene.width, scene.height);
    let mut pixels = vec![PixelTerms::default(); scene.width as usize * scene.height as usize];
    // Each pixel has its own terms recorder; the row's recorder sees it all.
    // Each pixel's recorder counts its primary ray's query (the cost image).
    let counts = trace_rows::<_, R>(
        scene,
        &viewport(scene, settings, size),
        PrimaryWalk::OneByOne,
        &mut pixels,
        row_done,
        cancel,
        |ray, nearest, cache, counts, pixel| {
            let mut rec = TermsRecorder::default();
            let both = &mut Both(counts, &mut rec);
            let color = trace_in_row(scene, settings, ray, nearest, cache, both);
            rec.terms.color = color;
            rec.terms.shadow =
                (rec.shadow_count > 0).then(|| rec.shadow_sum / rec.shadow_count as f64);
            *pixel = rec.terms;
        },
    )?;
    let images = TermImages {
        width: scene.width,
        height: scene.height,
        pixels,
        mistakes: settings.mistakes,
    };
    Some((images, counts))
}

/// Two recorders following one trace, each told every callback.
struct Both<'a, A, B>(&'a mut A, &'a mut B);

impl<A: Recorder, B: Recorder> Recorder for Both<'_, A, B> {
    const RECORDS_ALL_BLOCKERS: bool = A::RECORDS_ALL_BLOCKERS || B::RECORDS_ALL_BLOCKERS;
    const RECORDS_DEPTH_LIMIT: bool = A::RECORDS_DEPTH_LIMIT || B::RECORDS_DEPTH_LIMIT;

    fn ray_cast(&mut self, kind: RayKind, depth: u32, ray: &Ray, weight: f64) {
        self.0.ray_cast(kind, depth, ray, weight);
        self.1.ray_cast(kind, depth, ray, weight);
    }
    fn hit(&mut self, hit: &SurfaceHit, cost: Cost) {
        self.0.hit(hit, cost);
        self.1.hit(hit, cost);
    }
    fn miss(&mut self, background: Color, cost: Cost) {
        self.0.miss(background, cost);
        self.1.miss(background, cost);
    }
    fn ambient(&mut self, term: Color) {
        self.0.ambient(term);
        self.1.ambient(term);
    }
    fn emission(&mut self, term: Color) {
        self.0.emission(term);
        self.1.emission(term);
    }
    fn shadow_cast(&mut self, light: usize, ray: &Ray, distance: Option<f64>) {
        self.0.shadow_cast(light, ray, distance);
        self.1.shadow_cast(light, ray, distance);
    }
    fn blocker(&mut self, blocker: &Blocker) {
        self.0.blocker(blocker);
        self.1.blocker(blocker);
    }
    fn light(&mut self, term: &LightTerm) {
        self.0.light(term);
        self.1.light(term);
    }
    fn refraction(&mut self, refraction: &Refraction) {
        self.0.refraction(refraction);
        self.1.refraction(refraction);
    }
    fn child(&mut self, term: &ChildTerm) {
        self.0.child(term);
        self.1.child(term);
    }
    fn not_cast(&mut self, ray: &NotCast) {
        self.0.not_cast(ray);
        self.1.not_cast(ray);
    }
    fn depth_limit(&mut self, limit: &DepthLimit) {
        self.0.depth_limit(limit);
        self.1.depth_limit(limit);
    }
    fn ray_done(&mut self, color: Color) {
        self.0.ray_done(color);
        self.1.ray_done(color);
    }
}

impl TermImages {
    /// The largest count in a count view (rays or cost), for its legend.
    pub fn max_count(&self, term: Term) -> u32 {
        self.pixels
            .iter()
            .map(|p| if term == Term::Rays { p.rays } else { p.cost })
            .max()
            .unwrap_or(0)
    }

    /// The least and the most of a count view (rays or cost) over the
    /// image: its colour ramp runs from 0 (dark blue) to the most (yellow).
    pub fn count_range(&self, term: Term) -> (u32, u32) {
        let count = |p: &PixelTerms| if term == Term::Rays { p.rays } else { p.cost };
        let min = self.pixels.iter().map(count).min().unwrap_or(0);
        (min, self.max_count(term))
    }

    /// One pixel of a view as 8-bit RGB; counts are scaled by `max_count`.
    pub fn rgb(&self, term: Term, index: usize, max_count: u32) -> [u8; 3] {
        let p = &self.pixels[index];
        match term {
            Term::Ambient => to_rgb8(p.ambient),
            Term::Emission => to_rgb8(p.emission),
            Term::Diffuse => to_rgb8(p.diffuse),
            Term::Specular => to_rgb8(p.specular),
            Term::Reflected => to_rgb8(p.reflected),
            Term::Transmitted => to_rgb8(p.transmitted),
            Term::Shadow => match p.shadow {
                Some(s) => to_rgb8(Color::splat(s)),
                None if p.hit => NO_LIGHT_FACES,
                None => SHADOW_BACKGROUND,
            },
            Term::Rays => false_color(p.rays as f64 / max_count.max(1) as f64),
            Term::Cost => false_color(p.cost as f64 / max_count.max(1) as f64),
        }
    }

    /// The rendered image: each pixel's colour, as the plain render writes it.
    pub fn color_image(&self) -> RgbImage {
        RgbImage::from_fn(self.width, self.height, |x, y| {
            image::Rgb(
                self.mistakes
                    .rgb8(self.pixels[(y * self.width + x) as usize].color),
            )
        })
    }

    pub fn image(&self, term: Term) -> RgbImage {
        let max = self.max_count(term);
        RgbImage::from_fn(self.width, self.height, |x, y| {
            image::Rgb(self.rgb(term, (y * self.width + x) as usize, max))
        })
    }
}

/// `shadow.png` where the primary ray hits a point that no light faces
/// (no shadow ray is cast): purple, apart from the grey scale of S.
pub const NO_LIGHT_FACES: [u8; 3] = [110, 40, 120];
/// `shadow.png` where the primary ray misses: dark blue.
pub const SHADOW_BACKGROUND: [u8; 3] = [20, 30, 70];

/// A dark-blue to yellow ramp for counts in [0, 1].
pub fn false_color(v: f64) -> [u8; 3] {
    const STOPS: [[f64; 3]; 5] = [
        [0.05, 0.03, 0.25],
        [0.25, 0.2, 0.6],
        [0.1, 0.55, 0.55],
        [0.5, 0.8, 0.25],
        [1.0, 0.95, 0.2],
    ];
    let v = v.clamp(0.0, 1.0) * (STOPS.len() - 1) as f64;
    let i = (v.floor() as usize).min(STOPS.len() - 2);
    let f = v - i as f64;
    let [a, b] = [STOPS[i], STOPS[i + 1]];
    to_rgb8(Color::new(
        a[0] + f * (b[0] - a[0]),
        a[1] + f * (b[1] - a[1]),
        a[2] + f * (b[2] - a[2]),
    ))
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::scene::{load, parse};
    use crate::trace::NoRecorder;

    /// An emitting ball, lit and shiny, over a mirror floor that reflects
    /// it: every term of CSE 167's sum is in some pixel.
    const GLOWING_BALL: &str = "size 32 24
camera 0 0.5 6 0 0 0 0 1 0 40
point 2 3 4 1 1 1
ambient 0.1 0.1 0.1
emission 0.3 0.2 0.1
diffuse 0.5 0.4 0.3
specular 0.4 0.4 0.4
shininess 20
sphere 0 0 0 1
emission 0 0 0
diffuse 0.2 0.2 0.2
specular 0.6 0.6 0.6
sphere 0 -101 0 100
";

    /// MODEL §6 (and §11's I = A + E + ...): the primary ray's stored terms
    /// add up to its colour, so the term images are the image taken apart.
    #[test]
    fn the_terms_add_up_to_each_pixels_colour_emission_included() {
        let glowing = parse(Path::new("glowing.test"), GLOWING_BALL).unwrap();
        let on_disk = ["cse167/ambient-emission.test", "glass.toml"]
            .map(|f| load(&Path::new("../../scenes").join(f)).unwrap());
        let mut emitting = 0;
        for scene in std::iter::once(glowing).chain(on_disk) {
            let scene = scene.with_size(32, 24).unwrap();
            let (terms, NoRecorder) = render_terms(&scene, &scene.settings, &|| {});
            // A miss is the background, no term.
            for (i, p) in terms.pixels.iter().enumerate().filter(|(_, p)| p.hit) {
                let sum =
                    p.ambient + p.emission + p.diffuse + p.specular + p.reflected + p.transmitted;
                // Summed in another order than the tracer's: a few ulps.
                let off = (sum - p.color).abs().max_element();
                assert!(off < 1e-12, "pixel {i}: {sum} != {}", p.color);
                emitting += usize::from(p.emission != Color::ZERO);
            }
        }
        assert!(emitting > 0);
    }
}
