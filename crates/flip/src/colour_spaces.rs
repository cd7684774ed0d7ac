//! FLIP's colour spaces and its colour metric: sRGB to linear RGB to CIE
//! XYZ to YCxCz (the opponent space the contrast sensitivity filters work
//! in) and back, then CIELab with the Hunt adjustment and the HyAB
//! distance (paper, section 4.1).
//!
//! Every function is NVIDIA's (CPP/color.h, `FLIP::color3`) with its
//! constants and its order of operations, so that f32 rounds where the C++
//! rounds and the errors come out as nv-flip's, bit for bit where the math
//! library agrees.

/// A pixel's three channels, in whatever space the function names.
pub(crate) type Colour = [f32; 3];

/// The D65 white point in XYZ, `DEFAULT_ILLUMINANT` (color.h), and its
/// inverse, `INV_DEFAULT_ILLUMINANT`, as the C++ spells them (not computed:
/// the last digits are theirs).
#[allow(clippy::excessive_precision)]
const ILLUMINANT: Colour = [0.950428545, 1.000000000, 1.088900371];
#[allow(clippy::excessive_precision)]
const INV_ILLUMINANT: Colour = [1.052156925, 1.000000000, 0.918357670];

/// `color3::sRGB2LinearRGB`: the sRGB transfer function, undone.
pub(crate) fn srgb_to_linear(channel: f32) -> f32 {
    if channel <= 0.04045 {
        channel / 12.92
    } else {
        ((channel + 0.055) / 1.055).powf(2.4)
    }
}

/// `color3::LinearRGB2XYZ`: linear sRGB (D65) to CIE XYZ, with the
/// fractions the C++ writes (from image-engineering.de's technote 958).
pub(crate) fn linear_rgb_to_xyz([r, g, b]: Colour) -> Colour {
    const A11: f32 = 10_135_552.0 / 24_577_794.0;
    const A12: f32 = 8_788_810.0 / 24_577_794.0;
    const A13: f32 = 4_435_075.0 / 24_577_794.0;
    const A21: f32 = 2_613_072.0 / 12_288_897.0;
    const A22: f32 = 8_788_810.0 / 12_288_897.0;
    const A23: f32 = 887_015.0 / 12_288_897.0;
    const A31: f32 = 1_425_312.0 / 73_733_382.0;
    const A32: f32 = 8_788_810.0 / 73_733_382.0;
    const A33: f32 = 70_074_185.0 / 73_733_382.0;
    [
        A11 * r + A12 * g + A13 * b,
        A21 * r + A22 * g + A23 * b,
        A31 * r + A32 * g + A33 * b,
    ]
}

/// `color3::XYZ2LinearRGB`: CIE XYZ to linear sRGB (D65), the C++'s
/// rounded inverse matrix.
#[allow(clippy::excessive_precision)]
fn xyz_to_linear_rgb([x, y, z]: Colour) -> Colour {
    const A11: f32 = 3.241003275;
    const A12: f32 = -1.537398934;
    const A13: f32 = -0.498615861;
    const A21: f32 = -0.969224334;
    const A22: f32 = 1.875930071;
    const A23: f32 = 0.041554224;
    const A31: f32 = 0.055639423;
    const A32: f32 = -0.204011202;
    const A33: f32 = 1.057148933;
    [
        A11 * x + A12 * y + A13 * z,
        A21 * x + A22 * y + A23 * z,
        A31 * x + A32 * y + A33 * z,
    ]
}

/// `color3::XYZ2YCxCz`: the linear opponent space of the paper's section
/// 4.1 (achromatic Y, red-green Cx, blue-yellow Cz), relative to D65.
pub(crate) fn xyz_to_ycxcz(xyz: Colour) -> Colour {
    let [x, y, z] = times(xyz, INV_ILLUMINANT);
    [116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)]
}

/// `color3::YCxCz2XYZ`: back from the opponent space, after filtering.
fn ycxcz_to_xyz([luma, cx, cz]: Colour) -> Colour {
    let y = (luma + 16.0) / 116.0;
    let cx = cx / 500.0;
    let cz = cz / 200.0;
    times([y + cx, y, y - cz], ILLUMINANT)
}

/// `color3::XYZ2CIELab` with the D65 white.
fn xyz_to_lab(xyz: Colour) -> Colour {
    let delta: f32 = 6.0 / 29.0;
    let delta_square = delta * delta;
    let delta_cube = delta * delta_square;
    let factor = 1.0 / (3.0 * delta_square);
    let term = 4.0 / 29.0;
    let f = |t: f32| {
        if t > delta_cube {
            t.powf(1.0 / 3.0)
        } else {
            factor * t + term
        }
    };
    let [x, y, z] = times(xyz, INV_ILLUMINANT).map(f);
    [116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)]
}

/// `color3::Hunt`: chroma scaled by lightness (paper, section 4.1: dark
/// colours look less saturated), `0.01 · L · chroma`.
fn hunt(lightness: f32, chroma: f32) -> f32 {
    0.01 * lightness * chroma
}

/// `color3::HyAB`: city-block distance in L plus Euclidean distance in
/// (a, b) (Abasi et al., the paper's section 4.1), which does better than
/// ΔE for large colour differences.
fn hyab(reference: Colour, test: Colour) -> f32 {
    let (da, db) = (reference[1] - test[1], reference[2] - test[2]);
    (reference[0] - test[0]).abs() + (da * da + db * db).sqrt()
}

/// Lab with the Hunt adjustment on both chroma channels.
fn hunt_lab(lab: Colour) -> Colour {
    [lab[0], hunt(lab[0], lab[1]), hunt(lab[0], lab[2])]
}

/// `FLIPConstants.gqc`: the exponent that compresses the colour distance
/// (paper, section 4.1, q_c).
const GQC: f32 = 0.7;
/// `FLIPConstants.gpc`: where, as a fraction of the largest distance, the
/// compressed distance stops growing fast (p_c).
const GPC: f32 = 0.4;
/// `FLIPConstants.gpt`: the error that distance maps to (p_t).
const GPT: f32 = 0.95;

/// `color3::computeMaxDistance`: the compressed HyAB distance between pure
/// green and pure blue, the two sRGB primaries furthest apart in
/// Hunt-adjusted Lab (c_max).
fn max_distance() -> f32 {
    let green = hunt_lab(xyz_to_lab(linear_rgb_to_xyz([0.0, 1.0, 0.0])));
    let blue = hunt_lab(xyz_to_lab(linear_rgb_to_xyz([0.0, 0.0, 1.0])));
    hyab(green, blue).powf(GQC)
}

/// The colour half of FLIP for one pixel, from its spatially filtered
/// reference and test colours in YCxCz: the end of
/// `image::computeColorDifference`.
pub(crate) struct ColourDifference {
    /// c_max.
    cmax: f32,
    /// p_c · c_max.
    pccmax: f32,
}

impl ColourDifference {
    pub(crate) fn new() -> Self {
        let cmax = max_distance();
        Self {
            cmax,
            pccmax: GPC * cmax,
        }
    }

    /// The colour error in [0, 1]: both filtered colours clamped to the
    /// sRGB gamut in linear RGB, to Hunt-adjusted Lab, their HyAB distance
    /// compressed by q_c, then remapped so that [0, p_c · c_max) takes
    /// [0, p_t) and the rest up to c_max the last 1 − p_t (paper, eq. 2).
    pub(crate) fn error(&self, reference: Colour, test: Colour) -> f32 {
        let to_lab = |ycxcz: Colour| {
            let rgb = xyz_to_linear_rgb(ycxcz_to_xyz(ycxcz)).map(clamp_unit);
            hunt_lab(xyz_to_lab(linear_rgb_to_xyz(rgb)))
        };
        let distance = hyab(to_lab(reference), to_lab(test)).powf(GQC);
        if distance < self.pccmax {
            distance * (GPT / self.pccmax)
        } else {
            GPT + ((distance - self.pccmax) / (self.cmax - self.pccmax)) * (1.0 - GPT)
        }
    }
}

/// `color3::clamp` to [0, 1] with the C++'s `Min(Max(v, 0), 1)` macros
/// (a NaN becomes 0, as there).
fn clamp_unit(value: f32) -> f32 {
    let low = if value > 0.0 { value } else { 0.0 };
    if low > 1.0 { 1.0 } else { low }
}

/// Channel by channel product (`color3::operator*`).
fn times(a: Colour, b: Colour) -> Colour {
    [a[0] * b[0], a[1] * b[1], a[2] * b[2]]
}
