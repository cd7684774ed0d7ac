//! The pixels and paths a ray log has named so far, each with its line, to
//! name a repeat ("logged twice: first on line N") and to tell afterwards
//! what was logged. A log of a million lines names a million of them, so
//! each takes about 17 bytes: its pixel and path packed exactly into a
//! `u64`, an index into those in an open-addressing table, and its line
//! kept as runs of consecutive lines. (A map from pixel and `RayPath` took
//! about 200 bytes a ray with the path's allocation.) The few that do not
//! pack (a path deeper than the spare bits, a huge image) go to a plain map,
//! their paths spelled a bit a step (`Spelled`: a runaway recursion logs
//! paths thousands of steps deep, 16 bytes a step as `RayPath`s): nothing
//! is hashed into fewer bits than it has, so no two rays collide.

use std::collections::HashMap;

use super::path::{RayPath, Step};

pub(crate) struct SeenRays {
    packing: Packing,
    /// The packed pixel and path of each ray, in the order read: a ray's
    /// place here is its ordinal.
    keys: Vec<u64>,
    /// Ordinals into `keys`, placed by their key's hash (linear probing);
    /// `EMPTY` where none is.
    slots: Vec<u32>,
    lines: Lines,
    /// The rays whose pixel and path do not pack, with their lines.
    unpacked: HashMap<((u32, u32), Spelled), usize>,
}

/// A path a bit a reflected or transmitted step, eight to a byte, after
/// their count, then its shadow ray's light if it has one: one spelling
/// per path, an eighth of a byte a step.
#[derive(PartialEq, Eq, Hash)]
struct Spelled(Box<[u8]>);

impl Spelled {
    fn of(path: &RayPath) -> Self {
        let mut bytes = Vec::with_capacity(8 + path.steps.len() / 8 + 10);
        let branches = path.branches();
        bytes.extend_from_slice(&(branches as u64).to_le_bytes());
        for chunk in path.steps[..branches].chunks(8) {
            let byte = chunk.iter().enumerate().fold(0u8, |byte, (i, step)| {
                byte | u8::from(*step == Step::Transmitted) << i
            });
            bytes.push(byte);
        }
        if let Some(Step::Shadow(light)) = path.steps.last() {
            bytes.push(1);
            bytes.extend_from_slice(&(*light as u64).to_le_bytes());
        }
        Self(bytes.into())
    }
}

const EMPTY: u32 = u32::MAX;

impl SeenRays {
    /// For the logs of an image of `width` x `height` pixels lit by
    /// `lights` lights.
    pub(crate) fn new(width: u32, height: u32, lights: usize) -> Self {
        Self {
            packing: Packing::new(width, height, lights),
            keys: Vec::new(),
            slots: Vec::new(),
            lines: Lines::default(),
            unpacked: HashMap::new(),
        }
    }

    pub(crate) fn is_empty(&self) -> bool {
        self.keys.is_empty() && self.unpacked.is_empty()
    }

    /// The line `pixel` and `path` were first read on, if they were.
    pub(crate) fn first_line(&self, pixel: (u32, u32), path: &RayPath) -> Option<usize> {
        if let Some(key) = self.packing.pack(pixel, path)
            && let Some(slot) = self.find(key)
        {
            return Some(self.lines.get(self.slots[slot]));
        }
        // The rays that did not pack, and any read after the ordinals ran
        // out; mostly none, so no path is cloned to look.
        if self.unpacked.is_empty() {
            return None;
        }
        self.unpacked.get(&(pixel, Spelled::of(path))).copied()
    }

    /// Notes `pixel` and `path`, read on `line` (after every line before
    /// it), which `first_line` has not found.
    pub(crate) fn insert(&mut self, pixel: (u32, u32), path: &RayPath, line: usize) {
        let key = self.packing.pack(pixel, path);
        let ordinal = u32::try_from(self.keys.len()).ok().filter(|&o| o < EMPTY);
        let (Some(key), Some(ordinal)) = (key, ordinal) else {
            self.unpacked.insert((pixel, Spelled::of(path)), line);
            return;
        };
        // At most three quarters full, so that probes stay short.
        if (self.keys.len() + 1) * 4 > self.slots.len() * 3 {
            self.grow();
        }
        self.keys.push(key);
        self.lines.push(ordinal, line);
        let slot = self.free_slot(key);
        self.slots[slot] = ordinal;
    }

    /// The slot holding `key`'s ordinal.
    fn find(&self, key: u64) -> Option<usize> {
        if self.slots.is_empty() {
            return None;
        }
        let mask = self.slots.len() - 1;
        let mut slot = self.home(key);
        loop {
            match self.slots[slot] {
                EMPTY => return None,
                ordinal if self.keys[ordinal as usize] == key => return Some(slot),
                _ => slot = (slot + 1) & mask,
            }
        }
    }

    /// The first empty slot from `key`'s home.
    fn free_slot(&self, key: u64) -> usize {
        let mask = self.slots.len() - 1;
        let mut slot = self.home(key);
        while self.slots[slot] != EMPTY {
            slot = (slot + 1) & mask;
        }
        slot
    }

    /// Where `key` is looked for first: its low 4 bits (a path's light,
    /// shadow bit and last step) past a window placed by the rest (the top
    /// bits of its product with 2^64 / φ, Fibonacci hashing, which every
    /// bit moves). A pixel's rays, read together, so share a few windows
    /// of 16 slots: a cache line or two rather than a miss each; and no
    /// window is home to more than 16 keys, however a log is made.
    fn home(&self, key: u64) -> usize {
        let bits = self.slots.len().trailing_zeros();
        let window = (key >> 4).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> (64 - bits);
        (window as usize + (key & 15) as usize) & (self.slots.len() - 1)
    }

    /// Twice the slots (64 at first), every ordinal placed again.
    fn grow(&mut self) {
        let size = (self.slots.len() * 2).max(64);
        self.slots = vec![EMPTY; size];
        for (ordinal, &key) in self.keys.iter().enumerate() {
            let slot = self.free_slot(key);
            self.slots[slot] = ordinal as u32;
        }
    }
}

/// The line of each ray by its ordinal, as runs of rays on consecutive
/// lines: a log with no comment or blank line between its rays is one run.
#[derive(Default)]
struct Lines {
    /// The first ordinal of each run and its line.
    runs: Vec<(u32, usize)>,
    last: usize,
}

impl Lines {
    /// Ordinals come in order, each on a later line than the one before.
    fn push(&mut self, ordinal: u32, line: usize) {
        if self.runs.is_empty() || line != self.last + 1 {
            self.runs.push((ordinal, line));
        }
        self.last = line;
    }

    fn get(&self, ordinal: u32) -> usize {
        let run = self.runs.partition_point(|&(first, _)| first <= ordinal) - 1;
        let (first, line) = self.runs[run];
        line + (ordinal - first) as usize
    }
}

/// A pixel and path as one `u64`: the pixel's index in the image (y times
/// width, plus x) in the top bits, the path in the others: a 1 (the primary
/// ray, so that leading steps are not lost), a bit per step below it (R 0,
/// T 1), then a bit for a shadow ray and its light's index.
#[derive(Clone, Copy, Debug)]
struct Packing {
    width: u64,
    height: u64,
    /// Bits for the path: 64 less those for the pixel.
    path_bits: u32,
    /// Bits for a light's index: enough for the scene's last light.
    light_bits: u32,
}

/// The bits needed to write every number below `count`.
fn bits_below(count: u128) -> u32 {
    128 - count.saturating_sub(1).leading_zeros()
}

impl Packing {
    fn new(width: u32, height: u32, lights: usize) -> Self {
        let pixels = u128::from(width) * u128::from(height);
        Self {
            width: width.into(),
            height: height.into(),
            path_bits: 64 - bits_below(pixels),
            light_bits: bits_below(lights as u128),
        }
    }

    /// `None` when they do not fit: a pixel outside the image, a path too
    /// deep for the bits left, a light's index too large, or steps after a
    /// shadow ray (no log has them: they are refused when read).
    fn pack(&self, (x, y): (u32, u32), path: &RayPath) -> Option<u64> {
        let (x, y) = (u64::from(x), u64::from(y));
        if x >= self.width || y >= self.height {
            return None;
        }
        let leaf = match path.steps.split_last() {
            Some((Step::Shadow(light), _)) => Some(*light),
            _ => None,
        };
        let branches = &path.steps[..path.steps.len() - usize::from(leaf.is_some())];
        // The 1 for P, the steps, the shadow bit and the light's bits.
        let bits = 1 + branches.len() as u64 + 1 + u64::from(self.light_bits);
        if bits > u64::from(self.path_bits) {
            return None;
        }
        let mut code: u64 = 1;
        for step in branches {
            code = code << 1
                | match step {
                    Step::Reflected => 0,
                    Step::Transmitted => 1,
                    Step::Shadow(_) => return None,
                };
        }
        code = code << 1 | u64::from(leaf.is_some());
        let light = leaf.unwrap_or(0) as u64;
        if self.light_bits < 64 && light >> self.light_bits != 0 {
            return None;
        }
        code = code.checked_shl(self.light_bits).unwrap_or(0) | light;
        let pixel = (y * self.width + x)
            .checked_shl(self.path_bits)
            .unwrap_or(0);
        Some(pixel | code)
    }

    /// What `pack` packed: the inverse that shows it loses nothing.
    #[cfg(test)]
    fn unpack(&self, key: u64) -> ((u32, u32), RayPath) {
        let path_mask = 1u64.checked_shl(self.path_bits).map_or(u64::MAX, |b| b - 1);
        let pixel = key.checked_shr(self.path_bits).unwrap_or(0);
        let mut code = key & path_mask;
        let light = code & ((1u64 << self.light_bits) - 1);
        code >>= self.light_bits;
        let shadow = code & 1 == 1;
        code >>= 1;
        let depth = 63 - code.leading_zeros();
        let mut steps: Vec<Step> = (0..depth)
            .rev()
            .map(|i| match code >> i & 1 {
                0 => Step::Reflected,
                _ => Step::Transmitted,
            })
            .collect();
        if shadow {
            steps.push(Step::Shadow(light as usize));
        }
        let xy = ((pixel % self.width) as u32, (pixel / self.width) as u32);
        (xy, RayPath::of(steps))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn path(text: &str) -> RayPath {
        RayPath::parse(text, 1000).unwrap()
    }

    #[test]
    fn a_packed_ray_unpacks_to_itself_and_no_two_share_a_key() {
        // 512x512: 18 bits for the pixel (2^18 = 262,144 pixels), 46 for the
        // path; 3 lights: 2 bits for S0 to S2.
        let packing = Packing::new(512, 512, 3);
        assert_eq!((packing.path_bits, packing.light_bits), (46, 2));
        let deep = format!("P{}", "/T/R".repeat(21)); // 42 steps: 1+42+1+2 = 46 bits
        let mut keys = std::collections::HashSet::new();
        for text in [
            "P", "P/R", "P/T", "P/S0", "P/S2", "P/R/T/S1", "P/T/R", &deep,
        ] {
            for pixel in [(0, 0), (511, 0), (0, 511), (511, 511), (7, 300)] {
                let key = packing.pack(pixel, &path(text)).unwrap();
                assert_eq!(packing.unpack(key), (pixel, path(text)), "{text}");
                assert!(keys.insert(key), "{text} {pixel:?}: a key twice");
            }
        }
        // By hand: pixel (7, 300) is 300 * 512 + 7 = 153,607; P/R/T/S1 is
        // 1 (P), 0 (R), 1 (T), 1 (a shadow ray), 01 (light 1) = 0b101101.
        let key = packing.pack((7, 300), &path("P/R/T/S1")).unwrap();
        assert_eq!(key, (153_607 << 46) | 0b10_1101);
        // P alone is 1, then 0 (no shadow ray) and 00: 0b1000, not 0.
        assert_eq!(packing.pack((0, 0), &path("P")), Some(0b1000));
    }

    #[test]
    fn what_does_not_fit_is_not_packed() {
        let packing = Packing::new(512, 512, 3);
        let too_deep = format!("P{}/R", "/T/R".repeat(21)); // 43 steps: 47 bits
        assert_eq!(packing.pack((0, 0), &path(&too_deep)), None);
        // Light 4 needs 3 bits; no log names it with 3 lights, but the API may.
        assert_eq!(packing.pack((0, 0), &path("P/S4")), None);
        assert_eq!(packing.pack((512, 0), &path("P")), None);
        assert_eq!(packing.pack((0, 512), &path("P")), None);
        let after_shadow = RayPath {
            steps: vec![Step::Shadow(0), Step::Reflected].into(),
        };
        assert_eq!(packing.pack((0, 0), &after_shadow), None);
        // The largest image leaves no bits for a path; one pixel, all 64.
        assert_eq!(
            Packing::new(u32::MAX, u32::MAX, 1).pack((0, 0), &path("P")),
            None
        );
        let one = Packing::new(1, 1, 1);
        assert_eq!(one.path_bits, 64);
        let deepest = format!("P{}", "/T".repeat(62)); // 1+62+1+0 = 64 bits
        let key = one.pack((0, 0), &path(&deepest)).unwrap();
        assert_eq!(key, u64::MAX - 1);
        assert_eq!(one.unpack(key), ((0, 0), path(&deepest)));
    }

    #[test]
    fn a_ray_seen_is_found_with_its_line_whether_packed_or_not() {
        let mut seen = SeenRays::new(4, 3, 2);
        assert!(seen.is_empty());
        // 4x3 leaves 60 bits for a path, 2 lights 1 bit: 57 steps at most.
        let deep = format!("P{}", "/R".repeat(60));
        let rays = [
            ((0, 0), path("P"), 1),
            ((0, 0), path("P/S1"), 2),
            ((3, 2), path(&deep), 3),
            // A comment and a blank line before this one: a new run.
            ((3, 2), path("P/R/S0"), 6),
            ((1, 1), path("P"), 7),
        ];
        for (pixel, path, line) in &rays {
            assert_eq!(seen.first_line(*pixel, path), None);
            seen.insert(*pixel, path, *line);
        }
        assert!(!seen.is_empty());
        assert_eq!(seen.unpacked.len(), 1, "the deep path");
        for (pixel, path, line) in &rays {
            assert_eq!(seen.first_line(*pixel, path), Some(*line), "{path}");
        }
        assert_eq!(seen.first_line((1, 0), &path("P")), None);
        assert_eq!(seen.first_line((3, 2), &path(&format!("{deep}/T"))), None);
        assert_eq!(seen.first_line((3, 2), &path("P/R/S1")), None);
        assert_eq!(seen.first_line((9, 9), &path("P")), None, "outside");
    }

    #[test]
    fn the_table_grows_and_keeps_every_ray() {
        // 100x100 pixels, 4 paths each: 40,000 rays, the table grown from
        // 64 slots to 65,536 (40,000 is over 3/4 of 32,768); every line
        // right, nothing found that was not inserted.
        let mut seen = SeenRays::new(100, 100, 1);
        let paths = [path("P"), path("P/S0"), path("P/R"), path("P/R/S0")];
        let mut line = 0;
        for y in 0..100 {
            for x in 0..100 {
                for p in &paths {
                    line += 1;
                    seen.insert((x, y), p, line);
                }
                line += 1; // a blank line between pixels
            }
        }
        assert_eq!(seen.keys.len(), 40_000);
        assert_eq!(seen.slots.len(), 65_536);
        assert_eq!(seen.first_line((0, 0), &paths[0]), Some(1));
        // Pixel (37, 52) is the 5,237th (from 0): its rays start on line
        // 5,237 * 5 + 1; P/R is its third.
        assert_eq!(seen.first_line((37, 52), &paths[2]), Some(26_188));
        assert_eq!(seen.first_line((99, 99), &paths[3]), Some(50_000 - 1));
        assert_eq!(seen.first_line((99, 99), &path("P/T")), None);
    }
}
