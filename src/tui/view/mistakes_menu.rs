//! The `M` menu's text: one line per mistake of the catalogue, `[x]` when
//! it is on, its summary, and (when comparing) its place in the ranking.

use ratatui::style::{Modifier, Style, Stylize};
use ratatui::text::{Line, Span};

use crate::compare::Ranked;
use crate::mistakes::{Mistake, Mistakes};

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
    let parts: Vec<String> = ranked
        .iter()
        .map(|r| format!("{} {}", r.mistake, percent(r.explains)))
        .collect();
    parts.join(" · ")
}

/// The menu's lines, the `selected` row highlighted.
pub(crate) fn lines(on: Mistakes, selected: usize, ranked: &[Ranked]) -> Vec<Line<'static>> {
    // The names' column: the longest name and two spaces.
    let width = Mistake::ALL
        .iter()
        .map(|m| m.name().len())
        .max()
        .unwrap_or(0)
        + 2;
    Mistake::ALL
        .iter()
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
            explains,
            fits: 1.0,
            pixel: None,
        }
    }

    #[test]
    fn every_mistake_has_a_line_with_its_state_and_summary() {
        let on = Mistakes::NONE.with(Mistake::NoAmbient);
        let lines = lines(on, 0, &[ranked(Mistake::NoAmbient, 0.996)]);
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
    fn the_ranking_line_lists_names_and_shares() {
        let both = [
            ranked(Mistake::NoAmbient, 1.0),
            ranked(Mistake::ShadowAcne, 0.171),
        ];
        assert_eq!(ranking(&both, false), "no-ambient 100% · shadow-acne 17%");
        assert_eq!(ranking(&[], true), "your image matches");
    }
}
