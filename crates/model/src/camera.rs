//! The pinhole camera and its primary rays (MODEL §2).

mod rows;

use glam::DVec3;

use crate::math::Ray;
use crate::mistakes::{Mistake, Mistakes};

/// Where the eye is and where it looks. `fov` is the vertical field of view in
/// degrees, edge to edge of the image.
#[derive(Clone, Copy, Debug)]
pub struct Camera {
    pub eye: DVec3,
    pub look_at: DVec3,
    pub up: DVec3,
    pub fov: f64,
}

/// The camera's orthonormal frame for one image size, computed once per render,
/// and which primary ray each image pixel gets. A render takes a row's rays
/// at once (`accel::rows`).
#[derive(Clone, Copy, Debug)]
pub struct Viewport {
    pub(crate) eye: DVec3,
    pub(crate) forward: DVec3,
    pub(crate) right: DVec3,
    pub(crate) true_up: DVec3,
    /// s = tan(fov / 2), or tan(fov) under `fov-full-angle` (MODEL §8).
    pub(crate) half_height: f64,
    /// The camera's vertical field of view in degrees, whose tangent
    /// `fov-full-angle` takes.
    pub(crate) fov: f64,
    pub width: u32,
    pub(crate) height: u32,
    /// Where in its pixel a primary ray passes: 0.5 (the centre), or 0 (the
    /// top-left corner) under `pixel-corner` (MODEL §8).
    pub(crate) pixel_offset: f64,
    /// Image row y shows the row traced for height - 1 - y (`flipped-y`).
    pub(crate) flip_y: bool,
}

/// The camera's orthonormal frame: where it looks, its right and its true up
/// (`up` made perpendicular to `forward`).
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    pub forward: DVec3,
    pub right: DVec3,
    pub true_up: DVec3,
}

impl Camera {
    pub fn frame(&self) -> Frame {
        let forward = (self.look_at - self.eye).normalize();
        let right = forward.cross(self.up).normalize();
        let true_up = right.cross(forward);
        Frame {
            forward,
            right,
            true_up,
        }
    }

    pub fn viewport(&self, width: u32, height: u32) -> Viewport {
        let Frame {
            forward,
            right,
            true_up,
        } = self.frame();
        Viewport {
            eye: self.eye,
            forward,
            right,
            true_up,
            half_height: (self.fov.to_radians() / 2.0).tan(),
            fov: self.fov,
            width,
            height,
            pixel_offset: 0.5,
            flip_y: false,
        }
    }
}

impl Viewport {
    /// The viewport with the camera mistakes of `mistakes` (`pixel-corner`,
    /// `flipped-y`, `fov-full-angle`) in the mapping from image pixels to
    /// primary rays; the others do not concern it.
    pub fn with_mistakes(self, mistakes: Mistakes) -> Viewport {
        Viewport {
            half_height: if mistakes.contains(Mistake::FovFullAngle) {
                self.fov.to_radians().tan()
            } else {
                self.half_height
            },
            pixel_offset: if mistakes.contains(Mistake::PixelCorner) {
                0.0
            } else {
                0.5
            },
            flip_y: mistakes.contains(Mistake::FlippedY),
            ..self
        }
    }

    /// The row traced for image row y: y itself, or its mirror under `flipped-y`.
    pub fn traced_row(&self, y: u32) -> u32 {
        if self.flip_y { self.height - 1 - y } else { y }
    }

    /// Whether image rows are traced upside down (`flipped-y`).
    pub fn flips_rows(&self) -> bool {
        self.flip_y
    }

    /// s: tan(fov / 2), or tan(fov) under `fov-full-angle`.
    pub fn half_height(&self) -> f64 {
        self.half_height
    }

    /// Where in its pixel a primary ray passes: 0.5, the centre, or 0, the
    /// top-left corner under `pixel-corner`.
    pub fn pixel_offset(&self) -> f64 {
        self.pixel_offset
    }

    /// The camera's frame: forward, right, true up.
    pub fn frame(&self) -> Frame {
        Frame {
            forward: self.forward,
            right: self.right,
            true_up: self.true_up,
        }
    }

    /// (px, py), where the primary ray of image pixel (x, y) crosses the
    /// image plane one unit ahead of the eye, along right and true up:
    /// px = (2 (x + 0.5) / W - 1) s (W / H), py = (1 - 2 (y + 0.5) / H) s,
    /// y the traced row (MODEL §2, with the pixel mistakes of §8).
    #[inline]
    pub fn plane_offsets(&self, x: u32, y: u32) -> (f64, f64) {
        let (w, h) = (self.width as f64, self.height as f64);
        let s = self.half_height;
        let y = self.traced_row(y);
        let px = (2.0 * (x as f64 + self.pixel_offset) / w - 1.0) * s * (w / h);
        let py = (1.0 - 2.0 * (y as f64 + self.pixel_offset) / h) * s;
        (px, py)
    }

    /// The ray from the eye through the point (du, dv) pixels away, along
    /// the image's x and the traced rows' y, from where pixel (x, y)'s
    /// primary ray passes: what the scene shows a hair beside that ray
    /// (compare looks there for an edge through the pixel's centre).
    pub fn ray_beside(&self, x: u32, y: u32, (du, dv): (f64, f64)) -> Ray {
        let (w, h) = (self.width as f64, self.height as f64);
        let s = self.half_height;
        let y = self.traced_row(y);
        let px = (2.0 * (x as f64 + self.pixel_offset + du) / w - 1.0) * s * (w / h);
        let py = (1.0 - 2.0 * (y as f64 + self.pixel_offset + dv) / h) * s;
        let direction = (self.forward + px * self.right + py * self.true_up).normalize();
        Ray::new(self.eye, direction)
    }

    /// The mapping of `plane_offsets` read backwards: where a ray from the
    /// eye along `direction` crosses the image, in pixel units of the
    /// traced rows ((x + 0.5, y + 0.5) is the centre of pixel (x, y));
    /// `None` for a direction that does not go forward.
    pub fn image_point(&self, direction: DVec3) -> Option<(f64, f64)> {
        let along = direction.dot(self.forward);
        if along <= 0.0 {
            return None;
        }
        let (px, py) = (
            direction.dot(self.right) / along,
            direction.dot(self.true_up) / along,
        );
        let (w, h) = (self.width as f64, self.height as f64);
        let s = self.half_height;
        Some(((px / (s * w / h) + 1.0) * w / 2.0, (1.0 - py / s) * h / 2.0))
    }

    /// The primary ray of image pixel (x, y), through the centre of the
    /// pixel; x to the right and y downward, both from 0.
    pub fn primary_ray(&self, x: u32, y: u32) -> Ray {
        let (px, py) = self.plane_offsets(x, y);
        let direction = (self.forward + px * self.right + py * self.true_up).normalize();
        Ray::new(self.eye, direction)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_pixel_of_an_odd_image_looks_straight_ahead() {
        let camera = Camera {
            eye: DVec3::ZERO,
            look_at: DVec3::new(0.0, 0.0, -1.0),
            up: DVec3::Y,
            fov: 90.0,
        };
        let ray = camera.viewport(3, 3).primary_ray(1, 1);
        // px = (2 * 1.5 / 3 - 1) s = 0, py = 0: direction = forward.
        assert!((ray.direction - DVec3::new(0.0, 0.0, -1.0)).length() < 1e-15);
    }

    #[test]
    fn corner_pixel_follows_the_model_formula() {
        let camera = Camera {
            eye: DVec3::ZERO,
            look_at: DVec3::new(0.0, 0.0, -1.0),
            up: DVec3::Y,
            fov: 90.0,
        };
        // 4 x 2 image, fov 90: s = tan 45 = 1, aspect 2.
        // Pixel (0, 0): px = (2 * 0.5 / 4 - 1) * 1 * 2 = -1.5, py = (1 - 2 * 0.5 / 2) = 0.5.
        // forward (0,0,-1), right = f x up = (1,0,0), true up (0,1,0):
        // direction = normalize(-1.5, 0.5, -1) = (-1.5, 0.5, -1) / sqrt(3.5).
        let ray = camera.viewport(4, 2).primary_ray(0, 0);
        let expected = DVec3::new(-1.5, 0.5, -1.0) / 3.5f64.sqrt();
        assert!((ray.direction - expected).length() < 1e-15);
    }
}
