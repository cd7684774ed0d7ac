use std::process::ExitCode;

mod out_of_memory;

#[global_allocator]
static ALLOCATOR: out_of_memory::Bounded = out_of_memory::Bounded;

fn main() -> ExitCode {
    keep_large_blocks_mapped();
    let cli = raystep::cli::parse_or_exit();
    match raystep::cli::run(cli) {
        Ok(code) => code,
        Err(error) => {
            // A name quoted in the message may hold control characters.
            let message = format!("{error:#}");
            eprintln!(
                "error: {}",
                raystep_engine::printable::printable_text(&message)
            );
            ExitCode::FAILURE
        }
    }
}

/// glibc raises its mmap threshold each time a mapped block is freed, up to
/// 32 MiB, so the large buffers a scene's parse and build free (the file's
/// text, the object list's copies as it grows) end up inside the heap and
/// stay resident: the peak counted them twice. A fixed threshold keeps every
/// block of a mebibyte or more mapped and unmapped on its own.
fn keep_large_blocks_mapped() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only sets an allocator parameter; it is called once,
    // before any thread is started, with a valid parameter and value.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 1 << 20);
    }
}
