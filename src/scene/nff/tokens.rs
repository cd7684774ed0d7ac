//! The NFF tokenizer: whitespace-separated words with their byte spans, and
//! the readers of each entity's numbers, so every error names line and column.

use std::ops::Range;
use std::path::Path;

use glam::DVec3;

use super::*;

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
        let pos = if text.starts_with('\u{feff}') {
            '\u{feff}'.len_utf8()
        } else {
            0
        };
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

    pub(super) fn number(&mut self, what: impl FnOnce() -> String) -> Result<f64, SceneError> {
        Ok(self.number_token(what)?.0)
    }

    /// A finite number >= 0 (colours and material coefficients).
    pub(super) fn non_negative(&mut self, what: impl Fn() -> String) -> Result<f64, SceneError> {
        let (value, token) = self.number_token(&what)?;
        if value < 0.0 {
            return Err(self.error(
                token.span(),
                format!("{} must be >= 0, got `{}`", what(), token.text),
            ));
        }
        Ok(value)
    }

    /// Three numbers; `what` names each by its component name.
    pub(super) fn vec3(
        &mut self,
        names: [&str; 3],
        what: impl Fn(&str) -> String,
    ) -> Result<DVec3, SceneError> {
        let x = self.number(|| what(names[0]))?;
        let y = self.number(|| what(names[1]))?;
        let z = self.number(|| what(names[2]))?;
        Ok(DVec3::new(x, y, z))
    }

    /// A `p`/`pp` vertex count: a positive integer.
    pub(super) fn count(&mut self, what: &str) -> Result<usize, SceneError> {
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
    pub(super) fn view(&mut self, keyword: Token) -> Result<View, SceneError> {
        let mut view = View {
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
                    view.from = Some(self.vec3(XYZ, |c| format!("the viewpoint's `from` ({c})"))?)
                }
                "at" => view.at = Some(self.vec3(XYZ, |c| format!("the viewpoint's `at` ({c})"))?),
                "up" => view.up = Some(self.vec3(XYZ, |c| format!("the viewpoint's `up` ({c})"))?),
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
        let red = self.non_negative(|| "the material's colour (red)".into())?;
        let green = self.non_negative(|| "the material's colour (green)".into())?;
        let blue = self.non_negative(|| "the material's colour (blue)".into())?;
        let color = Color::new(red, green, blue);
        let kd = self.non_negative(|| "the material's Kd".into())?;
        let ks = self.non_negative(|| "the material's Ks".into())?;
        let shininess = self.non_negative(|| "the material's Shine".into())?;
        let (kt, kt_token) = self.number_token(|| "the material's T".into())?;
        if !(0.0..=1.0).contains(&kt) {
            return Err(self.error(
                kt_token.span(),
                format!(
                    "the material's T must be between 0 and 1, got `{}`",
                    kt_token.text
                ),
            ));
        }
        let (ior, ior_token) = self.number_token(|| "the material's index of refraction".into())?;
        let ior = if kt > 0.0 {
            if ior <= 0.0 {
                return Err(self.error(
                    ior_token.span(),
                    format!(
                        "f {index}: a transmitting material (T = {kt}) needs an index of refraction > 0, got {ior}"
                    ),
                ));
            }
            ior
        } else if ior <= 0.0 {
            // Opaque: the SPD writes ior 0, which means nothing; store air's.
            1.0
        } else {
            ior
        };
        Ok(Material {
            name: format!("f {index}"),
            color,
            kd,
            ks,
            shininess,
            kt,
            ior,
            ka: 1.0,
            specular: None,
        })
    }
}
