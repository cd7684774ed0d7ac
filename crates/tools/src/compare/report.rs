//! The comparison as a student reads it: the verdict first, then the likely
//! mistakes, then where the images differ and what each place looks like.

use std::fmt::Write;

use super::{Comparison, MATCH_GAP, MATCH_SHARE, RegionReport, Verdict};
use raystep_engine::record::count;

pub fn text(c: &Comparison, image: &str, scene: &str) -> String {
    let mut out = String::new();
    let m = &c.metrics;
    let _ = writeln!(
        out,
        "{image} against {scene} rendered at {}x{}:",
        c.width, c.height
    );
    for note in &c.notes {
        let _ = writeln!(out, "  note: {note}");
    }
    let verdict = if c.matches {
        "they match"
    } else {
        "they differ"
    };
    let steps = (m.tolerance * 255.0).round();
    let anti_aliased = m.anti_aliased_pixels > 0 && m.few_over_tolerance();
    let on_edge = m.on_edge_pixels > 0 && m.few_over_tolerance();
    let share = if anti_aliased || on_edge {
        // The rest: what the share rule counts.
        let excused = match (anti_aliased, on_edge) {
            (true, false) => "anti-aliased edges",
            (false, true) => "edges through their centres",
            _ => "anti-aliased edges or edges through their centres",
        };
        format!(
            "{verdict}: {} of the pixels differ by more than {steps} steps of 255, but {} {excused}, which a match allows; the rest are {} (a match allows {})",
            percent(m.pixels_over_tolerance),
            count(m.excused_pixels() as u64, "pixel is on", "pixels are on"),
            percent(m.counted_share()),
            percent(MATCH_SHARE)
        )
    } else {
        format!(
            "{verdict}: {} of the pixels differ by more than {steps} steps of 255 (a match allows {})",
            percent(m.pixels_over_tolerance),
            percent(MATCH_SHARE)
        )
    };
    if let Some(allowed) = m.hot_pixels_allowed {
        // CSE 167's rule counts every pixel past the tolerance and
        // excuses none: no edge or far-off pixel is spoken of.
        let _ = writeln!(
            out,
            "{verdict}: {} with a channel more than {steps} steps of 255 apart (the assignment's hot-pixel rule allows at most {allowed}).",
            count(m.over_pixels as u64, "pixel is hot,", "pixels are hot,"),
        );
    } else if c.matches || !m.few_over_tolerance() {
        let _ = writeln!(out, "{share}.");
    } else {
        // The share alone would match: the few pixels far off decide.
        let allowed = match m.far_off_allowed {
            0 => "none".to_string(),
            n => n.to_string(),
        };
        let _ = writeln!(
            out,
            "{share}, but {} by more than {MATCH_GAP} (a match allows {allowed}):",
            count(m.far_off_pixels as u64, "pixel differs", "pixels differ")
        );
        for p in &m.far_off {
            let _ = writeln!(
                out,
                "  pixel {},{}: yours {:?}, reference {:?}",
                p.pixel[0], p.pixel[1], p.yours, p.reference
            );
        }
        if m.far_off_pixels > m.far_off.len() {
            let _ = writeln!(out, "  and {} more", m.far_off_pixels - m.far_off.len());
        }
    }
    if on_edge {
        let _ = writeln!(
            out,
            "  on an edge through the centre: for each of those {} raystep's rays a thousandth of a pixel to either side of its centre see different things, and yours lies within what they see: which side the centre's own ray falls on is a matter of rounding (a horizon through a row of centres), so either value is right",
            count(m.on_edge_pixels as u64, "pixel", "pixels")
        );
    }
    if anti_aliased {
        let _ = writeln!(
            out,
            "  anti-aliased: each of those {} lies, in every channel, within what the scene shows inside it (raystep's rays through its centre and its four quarter points), as averaging several rays a pixel gives; raystep traces one ray through each pixel's centre (MODEL §2)",
            count(m.anti_aliased_pixels as u64, "pixel", "pixels")
        );
    } else if c.matches && m.hot_pixels_allowed.is_none() && m.sub_pixel_pixels > m.on_edge_pixels {
        // Those on an edge through their centre are said so above.
        let moved = m.sub_pixel_pixels - m.on_edge_pixels;
        let _ = writeln!(
            out,
            "  {} past the tolerance {} within raystep's values around {}: an edge moved by less than a pixel, as another tracer's rounding moves it, which a match allows",
            count(moved as u64, "pixel", "pixels"),
            if moved == 1 { "lies" } else { "lie" },
            if moved == 1 { "it" } else { "them" },
        );
    }
    let _ = match m.flip_mean {
        Some(flip) => writeln!(
            out,
            "  mean absolute error {:.4}, FLIP {flip:.4}",
            m.mean_abs
        ),
        None => writeln!(out, "  mean absolute error {:.4}", m.mean_abs),
    };
    if let Some(w) = &m.worst {
        let _ = writeln!(
            out,
            "  worst pixel ({}, {}): yours {:?}, reference {:?}",
            w.pixel[0], w.pixel[1], w.yours, w.reference
        );
    }
    write_mistakes(&mut out, c, scene);
    if let Some(s) = &c.shows {
        let _ = writeln!(out, "The image shows {}.", s.words);
    }
    if let Some(g) = &c.geometry {
        let _ = writeln!(
            out,
            "Geometry: {}, which explains {} of the difference where it covers the image: the camera or projection differs.",
            g.words,
            percent(g.explains)
        );
    }
    if !c.regions.is_empty() {
        let _ = writeln!(
            out,
            "Where ({} of differing pixels; the largest first):",
            count(c.region_count as u64, "region", "regions")
        );
        for (i, region) in c.regions.iter().enumerate() {
            write_region(&mut out, i + 1, region);
        }
    }
    out
}

fn write_mistakes(out: &mut String, c: &Comparison, scene: &str) {
    if c.matches {
        return;
    }
    if c.mistakes.is_empty() {
        let _ = writeln!(
            out,
            "Likely mistake: none of the catalogue explains the difference (see the regions below)."
        );
        return;
    }
    let _ = writeln!(
        out,
        "Likely mistakes (share of the difference each explains; how well it fits where it changes the image):"
    );
    for (i, ranked) in c.mistakes.iter().enumerate() {
        let fits = format!("fits {}", percent(ranked.fits));
        let with = if i == 0 { "" } else { " with the above" };
        let at = ranked
            .pixel
            .map(|[x, y]| format!("; see pixel {x},{y}"))
            .unwrap_or_default();
        let name = match ranked.verdict {
            Verdict::Is => ranked.mistake.name().to_string(),
            Verdict::LooksLike => format!("looks like {}", ranked.mistake.name()),
            Verdict::Superseded => format!("({})", ranked.mistake.name()),
        };
        let _ = writeln!(
            out,
            "  {name:<20} {:>6}  ({fits}{with})  {}{at}",
            percent(ranked.explains),
            match ranked.exponent {
                Some(exponent) => format!("a gamma of {exponent:.1} applied to the bytes"),
                None => ranked.mistake.summary().to_string(),
            }
        );
        match (ranked.verdict, &ranked.superseded_by) {
            (Verdict::LooksLike, _) => {
                let pixel = ranked
                    .pixel
                    .map_or("a pixel of a region below".into(), |[x, y]| {
                        format!("pixel {x},{y}")
                    });
                let _ = writeln!(
                    out,
                    "     not the cause for sure: its render does not reproduce yours, and other bugs give nearly this picture; to tell them apart, log your tracer's rays for {pixel} and run `raystep compare {scene} --rays LOG`"
                );
            }
            (Verdict::Superseded, Some(by)) => {
                let _ = writeln!(out, "     superseded: {by}");
            }
            _ => {}
        }
    }
}

fn write_region(out: &mut String, number: usize, r: &RegionReport) {
    let mut objects: Vec<String> = r
        .objects
        .iter()
        .map(|o| format!("{} ({})", o.object, o.pixels))
        .collect();
    if r.more_objects > 0 {
        objects.push(count(r.more_objects as u64, "more object", "more objects"));
    }
    let [x0, y0, x1, y1] = r.bounds;
    let _ = writeln!(
        out,
        "  {number}. {} in ({x0}, {y0})-({x1}, {y1}), on {}",
        count(r.pixels as u64, "pixel", "pixels"),
        objects.join(", ")
    );
    let _ = writeln!(
        out,
        "     pixel {},{}: yours {:?}, reference {:?}",
        r.pixel[0], r.pixel[1], r.yours, r.reference
    );
    if let Some(diagnosis) = &r.diagnosis {
        let _ = writeln!(out, "     {diagnosis}");
    }
    for line in &r.explain {
        let _ = writeln!(out, "     {line}");
    }
}

fn percent(share: f64) -> String {
    let p = share * 100.0;
    if p > 0.0 && p < 0.1 {
        format!("{p:.2}%")
    } else {
        format!("{p:.1}%")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compare::ObjectShare;

    #[test]
    fn one_pixel_and_one_more_object_are_singular() {
        let region = RegionReport {
            pixels: 1,
            bounds: [3, 4, 3, 4],
            objects: vec![ObjectShare {
                object: "floor".into(),
                pixels: 1,
            }],
            more_objects: 1,
            pixel: [3, 4],
            yours: [0, 0, 0],
            reference: [255, 255, 255],
            explain: Vec::new(),
            diagnosis: None,
        };
        let mut out = String::new();
        write_region(&mut out, 1, &region);
        let first = out.lines().next().unwrap();
        assert_eq!(
            first,
            "  1. 1 pixel in (3, 4)-(3, 4), on floor (1), 1 more object"
        );
    }
}
