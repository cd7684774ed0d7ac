//! A student's work dropped on the page: a render compared with ours as
//! `raystep compare` compares it, and a ray log read as `compare --rays`
//! reads it, whose pixels the tree then marks ray by ray.

use std::io::Cursor;
use std::path::Path;

use anyhow::{Context, Result};
use image::RgbImage;
use serde_json::{Value, json};

use raystep_engine::printable::printable_text;
use raystep_engine::record::{NodeId, RayTree};
use raystep_engine::scene::Scene;
use raystep_tools::divergence::{
    self, LogComparison, OurRays, PixelReport, RayStatus, compare_log, compare_pixel, value_text,
};
use raystep_tools::raylog::{LoggedRay, RayPath, RaylogReader, Step, rays_with_nodes};

/// What the student gave: the last image's comparison and the last log.
#[derive(Default)]
pub(crate) struct StudentWork {
    error_map: Option<RgbImage>,
    image_matches: Option<bool>,
    log: Option<ReadLog>,
}

/// A ray log read against the scene: its logged pixels and their rays.
struct ReadLog {
    comparison: LogComparison,
}

impl StudentWork {
    /// The student's PNG `bytes` against the scene rendered at the image's
    /// size: the report `compare` prints, its verdict and mistakes.
    pub(crate) fn compare(
        &mut self,
        scene: &Scene,
        scene_path: &Path,
        name: &str,
        bytes: &[u8],
    ) -> Result<Value> {
        let student = raystep_tools::compare::student::read(Cursor::new(bytes), name)?;
        let (width, height) = student.image.dimensions();
        let scene_at_size = scene.clone().with_size(width, height)?;
        crate::page_size::check_page_size(width, height)?;
        let comparison = raystep_tools::compare::compare(&scene_at_size, student)?;
        let report =
            raystep_tools::compare::text(&comparison, name, &scene_path.display().to_string());
        let json = json!({
            "report": printable_text(&report),
            "matches": comparison.matches,
            "mistakes": comparison.mistakes.iter().map(|m| m.mistake.name()).collect::<Vec<_>>(),
            "error_map": comparison.error_map.is_some(),
            "width": width,
            "height": height,
        });
        self.image_matches = Some(comparison.matches);
        self.error_map = comparison.error_map;
        Ok(json)
    }

    /// The last comparison's FLIP error map as PNG.
    pub(crate) fn error_map_png(&self) -> Result<Vec<u8>> {
        let map = (self.error_map.as_ref()).context("no error map: compare an image first")?;
        let mut png = Vec::new();
        raystep_tools::output::write_png(map, &mut Cursor::new(&mut png))?;
        Ok(png)
    }

    /// The ray log `bytes` against the scene: the report `compare --rays`
    /// prints, and each logged pixel with its first divergence.
    pub(crate) fn read_log(
        &mut self,
        scene: &Scene,
        scene_path: &Path,
        name: &str,
        bytes: &[u8],
    ) -> Result<Value> {
        let reader = RaylogReader::new(name, Cursor::new(bytes), scene);
        let comparison = compare_log(scene, reader, Default::default())?;
        let report = divergence::text(
            &comparison,
            name,
            &scene_path.display().to_string(),
            self.image_matches,
        );
        let pixels: Vec<Value> = (comparison.pixels.iter())
            .map(|p| {
                // The debugger's words for a logged pixel (src/tui/app/ray_log.rs).
                let words = match &p.first_divergence {
                    None => "your rays match ours".to_string(),
                    Some(d) => format!("first differs at {} {}", d.path, d.field),
                };
                json!({
                    "pixel": p.pixel,
                    "matches": p.matches,
                    "words": printable_text(&words).into_owned(),
                })
            })
            .collect();
        let json = json!({
            "report": printable_text(&report),
            "pixels": pixels,
            "pixel_count": comparison.pixel_count,
        });
        self.log = Some(ReadLog { comparison });
        Ok(json)
    }

    /// The log's rays of `pixel`, when it was logged.
    pub(crate) fn log_for(&self, pixel: (u32, u32)) -> Option<LoggedPixel<'_>> {
        let log = self.log.as_ref()?;
        let logged = log.comparison.pixels.iter().find(|p| p.pixel == pixel)?;
        Some(LoggedPixel(&logged.yours, log))
    }
}

/// A logged pixel's rays, before they are set beside a recorded tree.
pub(crate) struct LoggedPixel<'a>(&'a [LoggedRay], &'a ReadLog);

impl LoggedPixel<'_> {
    /// Your rays against the tree traced under the page's toggles, as the
    /// debugger compares them.
    pub(crate) fn against(&self, scene: &Scene, tree: &RayTree) -> PixelLog {
        let ours = OurRays::of(tree.clone());
        let tolerance = self.1.comparison.tolerance;
        PixelLog(compare_pixel(scene, self.0.to_vec(), &ours, &tolerance))
    }
}

/// One pixel of the log beside our tree.
pub(crate) struct PixelLog(PixelReport);

impl PixelLog {
    /// The path of our ray on a row: the node's own ray, or its shadow
    /// ray to `light`.
    fn path_of(tree: &RayTree, node: NodeId, light: Option<usize>) -> Option<RayPath> {
        let rays = rays_with_nodes(tree);
        rays.into_iter()
            .find(|(ray, n)| {
                *n == node
                    && match light {
                        Some(l) => ray.path.steps.last() == Some(&Step::Shadow(l)),
                        None => !ray.path.is_shadow(),
                    }
            })
            .map(|(ray, _)| ray.path)
    }

    /// A row's mark: ✓ the same as yours, ≠ differs, − not in your log,
    /// and whether it holds the first divergence.
    pub(crate) fn mark(&self, tree: &RayTree, node: NodeId, light: Option<usize>) -> Value {
        let Some(path) = Self::path_of(tree, node, light) else {
            return Value::Null;
        };
        let status = (self.0.aligned.iter())
            .find(|a| a.path == path)
            .map(|a| a.status());
        let mark = match status {
            Some(RayStatus::Matches) => "✓",
            Some(RayStatus::Differs) => "≠",
            Some(RayStatus::OnlyOurs) | None => "−",
            Some(RayStatus::OnlyYours) => "+",
        };
        let first = (self.0.first_divergence.as_ref()).is_some_and(|d| d.path == path);
        json!({ "mark": mark, "path": path.to_string(), "first": first })
    }

    /// The rays only in your log, each with the rule that keeps ours from
    /// casting it.
    pub(crate) fn only_yours_lines(&self) -> Vec<String> {
        (self.0.only_yours.iter())
            .map(|ray| {
                printable_text(&format!("{} only in yours: {}", ray.path, ray.rule)).into_owned()
            })
            .collect()
    }

    /// Ray `node`'s logged numbers beside ours: field, yours, ours, agrees.
    pub(crate) fn beside_ours(&self, tree: &RayTree, node: NodeId) -> Value {
        let Some(path) = Self::path_of(tree, node, None) else {
            return Value::Null;
        };
        let Some(aligned) = self.0.aligned.iter().find(|a| a.path == path) else {
            return Value::Null;
        };
        let checks: Vec<Value> = (aligned.checks.iter())
            .map(|c| {
                json!([
                    c.field.to_string(),
                    value_text(Some(c.yours)),
                    value_text(c.ours),
                    c.agrees
                ])
            })
            .collect();
        json!({ "path": path.to_string(), "checks": checks })
    }
}
