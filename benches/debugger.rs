//! Criterion benchmark: how long the debugger takes to draw its image pane
//! in a term view (issue 16 section 5: every key within 50 ms at 200x60),
//! the longest key during a fruitless image-wide find (`f t`), and each
//! key, answered and drawn, on a pixel whose tree holds 65,536 rays
//! (issue 27). Run with `cargo bench --bench debugger`.

use std::path::Path;
use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group, criterion_main};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use raystep::tui::{Action, App, Find, Picture, pane};
use raystep_engine::record::stepping::{Breakpoint, Step};

fn term_view_redraw(c: &mut Criterion) {
    for (name, relative) in [
        ("gears", "scenes/spd/gears.nff"),
        ("balls", "scenes/spd/balls.nff"),
    ] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(relative);
        if !path.exists() {
            continue;
        }
        // Synchronous: the term images (512x512) are there before drawing.
        let mut app = App::open(Some(path), true).unwrap();
        app.update(Action::Resize(200, 60));
        // ambient, diffuse, ..., shadow, rays: the count views scale by a maximum.
        while app.screen().picture() != Picture::Term(raystep_engine::terms::Term::Rays) {
            app.update(Action::CyclePicture);
        }
        assert!(app.renders().terms().is_some());
        let mut terminal = Terminal::new(TestBackend::new(200, 60)).unwrap();
        let mut group = c.benchmark_group(format!("debugger 200x60 {name}"));
        group.sample_size(10);
        group.bench_function("redraw in the rays view", |b| {
            b.iter(|| {
                terminal.draw(|frame| pane::draw(frame, &app)).unwrap();
            })
        });
        group.finish();
    }
}

/// The longest single `App::update` while `f t` (find the next total
/// internal reflection) scans all of balls.nff (512x512, no transparent
/// surface: the find is fruitless, every pixel is recorded). Criterion
/// reports that longest call, not the whole scan: it is how long a key
/// can wait. Before the find ran in the background it was the scan itself.
fn fruitless_find(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/spd/balls.nff");
    let mut group = c.benchmark_group("debugger balls 512x512");
    group.sample_size(10);
    group.bench_function("longest update during a fruitless f t", |b| {
        b.iter_custom(|iters| {
            let mut longest_sum = Duration::ZERO;
            for _ in 0..iters {
                let mut app = App::open(Some(path.clone()), false).unwrap();
                let mut longest = Duration::ZERO;
                let mut timed = |app: &mut App, action: Action| {
                    let started = Instant::now();
                    app.update(action);
                    longest = longest.max(started.elapsed());
                };
                timed(&mut app, Action::StartFind);
                timed(&mut app, Action::Find(Find::Tir));
                while app.finding_progress().is_some() {
                    std::thread::sleep(Duration::from_millis(20));
                    timed(&mut app, Action::Tick);
                }
                let message = app.message().unwrap_or_default().to_string();
                assert!(message.contains("none in the image"), "{message}");
                longest_sum += longest;
            }
            longest_sum
        })
    });
    group.finish();
}

/// Each key on the centre pixel of the three glass planes
/// (`tests/scenes/three-glass-planes.toml`) with no weight cutoff and the
/// largest ray budget: the tree holds 65,536 rays, 2 events each and more.
/// One iteration is the key's update and the redraw at 200x60 that shows
/// it, as the main loop does. The image renders in the background.
fn keys_on_a_big_tree(c: &mut Criterion) {
    let dir = std::env::temp_dir().join(format!("raystep-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("big-tree.toml");
    let scene = include_str!("../tests/scenes/three-glass-planes.toml").replace(
        "[settings]\n",
        "[settings]\nmin_weight = 0\nmax_rays = 65536\n",
    );
    std::fs::write(&path, scene).unwrap();
    let mut app = App::open(Some(path), false)
        .unwrap()
        .at_pixel((16, 12))
        .unwrap();
    app.update(Action::Resize(200, 60));
    assert_eq!(app.pixel().tree().nodes.len(), 65536);
    let mut terminal = Terminal::new(TestBackend::new(200, 60)).unwrap();
    let mut group = c.benchmark_group("debugger 200x60, a tree of 65536 rays");
    group.sample_size(10);
    let keys = [
        ("n next", Action::Step(Step::Next)),
        ("e end", Action::Step(Step::End)),
        ("p previous", Action::Step(Step::Previous)),
        ("g start", Action::Step(Step::Start)),
        ("i into", Action::Step(Step::Into)),
        ("o over", Action::Step(Step::Over)),
        ("u out", Action::Step(Step::Out)),
        ("b blocked shadow", Action::RunTo(Breakpoint::BlockedShadow)),
        ("T tir", Action::RunTo(Breakpoint::Tir)),
        ("d plane", Action::CyclePlane),
        ("Tab focus", Action::FocusNext),
        ("down a row", Action::SelectRow(1)),
        ("space fold", Action::ToggleCollapse),
    ];
    for (name, action) in keys {
        group.bench_function(name, |b| {
            b.iter(|| {
                app.update(action);
                terminal.draw(|frame| pane::draw(frame, &app)).unwrap();
            })
        });
    }
    group.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(
    benches,
    term_view_redraw,
    fruitless_find,
    keys_on_a_big_tree
);
criterion_main!(benches);
