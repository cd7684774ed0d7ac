//! One pixel's rays beside ours: aligned by path, every difference placed
//! in the order the trace makes it, the first one explained, the
//! catalogue's mistakes tried on the whole tree.

use std::collections::HashMap;

use super::absence::{why_not_ours, why_ours};
use super::checks::{Check, Value, checks};
use super::held::{CATALOGUE_RAYS, CatalogueBudget, CountedOnly};
use super::kind::{Kind, classify};
use super::meaning::meaning;
use super::moment::{Field, cast_order, in_trace_order};
use super::ours::OurRays;
use super::tolerance::Tolerance;
use crate::raylog::{LoggedRay, RayPath};
use raystep_engine::scene::{Profile, Scene, Settings};
use raystep_model::mistakes::{Mistake, Mistakes};

/// A ray of either tree, with the other tree's ray of the same path.
#[derive(Clone, Debug)]
pub struct AlignedRay {
    pub path: RayPath,
    /// Its index among your logged rays of the pixel.
    pub yours: Option<usize>,
    /// Its index among our rays (`OurRays::rays`).
    pub ours: Option<usize>,
    /// Each field you logged, against ours; empty unless both cast it.
    pub checks: Vec<Check>,
}

/// How a ray of the pixel compares.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RayStatus {
    Matches,
    Differs,
    OnlyYours,
    OnlyOurs,
}

impl AlignedRay {
    pub fn status(&self) -> RayStatus {
        match (self.yours, self.ours) {
            (Some(_), None) => RayStatus::OnlyYours,
            (None, _) => RayStatus::OnlyOurs,
            _ if self.checks.iter().all(|c| c.agrees) => RayStatus::Matches,
            _ => RayStatus::Differs,
        }
    }
}

/// Your rays of one pixel and ours, in the order the tracer casts them.
pub(crate) fn align(yours: &[LoggedRay], ours: &OurRays, tolerance: &Tolerance) -> Vec<AlignedRay> {
    let mut by_path: HashMap<&RayPath, usize> = HashMap::new();
    for (i, ray) in yours.iter().enumerate() {
        by_path.insert(&ray.path, i);
    }
    let mut aligned: Vec<AlignedRay> = ours
        .rays()
        .iter()
        .enumerate()
        .map(|(o, ray)| {
            let y = by_path.remove(&ray.path);
            AlignedRay {
                path: ray.path.clone(),
                yours: y,
                ours: Some(o),
                checks: y.map_or_else(Vec::new, |y| checks(&yours[y], ray, tolerance)),
            }
        })
        .collect();
    aligned.extend(by_path.into_iter().map(|(path, y)| AlignedRay {
        path: path.clone(),
        yours: Some(y),
        ours: None,
        checks: Vec::new(),
    }));
    aligned.sort_by(|a, b| cast_order(&a.path, &b.path));
    aligned
}

/// The first place your trace parts from ours.
#[derive(Clone, Debug)]
pub struct Divergence {
    pub path: RayPath,
    pub field: Field,
    pub yours: Value,
    pub ours: Option<Value>,
    pub kind: Kind,
    /// The kind in words, with the numbers that show it.
    pub words: String,
    /// The MODEL formula behind our value, with our numbers.
    pub meaning: Vec<String>,
}

/// A ray in one tree only, and the rule of MODEL that decides it.
#[derive(Clone, Debug)]
pub struct Unpaired {
    pub path: RayPath,
    pub rule: String,
}

/// One pixel of the log, compared in full.
#[derive(Clone, Debug)]
pub struct PixelReport {
    pub pixel: (u32, u32),
    /// Every ray and every logged number agree, and no ray is in one tree only.
    pub matches: bool,
    pub first_divergence: Option<Divergence>,
    /// How many differences (numbers, and rays in one tree only) come after
    /// the first: they follow from it.
    pub later_differences: usize,
    /// The rays in one tree only, in cast order: in a whole log's
    /// comparison the first `UNPAIRED_KEPT` of each, `unpaired_total`
    /// saying how many there are.
    pub only_yours: Vec<Unpaired>,
    pub only_ours: Vec<Unpaired>,
    /// How many rays are in yours only and in ours only.
    pub unpaired_total: (usize, usize),
    /// The catalogue mistakes named: each one's tree is your log at this
    /// pixel and at every other pixel of the log, and at least two of the
    /// log's pixels differ from ours in colour where it does.
    pub mistakes: Vec<Mistake>,
    /// The catalogue mistakes whose tree is your log here, where the log
    /// cannot tell them from a coincidence (one pixel alone, or only where
    /// your colour agrees with ours): "consistent with X here; log pixel
    /// A,B to tell".
    pub consistent: Vec<Consistent>,
    /// Whether your primary ray's colour agrees with ours within the
    /// tolerance; `None` when your log has no colour for it.
    pub colour_agrees: Option<bool>,
    /// What the comparison read differently from the log as written (a
    /// miss that logs a t), in words.
    pub notes: Vec<String>,
    /// Your rays as logged, and both trees aligned. A whole log's
    /// comparison (`compare_log`) keeps no alignment: every pixel's would
    /// be held at once, up to `max_rays` rays each, for nothing it reports.
    pub yours: Vec<LoggedRay>,
    pub aligned: Vec<AlignedRay>,
    pub rays_ours: usize,
    /// Your rays of the pixel that were counted, not held nor compared
    /// one by one (`held`): rays ours can never cast.
    pub counted_only: CountedOnly,
    /// Whether the catalogue's budget ran out before every mistake was
    /// tried here.
    pub catalogue_stopped: bool,
}

/// A mistake of the catalogue whose tree is your log at a pixel, and a
/// pixel to log that would tell it from the others and from ours.
#[derive(Clone, Debug, PartialEq)]
pub struct Consistent {
    pub mistake: Mistake,
    pub tell: Option<(u32, u32)>,
}

impl PixelReport {
    /// Your colour agrees with ours though your rays differ: they differ
    /// where they add nothing (within the colour tolerance).
    pub(crate) fn differs_where_it_adds_nothing(&self) -> bool {
        !self.matches && self.colour_agrees == Some(true)
    }
}

/// A difference's place: the ray (aligned) and the field.
pub(crate) struct Difference<'a> {
    ray: &'a AlignedRay,
    check: Option<&'a Check>,
}

impl Difference<'_> {
    fn field(&self) -> Field {
        self.check.map_or(Field::Ray, |c| c.field)
    }
}

pub(crate) fn differences(aligned: &[AlignedRay]) -> Vec<Difference<'_>> {
    let mut found: Vec<Difference> = Vec::new();
    for ray in aligned {
        match ray.status() {
            RayStatus::OnlyYours | RayStatus::OnlyOurs => {
                found.push(Difference { ray, check: None })
            }
            _ => found.extend(
                ray.checks
                    .iter()
                    .filter(|c| !c.agrees)
                    .map(|check| Difference {
                        ray,
                        check: Some(check),
                    }),
            ),
        }
    }
    found.sort_by(|a, b| in_trace_order((&a.ray.path, a.field()), (&b.ray.path, b.field())));
    found
}

/// Compares your rays of one pixel with `ours`, its reference tree, and
/// when they differ tries the catalogue (within `CATALOGUE_RAYS`).
pub fn compare_pixel(
    scene: &Scene,
    yours: Vec<LoggedRay>,
    ours: &OurRays,
    tolerance: &Tolerance,
) -> PixelReport {
    let mut budget = CatalogueBudget::new(CATALOGUE_RAYS);
    compare_within(
        scene,
        (yours, CountedOnly::default()),
        ours,
        tolerance,
        &mut budget,
        usize::MAX,
    )
}

/// `compare_pixel`, with the rays of the pixel that were only counted,
/// the catalogue's budget left and how many rays in one tree only to keep
/// (each with its rule in words) on either side.
pub(crate) fn compare_within(
    scene: &Scene,
    (yours, counted_only): (Vec<LoggedRay>, CountedOnly),
    ours: &OurRays,
    tolerance: &Tolerance,
    budget: &mut CatalogueBudget,
    unpaired_kept: usize,
) -> PixelReport {
    let notes = super::miss_t::notes(&yours);
    let aligned = align(&yours, ours, tolerance);
    let found = differences(&aligned);
    let colour_agrees = aligned
        .iter()
        .find(|a| a.path.steps.is_empty())
        .and_then(|a| a.checks.iter().find(|c| c.field == Field::Color))
        .map(|c| c.agrees);
    let first_divergence = found.first().map(|d| divergence(scene, ours, d));
    let unpaired = |status: RayStatus, rule: &dyn Fn(&AlignedRay) -> String| -> Vec<Unpaired> {
        aligned
            .iter()
            .filter(|a| a.status() == status)
            .take(unpaired_kept)
            .map(|a| Unpaired {
                path: a.path.clone(),
                rule: rule(a),
            })
            .collect()
    };
    let only_yours = unpaired(RayStatus::OnlyYours, &|a| {
        why_not_ours(scene, ours, &a.path)
    });
    let only_ours = unpaired(RayStatus::OnlyOurs, &|a| {
        why_ours(scene, ours, a.ours.unwrap_or(0))
    });
    let unpaired_total = (
        aligned
            .iter()
            .filter(|a| a.status() == RayStatus::OnlyYours)
            .count(),
        aligned
            .iter()
            .filter(|a| a.status() == RayStatus::OnlyOurs)
            .count(),
    );
    // A ray only counted is one ours never casts: a difference.
    let matches = found.is_empty() && counted_only.total() == 0;
    let later_differences = (found.len() + counted_only.total()).saturating_sub(1);
    let candidates = if matches {
        Vec::new()
    } else {
        catalogue(scene, ours.tree.pixel, &yours, tolerance, budget)
    };
    // Which pixel would tell is the log's question (`verdict::decide`).
    let consistent = candidates
        .into_iter()
        .map(|mistake| Consistent {
            mistake,
            tell: None,
        })
        .collect();
    PixelReport {
        pixel: ours.tree.pixel,
        matches,
        first_divergence,
        later_differences,
        only_yours,
        only_ours,
        unpaired_total,
        mistakes: Vec::new(),
        consistent,
        colour_agrees,
        notes,
        rays_ours: ours.rays().len(),
        yours,
        aligned,
        counted_only,
        catalogue_stopped: !matches && budget.stopped,
    }
}

fn divergence(scene: &Scene, ours: &OurRays, d: &Difference) -> Divergence {
    let path = d.ray.path.clone();
    match (d.check, d.ray.ours) {
        (Some(check), Some(ray)) => {
            let (kind, words) = classify(scene, ours, ray, check);
            Divergence {
                path,
                field: check.field,
                yours: check.yours,
                ours: check.ours,
                kind,
                words,
                meaning: meaning(scene, ours, ray, check.field),
            }
        }
        (_, Some(ray)) => Divergence {
            path,
            field: Field::Ray,
            yours: Value::Cast(false),
            ours: Some(Value::Cast(true)),
            kind: Kind::OnlyOurs,
            words: "your log does not have this ray: you never cast it".into(),
            meaning: vec![why_ours(scene, ours, ray)],
        },
        (_, None) => Divergence {
            words: "ours never casts this ray".into(),
            meaning: vec![why_not_ours(scene, ours, &path)],
            path,
            field: Field::Ray,
            yours: Value::Cast(true),
            ours: Some(Value::Cast(false)),
            kind: Kind::OnlyYours,
        },
    }
}

/// The catalogue mistakes a log can show: those of the bytes act after
/// every ray is traced, so no ray shows them; and of the rest those the
/// scene's profile offers (`Profile::offers`), the only ones named.
pub(crate) fn traceable_mistakes(profile: Profile) -> impl Iterator<Item = Mistake> {
    profile
        .offered_mistakes()
        .filter(|m| !m.acts_only_on_bytes())
}

/// Whether our tree of `pixel` under `mistake` is your log of it; `None`
/// when the budget is spent.
pub(crate) fn fits(
    scene: &Scene,
    mistake: Mistake,
    pixel: (u32, u32),
    yours: &[LoggedRay],
    tolerance: &Tolerance,
    budget: &mut CatalogueBudget,
) -> Option<bool> {
    if !budget.allows() {
        return None;
    }
    let settings = Settings {
        mistakes: Mistakes::from_iter([mistake]),
        ..scene.settings
    };
    let ours = OurRays::record(scene, &settings, pixel);
    budget.spend(ours.rays().len());
    Some(differences(&align(yours, &ours, tolerance)).is_empty())
}

/// The mistakes under which our tree of `pixel` is your log, of those
/// tried before the budget ran out.
fn catalogue(
    scene: &Scene,
    pixel: (u32, u32),
    yours: &[LoggedRay],
    tolerance: &Tolerance,
    budget: &mut CatalogueBudget,
) -> Vec<Mistake> {
    let mut found = Vec::new();
    for mistake in traceable_mistakes(scene.settings.profile) {
        match fits(scene, mistake, pixel, yours, tolerance, budget) {
            Some(true) => found.push(mistake),
            Some(false) => {}
            None => break,
        }
    }
    found
}
