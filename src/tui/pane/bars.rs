//! The header and status lines: the scene and the model's settings above
//! the panes; render progress, the message and the key hints below.

use ratatui::style::Stylize;
use ratatui::text::{Line, Span};

use crate::tui::{App, Picture, keymap};
use raystep_engine::scene::SpecularModel;

/// A switch's name: plain green when on, "no ..." in red when off.
fn on_off(name: &str, on: bool) -> Span<'static> {
    if on {
        Span::raw(name.to_string()).green()
    } else {
        Span::raw(format!("no {name}")).red().bold()
    }
}

/// The switches' names, long or (when the header is short of room) short.
const SWITCH_NAMES: [(&str, &str); 4] = [
    ("shadows", "shad"),
    ("reflection", "refl"),
    ("transmission", "trans"),
    ("ambient", "amb"),
];

/// The top line: the scene and the model's settings as the toggles left
/// them. Short of room, the switches' names shorten first, then the scene's.
pub(super) fn header(app: &App, width: u16) -> Line<'static> {
    let session = app.session();
    let scene = format!(
        " {} {}x{}",
        session.source().name(),
        session.scene().width,
        session.scene().height
    );
    let long = settings_spans(app, false);
    let room = |right: &[Span]| {
        (width as usize).saturating_sub(9 + right.iter().map(|s| s.width()).sum::<usize>())
    };
    let right = if scene.chars().count() <= room(&long) {
        long
    } else {
        settings_spans(app, true)
    };
    let room = room(&right);
    let scene = if scene.chars().count() <= room {
        scene
    } else {
        let tail: String = scene
            .chars()
            .rev()
            .take(room.saturating_sub(2))
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .collect();
        format!(" …{tail}")
    };
    let mut spans = vec![Span::raw(" raystep ").bold().reversed(), Span::raw(scene)];
    spans.extend(right);
    Line::from(spans)
}

fn settings_spans(app: &App, short: bool) -> Vec<Span<'static>> {
    let settings = app.session().settings();
    let s = settings.switches;
    let sep = || Span::raw(" · ").dark_gray();
    let on = [s.shadows, s.reflection, s.transmission, s.ambient];
    // A profile without refraction (cse167) has no transmission to switch.
    let has = [true, true, settings.profile.refracts(), true];
    let mut right = vec![sep()];
    let shown =
        (SWITCH_NAMES.iter().zip(on).zip(has)).filter_map(|(named, has)| has.then_some(named));
    for (i, ((long, brief), on)) in shown.enumerate() {
        if i > 0 {
            right.push(Span::raw(" "));
        }
        right.push(on_off(if short { brief } else { long }, on));
    }
    right.extend([
        sep(),
        Span::raw(match settings.specular {
            SpecularModel::Phong => "Phong",
            SpecularModel::Blinn => "Blinn",
        }),
        sep(),
        // CSE 167's `maxdepth` counts bounces, one less than MODEL §5's
        // depth (docs/CSE167.md): say both where that profile is traced.
        Span::raw(if settings.profile.is_lecture() {
            format!("depth {}", settings.max_depth)
        } else {
            let bounces = settings.max_depth.saturating_sub(1);
            format!("depth {} ({bounces} bounces)", settings.max_depth)
        }),
    ]);
    if !settings.profile.is_lecture() {
        // Which equation the scene means: every term follows it (MODEL §11).
        right.extend([
            sep(),
            Span::raw(format!("profile {}", settings.profile.name())).bold(),
        ]);
    }
    if !settings.mistakes.is_empty() {
        // A teacher must not forget a mistake is on: it changes every pixel.
        right.extend([
            sep(),
            Span::raw(format!("mistakes: {}", settings.mistakes))
                .bold()
                .red(),
        ]);
    }
    // On screen a picture is a "view", the `v` key's word.
    let picture = match app.screen().picture() {
        Picture::Render => None,
        Picture::Term(term) => Some(term.name()),
        Picture::Yours => Some("yours"),
        Picture::ErrorMap => Some("error map"),
    };
    if let Some(picture) = picture {
        right.extend([sep(), Span::raw(format!("view: {picture}")).bold().yellow()]);
    }
    right
}

pub(super) fn status(app: &App) -> Line<'static> {
    let mut spans = Vec::new();
    if let Some(text) = app.overlay().prompt() {
        // The prompt has the keys: it, then why the last Enter failed.
        spans.push(Span::raw(format!(" go to X,Y: {text}▏")).bold().reversed());
        let why = app.message().unwrap_or("Enter goes, Esc cancels");
        spans.push(Span::raw(format!(" {why} ")).yellow());
        return Line::from(spans);
    }
    if let Some(p) = app.renders().progress() {
        spans.push(
            Span::raw(format!(" rendering {}/{} rows ", p.rows_done, p.rows))
                .black()
                .on_yellow(),
        );
    }
    if let Some((what, row, rows)) = app.finding_progress() {
        spans.push(
            Span::raw(format!(" finding {what}… (row {row} of {rows}) "))
                .black()
                .on_yellow(),
        );
    }
    let region = (app.comparison()).and_then(|c| c.region_words(app.pixel().cursor()));
    if let Some(message) = app.message() {
        spans.push(Span::raw(format!(" {message} ")).yellow().bold());
    } else if let Some(region) = region {
        // The region `w` went to is still under the cursor: its diagnosis.
        spans.push(Span::raw(format!(" {region} ")).yellow());
    } else if app.show_timings() {
        let render = app.renders().render_time().map_or(String::new(), |t| {
            format!(", image in {:.0} ms", t.as_secs_f64() * 1e3)
        });
        spans.push(
            Span::raw(format!(
                " pixel traced in {} µs{render} ",
                app.pixel().pick_time().as_micros()
            ))
            .dark_gray(),
        );
    }
    spans.push(Span::raw(" "));
    for hint in keymap::hints_in(app.screen().focus()) {
        spans.push(Span::raw(hint.keys).bold().cyan());
        spans.push(Span::raw(format!(" {}  ", hint.what)));
    }
    Line::from(spans)
}
