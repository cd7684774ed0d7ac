//! Every integration test, in one binary. Each file here was its own test
//! binary, and each of those linked the whole crate: CI spent most of its
//! minutes linking, twice per run, while the tests themselves take seconds.
//! `tests/signals.rs` stays apart: it forks the debugger into
//! pseudo-terminals and job-control groups, which is its process's business.
//!
//! Snapshots go through `support::snapshot!` (and `json_snapshot!`), which
//! names them `snapshots/<file>__<name>.snap` after the file that pins them.

#[macro_use]
mod support;

mod accel;
mod cli;
mod cli_outputs;
mod compare;
mod compare_rays;
mod compare_rays_mistakes;
mod compare_slips;
mod compare_sub_pixel;
mod crossing;
mod cse167_raylog;
mod cse167_scenes;
mod cse167_tracer;
mod details_pane;
mod directional;
mod docs_contract;
mod ellipsoids;
mod explain_story;
mod figure;
mod five_questions;
mod fuzz_regressions;
mod grade;
mod grade_download;
mod grade_edge_cases;
mod grade_hot_pixels;
mod grade_report;
mod hostile;
mod layout;
mod meshes;
mod mistakes;
mod nff_import;
mod one_engine;
mod profiles;
mod pruning;
mod raylog;
mod readme;
mod scene_bounds;
mod scene_props;
mod shading;
mod snapshots;
mod student_tracer;
mod student_tracer_slips;
mod term_images;
mod text_files;
mod toml_sections;
mod tui;
mod tui_compare;
mod tui_diagram;
mod tui_rays;
mod tui_reach;
mod tui_screens;
mod web_page;
mod what_if;
