//! How large an image the page renders.

use anyhow::{Result, bail};

use raystep_engine::scene;

/// The most pixels the page renders: a browser tab's memory and one thread
/// (the command line renders up to 8192 x 8192).
pub(crate) const PAGE_MAX_PIXELS: u64 = 2048 * 2048;

/// Refuses what the page would not render in a browser tab, in the words
/// the command line refuses an image size with.
pub(crate) fn check_page_size(width: u32, height: u32) -> Result<()> {
    scene::check_image_size(width, height).map_err(anyhow::Error::msg)?;
    if width as u64 * height as u64 > PAGE_MAX_PIXELS {
        bail!(
            "image size {width}x{height} is too large for the page: at most {PAGE_MAX_PIXELS} \
             pixels (2048 x 2048) are rendered in a browser; `raystep render` renders up to \
             8192 x 8192"
        );
    }
    Ok(())
}
