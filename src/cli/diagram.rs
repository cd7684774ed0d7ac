//! `raystep diagram`: one pixel's rays as an SVG figure, in a plane of the
//! camera's frame or as the crossing test of a polygon.

use std::process::ExitCode;

use anyhow::Result;
use clap::ValueEnum;

use super::recorded::record;
use super::{DiagramArgs, PlaneArg, ShadowsArg};
use raystep_engine::record::RayTree;
use raystep_tools::diagram::svg::Caption;
use raystep_tools::output::{self, Target};

pub(super) fn run(args: &DiagramArgs) -> Result<ExitCode> {
    use raystep_tools::diagram::{Diagram, DiagramPlane, Progress, Shadows, svg};
    let target = output::file(&args.output)?;
    // `--plane crossing` with `--zoom` or `--shadows` is refused as a usage
    // error before this (`Cli::check_combinations`).
    let recorded = record(&args.pixel)?;
    // Once the scene is read, so that its meshes and MTL files are known.
    output::refuse_clashes(
        &output::Inputs::default().with_scene(&recorded.scene),
        &[(&target, "the figure (-o)".to_owned())],
    )?;
    let plane = match args.plane {
        PlaneArg::Top => DiagramPlane::Top,
        PlaneArg::Side => DiagramPlane::Side,
        PlaneArg::Ray => DiagramPlane::Primary,
        PlaneArg::Crossing => return crossing_figure(&recorded.tree, &target, &caption(args)),
    };
    let (scene, tree) = (&recorded.scene, &recorded.tree);
    let shadows = match args.shadows {
        ShadowsArg::All => Shadows::All,
        ShadowsArg::Primary => Shadows::Primary,
        ShadowsArg::None => Shadows::None,
    };
    let figure = svg::slide(
        &Diagram::new(scene, tree, plane, Progress::done(tree)).with_shadows(shadows),
        args.zoom,
        &caption(args),
    );
    output::write_text(&target, &figure)?;
    Ok(ExitCode::SUCCESS)
}

/// `--plane crossing`: the first polygon hit, or else passed by; none is an error.
fn crossing_figure(tree: &RayTree, target: &Target, caption: &Caption) -> Result<ExitCode> {
    use raystep_tools::diagram::svg::crossing_figure;
    let Some(subject) = crossing_figure::subject(tree) else {
        anyhow::bail!(
            "pixel ({}, {}): no ray of its tree hits a polygon or patch or passes one by, \
             so there is no crossing test to draw (try --plane top)",
            tree.pixel.0,
            tree.pixel.1
        );
    };
    output::write_text(target, &crossing_figure::svg(tree.pixel, &subject, caption))?;
    Ok(ExitCode::SUCCESS)
}

/// The figure's title: the scene file's name and every option that changed
/// what is drawn, as given (the plane and zoom are named by the figure).
fn caption(args: &DiagramArgs) -> Caption {
    let pixel = &args.pixel;
    let scene = (pixel.scene.file_name()).map_or_else(
        || pixel.scene.display().to_string(),
        |name| name.to_string_lossy().into_owned(),
    );
    let mut options: Vec<String> = (pixel.size.size.iter())
        .map(|(w, h)| format!("--size {w}x{h}"))
        .collect();
    options.extend(
        pixel
            .mistakes
            .mistakes
            .iter()
            .map(|m| format!("--mistake {}", m.0.name())),
    );
    options.extend(pixel.set.iter().map(|s| format!("--set {s}")));
    if args.shadows != ShadowsArg::All {
        let value = args
            .shadows
            .to_possible_value()
            .map(|v| v.get_name().to_owned());
        options.push(format!("--shadows {}", value.unwrap_or_default()));
    }
    Caption { scene, options }
}
