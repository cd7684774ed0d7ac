//! Criterion benchmark: how long the debugger takes to draw its image pane
//! in a term view (issue 16 section 5: every key within 50 ms at 200x60).
//! Run with `cargo bench --bench debugger`.

use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use raystep::tui::{Action, App, View, pane};

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
        while app.view() != View::Term(raystep::terms::Term::Rays) {
            app.update(Action::CycleView);
        }
        assert!(app.terms().is_some());
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

criterion_group!(benches, term_view_redraw);
criterion_main!(benches);
