//! The student's image: a PNG read into 8-bit RGB, saying what was converted
//! on the way (alpha, 16 bits, grey), and refusing what is not a usable PNG
//! with a message that names the file.

use std::io::{BufRead, BufReader, Read, Seek};
use std::path::Path;

use anyhow::{Context, Result, anyhow, bail};
use image::{ColorType, DynamicImage, ImageDecoder, ImageFormat, ImageReader, Limits, RgbImage};

use super::png_chunks::{self, MAX_ICC_PROFILE, Refusal};
use raystep_engine::input_file::{self, Cap};
use raystep_engine::record::count;
use raystep_engine::scene::check_image_size;

/// The largest image compared, in pixels (2048 x 2048, or 4096 x 1024, ...):
/// a comparison keeps about 90 bytes per pixel at once (BENCHMARKS.md), so
/// this fits in well under 1 GB. Renders may be larger; comparisons of them
/// would take gigabytes and minutes.
pub(crate) const MAX_PIXELS: u64 = 2048 * 2048;

/// The most the PNG decoder may allocate: the largest image compared at 16
/// bits in four channels (8 bytes a pixel), and the ancillary chunks (an
/// ICC profile, text) beside it.
pub(crate) const MAX_DECODER_BYTES: u64 = MAX_PIXELS * 8 + MAX_ICC_PROFILE;

/// The eight bytes every PNG file starts with.
const PNG_SIGNATURE: [u8; 8] = [0x89, b'P', b'N', b'G', b'\r', b'\n', 0x1a, b'\n'];

/// A student's render, as 8-bit RGB.
pub struct StudentImage {
    pub image: RgbImage,
    /// What was converted to make it 8-bit RGB, for the report.
    pub notes: Vec<String>,
}

/// The largest student image read: what a PNG of the largest size compared
/// (`MAX_PIXELS`) takes stored uncompressed at 16-bit RGBA, 8 bytes a pixel,
/// an ICC profile stored uncompressed, and 1 MiB for other chunks.
pub(crate) const IMAGE_CAP: Cap = Cap {
    bytes: 8 * MAX_PIXELS + MAX_ICC_PROFILE + (1 << 20),
    of: "a student's PNG",
};

/// Reads `path`, which must be a PNG no larger than raystep renders: a
/// regular file (a FIFO or a device is refused, never waited on) within
/// `IMAGE_CAP`.
pub fn load(path: &Path) -> Result<StudentImage> {
    let name = path.display().to_string();
    let file = input_file::open(path, "", IMAGE_CAP)?;
    read(BufReader::new(file), &name)
}

/// Reads a PNG from `reader`; `name` names it in messages. The signature is
/// checked first, then the size in the header and the ICC profile's, then
/// the pixels are decoded, the decoder's allocations capped.
pub fn read(mut reader: impl BufRead + Seek, name: &str) -> Result<StudentImage> {
    let mut signature = Vec::with_capacity(PNG_SIGNATURE.len());
    (&mut reader)
        .take(PNG_SIGNATURE.len() as u64)
        .read_to_end(&mut signature)
        .with_context(|| format!("cannot read {name}"))?;
    if signature != PNG_SIGNATURE {
        bail!("{name} is not a PNG image (it does not start with the PNG signature)");
    }
    let walked = png_chunks::walk(&mut reader, |width, height| {
        // An empty size is the decoder's to name ("invalid image
        // dimensions"), as it always was; only what is too large is
        // refused before it.
        if width == 0 || height == 0 {
            return Ok(());
        }
        check_compared_size(width, height)
    })
    .with_context(|| format!("cannot read {name}"))?;
    match walked {
        Ok(()) => {}
        Err(Refusal::Size(why)) => bail!("{name}: {why}"),
        Err(Refusal::IccProfile) => bail!(
            "{name}: its ICC profile (iCCP chunk) inflates to more than {} MiB: \
             save the image without a colour profile, or with sRGB's",
            MAX_ICC_PROFILE >> 20
        ),
    }
    reader
        .rewind()
        .with_context(|| format!("cannot read {name}"))?;
    let mut limits = Limits::default();
    limits.max_alloc = Some(MAX_DECODER_BYTES);
    let mut png = ImageReader::with_format(reader, ImageFormat::Png);
    png.limits(limits);
    let decoder = png
        .into_decoder()
        .map_err(|e| anyhow!("{name} is not a readable PNG: {}", decoder_said(&e)))?;
    let (width, height) = decoder.dimensions();
    check_compared_size(width, height).map_err(|e| anyhow::anyhow!("{name}: {e}"))?;
    let color = decoder.color_type();
    let image = DynamicImage::from_decoder(decoder)
        .map_err(|e| anyhow!("{name} is a damaged or truncated PNG: {}", decoder_said(&e)))?;
    let notes = conversion_notes(color, &image);
    Ok(StudentImage {
        image: image.into_rgb8(),
        notes,
    })
}

/// Refuses what raystep does not render, then what it does not compare.
pub(crate) fn check_compared_size(width: u32, height: u32) -> Result<(), String> {
    check_image_size(width, height)?;
    if u64::from(width) * u64::from(height) > MAX_PIXELS {
        return Err(format!(
            "image size {width}x{height} is too large to compare: at most {MAX_PIXELS} pixels \
             (2048 x 2048) are compared"
        ));
    }
    Ok(())
}

/// The decoder's own reason in the house style of messages: its innermost
/// cause only ("Format error decoding Png: X" repeats X as its source), the
/// first letter lower case unless it starts an acronym ("IDAT", "CRC"), no
/// full stop.
fn decoder_said(error: &image::ImageError) -> String {
    let mut cause: &dyn std::error::Error = error;
    while let Some(inner) = cause.source() {
        cause = inner;
    }
    let said = cause.to_string();
    let said = said.trim_end().trim_end_matches('.');
    let mut chars = said.chars();
    match (chars.next(), chars.next()) {
        (Some(first), Some(second)) if !second.is_uppercase() => first
            .to_lowercase()
            .chain(said[first.len_utf8()..].chars())
            .collect(),
        _ => said.to_string(),
    }
}

/// What turning an image of `color` into 8-bit RGB changes.
fn conversion_notes(color: ColorType, image: &DynamicImage) -> Vec<String> {
    let mut notes = Vec::new();
    if color.bytes_per_pixel() / color.channel_count() > 1 {
        notes.push("16 bits per channel: rounded to 8 bits".to_string());
    }
    if !color.has_color() {
        notes.push("a grey image: read as red = green = blue".to_string());
    }
    if color.has_alpha() {
        let see_through = image.to_rgba8().pixels().filter(|p| p.0[3] < 255).count();
        notes.push(if see_through == 0 {
            "an alpha channel, opaque everywhere: ignored".to_string()
        } else {
            format!(
                "an alpha channel: ignored ({} not opaque)",
                count(see_through as u64, "pixel is", "pixels are")
            )
        });
    }
    notes
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::{ImageBuffer, LumaA, Rgba};

    fn write(dir: &Path, name: &str, image: DynamicImage) -> std::path::PathBuf {
        let path = dir.join(name);
        image.save(&path).unwrap();
        path
    }

    /// A PNG chunk's CRC-32 over its type and data (polynomial 0xEDB88320).
    fn crc(kind: &[u8], data: &[u8]) -> u32 {
        let mut crc = !0u32;
        for &byte in kind.iter().chain(data) {
            crc ^= byte as u32;
            for _ in 0..8 {
                crc = if crc & 1 == 1 {
                    (crc >> 1) ^ 0xEDB8_8320
                } else {
                    crc >> 1
                };
            }
        }
        !crc
    }

    #[test]
    fn the_decoders_reason_is_said_once_in_lower_case() {
        // "IEND" with no data has the CRC every PNG ends with.
        assert_eq!(crc(b"IEND", &[]), 0xAE42_6082);
        let error = image::ImageError::Decoding(image::error::DecodingError::new(
            ImageFormat::Png.into(),
            "Chunk length wrong.",
        ));
        assert_eq!(decoder_said(&error), "chunk length wrong");
        let error = image::ImageError::Decoding(image::error::DecodingError::new(
            ImageFormat::Png.into(),
            "IDAT or fDAT chunk is missing.",
        ));
        assert_eq!(decoder_said(&error), "IDAT or fDAT chunk is missing");
    }

    #[test]
    fn alpha_and_sixteen_bits_are_converted_and_said() {
        let dir = tempfile::tempdir().unwrap();
        // 16-bit 65535 becomes 255; the one pixel with alpha 0 is counted.
        let rgba16 = ImageBuffer::from_fn(2, 1, |x, _| {
            Rgba([65535u16, 0, 0, if x == 0 { 65535 } else { 0 }])
        });
        let loaded = load(&write(
            dir.path(),
            "a.png",
            DynamicImage::ImageRgba16(rgba16),
        ))
        .unwrap();
        assert_eq!(loaded.image.get_pixel(0, 0).0, [255, 0, 0]);
        assert_eq!(
            loaded.notes,
            [
                "16 bits per channel: rounded to 8 bits",
                "an alpha channel: ignored (1 pixel is not opaque)"
            ]
        );
        let grey = ImageBuffer::from_pixel(1, 1, LumaA([100u8, 255]));
        let loaded = load(&write(dir.path(), "g.png", DynamicImage::ImageLumaA8(grey))).unwrap();
        assert_eq!(loaded.image.get_pixel(0, 0).0, [100, 100, 100]);
        assert_eq!(loaded.notes.len(), 2);
    }

    #[test]
    fn what_is_not_a_whole_png_is_refused_by_name() {
        let dir = tempfile::tempdir().unwrap();
        let text = dir.path().join("notes.png");
        std::fs::write(&text, "not an image").unwrap();
        let error = load(&text).err().unwrap().to_string();
        assert!(error.contains("notes.png is not a PNG"), "{error}");

        let whole = write(
            dir.path(),
            "whole.png",
            DynamicImage::ImageRgb8(RgbImage::from_fn(64, 64, |x, y| {
                image::Rgb([x as u8 * 4, y as u8 * 4, 7])
            })),
        );
        let bytes = std::fs::read(&whole).unwrap();
        let cut = dir.path().join("cut.png");
        std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
        let error = format!("{:#}", load(&cut).err().unwrap());
        assert!(error.contains("cut.png"), "{error}");

        // A header with bit depth 7, which PNG does not have: the
        // decoder's reason once, in lower case, without its "Format error
        // decoding Png:" prefix or a full stop.
        let mut seven = PNG_SIGNATURE.to_vec();
        let header = [0, 0, 0, 2, 0, 0, 0, 2, 7, 2, 0, 0, 0];
        seven.extend([0, 0, 0, 13]);
        seven.extend(b"IHDR");
        seven.extend(header);
        seven.extend(crc(b"IHDR", &header).to_be_bytes());
        let file = dir.path().join("seven.png");
        std::fs::write(&file, seven).unwrap();
        assert_eq!(
            format!("{:#}", load(&file).err().unwrap()),
            format!(
                "{} is not a readable PNG: invalid bit depth 7",
                file.display()
            )
        );

        let missing = format!("{:#}", load(&dir.path().join("none.png")).err().unwrap());
        assert!(
            missing.contains("cannot read") && missing.contains("none.png"),
            "{missing}"
        );
    }
}
