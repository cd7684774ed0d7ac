//! The module's C ABI, which the page's JavaScript calls: one `Page` per
//! module instance, inputs copied into memory the module allocates, and
//! the last reply kept until the next call asks for another.

use std::cell::RefCell;

use crate::page::Page;
use crate::reply::Reply;

thread_local! {
    static PAGE: RefCell<Page> = RefCell::new(Page::default());
    static REPLY: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
}

#[link(wasm_import_module = "env")]
unsafe extern "C" {
    /// The page hears of a render's rows as they finish.
    fn raystep_progress(done: u32, total: u32);
    /// The page hears a panic's message before the module traps, to say it.
    fn raystep_panicked(message: *const u8, length: usize);
}

/// What a reply holds, for the page to read it.
const JSON: u32 = 0;
const TEXT: u32 = 1;
const BYTES: u32 = 2;
const ERROR: u32 = 3;

/// `length` bytes for the page to fill; freed with `raystep_free`.
#[unsafe(no_mangle)]
pub extern "C" fn raystep_alloc(length: usize) -> *mut u8 {
    let mut buffer = Vec::<u8>::with_capacity(length);
    let start = buffer.as_mut_ptr();
    std::mem::forget(buffer);
    start
}

/// # Safety
/// `start` and `length` must be those of one `raystep_alloc`, freed once.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn raystep_free(start: *mut u8, length: usize) {
    // SAFETY: the caller passes back what raystep_alloc made.
    drop(unsafe { Vec::from_raw_parts(start, 0, length) });
}

/// # Safety
/// `start` must point to `length` readable bytes (or `length` be 0).
unsafe fn bytes<'a>(start: *const u8, length: usize) -> &'a [u8] {
    if length == 0 {
        return &[];
    }
    // SAFETY: as the caller promises.
    unsafe { std::slice::from_raw_parts(start, length) }
}

/// Makes call `op` (UTF-8) with its JSON arguments and a file's bytes;
/// answers what the reply holds (`JSON`, `TEXT`, `BYTES`, or `ERROR` with
/// the message as text), the reply itself at `raystep_reply`.
///
/// # Safety
/// Each pointer must point to its length of readable bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn raystep_call(
    op: *const u8,
    op_length: usize,
    args: *const u8,
    args_length: usize,
    file: *const u8,
    file_length: usize,
) -> u32 {
    hear_panics();
    // SAFETY: as the caller promises.
    let (op, args, file) = unsafe {
        (
            bytes(op, op_length),
            bytes(args, args_length),
            bytes(file, file_length),
        )
    };
    let progress = |done: u32, total: u32| {
        // SAFETY: a plain call into JavaScript with two numbers.
        unsafe { raystep_progress(done, total) }
    };
    let result = match (std::str::from_utf8(op), std::str::from_utf8(args)) {
        (Ok(op), Ok(args)) => PAGE.with(|page| page.borrow_mut().call(op, args, file, &progress)),
        _ => Err(anyhow::anyhow!("a call's name and arguments must be UTF-8")),
    };
    let (kind, reply) = match result {
        Ok(Reply::Json(json)) => (JSON, json.to_string().into_bytes()),
        Ok(Reply::Text(text)) => (TEXT, text.into_bytes()),
        Ok(Reply::Bytes(bytes)) => (BYTES, bytes),
        Err(error) => (ERROR, format!("{error:#}").into_bytes()),
    };
    REPLY.with(|r| *r.borrow_mut() = reply);
    kind
}

/// Where the last reply starts.
#[unsafe(no_mangle)]
pub extern "C" fn raystep_reply() -> *const u8 {
    REPLY.with(|r| r.borrow().as_ptr())
}

/// How long the last reply is.
#[unsafe(no_mangle)]
pub extern "C" fn raystep_reply_length() -> usize {
    REPLY.with(|r| r.borrow().len())
}

/// Sends a panic's message to the page (once set, on the first call).
fn hear_panics() {
    static SET: std::sync::Once = std::sync::Once::new();
    SET.call_once(|| {
        std::panic::set_hook(Box::new(|info| {
            let message = info.to_string();
            // SAFETY: the message's bytes are alive for the call.
            unsafe { raystep_panicked(message.as_ptr(), message.len()) }
        }));
    });
}
