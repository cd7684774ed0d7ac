//! One pixel as the page shows it: its ray tree's rows, its events for
//! stepping, a ray's working and terms, the `explain` story and the
//! diagram, all in the words the debugger and the command line use.

use anyhow::{Context, Result, bail};
use serde::Deserialize;
use serde_json::{Value, json};

use raystep_engine::printable::printable_text;
use raystep_engine::record::stepping::{self, Step};
use raystep_engine::record::{
    self, About, Children, Line, NodeId, RayTree, describe_event, explain, light_summary,
    path_factor, ray_summary, record_pixel, share_of_pixel,
};
use raystep_engine::scene::{Scene, Settings};
use raystep_model::math::{Color, to_rgb8};
use raystep_tools::diagram::svg::{self, Caption, crossing_figure};
use raystep_tools::diagram::{Diagram, DiagramPlane, Progress, Shadows};

use crate::reply::Reply;
use crate::student_work::{LoggedPixel, PixelLog};

/// A recorded pixel and the event the stepping is at.
pub(crate) struct PixelView {
    tree: RayTree,
    at: usize,
    /// The scene file's name and the options traced with, for the
    /// diagram's caption.
    caption: Caption,
    /// The student's rays of the pixel beside ours, when it was logged.
    log: Option<PixelLog>,
}

impl PixelView {
    /// Records pixel `(x, y)`, refusing one outside the image as `inspect`
    /// does.
    pub(crate) fn record(
        scene: &Scene,
        settings: &Settings,
        (x, y): (u32, u32),
        caption: Caption,
        logged: Option<LoggedPixel>,
    ) -> Result<PixelView> {
        let (width, height) = (scene.width, scene.height);
        if x >= width || y >= height {
            bail!(
                "pixel ({x}, {y}) is outside the {width}x{height} image: x must be below {width} and y below {height}"
            );
        }
        let tree = record_pixel(scene, settings, x, y);
        let log = logged.map(|l| l.against(scene, &tree));
        Ok(PixelView {
            tree,
            at: 0,
            caption,
            log,
        })
    }

    /// Everything the page shows of the pixel at once.
    pub(crate) fn json(&self, scene: &Scene) -> Value {
        let tree = &self.tree;
        let events: Vec<Value> = (tree.events.iter())
            .map(|event| {
                let (text, color) = describe_event(tree, scene, event);
                json!({
                    "node": event.node,
                    "indent": tree.nodes[event.node].depth.saturating_sub(1),
                    "text": printable_text(&text),
                    "rgb8": color.map(to_rgb8),
                })
            })
            .collect();
        let (x, y) = tree.pixel;
        let [r, g, b] = tree.rgb8();
        let title = format!(
            "Pixel ({x}, {y}): colour {} = rgb8 ({r}, {g}, {b}), {}",
            record::color(tree.color()),
            record::count(tree.nodes.len() as u64, "ray", "rays")
        );
        json!({
            "pixel": tree.pixel,
            "title": title,
            "rgb8": tree.rgb8(),
            "color": record::color(tree.color()),
            "rays": tree.nodes.len(),
            "explain": printable_text(&explain(tree)),
            "rows": self.rows(),
            "events": events,
            "at": self.at,
            "only_yours": self.log.as_ref().map(PixelLog::only_yours_lines),
        })
    }

    /// The tree's rows, depth first: a ray, the lights it asked, then its
    /// child rays; each with its colour and its share of the pixel, and
    /// with a ray log, how it compares with the student's ray.
    fn rows(&self) -> Vec<Value> {
        let (tree, log) = (&self.tree, self.log.as_ref());
        let mut rows = Vec::new();
        let mut stack = vec![(0 as NodeId, 0usize)];
        while let Some((id, indent)) = stack.pop() {
            let node = &tree.nodes[id];
            let mark = |light: Option<usize>| log.map(|l| l.mark(tree, id, light));
            rows.push(json!({
                "kind": "ray",
                "node": id,
                "indent": indent,
                "text": printable_text(&format!("r{id} {}", ray_summary(node))),
                "rgb8": to_rgb8(node.color),
                "share": share_of_pixel(tree, node.color * path_factor(tree, id)).trim(),
                "log": mark(None),
            }));
            for (index, light) in node.lights.iter().enumerate() {
                let color: Color = light.diffuse + light.specular;
                rows.push(json!({
                    "kind": "light",
                    "node": id,
                    "light": light.light_index,
                    "index": index,
                    "indent": indent + 1,
                    "text": printable_text(&format!("☼ {}", light_summary(light))),
                    "rgb8": to_rgb8(color),
                    "share": share_of_pixel(tree, color * path_factor(tree, id)).trim(),
                    "log": mark(Some(light.light_index)),
                }));
            }
            let children: Vec<NodeId> = tree.children(id).collect();
            stack.extend(children.into_iter().rev().map(|c| (c, indent + 1)));
        }
        rows
    }

    /// The calls about the pixel picked: a ray's lines, a step, a jump to
    /// an event, the diagram.
    pub(crate) fn call(&mut self, op: &str, args: &str, scene: &Scene) -> Result<Reply> {
        let context = || format!("the arguments of {op:?}");
        match op {
            "ray" => {
                #[derive(Deserialize)]
                #[serde(deny_unknown_fields)]
                struct Ray {
                    id: NodeId,
                }
                let Ray { id } = serde_json::from_str(args).with_context(context)?;
                Ok(Reply::Json(self.ray_lines(id)?))
            }
            "step" => {
                #[derive(Deserialize)]
                #[serde(deny_unknown_fields)]
                struct How {
                    how: String,
                }
                let How { how } = serde_json::from_str(args).with_context(context)?;
                let step = match how.as_str() {
                    "next" => Step::Next,
                    "previous" => Step::Previous,
                    "into" => Step::Into,
                    "over" => Step::Over,
                    "out" => Step::Out,
                    "start" => Step::Start,
                    "end" => Step::End,
                    _ => bail!(
                        "no step is named {how:?}: next, previous, into, over, out, start or end"
                    ),
                };
                self.at = stepping::step(&self.tree, self.at, step);
                Ok(Reply::Json(self.position()))
            }
            "goto" => {
                #[derive(Deserialize)]
                #[serde(deny_unknown_fields)]
                struct At {
                    at: usize,
                }
                let At { at } = serde_json::from_str(args).with_context(context)?;
                if at >= self.tree.events.len() {
                    bail!(
                        "event {at}: the pixel has {} events",
                        self.tree.events.len()
                    );
                }
                self.at = at;
                Ok(Reply::Json(self.position()))
            }
            "diagram" => Ok(Reply::Text(
                self.diagram(scene, serde_json::from_str(args)?)?,
            )),
            _ => unreachable!("Page::call passes only the pixel's calls"),
        }
    }

    /// Where the stepping is: the event, its ray and the light it is about.
    fn position(&self) -> Value {
        let event = &self.tree.events[self.at];
        json!({ "at": self.at, "node": event.node, "light": event.kind.light() })
    }

    /// Ray `id`'s lines as the debugger's details pane lists them: a header,
    /// then what `inspect` prints, the current event's lines marked.
    fn ray_lines(&self, id: NodeId) -> Result<Value> {
        let tree = &self.tree;
        let node = tree.nodes.get(id).context("no such ray")?;
        let header = format!("r{id}: {}", record::ray_header(node));
        let mut lines = vec![Line::text(None, header)];
        lines.extend(record::node_lines(tree, id, Children::Listed));
        let marked: Option<About> = (tree.events.get(self.at))
            .filter(|e| e.node == id)
            .map(|e| About::of(tree, e));
        let lines: Vec<Value> = lines
            .iter()
            .map(|line| {
                // One row as wide as the line: the page wraps it itself.
                let words: Vec<Value> = (line.wrap(usize::MAX / 2, 0).into_iter())
                    .flat_map(|row| row.words)
                    .map(|w| json!([printable_text(&w.text), w.color.map(to_rgb8)]))
                    .collect();
                let indent = line.wrap(usize::MAX / 2, 0).first().map_or(0, |r| r.indent);
                json!({
                    "indent": indent,
                    "words": words,
                    "marked": marked.is_some() && line.about == marked,
                })
            })
            .collect();
        Ok(json!({
            "id": id,
            "lines": lines,
            "yours": self.log.as_ref().map(|l| l.beside_ours(tree, id)),
        }))
    }

    /// The SVG of `raystep diagram` for the pixel, drawn as far as the
    /// stepping has come, or whole (`whole`, for the download).
    fn diagram(&self, scene: &Scene, args: DiagramArgs) -> Result<String> {
        let tree = &self.tree;
        let plane = match args.plane.as_str() {
            "top" => DiagramPlane::Top,
            "side" => DiagramPlane::Side,
            "ray" => DiagramPlane::Primary,
            "crossing" => {
                let subject = crossing_figure::subject(tree).with_context(|| {
                    format!(
                        "pixel ({}, {}): no ray of its tree hits a polygon or patch or passes one by, \
                         so there is no crossing test to draw (try the top plane)",
                        tree.pixel.0, tree.pixel.1
                    )
                })?;
                return Ok(crossing_figure::svg(tree.pixel, &subject, &self.caption));
            }
            other => bail!("no plane is named {other:?}: top, side, ray or crossing"),
        };
        let shadows = match args.shadows.as_deref() {
            None | Some("all") => Shadows::All,
            Some("primary") => Shadows::Primary,
            Some("none") => Shadows::None,
            Some(other) => bail!("shadows {other:?}: all, primary or none"),
        };
        let progress = if args.whole {
            Progress::done(tree)
        } else {
            Progress::at(tree, self.at)
        };
        let mut caption = self.caption.clone();
        if shadows != Shadows::All {
            caption
                .options
                .push(format!("--shadows {}", args.shadows.unwrap_or_default()));
        }
        let diagram = Diagram::new(scene, tree, plane, progress).with_shadows(shadows);
        Ok(svg::slide(&diagram, args.zoom.unwrap_or(1.0), &caption))
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct DiagramArgs {
    /// top, side, ray or crossing, as `--plane` takes them.
    plane: String,
    shadows: Option<String>,
    zoom: Option<f64>,
    /// Every event drawn, as `raystep diagram` draws it.
    #[serde(default)]
    whole: bool,
}
