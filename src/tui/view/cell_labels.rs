//! Where the diagram's labels go in the terminal, so that none is written
//! over another: a marker (the eye's ◉, a light's ☼, a blocker's ×, a
//! passed-by ring's ○) sits on its point's cell or is left out when an
//! earlier marker has it; a name goes where it is asked (right of its
//! marker, for the eye and the lights), else above, below, left or further
//! out, at the first place where it meets no placed label; with no room
//! anywhere it is shortened with "…", and left out when even three
//! characters do not fit, or when it only explains a marker left out (a
//! ring's "passed by"). Earlier labels win, so the caller lists the most
//! important first.

/// A label asked for, at a cell (column, row) of the drawing area.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Wanted<'a> {
    pub(crate) at: (i32, i32),
    pub(crate) text: &'a str,
    /// A marker: exactly at `at` or nowhere.
    pub(crate) fixed: bool,
    /// Placed only if the label at this index (earlier in the list) was:
    /// a name that says what its marker is, meaningless without it.
    pub(crate) with: Option<usize>,
}

/// A label's place: the cell its text starts in, and the text shown.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Placed {
    pub(crate) at: (u16, u16),
    pub(crate) text: String,
}

/// The cell of a world point on a canvas of `size` cells showing `x` and
/// `y` (ratatui's canvas puts its labels there too); none when outside.
pub(crate) fn cell(
    p: (f64, f64),
    x: [f64; 2],
    y: [f64; 2],
    size: (u16, u16),
) -> Option<(i32, i32)> {
    let inside = (x[0]..=x[1]).contains(&p.0) && (y[0]..=y[1]).contains(&p.1);
    let (w, h) = (x[1] - x[0], y[1] - y[0]);
    if !inside || w <= 0.0 || h <= 0.0 || size.0 == 0 || size.1 == 0 {
        return None;
    }
    let col = (p.0 - x[0]) * f64::from(size.0 - 1) / w;
    let row = (y[1] - p.1) * f64::from(size.1 - 1) / h;
    Some((col as i32, row as i32))
}

/// Places `wanted` in order within an area of `size` cells; each gets its
/// place, or `None` when it is left out.
pub fn place(wanted: &[Wanted], size: (u16, u16)) -> Vec<Option<Placed>> {
    let mut taken = Taken::new(size);
    let mut placed_so_far: Vec<Option<Placed>> = Vec::with_capacity(wanted.len());
    for w in wanted {
        let companion_missing = w
            .with
            .is_some_and(|i| placed_so_far.get(i).is_none_or(Option::is_none));
        let placed = (!companion_missing).then(|| {
            let placed = if w.fixed {
                taken
                    .fits(w.at, w.text.chars().count())
                    .then(|| (w.at, w.text.to_owned()))
            } else {
                shortenings(w.text).find_map(|text| {
                    let n = text.chars().count();
                    candidates(w.at, n)
                        .find(|&at| taken.fits(at, n))
                        .map(|at| (at, text))
                })
            };
            let (at, text) = placed?;
            taken.take(at, text.chars().count());
            Some(Placed {
                at: (at.0 as u16, at.1 as u16),
                text,
            })
        });
        placed_so_far.push(placed.flatten());
    }
    placed_so_far
}

/// Where a name of `n` characters asked at `at` may start, best first:
/// there, a row above or below, left of it (past a marker just before it),
/// then the same a little further out.
fn candidates(at: (i32, i32), n: usize) -> impl Iterator<Item = (i32, i32)> {
    let (c, r) = at;
    let left = c - n as i32 - 3;
    (0..3).flat_map(move |ring| {
        let d = 1 + ring;
        let (right, left) = (c + 3 * ring, left - 3 * ring);
        [
            (right, r),
            (c, r - d),
            (c, r + d),
            (left, r),
            (left, r - d),
            (left, r + d),
        ]
    })
}

/// The text, then ever shorter cuts of it ending in "…", down to three
/// characters.
fn shortenings(text: &str) -> impl Iterator<Item = String> + '_ {
    let n = text.chars().count();
    std::iter::once(text.to_owned()).chain(
        (2..n.saturating_sub(1))
            .rev()
            .map(move |keep| text.chars().take(keep).chain(['…']).collect()),
    )
}

/// The cells labels already hold.
struct Taken {
    size: (u16, u16),
    cells: Vec<bool>,
}

impl Taken {
    fn new(size: (u16, u16)) -> Self {
        Self {
            size,
            cells: vec![false; usize::from(size.0) * usize::from(size.1)],
        }
    }

    fn index(&self, col: i32, row: i32) -> Option<usize> {
        let inside = (0..i32::from(self.size.0)).contains(&col)
            && (0..i32::from(self.size.1)).contains(&row);
        inside.then(|| row as usize * usize::from(self.size.0) + col as usize)
    }

    /// Whether `n` cells from `at` are inside and free.
    fn fits(&self, at: (i32, i32), n: usize) -> bool {
        (0..n as i32).all(|i| self.index(at.0 + i, at.1).is_some_and(|k| !self.cells[k]))
    }

    fn take(&mut self, at: (i32, i32), n: usize) {
        for i in 0..n as i32 {
            if let Some(k) = self.index(at.0 + i, at.1) {
                self.cells[k] = true;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn name(at: (i32, i32), text: &str) -> Wanted<'_> {
        Wanted {
            at,
            text,
            fixed: false,
            with: None,
        }
    }

    fn marker(at: (i32, i32), text: &str) -> Wanted<'_> {
        Wanted {
            at,
            text,
            fixed: true,
            with: None,
        }
    }

    #[test]
    fn two_names_at_one_place_go_there_and_above() {
        let placed = place(&[name((10, 5), "lamp"), name((10, 5), "lamp")], (40, 10));
        assert_eq!(placed[0].as_ref().unwrap().at, (10, 5));
        assert_eq!(placed[1].as_ref().unwrap().at, (10, 4));
    }

    #[test]
    fn a_marker_keeps_its_cell_and_names_avoid_it() {
        // The eye's marker at (3, 2), its name asked two right of it. A
        // name asked at the marker's cell (3, 2) cannot go there, nor above
        // (row 1 is free: it goes there).
        let placed = place(
            &[
                marker((3, 2), "◉"),
                name((5, 2), "eye"),
                name((3, 2), "lamp"),
            ],
            (20, 5),
        );
        assert_eq!(placed[0].as_ref().unwrap().at, (3, 2));
        assert_eq!(placed[1].as_ref().unwrap().at, (5, 2));
        assert_eq!(placed[2].as_ref().unwrap().at, (3, 1));
        // On one row, the name goes left of the marker, ending two before
        // the asked cell: 3 - 4 - 3 = -4 is outside, so further right:
        // 3 + 3 = 6 is inside the eye's name (5..8), and 9 is free.
        let row = place(
            &[
                marker((3, 0), "◉"),
                name((5, 0), "eye"),
                name((3, 0), "lamp"),
            ],
            (20, 1),
        );
        assert_eq!(row[2].as_ref().unwrap().at, (9, 0));
        // A second marker on a taken cell is left out.
        let two = place(&[marker((3, 2), "◉"), marker((3, 2), "☼")], (20, 5));
        assert_eq!(two[1], None);
    }

    #[test]
    fn a_name_with_no_room_is_shortened_then_left_out() {
        // One row of 8 cells: "sphere" (6) asked at column 2 fits there; for
        // a second, even "sp…" has no room: columns 0 and 1 are free but
        // only 2 wide, and there is no other row.
        let placed = place(&[name((2, 0), "sphere"), name((2, 0), "sphere")], (8, 1));
        assert_eq!(placed[0].as_ref().unwrap().at, (2, 0));
        assert_eq!(placed[1], None);
        // With a row below, the second goes there whole.
        let placed = place(&[name((2, 0), "sphere"), name((2, 0), "sphere")], (8, 2));
        assert_eq!(placed[1].as_ref().unwrap().at, (2, 1));
        // Cut to fit: in 6 columns, "sphere" at 2 would end at 8: "sph…" fits.
        let cut = place(&[name((2, 0), "sphere")], (6, 1));
        assert_eq!(cut[0].as_ref().unwrap().text, "sph…");
    }

    #[test]
    fn no_two_placed_labels_share_a_cell() {
        let texts = ["eye", "lamp", "key light", "ball", "floor", "glass"];
        let wanted: Vec<_> = texts.iter().map(|t| name((6, 3), t)).collect();
        let placed: Vec<Placed> = place(&wanted, (24, 7)).into_iter().flatten().collect();
        let mut cells = std::collections::HashSet::new();
        for p in &placed {
            for i in 0..p.text.chars().count() as u16 {
                assert!(cells.insert((p.at.0 + i, p.at.1)), "{placed:?}");
            }
        }
        assert_eq!(placed.len(), texts.len(), "room for all: {placed:?}");
    }

    #[test]
    fn a_name_that_goes_with_its_marker_is_left_out_with_it() {
        // A ring's "passed by" on the eye's cell: the ring (a marker) is
        // left out, and so is its name, which would name the eye's cell;
        // with the ring placed elsewhere, its name is placed too.
        let passed = |at| Wanted {
            at,
            text: "passed by",
            fixed: false,
            with: Some(1),
        };
        let hidden = place(
            &[marker((3, 2), "◉"), marker((3, 2), "○"), passed((5, 2))],
            (20, 5),
        );
        assert_eq!(hidden[1], None);
        assert_eq!(hidden[2], None);
        let shown = place(
            &[marker((3, 2), "◉"), marker((8, 2), "○"), passed((10, 2))],
            (20, 5),
        );
        assert_eq!(shown[2].as_ref().unwrap().at, (10, 2));
    }

    #[test]
    fn cells_match_the_canvas() {
        // x 0..10 over 11 columns: one column per unit; y 0..4 over 5 rows,
        // row 0 at the top.
        let at = |x, y| cell((x, y), [0.0, 10.0], [0.0, 4.0], (11, 5));
        assert_eq!(at(0.0, 4.0), Some((0, 0)));
        assert_eq!(at(10.0, 0.0), Some((10, 4)));
        assert_eq!(at(3.5, 2.0), Some((3, 2)));
        assert_eq!(at(11.0, 2.0), None);
    }
}
