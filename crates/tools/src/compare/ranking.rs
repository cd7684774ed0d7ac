//! Which classic mistake explains the student's image: the scene rendered
//! again under each mistake with the same engine, and each variant measured
//! against the student's image.
//!
//! The student's tracer is another program: its rounding speckles other
//! pixels than ours (shadow acne) and its edges fall elsewhere. So images are
//! compared by the mean colour of 16 x 16 blocks (`BLOCK`), not pixel by
//! pixel: two speckled images of the same density agree there, where a
//! clean one does not.
//!
//! A mistake is judged where it changes the image: in the blocks its render
//! changes, does it bring the reference to the student's image? That finds
//! a small mistake (a highlight's shape) beside a large one (black
//! shadows), and turns down a look-alike: once the mistake that darkens
//! everything is chosen, another that darkens shadows brings nothing more.

use image::RgbImage;
use serde::Serialize;

use super::metrics::{TOLERANCE_STEPS, channel_gap};
use super::scene_renders::SceneRenders;
use raystep_engine::scene::{Material, Scene, Settings};
use raystep_model::math::Color;
use raystep_model::mistakes::{ActsOn, Mistake, Mistakes};

/// The side of the blocks compared.
const BLOCK: u32 = 16;
/// A mistake is ranked when, in the blocks it changes, it takes the image
/// at least this far from the reference (or from the mistakes listed above
/// it) to the student's.
pub(crate) const MIN_FIT: f64 = 0.5;
/// Unless the listed mistakes together reproduce the student's image, one
/// that fits less than this is not listed at all. Set from the evidence of
/// issue 39 (docs/STUDENTS.md has the table): a catalogued mistake in
/// another tracer's render fits at least 70.6% (shadow-acne on glass.toml
/// with the eye moved 1e-6, its speckles elsewhere; tests/student/
/// whitted.py's slips 84.8% and up, raystep's own renders 100%); a slip
/// outside the catalogue fitted a wrong mistake that nothing else overrode
/// at most 61.3% (`two-sided-diffuse` beside a missing TIR test on
/// prism.toml), 52.6% (`phong-not-blinn` for a highlight times the
/// object's colour on highlights.toml).
pub(crate) const LISTED_FIT: f64 = 0.65;
/// At most this many mistakes are listed.
const MAX_LISTED: usize = 3;
/// A mistake that takes away less than this share of the whole difference
/// on top of those listed above it is not listed: its change is below
/// what the blocks tell apart, and there any mistake that touches the few
/// blocks left fits by chance (a student's NaN image, white where lit, is
/// light-not-normalised at 99.9%; two-sided-diffuse then "fit" 61% and
/// took 0.06%).
const MIN_SHARE: f64 = 0.001;

/// What `compare` claims of a listed mistake (a name is a claim).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// The listed mistakes' render reproduces the student's image by the
    /// match rule: the mistake is the cause.
    Is,
    /// It explains much but its render does not reproduce the student's
    /// image: other bugs give nearly this picture.
    LooksLike,
    /// Something that explains more overrides it: the geometry, what the
    /// image shows (channels swapped, a constant factor, ...) or the
    /// student's ray log (`superseded_by` says which, in words).
    Superseded,
}

/// A mistake, how much of the difference it explains and how well it fits.
#[derive(Clone, Debug, Serialize)]
pub struct Ranked {
    #[serde(rename = "name")]
    pub mistake: Mistake,
    /// Whether it is the cause, looks like it, or is overridden.
    pub verdict: Verdict,
    /// What overrides it, in words, when `verdict` is `superseded`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub superseded_by: Option<String>,
    /// The share of the whole difference, D(yours, reference), that this
    /// mistake takes away on top of those listed above it: (D before − D
    /// after) / D(yours, reference), D the block difference over the whole
    /// image, "before" the closest the mistakes above came. Never negative,
    /// and the shares add up to at most 1: their sum is how much of the
    /// difference the listed mistakes explain together.
    pub explains: f64,
    /// The same over the blocks the mistake changes, starting from the
    /// render with the mistakes listed above it: 1 when there it gives the
    /// student's image.
    pub fits: f64,
    /// A pixel where the mistake shows: the student's pixel differs from the
    /// reference there and the mistaken render comes closest to it.
    pub pixel: Option<[u32; 2]>,
    /// For `gamma`, the exponent that fits the student's bytes best (2.2,
    /// 2.0, ...), to one decimal; absent for every other mistake.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exponent: Option<f64>,
}

/// The mistakes that explain the difference between `yours` and the
/// scene's reference, most first. Each next one is, among the mistakes that
/// fit at least `MIN_FIT` on top of those above it, the one that explains
/// most; one that takes away less than `MIN_SHARE` on top of them is passed
/// over. Every render comes from `shared`.
pub(crate) fn rank(shared: &SceneRenders, yours: &RgbImage) -> Vec<Ranked> {
    let reference = &shared.reference().image;
    let yours_blocks = block_sums(yours);
    let reference_blocks = block_sums(reference);
    if yours_blocks == reference_blocks && yours == reference {
        return Vec::new();
    }
    let render_with = |mistakes: Mistakes| block_sums(&shared.mistaken(mistakes));
    // Each mistake alone, with the blocks it changes; one that changes
    // nothing in this scene drops out. (Dropping those that fit poorly
    // alone would save renders but lose a small mistake hidden under a
    // large one, as phong-not-blinn's highlights under opaque shadows.)
    let mut candidates: Vec<Candidate> = candidates(shared.scene())
        .filter_map(|mistake| {
            let image = shared.mistaken(Mistakes::NONE.with(mistake));
            let blocks = block_sums(&image);
            let changed: Vec<bool> = blocks
                .iter()
                .zip(&reference_blocks)
                .map(|(a, b)| a != b)
                .collect();
            changed.contains(&true).then(|| Candidate {
                mistake,
                explains: explains(&yours_blocks, &reference_blocks, &blocks, None),
                pixel: showing_pixel(yours, reference, &image),
                changed,
                blocks,
            })
        })
        .collect();
    let mut ranked: Vec<Ranked> = Vec::new();
    let mut chosen = Mistakes::NONE;
    let mut base = reference_blocks.clone();
    let whole = gap(&yours_blocks, &reference_blocks, None);
    let mut closest = whole;
    while ranked.len() < MAX_LISTED {
        // How each remaining mistake fits on top of the chosen ones.
        let fits: Vec<(f64, Vec<[u32; 3]>)> = candidates
            .iter()
            .map(|c| {
                let blocks = if chosen.is_empty() {
                    c.blocks.clone()
                } else if !worth_a_render(&yours_blocks, &base, &reference_blocks, c) {
                    return (0.0, Vec::new());
                } else {
                    render_with(chosen.with(c.mistake))
                };
                (
                    explains(&yours_blocks, &base, &blocks, Some(&c.changed)),
                    blocks,
                )
            })
            .collect();
        // On a tie the first in the catalogue's order wins: two mistakes
        // that render the same image here (shadow-acne and no-epsilon where
        // no secondary ray meets its own surface) are named by the narrower,
        // listed first in MODEL §8.
        let best = (0..candidates.len())
            .filter(|&i| fits[i].0 >= MIN_FIT)
            .max_by(|&a, &b| {
                (candidates[a].explains.total_cmp(&candidates[b].explains)).then(b.cmp(&a))
            });
        let Some(best) = best else { break };
        let (fit, blocks) = fits.into_iter().nth(best).expect("in range");
        let c = candidates.remove(best);
        let after = gap(&yours_blocks, &blocks, None);
        let share = share_taken(whole, closest, after);
        if share < MIN_SHARE {
            continue;
        }
        ranked.push(Ranked {
            mistake: c.mistake,
            verdict: Verdict::LooksLike,
            superseded_by: None,
            explains: share,
            fits: fit,
            pixel: c.pixel,
            exponent: (c.mistake == Mistake::Gamma)
                .then(|| gamma_exponent(yours, reference))
                .flatten(),
        });
        chosen = chosen.with(c.mistake);
        closest = closest.min(after);
        base = blocks;
    }
    // The match rule: the listed mistakes are the cause only when their
    // render together reproduces the student's image.
    if !ranked.is_empty() && super::metrics::reproduces(yours, &shared.mistaken(chosen)) {
        for r in &mut ranked {
            r.verdict = Verdict::Is;
        }
    } else {
        ranked.retain(|r| r.fits >= LISTED_FIT);
    }
    ranked
}

/// The gamma exponent γ that turns the reference's bytes into the
/// student's, yours = 255 (ref / 255)^(1/γ): the median over every channel
/// of every pixel where both are away from black and white (where the
/// curve is flat and rounding rules), to one decimal. None when no channel
/// tells.
fn gamma_exponent(yours: &RgbImage, reference: &RgbImage) -> Option<f64> {
    let mut found: Vec<f64> = yours
        .pixels()
        .zip(reference.pixels())
        .flat_map(|(y, r)| y.0.into_iter().zip(r.0))
        .filter(|&(y, r)| (16..=239).contains(&r) && (16..=250).contains(&y) && y > r)
        .map(|(y, r)| (f64::from(r) / 255.0).ln() / (f64::from(y) / 255.0).ln())
        .collect();
    if found.is_empty() {
        return None;
    }
    let middle = found.len() / 2;
    let (_, median, _) = found.select_nth_unstable_by(middle, f64::total_cmp);
    Some((*median * 10.0).round() / 10.0)
}

/// The mistakes the ranking tries alone first: those that may change the
/// scene's image.
fn candidates(scene: &Scene) -> impl Iterator<Item = Mistake> + '_ {
    Mistake::ALL
        .into_iter()
        .filter(|&mistake| may_change(scene, &scene.settings, mistake))
}

/// Renders, in parallel, each mistake the ranking tries alone: what every
/// ranking of this scene renders first.
#[cfg(feature = "flip")]
pub(crate) fn prepare(shared: &SceneRenders) {
    use rayon::prelude::*;
    let tried: Vec<Mistake> = candidates(shared.scene()).collect();
    tried.into_par_iter().for_each(|mistake| {
        shared.mistaken(Mistakes::NONE.with(mistake));
    });
}

/// Whether `mistake` can change this scene's image at all: false when the
/// scene's profile does not offer it (`Profile::offers`: cse167 has no
/// refraction, MODEL §11), so that compare never names it, or when the
/// scene lacks what it acts on (no transparent material for eta-inverted,
/// no distance attenuation for no-light-attenuation, ...), which saves its
/// render.
fn may_change(scene: &Scene, settings: &Settings, mistake: Mistake) -> bool {
    if !settings.profile.offers(mistake) {
        return false;
    }
    let any = |f: fn(&Material) -> bool| scene.materials.iter().any(f);
    let switches = settings.switches;
    match mistake.acts_on() {
        ActsOn::ShadowRays => switches.shadows,
        ActsOn::TransparentShadows => switches.shadows && any(|m| m.kt > 0.0),
        ActsOn::Refraction => switches.transmission && any(|m| m.kt > 0.0),
        ActsOn::LightAttenuation => {
            let none = [1.0, 0.0, 0.0];
            settings.light_attenuation != none
                || (scene.lights.iter()).any(|l| l.attenuation.is_some_and(|a| a != none))
        }
        ActsOn::Ambient => {
            let own = any(|m| m.ambient.is_some_and(|a| a != Color::ZERO));
            let lit = settings.ambient != Color::ZERO && any(|m| m.ambient.is_none() && m.ka > 0.0);
            switches.ambient && (own || lit)
        }
        ActsOn::Highlights => any(|m| m.ks > 0.0),
        ActsOn::SecondaryRays => settings.max_depth > 1 && any(|m| m.ks > 0.0 || m.kt > 0.0),
        ActsOn::Lights => !scene.lights.is_empty(),
        ActsOn::ShadowOrSecondaryRays => {
            switches.shadows || (settings.max_depth > 1 && any(|m| m.ks > 0.0 || m.kt > 0.0))
        }
        ActsOn::AnyScene => true,
    }
}

/// Whether rendering `c` on top of the chosen mistakes can fit: where `c`
/// changes the image, the student's image must still differ from the
/// chosen mistakes' render by a thirtieth of what `c` itself changes there. A
/// mistake the student made passes (there the difference is about its own
/// change); one whose blocks the chosen mistakes already explain, or whose
/// change dwarfs what is left (gamma's, everywhere), is not rendered.
fn worth_a_render(
    yours: &[[u32; 3]],
    base: &[[u32; 3]],
    reference: &[[u32; 3]],
    c: &Candidate,
) -> bool {
    let only = Some(c.changed.as_slice());
    30 * gap(yours, base, only) >= gap(&c.blocks, reference, only)
}

/// The summed channel difference of two block lists over the blocks in
/// `only` (all when `None`).
fn gap(a: &[[u32; 3]], b: &[[u32; 3]], only: Option<&[bool]>) -> u64 {
    (0..a.len())
        .filter(|&i| only.is_none_or(|o| o[i]))
        .map(|i| {
            (0..3)
                .map(|k| a[i][k].abs_diff(b[i][k]) as u64)
                .sum::<u64>()
        })
        .sum()
}

/// One mistake's render, as the ranking needs it.
struct Candidate {
    mistake: Mistake,
    /// Over the whole image, alone.
    explains: f64,
    pixel: Option<[u32; 2]>,
    /// Which blocks the mistake alone changes.
    changed: Vec<bool>,
    blocks: Vec<[u32; 3]>,
}

/// 1 - D(yours, variant) / D(yours, base) over the blocks in `only` (all
/// when `None`); 0 when yours and base agree there.
fn explains(
    yours: &[[u32; 3]],
    base: &[[u32; 3]],
    variant: &[[u32; 3]],
    only: Option<&[bool]>,
) -> f64 {
    let apart = gap(yours, base, only);
    if apart == 0 {
        return 0.0;
    }
    1.0 - gap(yours, variant, only) as f64 / apart as f64
}

/// The share of `whole` a mistake takes away when it brings the closest
/// difference so far, `before`, to `after`: 0 when it brings nothing closer,
/// so the shares of the listed mistakes add up to 1 − (the closest) / `whole`.
fn share_taken(whole: u64, before: u64, after: u64) -> f64 {
    if whole == 0 {
        return 0.0;
    }
    before.saturating_sub(after) as f64 / whole as f64
}

/// Each block's channel sums, row-major by block.
fn block_sums(image: &RgbImage) -> Vec<[u32; 3]> {
    let (width, height) = image.dimensions();
    let across = width.div_ceil(BLOCK);
    let mut sums = vec![[0u32; 3]; (across * height.div_ceil(BLOCK)) as usize];
    for (x, y, p) in image.enumerate_pixels() {
        let block = &mut sums[((y / BLOCK) * across + x / BLOCK) as usize];
        for (sum, &value) in block.iter_mut().zip(&p.0) {
            *sum += value as u32;
        }
    }
    sums
}

/// Where the variant comes closest to the student's image, among the pixels
/// that both the variant and the student's image change.
fn showing_pixel(yours: &RgbImage, reference: &RgbImage, variant: &RgbImage) -> Option<[u32; 2]> {
    let mut best: Option<(i32, u32, u32)> = None;
    for (x, y, p) in yours.enumerate_pixels() {
        let (r, v) = (reference.get_pixel(x, y).0, variant.get_pixel(x, y).0);
        let off = channel_gap(p.0, r);
        if off <= TOLERANCE_STEPS || channel_gap(v, r) <= TOLERANCE_STEPS {
            continue;
        }
        let gain = off as i32 - channel_gap(p.0, v) as i32;
        if best.is_none_or(|(g, _, _)| gain > g) {
            best = Some((gain, x, y));
        }
    }
    best.map(|(_, x, y)| [x, y])
}

#[cfg(test)]
mod tests {
    use super::*;
    use raystep_engine::render::render;
    use raystep_engine::trace::NoRecorder;

    #[test]
    fn block_sums_make_speckles_of_equal_density_agree() {
        // Two 8 x 8 images, each with 32 white pixels on black, in other
        // places: pixel by pixel they differ everywhere they are white, but
        // their one block holds 32 * 255 in each channel in both.
        let a = RgbImage::from_fn(8, 8, |x, y| {
            image::Rgb([if (x + y) % 2 == 0 { 255 } else { 0 }; 3])
        });
        let b = RgbImage::from_fn(8, 8, |x, y| {
            image::Rgb([if (x + y) % 2 == 1 { 255 } else { 0 }; 3])
        });
        assert_eq!(block_sums(&a), block_sums(&b));
        assert_eq!(block_sums(&a), [[32 * 255; 3]]);
        // So, against a black reference, b explains all of a's difference.
        let black = block_sums(&RgbImage::new(8, 8));
        assert_eq!(
            explains(&block_sums(&a), &black, &block_sums(&b), None),
            1.0
        );
    }

    #[test]
    fn a_mistake_is_judged_only_where_it_changes_the_image() {
        // Two blocks. Yours differs from the base by 100 in block 0 and by
        // 300 in block 1; the variant changes block 0 only, to yours. Over
        // the whole image it explains 100 / 400 = 0.25; where it changes
        // the image (block 0) it fits fully.
        let base = [[0, 0, 0], [0, 0, 0]];
        let yours = [[100, 0, 0], [300, 0, 0]];
        let variant = [[100, 0, 0], [0, 0, 0]];
        assert_eq!(explains(&yours, &base, &variant, None), 0.25);
        assert_eq!(explains(&yours, &base, &variant, Some(&[true, false])), 1.0);
        // Where yours and base agree, nothing is there to explain: 0.
        assert_eq!(explains(&base, &base, &variant, Some(&[true, false])), 0.0);
    }

    #[test]
    fn shares_are_what_each_mistake_takes_away_and_never_negative() {
        // Yours is 1000 apart from the reference. The first mistake brings
        // it to 300: 700 / 1000 = 0.7. The second, on top, to 100: 200 /
        // 1000 = 0.2. A third that makes it 400 (further than 100) takes
        // nothing: 0, not -0.3. Together 0.9 = 1 - 100 / 1000.
        assert_eq!(share_taken(1000, 1000, 300), 0.7);
        assert_eq!(share_taken(1000, 300, 100), 0.2);
        assert_eq!(share_taken(1000, 100, 400), 0.0);
        assert_eq!(share_taken(0, 0, 0), 0.0);
    }

    #[test]
    fn the_showing_pixel_is_where_the_variant_meets_the_student() {
        // Reference black; the student brightened pixels 1 and 2 to 200;
        // the variant brightens pixel 1 to 200 and pixel 2 to 50: it meets
        // the student at pixel 1 (gain 200) better than at 2 (gain 50).
        let reference = RgbImage::new(3, 1);
        let mut yours = reference.clone();
        yours.put_pixel(1, 0, image::Rgb([200; 3]));
        yours.put_pixel(2, 0, image::Rgb([200; 3]));
        let mut variant = reference.clone();
        variant.put_pixel(1, 0, image::Rgb([200; 3]));
        variant.put_pixel(2, 0, image::Rgb([50; 3]));
        assert_eq!(showing_pixel(&yours, &reference, &variant), Some([1, 0]));
    }

    #[test]
    fn the_gamma_exponent_is_read_back_from_the_bytes() {
        // Bytes 16 to 239 under γ = 2.0: 255 (r/255)^(1/2), rounded; e.g.
        // r = 64 gives 255 × 0.50099 = 127.75, byte 128, and
        // ln(64/255) / ln(128/255) = 2.0055. The median rounds to 2.0.
        let reference = RgbImage::from_fn(224, 1, |x, _| image::Rgb([16 + x as u8; 3]));
        let curve = |g: f64| {
            RgbImage::from_fn(224, 1, |x, _| {
                let c = f64::from(16 + x as u8) / 255.0;
                image::Rgb([(255.0 * c.powf(1.0 / g) + 0.5).floor() as u8; 3])
            })
        };
        assert_eq!(gamma_exponent(&curve(2.0), &reference), Some(2.0));
        assert_eq!(gamma_exponent(&curve(2.2), &reference), Some(2.2));
        assert_eq!(gamma_exponent(&curve(1.8), &reference), Some(1.8));
        assert_eq!(gamma_exponent(&reference, &reference), None);
    }

    #[test]
    fn a_mistake_is_rendered_only_where_the_scene_has_what_it_acts_on() {
        // A matte plane lit by one light, shadows switched off: no shadow
        // ray, no transparency, no highlight, no secondary ray (max_depth
        // 1), no ambient (I_a black), no attenuation. Only the mistakes of
        // the bytes, rows, primary rays and normals, and those of the
        // light's own terms, can change it.
        let scene = raystep_engine::scene::parse(
            std::path::Path::new("matte.toml"),
            "[camera]
            eye = [0, 0, 0]
            look_at = [0, 0, -1]
            [image]
            width = 16
            height = 16
            [settings]
            max_depth = 1
            ambient = [0, 0, 0]
            [materials.matte]
            color = [0.9, 0.5, 0.2]
            kd = 1
            [[light]]
            position = [0, 2, 0]
            [[object]]
            material = \"matte\"
            plane = { normal = [0, 0, 1], point = [0, 0, -3] }",
        )
        .unwrap();
        let mut settings = scene.settings;
        settings.switches.shadows = false;
        let possible: Vec<Mistake> = Mistake::ALL
            .into_iter()
            .filter(|&m| may_change(&scene, &settings, m))
            .collect();
        assert_eq!(
            possible,
            [
                Mistake::NoNormalFlip,
                Mistake::ByteWrap,
                Mistake::Gamma,
                Mistake::FlippedY,
                Mistake::PixelCorner,
                Mistake::LightNotNormalised,
                Mistake::TwoSidedDiffuse,
                Mistake::InverseSquare,
                Mistake::FovFullAngle,
            ]
        );
        // And each mistake skipped indeed changes nothing.
        let reference = render::<NoRecorder>(&scene, &settings, &|| {}).0;
        for mistake in Mistake::ALL.into_iter().filter(|m| !possible.contains(m)) {
            let mut mistaken = settings;
            mistaken.mistakes = Mistakes::NONE.with(mistake);
            let image = render::<NoRecorder>(&scene, &mistaken, &|| {}).0;
            assert!(image == reference, "{mistake} changed the image");
        }
    }

    #[test]
    fn under_cse167_only_offered_mistakes_are_tried() {
        // A glass ball (k_t = 0.5) casting a shadow on a matte floor, under
        // the cse167 profile: no transmitted ray is cast (MODEL §11), so
        // eta-inverted, tir-dropped and refraction-outward-normal change
        // nothing and are not offered; the shadow through the ball is still
        // S = k_t = 0.5, so opaque-shadows (S = 0) does change it.
        let scene = raystep_engine::scene::parse(
            std::path::Path::new("glass.toml"),
            "[camera]
            eye = [0, 1, 4]
            look_at = [0, 0, 0]
            [image]
            width = 24
            height = 24
            [settings]
            profile = \"cse167\"
            [materials.glass]
            kd = 0.2
            kt = 0.5
            ior = 1.5
            [materials.floor]
            [[light]]
            position = [0, 5, 0]
            [[object]]
            material = \"glass\"
            sphere = { center = [0, 0.5, 0], radius = 0.5 }
            [[object]]
            material = \"floor\"
            plane = { normal = [0, 1, 0], point = [0, 0, 0] }",
        )
        .unwrap();
        let settings = scene.settings;
        let tried: Vec<Mistake> = candidates(&scene).collect();
        for mistake in &tried {
            assert!(settings.profile.offers(*mistake), "{mistake} tried");
        }
        assert!(tried.contains(&Mistake::OpaqueShadows));
        let reference = render::<NoRecorder>(&scene, &settings, &|| {}).0;
        let under = |mistake: Mistake| {
            let mut mistaken = settings;
            mistaken.mistakes = Mistakes::NONE.with(mistake);
            render::<NoRecorder>(&scene, &mistaken, &|| {}).0
        };
        for mistake in Mistake::ALL
            .into_iter()
            .filter(|&m| !settings.profile.offers(m))
        {
            assert!(under(mistake) == reference, "{mistake} changed the image");
        }
        assert!(under(Mistake::OpaqueShadows) != reference);
    }
}
