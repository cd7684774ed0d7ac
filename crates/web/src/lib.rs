//! raystep in a web page: the engine and its tools behind a few calls that
//! the page's JavaScript makes, so that every number and sentence the page
//! shows comes from the same code as the command line's.
//!
//! A `Page` holds what one page (or its render worker) has open: the files
//! given to it, the scene read from them, the debugger's toggles and the
//! pixel being looked at. Each call takes its arguments as JSON and answers
//! with JSON, text or bytes (`Reply`); `exports` puts the calls behind the
//! WebAssembly module's C ABI, and the native tests call them directly.

#[cfg(target_family = "wasm")]
mod exports;
mod options;
mod page;
mod page_size;
mod pixel_view;
mod reply;
mod student_work;

pub use page::Page;
pub use reply::Reply;
