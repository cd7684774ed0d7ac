//! Finding across the image (`f` then a key): which pixel's recording has a
//! blocked (or partly blocked) shadow ray, a total internal reflection, a ray cut by the depth
//! limit, a hit on the breakpoint object, or a near miss (polygon or sphere); and the go-to prompt's `X,Y`.

use raystep_engine::record::{EventKind, LightFate, RayTree};

use crate::tui::action::Find;
use raystep_engine::record::stepping::{self, Breakpoint};

impl Find {
    /// For the status line: "no pixel with {what}".
    pub(crate) fn what(self) -> &'static str {
        match self {
            Find::BlockedShadow => "a blocked shadow ray",
            Find::PartialShadow => "a partly blocked shadow ray (0 < S < 1)",
            Find::Tir => "a total internal reflection",
            Find::DepthLimit => "a ray cut by the depth limit",
            Find::BreakObject => "a hit on the object",
            Find::NearMiss => {
                "a near miss (a polygon's plane crossed outside it, or a sphere's box crossed without a hit)"
            }
        }
    }
}

/// The first event of `tree` that `find` looks for; `object` is the
/// breakpoint object (`Find::BreakObject` needs one; `Find::NearMiss`
/// looks at it alone when there is one). Everything is read from `tree`.
pub(crate) fn first_event(tree: &RayTree, find: Find, object: Option<usize>) -> Option<usize> {
    let breakpoint = match find {
        Find::BlockedShadow => Breakpoint::BlockedShadow,
        Find::Tir => Breakpoint::Tir,
        Find::BreakObject => Breakpoint::HitObject(object?),
        Find::DepthLimit => {
            let cut = tree
                .nodes
                .iter()
                .position(|n| n.depth_cut().next().is_some())?;
            return stepping::cast_event(tree, cut);
        }
        Find::PartialShadow => {
            return (0..tree.events.len()).find(|&i| {
                stepping::matches(tree, i, Breakpoint::BlockedShadow) && partly_blocked(tree, i)
            });
        }
        Find::NearMiss => {
            let node = tree.nodes.iter().position(|n| {
                n.near_misses
                    .iter()
                    .any(|near| object.is_none_or(|o| near.object_index == o))
            })?;
            return stepping::cast_event(tree, node);
        }
    };
    (0..tree.events.len()).find(|&i| stepping::matches(tree, i, breakpoint))
}

/// Whether the blocker event `i` is on a shadow ray with 0 < S < 1.
fn partly_blocked(tree: &RayTree, i: usize) -> bool {
    let event = &tree.events[i];
    let EventKind::Blocker { light, .. } = event.kind else {
        return false;
    };
    tree.nodes[event.node]
        .lights
        .iter()
        .find(|l| l.light_index == light)
        .is_some_and(|l| matches!(LightFate::of(l), LightFate::PartlyBlocked(_)))
}

/// The pixels after `from` in reading order (left to right, rows down),
/// wrapping at the end and ending with `from` itself: each pixel once.
pub(crate) fn reading_order(
    from: (u32, u32),
    size: (u32, u32),
) -> impl Iterator<Item = (u32, u32)> {
    let count = size.0 as u64 * size.1 as u64;
    let start = from.1 as u64 * size.0 as u64 + from.0 as u64;
    (1..=count).map(move |k| {
        let i = (start + k) % count;
        ((i % size.0 as u64) as u32, (i / size.0 as u64) as u32)
    })
}

/// The go-to prompt's text as a pixel of an image of `size`, or why not.
pub(crate) fn parse_goto(text: &str, size: (u32, u32)) -> Result<(u32, u32), String> {
    let bad =
        || format!("`{text}` is not a pixel: expected X,Y with whole numbers from 0, e.g. 120,40");
    let (x, y) = text.split_once(',').ok_or_else(bad)?;
    let (x, y): (u32, u32) = (
        x.trim().parse().map_err(|_| bad())?,
        y.trim().parse().map_err(|_| bad())?,
    );
    if x >= size.0 || y >= size.1 {
        return Err(outside((x, y), size));
    }
    Ok((x, y))
}

/// Why a pixel is not in the image.
pub(crate) fn outside((x, y): (u32, u32), (width, height): (u32, u32)) -> String {
    format!(
        "pixel ({x}, {y}) is outside the {width}x{height} image: x must be below {width} and y below {height}"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reading_order_visits_each_pixel_once_ending_at_the_start() {
        // 3 x 2 from (1, 1), index 4: then 5, 0, 1, 2, 3, 4.
        let order: Vec<_> = reading_order((1, 1), (3, 2)).collect();
        assert_eq!(order, [(2, 1), (0, 0), (1, 0), (2, 0), (0, 1), (1, 1)]);
    }

    #[test]
    fn the_prompt_takes_x_comma_y_inside_the_image() {
        assert_eq!(parse_goto("120,40", (160, 120)), Ok((120, 40)));
        assert_eq!(parse_goto(" 0, 119 ", (160, 120)), Ok((0, 119)));
        let err = parse_goto("160,0", (160, 120)).unwrap_err();
        assert!(err.contains("outside the 160x120 image"), "{err}");
        let err = parse_goto("12", (160, 120)).unwrap_err();
        assert!(err.contains("expected X,Y"), "{err}");
        assert!(parse_goto("-1,3", (160, 120)).is_err());
    }
}
