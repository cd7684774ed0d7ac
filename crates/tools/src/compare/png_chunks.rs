//! A PNG's chunks walked before it is decoded: the size its header states,
//! and how far its ICC profile inflates. A decoder allocates by what the
//! file says, not by its length (a 1 MB file of 16 x 12 pixels may carry an
//! iCCP chunk that inflates to 1 GiB), so both are checked first, reading
//! chunk headers and inflating the profile into a counter, never a buffer.
//! `grade` reads a submission's size the same way, from the header alone.

use std::io::{self, BufRead, Read, Seek, SeekFrom};

use flate2::bufread::ZlibDecoder;

/// The most an ICC profile may inflate to: real profiles are a few
/// kilobytes, a printer's with large tables a few megabytes.
pub(crate) const MAX_ICC_PROFILE: u64 = 16 << 20;

/// What the walk found wrong, told by `student` with the file's name.
#[derive(Debug, PartialEq)]
pub(crate) enum Refusal {
    /// The header's size, when the compare limits refuse it.
    Size(String),
    /// The iCCP chunk inflates past `MAX_ICC_PROFILE`.
    IccProfile,
}

/// Walks the chunks after the signature up to the first IDAT: the header's
/// size goes to `check_size`, and an iCCP chunk is inflated into a
/// counter. A file that is cut short or not a PNG at all is left for the
/// decoder to name; only what the walk can refuse for sure is refused.
pub(crate) fn walk(
    reader: &mut (impl BufRead + Seek),
    check_size: impl Fn(u32, u32) -> Result<(), String>,
) -> io::Result<Result<(), Refusal>> {
    reader.seek(SeekFrom::Start(8))?;
    let mut first = true;
    while let Some((length, kind)) = chunk_header(reader)? {
        let data_starts = reader.stream_position()?;
        match &kind {
            b"IHDR" if first && length == 13 => {
                let mut size = [0u8; 8];
                if reader.read_exact(&mut size).is_err() {
                    return Ok(Ok(()));
                }
                let width = u32::from_be_bytes(size[..4].try_into().expect("4 bytes"));
                let height = u32::from_be_bytes(size[4..].try_into().expect("4 bytes"));
                if let Err(why) = check_size(width, height) {
                    return Ok(Err(Refusal::Size(why)));
                }
            }
            // The decoder refuses a file that does not start with its header.
            _ if first => return Ok(Ok(())),
            b"iCCP" if inflates_past(&mut (&mut *reader).take(length.into()), MAX_ICC_PROFILE)? => {
                return Ok(Err(Refusal::IccProfile));
            }
            b"IDAT" | b"IEND" => return Ok(Ok(())),
            _ => {}
        }
        first = false;
        // Past the data and its CRC.
        reader.seek(SeekFrom::Start(data_starts + u64::from(length) + 4))?;
    }
    Ok(Ok(()))
}

/// The size a PNG's header states, read from the signature and the IHDR
/// chunk alone (nothing else is read or inflated); `None` when the file
/// does not start with a whole, undamaged header of a non-empty size, which
/// the checked reader then names.
pub(crate) fn header_size(reader: &mut impl Read) -> io::Result<Option<(u32, u32)>> {
    // The signature, IHDR's length and type, its 13 bytes and its CRC.
    let mut start = [0u8; 8 + 8 + 13 + 4];
    match reader.read_exact(&mut start) {
        Ok(()) => {}
        Err(e) if e.kind() == io::ErrorKind::UnexpectedEof => return Ok(None),
        Err(e) => return Err(e),
    }
    let (signature, chunk) = start.split_at(8);
    let (kind_and_data, crc) = chunk[4..].split_at(4 + 13);
    let mut sum = flate2::Crc::new();
    sum.update(kind_and_data);
    if signature != b"\x89PNG\r\n\x1a\n"
        || chunk[..8] != [0, 0, 0, 13, b'I', b'H', b'D', b'R']
        || sum.sum().to_be_bytes() != crc
    {
        return Ok(None);
    }
    let width = u32::from_be_bytes(chunk[8..12].try_into().expect("4 bytes"));
    let height = u32::from_be_bytes(chunk[12..16].try_into().expect("4 bytes"));
    Ok((width > 0 && height > 0).then_some((width, height)))
}

/// The next chunk's length and type; `None` at the end of the file or of
/// what can be read.
fn chunk_header(reader: &mut impl Read) -> io::Result<Option<(u32, [u8; 4])>> {
    let mut header = [0u8; 8];
    match reader.read_exact(&mut header) {
        Ok(()) => Ok(Some((
            u32::from_be_bytes(header[..4].try_into().expect("4 bytes")),
            header[4..].try_into().expect("4 bytes"),
        ))),
        Err(e) if e.kind() == io::ErrorKind::UnexpectedEof => Ok(None),
        Err(e) => Err(e),
    }
}

/// Whether an iCCP chunk's data (a name of 1 to 79 bytes, a zero byte, the
/// compression method, then a zlib stream) inflates to more than `cap`
/// bytes. A damaged stream counts what it gave before the damage: the
/// decoder drops such a profile, as before.
fn inflates_past(data: &mut impl BufRead, cap: u64) -> io::Result<bool> {
    let mut name = Vec::new();
    data.take(80).read_until(0, &mut name)?;
    let mut method = [0u8; 1];
    if name.last() != Some(&0) || data.read_exact(&mut method).is_err() {
        return Ok(false);
    }
    let mut profile = ZlibDecoder::new(data).take(cap + 1);
    // An error here is a damaged stream or a file that cannot be read:
    // either way the decoder says so, or drops the profile.
    Ok(io::copy(&mut profile, &mut io::sink()).is_ok_and(|inflated| inflated > cap))
}

#[cfg(test)]
mod tests {
    use super::*;
    use flate2::{Compression, write::ZlibEncoder};
    use std::io::{Cursor, Write};

    fn chunk(kind: &[u8; 4], data: &[u8]) -> Vec<u8> {
        let mut out = (data.len() as u32).to_be_bytes().to_vec();
        out.extend(kind);
        out.extend(data);
        out.extend([0; 4]); // the walk does not check CRCs: the decoder does
        out
    }

    fn iccp(zeros: usize) -> Vec<u8> {
        let mut encoder = ZlibEncoder::new(b"icc\0\0".to_vec(), Compression::fast());
        encoder.write_all(&vec![0; zeros]).unwrap();
        chunk(b"iCCP", &encoder.finish().unwrap())
    }

    fn file(chunks: &[Vec<u8>]) -> Cursor<Vec<u8>> {
        let mut bytes = b"\x89PNG\r\n\x1a\n".to_vec();
        for c in chunks {
            bytes.extend(c);
        }
        Cursor::new(bytes)
    }

    fn header(width: u32, height: u32) -> Vec<u8> {
        let mut data = width.to_be_bytes().to_vec();
        data.extend(height.to_be_bytes());
        data.extend([8, 2, 0, 0, 0]);
        chunk(b"IHDR", &data)
    }

    fn small(width: u32, height: u32) -> Result<(), String> {
        if width * height > 100 {
            return Err(format!("{width}x{height} is over 100 pixels"));
        }
        Ok(())
    }

    #[test]
    fn the_size_is_checked_from_the_header() {
        let walked = |w, h| walk(&mut file(&[header(w, h)]), small).unwrap();
        assert_eq!(walked(10, 10), Ok(()));
        assert_eq!(
            walked(11, 10),
            Err(Refusal::Size("11x10 is over 100 pixels".into()))
        );
    }

    #[test]
    fn a_profile_is_refused_only_past_the_cap() {
        // Exactly the cap passes; one byte more does not.
        let cap = MAX_ICC_PROFILE as usize;
        let walked = |profile| walk(&mut file(&[header(2, 2), profile]), small).unwrap();
        assert_eq!(walked(iccp(cap)), Ok(()));
        assert_eq!(walked(iccp(cap + 1)), Err(Refusal::IccProfile));
        // After IDAT the walk stops: the decoder refuses a late iCCP.
        let late = walk(
            &mut file(&[header(2, 2), chunk(b"IDAT", &[]), iccp(cap + 1)]),
            small,
        )
        .unwrap();
        assert_eq!(late, Ok(()));
    }

    #[test]
    fn the_header_size_is_read_from_a_whole_undamaged_header_only() {
        // A 3 x 2 PNG as the image crate writes it, then with its header's
        // CRC damaged, cut inside the header, and not a PNG.
        let mut png = Vec::new();
        image::RgbImage::new(3, 2)
            .write_to(&mut Cursor::new(&mut png), image::ImageFormat::Png)
            .unwrap();
        let size = |bytes: &[u8]| header_size(&mut Cursor::new(bytes)).unwrap();
        assert_eq!(size(&png), Some((3, 2)));
        let mut damaged = png.clone();
        damaged[29] ^= 1;
        assert_eq!(size(&damaged), None);
        assert_eq!(size(&png[..32]), None);
        assert_eq!(size(b"GIF89a"), None);
    }

    #[test]
    fn what_the_decoder_tells_better_is_left_to_it() {
        // No header first, a cut header, a damaged profile, a cut file.
        for chunks in [
            vec![chunk(b"tEXt", b"a\0b"), header(1000, 1000)],
            vec![chunk(b"IHDR", &[0, 0])],
            vec![header(2, 2), chunk(b"iCCP", b"icc\0\0not zlib")],
            vec![header(2, 2)[..10].to_vec()],
        ] {
            assert_eq!(walk(&mut file(&chunks), small).unwrap(), Ok(()));
        }
    }
}
