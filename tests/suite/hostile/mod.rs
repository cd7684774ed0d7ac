//! Issue 27's cases, tried as an attacker and as a clumsy user would: each
//! input that once hung, exhausted memory, died by a signal or destroyed a
//! file is pinned here, one file per kind of harm, so that it stays fixed.

mod argv;
mod compare_input;
mod errors;
mod files;
mod linear;
mod memory;
mod names;
mod results;
