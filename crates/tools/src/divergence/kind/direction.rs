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
use raystep_engine::trace::refract;
use raystep_model::mistakes::Mistake;

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
        && let Some(found) = refraction_kind(ours, ours.source(ray)?, yours)
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

/// A transmitted direction refracted with η and 1/η swapped, or with the
/// other normal: ours refracted again by the tracer's own Snell's law
/// (`trace::refract`), from the η it recorded and the normal the rules in
/// force gave it (MODEL §5, §8).
fn refraction_kind(ours: &OurRays, parent: &Node, yours: DVec3) -> Option<(Kind, String)> {
    let hit = parent.hit.as_ref()?;
    let d = parent.direction;
    let ior = hit.factors.ior;
    let eta = parent.refraction?.eta;
    let refract = |eta: f64, n: DVec3| refract(d, n, eta).direction;
    let matches = |t: Option<DVec3>| {
        t.is_some_and(|t| close(yours.normalize_or_zero(), t.normalize_or_zero()))
    };
    let n = ours.rules().refraction_normal(&hit.surface_hit());
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
            let normals = if n == hit.normal {
                "yours is refracted with −N, the normal facing away from the ray \
                 (N_g when leaving)"
            } else {
                "yours is refracted with N facing the ray, ours with N_g, the outward \
                 normal (refraction-outward-normal, MODEL §8)"
            };
            return Some((
                Kind::OutwardNormal,
                format!("{normals}, and {words}; MODEL §5 uses N facing the ray, N·d ≤ 0"),
            ));
        }
    }
    None
}

/// A primary direction another field of view would give: yours crosses
/// the image plane at the same point scaled about its centre. Ours is the
/// camera's, with the pixel mistakes it was traced with (MODEL §8).
fn field_of_view(scene: &Scene, ours: &OurRays, yours: DVec3) -> Option<(Kind, String)> {
    let viewport = ours.viewport(scene);
    let frame = viewport.frame();
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
    let s = viewport.half_height();
    if same && ratio.is_finite() && ratio > 0.0 && !close_numbers(ratio, 1.0) {
        let yours_fov = 2.0 * (ratio * s).atan().to_degrees();
        let ours_fov = if ours.tree.mistakes.contains(Mistake::FovFullAngle) {
            format!(
                "ours {}° taken as the half angle under fov-full-angle (MODEL §8), so {}° edge \
                 to edge",
                num(fov),
                num(2.0 * s.atan().to_degrees())
            )
        } else {
            format!("ours {}°, edge to edge, MODEL §2", num(fov))
        };
        return Some((
            Kind::FieldOfView,
            format!(
                "yours is the ray of a vertical field of view of {}° ({ours_fov}): its offsets \
                 px and py on the image plane are {} × ours",
                num(yours_fov),
                num(ratio)
            ),
        ));
    }
    // Where yours crosses the image, in pixel units (the camera's mapping
    // read backwards); ours where the viewport sent it.
    let (image_x, image_y) = viewport.image_point(yours)?;
    let (x, y) = ours.tree.pixel;
    let row = viewport.traced_row(y);
    let offset = viewport.pixel_offset();
    let place = if offset == 0.0 {
        "the top-left corner (pixel-corner, MODEL §8)"
    } else {
        "the centre"
    };
    let pixel = if viewport.flips_rows() {
        format!("pixel ({x}, {row}), the row traced for image row {y} (flipped-y, MODEL §8)")
    } else {
        format!("pixel ({x}, {y})")
    };
    Some((
        Kind::OtherPixel,
        format!(
            "yours crosses the image at ({}, {}) in pixel units; ours at ({}, {}), {place} of \
             {pixel}",
            num(image_x),
            num(image_y),
            x as f64 + offset,
            row as f64 + offset
        ),
    ))
}
