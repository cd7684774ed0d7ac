//! When a mistake of the catalogue may be named from a log. A tree that
//! matches one pixel can be a coincidence (a pixel-span slip gives
//! pixel-corner's ray at pixel 0,0; a shadow ray cast to a light behind
//! the surface gives two-sided-diffuse's tree where the light is blocked
//! anyway), so a name needs the mistake's tree to be the log at every
//! logged pixel, and at least two pixels whose colour differs from ours
//! where it acts. Short of that the report says "consistent with X here;
//! log pixel A,B to tell", A,B a pixel where the candidates' colours
//! differ from ours and from each other.

use std::collections::BTreeSet;

use super::held::CatalogueBudget;
use super::ours::OurRays;
use super::pixel_report::{Consistent, PixelReport, fits};
use super::tolerance::Tolerance;
use raystep_engine::scene::{Scene, Settings};
use raystep_model::mistakes::{Mistake, Mistakes};

/// Pixels at which a name needs the mistake to act, the colour differing.
const PIXELS_TO_NAME: usize = 2;

/// The pixels tried when looking for a pixel that tells the candidates
/// apart: this many nearest first, then every `GRID`th pixel of every
/// `GRID`th row of the image.
const PIXELS_NEAR: usize = 1024;
const GRID: u32 = 4;

/// Whether two of our trees of one pixel differ in colour: a pixel where
/// only rays that add nothing differ would not tell (a log is named from
/// the pixels whose colour differs).
fn colours_differ(a: &OurRays, b: &OurRays) -> bool {
    match (a.rays()[0].color, b.rays()[0].color) {
        (Some(a), Some(b)) => !Tolerance::default().colours(a, b),
        _ => false,
    }
}

fn under(
    scene: &Scene,
    mistake: Option<Mistake>,
    pixel: (u32, u32),
    budget: &mut CatalogueBudget,
) -> Option<OurRays> {
    if !budget.allows() {
        return None;
    }
    let settings = Settings {
        mistakes: Mistakes::from_iter(mistake),
        ..scene.settings
    };
    let ours = OurRays::record(scene, &settings, pixel);
    budget.spend(ours.rays().len());
    Some(ours)
}

/// The pixel nearest `near`, not among `logged`, where each candidate's
/// colour differs from ours and from every other candidate's: logging it
/// tells them apart. `None` when there is no candidate, or no such pixel
/// within the budget.
pub(crate) fn tell_pixel(
    scene: &Scene,
    near: (u32, u32),
    candidates: &[Mistake],
    logged: &[(u32, u32)],
    budget: &mut CatalogueBudget,
) -> Option<(u32, u32)> {
    if candidates.is_empty() {
        return None;
    }
    let (w, h) = (scene.width, scene.height);
    let mut pixels: Vec<(u32, u32)> = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .filter(|p| !logged.contains(p))
        .collect();
    let distance = |(x, y): (u32, u32)| {
        let (dx, dy) = (x as i64 - near.0 as i64, y as i64 - near.1 as i64);
        dx * dx + dy * dy
    };
    pixels.sort_by_key(|&p| distance(p));
    let grid = pixels
        .iter()
        .skip(PIXELS_NEAR)
        .filter(|(x, y)| x % GRID == 0 && y % GRID == 0)
        .copied()
        .collect::<Vec<_>>();
    pixels.truncate(PIXELS_NEAR);
    for pixel in pixels.into_iter().chain(grid) {
        let model = under(scene, None, pixel, budget)?;
        let trees: Vec<OurRays> = candidates
            .iter()
            .map(|&m| under(scene, Some(m), pixel, budget))
            .collect::<Option<_>>()?;
        let tells = trees.iter().enumerate().all(|(i, tree)| {
            colours_differ(tree, &model)
                && trees[..i].iter().all(|other| colours_differ(tree, other))
        });
        if tells {
            return Some(pixel);
        }
    }
    None
}

/// The log-level verdict on the pixels shown: each candidate of a pixel
/// (`consistent`, from that pixel alone) is named on the pixels it
/// explains when its tree is the log at every logged pixel and it acts on
/// the colour at two of them or more; it is dropped everywhere when
/// another logged pixel refutes it; otherwise it stays consistent, with
/// a pixel to log that would tell.
pub(crate) fn decide(
    scene: &Scene,
    pixels: &mut [PixelReport],
    tolerance: &Tolerance,
    budget: &mut CatalogueBudget,
) {
    let candidates: BTreeSet<Mistake> = pixels
        .iter()
        .flat_map(|p| p.consistent.iter().map(|c| c.mistake))
        .collect();
    let logged: Vec<(u32, u32)> = pixels.iter().map(|p| p.pixel).collect();
    let claims = |p: &PixelReport, m: Mistake| p.consistent.iter().any(|c| c.mistake == m);
    let mut named = Vec::new();
    let mut refuted = Vec::new();
    for m in candidates {
        // A pixel the budget left untried neither names nor refutes.
        let mut fits_all = Some(true);
        for p in pixels.iter().filter(|p| !claims(p, m)) {
            let fits_here = match p.matches {
                true => fits(scene, m, p.pixel, &p.yours, tolerance, budget),
                false => Some(false),
            };
            match fits_here {
                Some(true) => {}
                Some(false) => {
                    fits_all = Some(false);
                    break;
                }
                None => fits_all = None,
            }
        }
        let evidence = pixels
            .iter()
            .filter(|p| claims(p, m) && !p.matches && p.colour_agrees != Some(true))
            .count();
        match fits_all {
            Some(false) => refuted.push(m),
            Some(true) if evidence >= PIXELS_TO_NAME => named.push(m),
            _ => {}
        }
    }
    for pixel in pixels.iter_mut() {
        let (name, keep): (Vec<Consistent>, Vec<Consistent>) =
            std::mem::take(&mut pixel.consistent)
                .into_iter()
                .filter(|c| !refuted.contains(&c.mistake))
                .partition(|c| named.contains(&c.mistake));
        pixel.mistakes = name.into_iter().map(|c| c.mistake).collect();
        pixel.consistent = keep;
    }
    // One pixel to tell the candidates still open, away from every logged one.
    if let Some(first) = pixels.iter().position(|p| !p.consistent.is_empty()) {
        let open: Vec<Mistake> = pixels[first].consistent.iter().map(|c| c.mistake).collect();
        let tell = tell_pixel(scene, pixels[first].pixel, &open, &logged, budget);
        for pixel in pixels.iter_mut() {
            for c in &mut pixel.consistent {
                c.tell = tell;
            }
        }
    }
}
