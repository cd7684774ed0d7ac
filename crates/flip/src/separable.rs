//! FLIP's filters, one dimension at a time: the contrast sensitivity
//! functions of the spatial filter (paper, section 4.1) and the Gaussian
//! with its first and second derivatives of the feature detection (section
//! 4.2), and the two passes that apply a 1D kernel along rows and along
//! columns, repeating the edge pixel beyond the image as the C++ does
//! (`Min(Max(0, x + ix), w - 1)`).
//!
//! The kernels are built as `image::setSpatialFilters` and
//! `image::setFeatureFilter` build them (CPP/image.h, and
//! separatedConvolutions.pdf in NVIDIA's repository for why a sum of
//! Gaussians separates). The passes sum each output pixel's taps in the
//! C++'s order, from the leftmost (topmost) tap, starting at zero; they
//! only walk the taps in the outer loop and the pixels of a row in the
//! inner one, so that the compiler vectorises across pixels while each
//! pixel's f32 sum rounds exactly as nv-flip's.

use crate::colour_spaces::Colour;

/// `FLIP::PI` (sharedflip.h), 3.14159265358979f: the same f32 as Rust's.
const PI: f32 = std::f32::consts::PI;

/// `GaussianConstants` (sharedflip.h; paper, section 4.1, table of the
/// contrast sensitivity functions): the weights a and the scales b of the
/// Gaussians in the frequency domain for the Y, Cx and Cz channels; Cz's
/// filter is the sum of two Gaussians, (a1, b1) and (a2, b2).
const A1: Colour = [1.0, 1.0, 34.1];
const B1: Colour = [0.0047, 0.0053, 0.04];
const A2: Colour = [0.0, 0.0, 13.5];
const B2: Colour = [1.0e-5, 1.0e-5, 0.025];

/// `FLIPConstants.gw`: the width, in degrees, of the edge detector
/// (paper, section 4.2, w = 0.082).
const GW: f32 = 0.082;

/// `Gaussian(x2, a, b)`: the spatial-domain Gaussian of a contrast
/// sensitivity function, at squared distance `x2` in degrees.
fn gaussian(x2: f32, a: f32, b: f32) -> f32 {
    let pi_sq = PI * PI;
    a * (PI / b).sqrt() * (-pi_sq * x2 / b).exp()
}

/// `GaussianSqrt(x2, a, b)`: one of the two equal 1D factors of a 2D
/// Gaussian of a sum (Cz's filter is separated as two such sums).
fn gaussian_sqrt(x2: f32, a: f32, b: f32) -> f32 {
    let pi_sq = PI * PI;
    (a * (PI / b).sqrt()).sqrt() * (-pi_sq * x2 / b).exp()
}

/// `calculateSpatialFilterRadius`: three standard deviations of the
/// widest Gaussian, in pixels (10 at 67 pixels per degree).
fn spatial_radius(pixels_per_degree: f32) -> usize {
    let pi_sq = PI * PI;
    let widest = B1[0].max(B1[1]).max(B1[2].max(B2[0])).max(B2[1].max(B2[2]));
    (3.0 * (widest / (2.0 * pi_sq)).sqrt() * pixels_per_degree).ceil() as usize
}

/// The spatial filter's 1D kernels: the achromatic and red-green channels
/// each have one, normalised to sum to one; the blue-yellow channel's sum
/// of two Gaussians gives two, filtered separately and added.
pub(crate) struct SpatialKernels {
    pub(crate) y: Vec<f32>,
    pub(crate) cx: Vec<f32>,
    pub(crate) cz1: Vec<f32>,
    pub(crate) cz2: Vec<f32>,
}

impl SpatialKernels {
    /// `image::setSpatialFilters`.
    pub(crate) fn new(pixels_per_degree: f32) -> Self {
        let radius = spatial_radius(pixels_per_degree);
        let delta_x = 1.0 / pixels_per_degree;
        let width = 2 * radius + 1;
        let mut kernels = Self {
            y: Vec::with_capacity(width),
            cx: Vec::with_capacity(width),
            cz1: Vec::with_capacity(width),
            cz2: Vec::with_capacity(width),
        };
        let (mut sum_y, mut sum_cx, mut sum_cz1, mut sum_cz2) = (0f32, 0f32, 0f32, 0f32);
        for x in 0..width {
            let ix = (x as i32 - radius as i32) as f32 * delta_x;
            let ix2 = ix * ix;
            let y = gaussian(ix2, A1[0], B1[0]);
            let cx = gaussian(ix2, A1[1], B1[1]);
            let cz1 = gaussian_sqrt(ix2, A1[2], B1[2]);
            let cz2 = gaussian_sqrt(ix2, A2[2], B2[2]);
            kernels.y.push(y);
            kernels.cx.push(cx);
            kernels.cz1.push(cz1);
            kernels.cz2.push(cz2);
            sum_y += y;
            sum_cx += cx;
            sum_cz1 += cz1;
            sum_cz2 += cz2;
        }
        // Weights times the reciprocal of their sum, as the C++ (not a
        // division: the last bit differs); Cz's pair by one common factor.
        let (norm_y, norm_cx) = (1.0 / sum_y, 1.0 / sum_cx);
        let norm_cz = 1.0 / (sum_cz1 * sum_cz1 + sum_cz2 * sum_cz2).sqrt();
        kernels.y.iter_mut().for_each(|w| *w *= norm_y);
        kernels.cx.iter_mut().for_each(|w| *w *= norm_cx);
        kernels.cz1.iter_mut().for_each(|w| *w *= norm_cz);
        kernels.cz2.iter_mut().for_each(|w| *w *= norm_cz);
        kernels
    }
}

/// The feature detection's 1D kernels: a Gaussian of standard deviation
/// w / 2 degrees, its first derivative and its second.
pub(crate) struct FeatureKernels {
    pub(crate) gaussian: Vec<f32>,
    pub(crate) first: Vec<f32>,
    pub(crate) second: Vec<f32>,
}

impl FeatureKernels {
    /// `image::setFeatureFilter`: radius ⌈3σ⌉ pixels (9 at 67 pixels per
    /// degree); the Gaussian sums to one, the derivatives' positive
    /// weights to one and their negative weights to minus one.
    pub(crate) fn new(pixels_per_degree: f32) -> Self {
        let std_dev = 0.5 * GW * pixels_per_degree;
        let radius = (3.0 * std_dev).ceil() as i32;
        let mut kernels = Self {
            gaussian: Vec::new(),
            first: Vec::new(),
            second: Vec::new(),
        };
        let (mut g_sum, mut dg_negative, mut dg_positive) = (0f32, 0f32, 0f32);
        let (mut ddg_negative, mut ddg_positive) = (0f32, 0f32);
        for xx in -radius..=radius {
            let x = xx as f32;
            // `Gaussian(x, sigma)`, without its normalisation.
            let g = (-(x * x) / (2.0 * std_dev * std_dev)).exp();
            g_sum += g;
            let dg = -x * g;
            if dg > 0.0 {
                dg_positive += dg;
            } else {
                dg_negative -= dg;
            }
            let ddg = (x * x / (std_dev * std_dev) - 1.0) * g;
            if ddg > 0.0 {
                ddg_positive += ddg;
            } else {
                ddg_negative -= ddg;
            }
            kernels.gaussian.push(g);
            kernels.first.push(dg);
            kernels.second.push(ddg);
        }
        kernels.gaussian.iter_mut().for_each(|w| *w /= g_sum);
        for w in &mut kernels.first {
            *w /= if *w > 0.0 { dg_positive } else { dg_negative };
        }
        for w in &mut kernels.second {
            *w /= if *w > 0.0 { ddg_positive } else { ddg_negative };
        }
        kernels
    }
}

/// A row of an image with `radius` copies of its edge pixels on either
/// side, reused from row to row.
pub(crate) struct PaddedRow {
    radius: usize,
    values: Vec<f32>,
}

impl PaddedRow {
    pub(crate) fn new(radius: usize) -> Self {
        Self {
            radius,
            values: Vec::new(),
        }
    }

    /// Holds `row` with its edge pixels repeated `radius` times outside.
    pub(crate) fn fill(&mut self, row: &[f32]) {
        let (first, last) = (row[0], row[row.len() - 1]);
        self.values.clear();
        self.values.extend(std::iter::repeat_n(first, self.radius));
        self.values.extend_from_slice(row);
        self.values.extend(std::iter::repeat_n(last, self.radius));
    }

    /// The held row filtered by `kernel` (of width 2 · radius + 1), into
    /// `out` (of the row's width).
    pub(crate) fn filter(&self, kernel: &[f32], out: &mut [f32]) {
        debug_assert_eq!(kernel.len(), 2 * self.radius + 1);
        let width = out.len();
        out.fill(0.0);
        for (k, &weight) in kernel.iter().enumerate() {
            for (sum, &value) in out.iter_mut().zip(&self.values[k..k + width]) {
                *sum += weight * value;
            }
        }
    }
}

/// Filters every row of `plane` (`width` wide) by `kernel`: the first,
/// horizontal pass.
pub(crate) fn rows(
    plane: &[f32],
    width: usize,
    kernel: &[f32],
    padded: &mut PaddedRow,
) -> Vec<f32> {
    let mut out = vec![0f32; plane.len()];
    for (row, out_row) in plane.chunks_exact(width).zip(out.chunks_exact_mut(width)) {
        padded.fill(row);
        padded.filter(kernel, out_row);
    }
    out
}

/// Row `y` of `plane` (`width` wide, `height` high) filtered along its
/// columns by `kernel`, into `out`: the second, vertical pass, one output
/// row at a time; rows beyond the image repeat its first or last.
pub(crate) fn column_row(
    plane: &[f32],
    (width, height): (usize, usize),
    y: usize,
    kernel: &[f32],
    out: &mut [f32],
) {
    let radius = kernel.len() / 2;
    out.fill(0.0);
    for (k, &weight) in kernel.iter().enumerate() {
        let source = (y + k).saturating_sub(radius).min(height - 1);
        let row = &plane[source * width..(source + 1) * width];
        for (sum, &value) in out.iter_mut().zip(row) {
            *sum += weight * value;
        }
    }
}
