//! The `M` menu's text: one line per mistake of the catalogue, `[x]` when
//! it is on, its summary, and (when comparing) its place in the ranking;
//! the ranked mistakes come first.

use ratatui::style::{Modifier, Style, Stylize};
use ratatui::text::{Line, Span};

use raystep_engine::scene::Profile;
use raystep_model::mistakes::{Mistake, Mistakes};
use raystep_tools::compare::{Ranked, Verdict};

/// "#1 explains 100%": where the comparison ranks `mistake`, if it does.
pub(crate) fn rank_label(ranked: &[Ranked], mistake: Mistake) -> Option<String> {
    let place = ranked.iter().position(|r| r.mistake == mistake)?;
    Some(format!(
        "#{} explains {}",
        place + 1,
        percent(ranked[place].explains)
    ))
}

/// A share as a whole percentage, 0 to 100.
pub(crate) fn percent(share: f64) -> String {
    format!("{:.0}%", (share * 100.0).clamp(0.0, 100.0))
}

/// "no-ambient 100% · shadow-acne 17%", or that nothing is ranked.
pub(crate) fn ranking(ranked: &[Ranked], matches: bool) -> String {
    if ranked.is_empty() {
        return if matches {
            "your image matches".into()
        } else {
            "no classic mistake explains the difference".into()
        };
    }
    let parts: Vec<String> = ranked.iter().map(item).collect();
    parts.join(" · ")
}

/// "no-ambient 100%": one ranked mistake and its share; "looks like
/// eta-inverted 99%" when its render does not reproduce the image;
/// "eta-inverted 99%, superseded: your ray log" when something overrides
/// it (issue 39: the footer and the details pane disagreed).
fn item(ranked: &Ranked) -> String {
    let share = percent(ranked.explains);
    match ranked.verdict {
        Verdict::Is => format!("{} {share}", ranked.mistake),
        Verdict::LooksLike => format!("looks like {} {share}", ranked.mistake),
        Verdict::Superseded => {
            let by = ranked.superseded_by.as_deref().unwrap_or("");
            let by = by.split(':').next().unwrap_or(by);
            format!("{} {share}, superseded: {by}", ranked.mistake)
        }
    }
}

/// The image pane's " compare: no-ambient 100% · shadow-acne 17% " in at
/// most `room` columns: short of room, the last items give way to "+N
/// more" (the `M` menu lists them all), never half a word; `None` when not
/// even that fits.
pub(crate) fn compare_line(ranked: &[Ranked], matches: bool, room: usize) -> Option<String> {
    let fits = |text: String| (text.chars().count() <= room).then_some(text);
    let framed = |body: &str| format!(" compare: {body} ");
    if ranked.is_empty() {
        return fits(framed(&ranking(ranked, matches))).or_else(|| {
            let brief = if matches {
                "matches"
            } else {
                "no mistake fits"
            };
            fits(framed(brief))
        });
    }
    let items: Vec<String> = ranked.iter().map(item).collect();
    (0..=items.len()).rev().find_map(|shown| {
        let mut parts = items[..shown].to_vec();
        if shown < items.len() {
            parts.push(format!("+{} more", items.len() - shown));
        }
        fits(framed(&parts.join(" · ")))
    })
}

/// The menu's rows: the ranked mistakes, best first, then the rest of the
/// catalogue in its order, so the mistake `compare` names is a key away;
/// only those `profile` offers (`Profile::offers`: cse167 has no
/// refraction for eta-inverted to change).
pub(crate) fn order(ranked: &[Ranked], profile: Profile) -> Vec<Mistake> {
    let mut rows: Vec<Mistake> = Vec::with_capacity(Mistake::ALL.len());
    let ranked = ranked.iter().map(|r| r.mistake);
    for mistake in ranked.chain(Mistake::ALL) {
        if profile.offers(mistake) && !rows.contains(&mistake) {
            rows.push(mistake);
        }
    }
    rows
}

/// The menu's lines, one per mistake of `rows`, the `selected` row highlighted.
pub(crate) fn lines(
    rows: &[Mistake],
    on: Mistakes,
    selected: usize,
    ranked: &[Ranked],
) -> Vec<Line<'static>> {
    // The names' column: the longest name and two spaces.
    let width = Mistake::ALL
        .iter()
        .map(|m| m.name().len())
        .max()
        .unwrap_or(0)
        + 2;
    rows.iter()
        .enumerate()
        .map(|(i, &mistake)| {
            let check = if on.contains(mistake) { "[x]" } else { "[ ]" };
            let mut spans = vec![
                Span::raw(format!(" {check} ")),
                Span::raw(format!("{:<width$}", mistake.name())).bold(),
                Span::raw(mistake.summary().to_string()),
            ];
            if let Some(label) = rank_label(ranked, mistake) {
                spans.push(Span::raw(format!("  {label}")).yellow().bold());
            }
            spans.push(Span::raw(" "));
            let line = Line::from(spans);
            if i == selected {
                line.patch_style(Style::new().add_modifier(Modifier::REVERSED))
            } else {
                line
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(line: &Line) -> String {
        line.spans.iter().map(|s| s.content.as_ref()).collect()
    }

    fn ranked(mistake: Mistake, explains: f64) -> Ranked {
        Ranked {
            mistake,
            verdict: Verdict::Is,
            superseded_by: None,
            explains,
            fits: 1.0,
            pixel: None,
            exponent: None,
        }
    }

    #[test]
    fn every_mistake_has_a_line_with_its_state_and_summary() {
        let on = Mistakes::NONE.with(Mistake::NoAmbient);
        let lines = lines(&Mistake::ALL, on, 0, &[ranked(Mistake::NoAmbient, 0.996)]);
        assert_eq!(lines.len(), 22);
        // Row 9 of the catalogue is no-ambient: on, ranked first, 99.6% ->
        // 100%; the name padded to 27 (refraction-outward-normal's 25, and 2).
        assert_eq!(
            text(&lines[9]),
            " [x] no-ambient                 no ambient term  #1 explains 100% "
        );
        assert!(text(&lines[7]).starts_with(" [ ] no-light-attenuation       lights not"));
        assert!(text(&lines[0]).starts_with(" [ ] shadow-acne "));
        assert!(text(&lines[0]).contains(Mistake::ShadowAcne.summary()));
    }

    #[test]
    fn the_ranked_mistakes_come_first_then_the_catalogue() {
        let both = [
            ranked(Mistake::PixelCorner, 1.0),
            ranked(Mistake::NoAmbient, 0.2),
        ];
        let rows = order(&both, Profile::Lecture);
        assert_eq!(rows[..2], [Mistake::PixelCorner, Mistake::NoAmbient]);
        // The rest in the catalogue's order, each offered mistake once
        // (under the lecture, every one).
        let rest: Vec<Mistake> = Mistake::ALL
            .into_iter()
            .filter(|m| !matches!(m, Mistake::PixelCorner | Mistake::NoAmbient))
            .collect();
        assert_eq!(rows[2..], rest[..]);
        assert_eq!(order(&[], Profile::Lecture), Mistake::ALL);
        let text =
            |line: &Line| -> String { line.spans.iter().map(|s| s.content.as_ref()).collect() };
        let lines = lines(&rows, Mistakes::NONE, 0, &both);
        assert!(text(&lines[0]).contains("pixel-corner"));
        assert!(text(&lines[0]).ends_with("#1 explains 100% "));
        assert!(text(&lines[1]).ends_with("#2 explains 20% "));
    }

    #[test]
    fn under_cse167_the_menu_has_every_offered_mistake_once() {
        // cse167 casts no transmitted ray (MODEL §11): the three mistakes
        // of refraction are left out, even one a ranking named; the other
        // 19 keep the catalogue's order.
        let both = [
            ranked(Mistake::NoAmbient, 1.0),
            ranked(Mistake::EtaInverted, 0.5),
        ];
        let rows = order(&both, Profile::Cse167);
        let offered: Vec<Mistake> = Mistake::ALL
            .into_iter()
            .filter(|m| {
                !matches!(
                    m,
                    Mistake::EtaInverted | Mistake::TirDropped | Mistake::RefractionOutwardNormal
                )
            })
            .collect();
        assert_eq!(offered.len(), 19);
        assert_eq!(rows[0], Mistake::NoAmbient);
        let rest: Vec<Mistake> = offered
            .iter()
            .copied()
            .filter(|&m| m != Mistake::NoAmbient)
            .collect();
        assert_eq!(rows[1..], rest[..]);
        assert_eq!(order(&[], Profile::Cse167), offered);
    }

    #[test]
    fn the_compare_line_drops_whole_items_to_fit() {
        let three = [
            ranked(Mistake::NoAmbient, 1.0),
            ranked(Mistake::ShadowAcne, 0.171),
            ranked(Mistake::FlippedY, 0.05),
        ];
        // All three: " compare: " 10, "no-ambient 100%" 15, " · " 3,
        // "shadow-acne 17%" 15, 3, "flipped-y 5%" 12, " " 1: 59 columns.
        let all = " compare: no-ambient 100% · shadow-acne 17% · flipped-y 5% ";
        assert_eq!(compare_line(&three, false, 59).as_deref(), Some(all));
        // One short: the third gives way to "+1 more" (10 + 15 + 3 + 15 +
        // 3 + 7 + 1 = 54 columns).
        let two = " compare: no-ambient 100% · shadow-acne 17% · +1 more ";
        assert_eq!(compare_line(&three, false, 58).as_deref(), Some(two));
        assert_eq!(compare_line(&three, false, 54).as_deref(), Some(two));
        // 10 + 15 + 3 + 7 + 1 = 36; then 10 + 7 + 1 = 18.
        let one = " compare: no-ambient 100% · +2 more ";
        assert_eq!(compare_line(&three, false, 53).as_deref(), Some(one));
        assert_eq!(compare_line(&three, false, 36).as_deref(), Some(one));
        let none = " compare: +3 more ";
        assert_eq!(compare_line(&three, false, 35).as_deref(), Some(none));
        assert_eq!(compare_line(&three, false, 18).as_deref(), Some(none));
        assert_eq!(compare_line(&three, false, 17), None);
        assert_eq!(
            compare_line(&[], true, 40).as_deref(),
            Some(" compare: your image matches ")
        );
        assert_eq!(
            compare_line(&[], false, 30).as_deref(),
            Some(" compare: no mistake fits ")
        );
    }

    #[test]
    fn the_ranking_line_lists_names_and_shares() {
        let both = [
            ranked(Mistake::NoAmbient, 1.0),
            ranked(Mistake::ShadowAcne, 0.171),
        ];
        assert_eq!(ranking(&both, false), "no-ambient 100% · shadow-acne 17%");
        assert_eq!(ranking(&[], true), "your image matches");
    }
}
