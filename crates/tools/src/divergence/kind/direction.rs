//! The kinds only a direction can have, told from the hit the ray leaves:
//! mirrored, refracted with η and 1/η swapped or with the outward normal,
//! another field of view, another point of the image.

use glam::DVec3;

use super::{Kind, close, close_numbers, vec3};
use crate::divergence::moment::Field;
use crate::divergence::ours::OurRays;
use crate::raylog::Step;
use raystep_engine::record::{Node, num};
use raystep_engine::scene::Scene;

/// The kinds only a direction can have, from the hit the ray leaves.
pub(super) fn direction_kind(
    scene: &Scene,
    ours: &OurRays,
    ray: usize,
    field: Field,
    yours: DVec3,
    theirs: DVec3,
) -> Option<(Kind, String)> {
    let path = &ours.rays()[ray].path;
    if field == Field::Dir && path.steps.is_empty() {
        return field_of_view(scene, ours, yours);
    }
    let surface = if field == Field::Normal {
        ours.node(ray).hit.as_ref()
    } else {
        ours.source(ray)?.hit.as_ref()
    }?;
    // Refracted with −N is also ours mirrored in the surface's plane (both
    // differ from ours by 2√k N): the refraction's own mistake is the one
    // a student recognises, so it is tried first.
    if field == Field::Dir
        && path.steps.last() == Some(&Step::Transmitted)
        && let Some(found) = refraction_kind(ours.source(ray)?, yours)
    {
        return Some(found);
    }
    let n = surface.normal;
    let yours_unit = yours.normalize_or_zero();
    let in_plane = theirs - 2.0 * theirs.dot(n) * n;
    if close(yours_unit, in_plane.normalize_or_zero()) {
        return Some((
            Kind::Mirrored,
            format!(
                "yours is ours reflected in the surface's plane (N = {})",
                vec3(n)
            ),
        ));
    }
    if close(yours_unit, (-in_plane).normalize_or_zero()) {
        return Some((
            Kind::Mirrored,
            format!("yours is ours turned half a turn about N = {}", vec3(n)),
        ));
    }
    None
}

/// A transmitted direction refracted with η and 1/η swapped, or with N
/// not turned to face the ray.
fn refraction_kind(parent: &Node, yours: DVec3) -> Option<(Kind, String)> {
    let hit = parent.hit.as_ref()?;
    let d = parent.direction;
    let ior = hit.factors.ior;
    let eta = if hit.entering { 1.0 / ior } else { ior };
    let refract = |eta: f64, n: DVec3| {
        let cos_i = -d.dot(n);
        let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
        (k >= 0.0).then(|| eta * d + (eta * cos_i - k.sqrt()) * n)
    };
    let matches = |t: Option<DVec3>| {
        t.is_some_and(|t| close(yours.normalize_or_zero(), t.normalize_or_zero()))
    };
    let n = hit.normal;
    if matches(refract(1.0 / eta, n)) {
        return Some((
            Kind::EtaSwapped,
            format!(
                "yours is refracted with η = {}, ours with η = {} ({}, ior {}): η is n_i / n_t",
                num(1.0 / eta),
                num(eta),
                if hit.entering { "entering" } else { "leaving" },
                num(ior)
            ),
        ));
    }
    for (eta_used, words) in [(eta, "the same η"), (1.0 / eta, "η and 1/η swapped")] {
        if matches(refract(eta_used, -n)) {
            return Some((
                Kind::OutwardNormal,
                format!(
                    "yours is refracted with −N, the normal facing away from the ray \
                     (N_g when leaving), and {words}; MODEL §5 uses N facing the ray, N·d ≤ 0"
                ),
            ));
        }
    }
    None
}

/// A primary direction another field of view would give: yours crosses
/// the image plane at the same point scaled about its centre.
fn field_of_view(scene: &Scene, ours: &OurRays, yours: DVec3) -> Option<(Kind, String)> {
    let frame = scene.camera.frame();
    let ours_dir = ours.rays().first()?.dir?;
    let plane = |d: DVec3| {
        let along = d.dot(frame.forward);
        (along > 0.0).then(|| (d.dot(frame.right) / along, d.dot(frame.true_up) / along))
    };
    let ((yx, yy), (ox, oy)) = (plane(yours)?, plane(ours_dir)?);
    // The larger offset decides the ratio; the other must follow it.
    let ratio = if ox.abs() >= oy.abs() {
        yx / ox
    } else {
        yy / oy
    };
    let scale = ox.abs().max(oy.abs());
    let same = (yx - ratio * ox).abs() <= 1e-3 * scale && (yy - ratio * oy).abs() <= 1e-3 * scale;
    let fov = scene.camera.fov;
    if same && ratio.is_finite() && ratio > 0.0 && !close_numbers(ratio, 1.0) {
        let yours_fov = 2.0 * (ratio * (fov.to_radians() / 2.0).tan()).atan().to_degrees();
        return Some((
            Kind::FieldOfView,
            format!(
                "yours is the ray of a vertical field of view of {}° (ours {}°, edge to edge, \
                 MODEL §2): its offsets px and py on the image plane are {} × ours",
                num(yours_fov),
                num(fov),
                num(ratio)
            ),
        ));
    }
    // Where yours crosses the image plane, in pixel units (MODEL §2 read
    // backwards): ours crosses at the pixel's centre.
    let (w, h) = (scene.width as f64, scene.height as f64);
    let s = (fov.to_radians() / 2.0).tan();
    let image_x = (yx / (s * w / h) + 1.0) * w / 2.0;
    let image_y = (1.0 - yy / s) * h / 2.0;
    let (x, y) = ours.tree.pixel;
    Some((
        Kind::OtherPixel,
        format!(
            "yours crosses the image at ({}, {}) in pixel units; ours at ({}, {}), the centre of \
             pixel ({x}, {y})",
            num(image_x),
            num(image_y),
            x as f64 + 0.5,
            y as f64 + 0.5
        ),
    ))
}
