//! Under a memory limit (`ulimit -v`, an autograder's container), an
//! allocation refused ends raystep with a message and exit status 1,
//! never SIGABRT: Rust's own handler aborts ("memory allocation of N
//! bytes failed"), which a grader's script reads as a crash and which
//! writes no results. Every allocation goes through `Bounded`, the system
//! allocator with that one difference; nothing is estimated, so no input
//! that fits is refused (README, "Memory").

use std::alloc::{GlobalAlloc, Layout, System};

pub struct Bounded;

// SAFETY: every call is passed on to `System` unchanged; only a null
// result, which the caller would have to handle, never reaches it.
unsafe impl GlobalAlloc for Bounded {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller's contract is `System`'s.
        refused_if_null(unsafe { System.alloc(layout) }, layout.size())
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: as `alloc`.
        refused_if_null(unsafe { System.alloc_zeroed(layout) }, layout.size())
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: as `alloc`; `ptr` was allocated by `System` through us.
        refused_if_null(unsafe { System.realloc(ptr, layout, new_size) }, new_size)
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as `realloc`.
        unsafe { System.dealloc(ptr, layout) }
    }
}

fn refused_if_null(block: *mut u8, bytes: usize) -> *mut u8 {
    if block.is_null() {
        out_of_memory(bytes);
    }
    block
}

/// Says what was refused and under which limit, then exits with status
/// 1. Nothing here allocates: the message is written from the stack.
fn out_of_memory(bytes: usize) -> ! {
    use std::fmt::Write;
    let mut message = StackText::default();
    let _ = write!(
        message,
        "error: out of memory: a block of {bytes} bytes was refused"
    );
    match address_space_limit() {
        Some(limit) => {
            let _ = write!(
                message,
                " under an address-space limit of {} MB (ulimit -v)",
                limit >> 20
            );
        }
        None => message.push(" (the machine's memory is spent)"),
    }
    message.push(
        "; this input needs more memory than that: raise the limit, or make the scene, \
         the image or the ray log smaller (README, \"Memory\")\n",
    );
    // The debugger's terminal first, so the message lands on the shell's
    // screen and the shell gets back a cooked terminal.
    raystep::tui::give_back_unlocked();
    // SAFETY: writes initialised bytes to standard error, then ends the
    // process at once without running anything that could allocate.
    unsafe {
        libc::write(2, message.bytes.as_ptr().cast(), message.len);
        libc::_exit(1);
    }
}

/// RLIMIT_AS in bytes, if there is one.
fn address_space_limit() -> Option<u64> {
    let mut limit = libc::rlimit {
        rlim_cur: 0,
        rlim_max: 0,
    };
    // SAFETY: getrlimit writes the struct it is given and nothing else.
    let read = unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut limit) } == 0;
    (read && limit.rlim_cur != libc::RLIM_INFINITY).then_some(limit.rlim_cur)
}

/// Text in a fixed buffer, cut short when full.
struct StackText {
    bytes: [u8; 512],
    len: usize,
}

impl Default for StackText {
    fn default() -> Self {
        Self {
            bytes: [0; 512],
            len: 0,
        }
    }
}

impl StackText {
    fn push(&mut self, text: &str) {
        let room = self.bytes.len() - self.len;
        let n = text.len().min(room);
        self.bytes[self.len..self.len + n].copy_from_slice(&text.as_bytes()[..n]);
        self.len += n;
    }
}

impl std::fmt::Write for StackText {
    fn write_str(&mut self, text: &str) -> std::fmt::Result {
        self.push(text);
        Ok(())
    }
}
