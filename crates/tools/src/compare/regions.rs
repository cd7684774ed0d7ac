//! The differing pixels grouped into connected regions (8-connected), the
//! largest first, so a report can speak of "the shadow under the ball"
//! rather than of 4,000 pixels.

use image::GrayImage;

/// One connected set of marked pixels.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Region {
    /// Row-major order.
    pub(crate) pixels: Vec<(u32, u32)>,
}

impl Region {
    /// The smallest box holding the region: (x0, y0, x1, y1), inclusive.
    pub(crate) fn bounds(&self) -> (u32, u32, u32, u32) {
        let xs = self.pixels.iter().map(|p| p.0);
        let ys = self.pixels.iter().map(|p| p.1);
        (
            xs.clone().min().unwrap_or(0),
            ys.clone().min().unwrap_or(0),
            xs.max().unwrap_or(0),
            ys.max().unwrap_or(0),
        )
    }
}

/// The regions of `mask`'s non-zero pixels, largest first (ties: the one
/// whose first pixel comes first in row-major order).
pub(crate) fn regions(mask: &GrayImage) -> Vec<Region> {
    let (width, height) = mask.dimensions();
    let index = |x: u32, y: u32| (y * width + x) as usize;
    let mut seen = vec![false; (width * height) as usize];
    let mut found = Vec::new();
    for (x, y, p) in mask.enumerate_pixels() {
        if p.0[0] == 0 || seen[index(x, y)] {
            continue;
        }
        seen[index(x, y)] = true;
        let mut pixels = Vec::new();
        let mut stack = vec![(x, y)];
        while let Some((px, py)) = stack.pop() {
            pixels.push((px, py));
            for (nx, ny) in neighbours(px, py, width, height) {
                if mask.get_pixel(nx, ny).0[0] != 0 && !seen[index(nx, ny)] {
                    seen[index(nx, ny)] = true;
                    stack.push((nx, ny));
                }
            }
        }
        pixels.sort_by_key(|&(px, py)| (py, px));
        found.push(Region { pixels });
    }
    // A stable sort keeps row-major order among regions of equal size.
    found.sort_by_key(|r| std::cmp::Reverse(r.pixels.len()));
    found
}

/// The up to eight pixels around (x, y) inside the image.
fn neighbours(x: u32, y: u32, width: u32, height: u32) -> impl Iterator<Item = (u32, u32)> {
    (-1i64..=1)
        .flat_map(|dy| (-1i64..=1).map(move |dx| (dx, dy)))
        .filter(|&d| d != (0, 0))
        .map(move |(dx, dy)| (x as i64 + dx, y as i64 + dy))
        .filter(move |&(nx, ny)| nx >= 0 && ny >= 0 && nx < width as i64 && ny < height as i64)
        .map(|(nx, ny)| (nx as u32, ny as u32))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mask(rows: &[&str]) -> GrayImage {
        GrayImage::from_fn(rows[0].len() as u32, rows.len() as u32, |x, y| {
            image::Luma([if rows[y as usize].as_bytes()[x as usize] == b'#' {
                255
            } else {
                0
            }])
        })
    }

    #[test]
    fn diagonal_neighbours_join_and_the_largest_comes_first() {
        // Left: (0,0) and (1,1) touch at a corner: one region of 2. Right:
        // a column of 3 at x = 4. The column comes first.
        let found = regions(&mask(&["#...#", ".#..#", "....#"]));
        assert_eq!(found.len(), 2);
        assert_eq!(found[0].pixels, [(4, 0), (4, 1), (4, 2)]);
        assert_eq!(found[1].pixels, [(0, 0), (1, 1)]);
        assert_eq!(found[0].bounds(), (4, 0, 4, 2));
    }

    #[test]
    fn an_empty_mask_has_no_region() {
        assert!(regions(&mask(&["...", "..."])).is_empty());
    }
}
