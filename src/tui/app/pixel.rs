//! The pixel being traced: where the cursor is, the pixel's recording, the
//! current event, the tree's folded rows, the details' scroll, the object
//! the `x` breakpoint stops at, and what the last toggle changed in it.
//! Stepping and the tree's keys change only this.

use std::cell::{Cell, OnceCell, RefCell};
use std::collections::BTreeSet;
use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::tui::action::Action;
use crate::tui::find_job::Found;
use crate::tui::view::canvas_lines::{CanvasLines, View};
use crate::tui::view::steps;
use crate::tui::view::tree::{self, Row, RowKind};
use raystep_engine::record::stepping::{self, Breakpoint};
use raystep_engine::record::{NodeId, RayTree, record_pixel};
use raystep_engine::scene::{Scene, Settings};
use raystep_tools::diagram::{Diagram, DiagramPlane, Progress};

pub struct TracedPixel {
    /// The selected pixel, in the scene image's coordinates.
    cursor: (u32, u32),
    tree: RayTree,
    /// The current event of `tree.events`.
    current: usize,
    collapsed: BTreeSet<NodeId>,
    /// Manual scroll of the details; `None` follows the current event.
    details_scroll: Option<u16>,
    /// What-if: how the pixel's tree changed with the last toggle (or
    /// reload), in `record::diff`'s words; cleared when another pixel is picked.
    what_if: Option<String>,
    /// The object the `x` breakpoint stops at, once chosen.
    break_object: Option<usize>,
    /// How long the last pick took.
    pick_time: Duration,
    /// The tree's diagram on each plane (top, side, the primary ray's),
    /// assembled once per tree when first drawn, at the end of the
    /// step-through: the pane strokes it at the current event. A frame
    /// then costs no assembly (half a second for 65,536 rays).
    diagrams: [OnceCell<Diagram>; 3],
    /// How many diagrams have been assembled, for the tests.
    assembled: Cell<usize>,
    /// Each diagram's segments grouped by the dots they paint, for the
    /// view last drawn (`view::canvas_lines`): made again only when the
    /// window or the pane's size changes, not at each step.
    canvas_lines: [RefCell<Option<Arc<CanvasLines>>>; 3],
    /// The tree pane's rows, made once per tree and folding (the layout,
    /// the pane and the row keys all ask for them every frame).
    rows: OnceCell<Vec<Row>>,
}

/// Where a plane's diagram is kept.
fn slot(plane: DiagramPlane) -> usize {
    match plane {
        DiagramPlane::Top => 0,
        DiagramPlane::Side => 1,
        DiagramPlane::Primary => 2,
    }
}

impl TracedPixel {
    /// `scene`'s pixel `cursor`, recorded with `settings`, at its first event.
    pub(super) fn new(scene: &Scene, settings: &Settings, cursor: (u32, u32)) -> TracedPixel {
        let started = Instant::now();
        let tree = record_pixel(scene, settings, cursor.0, cursor.1);
        TracedPixel {
            cursor,
            tree,
            current: 0,
            collapsed: BTreeSet::new(),
            details_scroll: None,
            what_if: None,
            break_object: None,
            pick_time: started.elapsed(),
            diagrams: Default::default(),
            assembled: Cell::new(0),
            canvas_lines: Default::default(),
            rows: OnceCell::new(),
        }
    }

    /// Stepping, breakpoints, the tree's rows and the details' scroll; the
    /// status line's message, when the action has one.
    pub(super) fn update(&mut self, action: Action, scene: &Scene) -> Option<String> {
        match action {
            Action::Step(step) => self.set_current(stepping::step(&self.tree, self.current, step)),
            Action::RunTo(breakpoint) => return self.run_to(breakpoint, scene),
            Action::RunToObject => return self.run_to_object(scene),
            Action::CycleBreakObject => return self.cycle_break_object(scene),
            Action::SelectRow(delta) => self.select_row(delta),
            Action::ToggleCollapse => {
                let node = self.selected_node();
                if !self.collapsed.remove(&node) {
                    self.collapsed.insert(node);
                }
                self.rows = OnceCell::new();
            }
            Action::ScrollDetails(delta) => {
                let from = self.details_scroll.unwrap_or(0) as i32;
                self.details_scroll = Some((from + delta).max(0) as u16);
            }
            _ => {}
        }
        None
    }

    /// The selected pixel, in the scene image's coordinates.
    pub fn cursor(&self) -> (u32, u32) {
        self.cursor
    }

    /// The selected pixel's recording.
    pub fn tree(&self) -> &RayTree {
        &self.tree
    }

    /// The current event, an index into `tree().events`.
    pub fn current(&self) -> usize {
        self.current
    }

    /// The rays whose rows the tree pane folds away.
    pub fn collapsed(&self) -> &BTreeSet<NodeId> {
        &self.collapsed
    }

    /// The tree pane's visible rows (`view::tree::rows`), made once per
    /// tree and folding.
    pub fn rows(&self) -> &[Row] {
        self.rows
            .get_or_init(|| tree::rows(&self.tree, &self.collapsed))
    }

    /// Manual scroll of the details; `None` follows the current event.
    pub(crate) fn details_scroll(&self) -> Option<u16> {
        self.details_scroll
    }

    /// How the pixel changed with the last toggle, when it did.
    pub fn what_if(&self) -> Option<&str> {
        self.what_if.as_deref()
    }

    /// The object the `x` breakpoint stops at, once chosen.
    pub fn break_object(&self) -> Option<usize> {
        self.break_object
    }

    /// How long the last pick took.
    pub fn pick_time(&self) -> Duration {
        self.pick_time
    }

    /// The tree's diagram on `plane` (recorded in `scene`), with every ray
    /// reached: assembled the first time it is asked for, then kept until
    /// the tree changes.
    pub(crate) fn diagram(&self, scene: &Scene, plane: DiagramPlane) -> &Diagram {
        self.diagrams[slot(plane)].get_or_init(|| {
            self.assembled.set(self.assembled.get() + 1);
            Diagram::new(scene, &self.tree, plane, Progress::done(&self.tree))
        })
    }

    /// The diagram on `plane`'s segments grouped for `view`: kept from the
    /// last frame when it drew the same view, else grouped again.
    pub(crate) fn canvas_lines(
        &self,
        scene: &Scene,
        plane: DiagramPlane,
        view: View,
    ) -> Arc<CanvasLines> {
        let mut kept = self.canvas_lines[slot(plane)].borrow_mut();
        match &*kept {
            Some(lines) if lines.view() == view => Arc::clone(lines),
            _ => {
                let segments = (self.diagram(scene, plane).segments.iter()).map(|s| (s.from, s.to));
                let lines = Arc::new(CanvasLines::new(segments, view));
                *kept = Some(Arc::clone(&lines));
                lines
            }
        }
    }

    /// How many diagrams have been assembled since the app opened: one per
    /// tree and plane drawn, however many frames show it.
    pub fn diagrams_assembled(&self) -> usize {
        self.assembled.get()
    }

    /// Takes a new recording: its diagrams are assembled when drawn.
    fn set_tree(&mut self, tree: RayTree) {
        self.tree = tree;
        self.diagrams = Default::default();
        self.canvas_lines = Default::default();
        self.rows = OnceCell::new();
    }

    /// The node the tree and details show: the current event's ray.
    pub(crate) fn selected_node(&self) -> NodeId {
        self.tree.events.get(self.current).map_or(0, |e| e.node)
    }

    /// The object breakpoint: the chosen one, else the selected ray's object.
    pub(crate) fn break_target(&self) -> Option<usize> {
        self.break_object.or_else(|| {
            self.tree.nodes[self.selected_node()]
                .hit
                .as_ref()
                .map(|h| h.object_index)
        })
    }

    /// The breakpoint's target chosen as the breakpoint object (`x`, `f x`).
    pub(super) fn choose_break_target(&mut self) -> Option<usize> {
        let object = self.break_target()?;
        self.break_object = Some(object);
        Some(object)
    }

    /// Re-records the pixel in `scene` with `settings`, keeping the step.
    pub(super) fn retrace(&mut self, scene: &Scene, settings: &Settings) {
        self.cursor = (
            self.cursor.0.min(scene.width - 1),
            self.cursor.1.min(scene.height - 1),
        );
        let started = Instant::now();
        self.set_tree(record_pixel(scene, settings, self.cursor.0, self.cursor.1));
        self.pick_time = started.elapsed();
        self.current = self.current.min(self.tree.events.len().saturating_sub(1));
        self.collapsed.clear();
        self.rows = OnceCell::new();
        self.details_scroll = None;
    }

    /// Selects another pixel and records it, from its first event.
    pub(super) fn pick(&mut self, (x, y): (u32, u32), scene: &Scene, settings: &Settings) {
        self.cursor = (x, y);
        self.current = 0;
        self.what_if = None;
        self.retrace(scene, settings);
    }

    /// Records the pixel with new settings; the trees before and after give
    /// the what-if, and the details open at the top, on what changed.
    pub(super) fn retrace_with(&mut self, scene: &Scene, settings: &Settings) {
        let before = self.tree.clone();
        self.retrace(scene, settings);
        self.what_if = (before.pixel == self.tree.pixel)
            .then(|| raystep_engine::record::diff(&before, &self.tree));
        self.details_scroll = self.what_if.as_ref().map(|_| 0);
    }

    /// A find's pixel, already recorded, at its first matching event.
    pub(super) fn take_found(&mut self, found: Found, pick_time: Duration) {
        self.cursor = found.pixel;
        self.set_tree(found.tree);
        self.pick_time = pick_time;
        self.current = found.event;
        self.what_if = None;
        self.collapsed.clear();
        self.rows = OnceCell::new();
        self.details_scroll = None;
    }

    /// A click on line `line` of the tree pane, `height` lines high.
    pub(super) fn click_tree(&mut self, line: usize, height: usize) {
        let rows = self.rows();
        let selected = tree::selected_row(&self.tree, rows, self.current).unwrap_or(0);
        let first = tree::scroll_offset(selected, height);
        if let Some(row) = rows.get(first + line) {
            self.select(row.kind);
        }
    }

    /// A click on line `line` of the step list, `height` lines high.
    pub(super) fn click_steps(&mut self, line: usize, height: usize) {
        let first = steps::first_line(self.current, self.tree.events.len(), height);
        if first + line < self.tree.events.len() {
            self.set_current(first + line);
        }
    }

    /// Makes `event` current with its ray's row in sight (its folded
    /// ancestors opened) and the details at their top.
    pub(super) fn go_to(&mut self, event: usize) {
        self.set_current(event);
        let mut node = Some(self.selected_node());
        while let Some(n) = node {
            node = self.tree.nodes[n].parent;
            if let Some(parent) = node {
                self.collapsed.remove(&parent);
                self.rows = OnceCell::new();
            }
        }
        self.details_scroll = Some(0);
    }

    fn set_current(&mut self, event: usize) {
        self.current = event.min(self.tree.events.len().saturating_sub(1));
        self.details_scroll = None;
    }

    fn run_to(&mut self, breakpoint: Breakpoint, scene: &Scene) -> Option<String> {
        if let Some(event) = stepping::run_to(&self.tree, self.current, breakpoint) {
            self.set_current(event);
            return None;
        }
        let what = match breakpoint {
            Breakpoint::BlockedShadow => "blocked shadow ray".to_string(),
            Breakpoint::HitObject(object) => format!("hit on {}", scene.object_name(object)),
            Breakpoint::Tir => "total internal reflection".to_string(),
        };
        Some(format!(
            "no {what} after event {} in this pixel",
            self.current + 1
        ))
    }

    fn run_to_object(&mut self, scene: &Scene) -> Option<String> {
        match self.choose_break_target() {
            Some(object) => self.run_to(Breakpoint::HitObject(object), scene),
            None => Some("the selected ray hits nothing: press X to choose an object".into()),
        }
    }

    fn cycle_break_object(&mut self, scene: &Scene) -> Option<String> {
        let count = scene.objects.len();
        self.break_object = match self.break_target() {
            _ if count == 0 => None,
            Some(object) if self.break_object.is_some() => Some((object + 1) % count),
            Some(object) => Some(object),
            None => Some(0),
        };
        let object = self.break_object?;
        Some(format!(
            "x runs to the next hit on {}",
            scene.object_name(object)
        ))
    }

    /// Makes a tree row's ray or light the current event.
    fn select(&mut self, kind: RowKind) {
        let event = match kind {
            RowKind::Ray(node) => stepping::cast_event(&self.tree, node),
            RowKind::Light { node, light } => stepping::light_event(
                &self.tree,
                node,
                self.tree.nodes[node].lights[light].light_index,
            ),
        };
        if let Some(event) = event {
            self.set_current(event);
        }
    }

    fn select_row(&mut self, delta: i32) {
        let rows = self.rows();
        let Some(selected) = tree::selected_row(&self.tree, rows, self.current) else {
            return;
        };
        let row = (selected as i64 + delta as i64).clamp(0, rows.len() as i64 - 1) as usize;
        self.select(rows[row].kind);
    }
}
