//! The NFF tokenizer: whitespace-separated words with their byte spans, and
//! the readers of each entity's numbers, so every error names line and column.

use std::ops::Range;
use std::path::Path;

use glam::DVec3;

use super::*;
use crate::scene::limits::{Bounds, COEFFICIENT, COLOR, COORDINATE, IOR, SHININESS, TRANSMISSION};

/// One whitespace-separated word of the file and where it starts.
#[derive(Clone, Copy, Debug)]
pub(super) struct Token<'a> {
    pub(super) text: &'a str,
    start: usize,
}

impl Token<'_> {
    pub(super) fn span(&self) -> Range<usize> {
        self.start..self.start + self.text.len()
    }
}

/// A hand-written tokenizer over the text, with the readers of each entity's parts.
pub(super) struct Parser<'a> {
    path: &'a Path,
    text: &'a str,
    pos: usize,
    /// The end of the last token read: where "end of the file" errors point.
    last_end: usize,
}

impl<'a> Parser<'a> {
    pub(super) fn new(path: &'a Path, text: &'a str) -> Self {
        let pos = crate::input_file::byte_order_mark(text.as_bytes());
        Self {
            path,
            text,
            pos,
            last_end: pos,
        }
    }

    pub(super) fn error(&self, span: Range<usize>, message: impl Into<String>) -> SceneError {
        SceneError::at(self.path, self.text, span, message)
    }

    /// The next token, without consuming it. Tokens end at ASCII whitespace or
    /// `#`, so every span lies on character boundaries.
    pub(super) fn peek(&mut self) -> Option<Token<'a>> {
        let bytes = self.text.as_bytes();
        loop {
            while self.pos < bytes.len() && bytes[self.pos].is_ascii_whitespace() {
                self.pos += 1;
            }
            if self.pos < bytes.len() && bytes[self.pos] == b'#' {
                while self.pos < bytes.len() && bytes[self.pos] != b'\n' {
                    self.pos += 1;
                }
            } else {
                break;
            }
        }
        let start = self.pos;
        let mut end = start;
        while end < bytes.len() && !bytes[end].is_ascii_whitespace() && bytes[end] != b'#' {
            end += 1;
        }
        (end > start).then(|| Token {
            text: &self.text[start..end],
            start,
        })
    }

    pub(super) fn next(&mut self) -> Option<Token<'a>> {
        let token = self.peek()?;
        self.pos = token.start + token.text.len();
        self.last_end = self.pos;
        Some(token)
    }

    /// The next token as a finite number; `what` names it in messages.
    pub(super) fn number_token(
        &mut self,
        what: impl FnOnce() -> String,
    ) -> Result<(f64, Token<'a>), SceneError> {
        let Some(token) = self.next() else {
            let end = self.last_end;
            return Err(self.error(
                end..end,
                format!(
                    "expected a number for {}, found the end of the file",
                    what()
                ),
            ));
        };
        match token.text.parse::<f64>() {
            Ok(value) if value.is_finite() => Ok((value, token)),
            Ok(_) => Err(self.error(
                token.span(),
                format!("{} must be a finite number, got `{}`", what(), token.text),
            )),
            Err(_) => Err(self.error(
                token.span(),
                format!("expected a number for {}, found `{}`", what(), token.text),
            )),
        }
    }

    pub fn number(&mut self, what: impl FnOnce() -> String) -> Result<f64, SceneError> {
        Ok(self.number_token(what)?.0)
    }

    /// A number within `bounds` (MODEL §4, `limits`).
    pub(super) fn bounded(
        &mut self,
        bounds: Bounds,
        what: impl Fn() -> String,
    ) -> Result<f64, SceneError> {
        let (value, token) = self.number_token(&what)?;
        bounds.check(value).map_err(|reason| {
            self.error(
                token.span(),
                format!("{} {reason}, got `{}`", what(), token.text),
            )
        })?;
        Ok(value)
    }

    /// A number whose absolute value is 0 (when `zero` allows it) or within
    /// `bounds`: NFF radii, negative for "inside visible".
    pub(super) fn radius(
        &mut self,
        bounds: Bounds,
        zero: bool,
        what: impl Fn() -> String,
    ) -> Result<f64, SceneError> {
        let (value, token) = self.number_token(&what)?;
        let magnitude = value.abs();
        if (zero && magnitude == 0.0) || bounds.check(magnitude).is_ok() {
            return Ok(magnitude);
        }
        let reason = bounds.check(magnitude).unwrap_err();
        let zero = if zero { " (or be 0)" } else { "" };
        Err(self.error(
            token.span(),
            format!(
                "{} {reason} in absolute value{zero}, got `{}`",
                what(),
                token.text
            ),
        ))
    }

    /// Three numbers within `bounds`; `what` names each by its component name.
    pub(super) fn vec3(
        &mut self,
        names: [&str; 3],
        bounds: Bounds,
        what: impl Fn(&str) -> String,
    ) -> Result<DVec3, SceneError> {
        let x = self.bounded(bounds, || what(names[0]))?;
        let y = self.bounded(bounds, || what(names[1]))?;
        let z = self.bounded(bounds, || what(names[2]))?;
        Ok(DVec3::new(x, y, z))
    }

    /// A `p`/`pp` vertex count: a positive integer.
    pub fn count(&mut self, what: &str) -> Result<usize, SceneError> {
        let (_, token) = self.number_token(|| what.to_string())?;
        match token.text.parse::<usize>() {
            Ok(count) if count > 0 => Ok(count),
            // Too large to hold: the vertices will run out first and say so.
            Err(_) if token.text.bytes().all(|b| b.is_ascii_digit()) => Ok(usize::MAX),
            _ => Err(self.error(
                token.span(),
                format!("{what} must be a positive integer, got `{}`", token.text),
            )),
        }
    }

    /// A side of the image in pixels: a whole number (its range is checked later).
    pub(super) fn pixels(&mut self, what: &str) -> Result<u32, SceneError> {
        let (value, token) = self.number_token(|| what.to_string())?;
        if value.fract() != 0.0 || !(0.0..=u32::MAX as f64).contains(&value) {
            return Err(self.error(
                token.span(),
                format!(
                    "{what} must be a whole number of pixels, got `{}`",
                    token.text
                ),
            ));
        }
        Ok(value as u32)
    }

    /// The viewpoint's keyword groups after `v`, in any order, each at most once.
    pub(super) fn view(&mut self, keyword: Token) -> Result<Viewpoint, SceneError> {
        let mut view = Viewpoint {
            keyword: keyword.span(),
            from: None,
            at: None,
            up: None,
            angle: None,
            resolution: None,
        };
        let mut hither = false;
        while let Some(token) = self.peek() {
            let given = match token.text {
                "from" => view.from.is_some(),
                "at" => view.at.is_some(),
                "up" => view.up.is_some(),
                "angle" => view.angle.is_some(),
                "hither" => hither,
                "resolution" => view.resolution.is_some(),
                _ => break,
            };
            if given {
                return Err(self.error(
                    token.span(),
                    format!("the viewpoint gives `{}` twice", token.text),
                ));
            }
            self.next();
            match token.text {
                "from" => {
                    view.from = Some(
                        self.vec3(XYZ, COORDINATE, |c| format!("the viewpoint's `from` ({c})"))?,
                    )
                }
                "at" => {
                    view.at =
                        Some(self.vec3(XYZ, COORDINATE, |c| format!("the viewpoint's `at` ({c})"))?)
                }
                "up" => {
                    view.up =
                        Some(self.vec3(XYZ, COORDINATE, |c| format!("the viewpoint's `up` ({c})"))?)
                }
                "angle" => {
                    let (angle, token) = self.number_token(|| "the viewpoint's `angle`".into())?;
                    if angle <= 0.0 || angle >= 180.0 {
                        return Err(self.error(
                            token.span(),
                            format!("the viewpoint's `angle` must be between 0 and 180 degrees (exclusive), got {angle}"),
                        ));
                    }
                    view.angle = Some(angle);
                }
                "hither" => {
                    // Read and ignored (MODEL §2).
                    self.number(|| "the viewpoint's `hither`".into())?;
                    hither = true;
                }
                _ => {
                    let width = self.pixels("the viewpoint's resolution width")?;
                    let height = self.pixels("the viewpoint's resolution height")?;
                    view.resolution = Some((width, height, token.start..self.last_end));
                }
            }
        }
        Ok(view)
    }

    /// `f r g b Kd Ks Shine T ior`, the `index`-th `f` line.
    pub(super) fn material(&mut self, index: usize) -> Result<Material, SceneError> {
        let color = self.vec3(RGB, COLOR, |c| format!("the material's colour ({c})"))?;
        let kd = self.bounded(COEFFICIENT, || "the material's Kd".into())?;
        let ks = self.bounded(COEFFICIENT, || "the material's Ks".into())?;
        let shininess = self.bounded(SHININESS, || "the material's Shine".into())?;
        let kt = self.bounded(TRANSMISSION, || "the material's T".into())?;
        let (ior, ior_token) = self.number_token(|| "the material's index of refraction".into())?;
        // The SPD writes ior 0 for opaque materials, where it is never used
        // (MODEL §5): stored as air's. Any other value must be an index.
        if kt == 0.0 && ior == 0.0 {
            return Ok(material(index, color, [kd, ks, shininess, kt], 1.0));
        }
        IOR.check(ior).map_err(|reason| {
            let opaque = if kt == 0.0 {
                " (or be 0 where T = 0)"
            } else {
                ""
            };
            self.error(
                ior_token.span(),
                format!(
                    "f {index}: the material's index of refraction {reason}{opaque}, got `{}`",
                    ior_token.text
                ),
            )
        })?;
        Ok(material(index, color, [kd, ks, shininess, kt], ior))
    }
}

/// The `index`-th `f` line's material, from its numbers.
fn material(index: usize, color: Color, [kd, ks, shininess, kt]: [f64; 4], ior: f64) -> Material {
    Material {
        name: format!("f {index}"),
        color,
        kd,
        ks,
        shininess,
        kt,
        ior,
        ka: 1.0,
        specular: None,
        reflects: true,
        ..Material::default_white()
    }
}
