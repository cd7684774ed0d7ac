//! Issue 16, sections 2 and 5: reaching any pixel in a few keys, and term
//! views that redraw in the time of the cells shown.

use raystep::terms::Term;
use raystep::tui::{Action, App, View};

mod common;

use common::*;

/// A term view's pixels, scaled as the image files scale them: each
/// rescanning the whole image for its maximum (the slow way the pane
/// used to take, once per shown pixel).
fn slow_pixel(app: &App, term: Term, x: u32, y: u32) -> [u8; 3] {
    let terms = app.terms().unwrap();
    terms.rgb(term, (y * terms.width + x) as usize, terms.max_count(term))
}

#[test]
fn count_views_show_the_pixels_scaled_by_the_whole_image() {
    let mut app = app();
    while app.view() != View::Term(Term::Rays) {
        app.update(Action::CycleView);
    }
    let (width, height) = (app.scene().width, app.scene().height);
    for term in [Term::Rays, Term::Cost] {
        // The scale matters only when counts differ: a miss casts 1 ray,
        // the glass in the middle many more.
        assert!(app.terms().unwrap().max_count(term) > 1, "{term:?}");
        assert_eq!(
            app.count_max(term),
            app.terms().unwrap().max_count(term),
            "{term:?}"
        );
        for y in 0..height {
            for x in 0..width {
                assert_eq!(
                    app.shown_pixel(x, y),
                    Some(slow_pixel(&app, term, x, y)),
                    "{term:?} at ({x}, {y})"
                );
            }
        }
        app.update(Action::CycleView);
    }
}
