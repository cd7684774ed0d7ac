//! Taking the terminal over and giving it back. Whatever ends the debugger
//! (quit, an error, a panic of the UI thread, or SIGTERM, SIGHUP, SIGINT or
//! SIGQUIT) leaves through `restore`, so the shell always gets back a cooked,
//! echoing terminal on its main screen, cursor shown, mouse reporting off.
//!
//! Signals are handled on a thread of their own rather than by the event
//! loop: the loop may be blocked in a read, a long draw or a reload, and the
//! terminal must come back at once whatever it is doing.

use std::io::{self, Stdout, Write, stdout};
use std::sync::{Mutex, PoisonError};

use anyhow::{Context, Result};
use crossterm::cursor::Show;
use crossterm::event::{DisableMouseCapture, EnableMouseCapture};
use crossterm::style::ResetColor;
use crossterm::terminal::{
    EnterAlternateScreen, LeaveAlternateScreen, disable_raw_mode, enable_raw_mode,
};
use crossterm::{execute, queue};
use ratatui::Terminal;
use ratatui::backend::CrosstermBackend;
use signal_hook::consts::{SIGHUP, SIGINT, SIGQUIT, SIGTERM};
use signal_hook::iterator::Signals;

/// The signals that end the debugger; each exits with 128 + its number,
/// as a shell reports a process killed by it.
pub const SIGNALS: [i32; 4] = [SIGTERM, SIGHUP, SIGINT, SIGQUIT];

/// Whether the terminal is ours to give back. The lock also makes a restore
/// that is under way finish before a second one (a signal during quit) exits.
static TAKEN: Mutex<bool> = Mutex::new(false);

/// Raw mode, the alternate screen and mouse capture, with the signal thread
/// and the panic hook that undo them.
pub fn take() -> Result<Terminal<CrosstermBackend<Stdout>>> {
    // Signals first: from the moment raw mode is on, any of them restores it.
    watch_signals().context("cannot watch for signals")?;
    install_panic_hook();
    {
        let mut taken = TAKEN.lock().unwrap_or_else(PoisonError::into_inner);
        *taken = true;
        enable_raw_mode().context("cannot set up the terminal")?;
        execute!(stdout(), EnterAlternateScreen, EnableMouseCapture)
            .context("cannot set up the terminal")?;
    }
    Terminal::new(CrosstermBackend::new(stdout())).context("cannot set up the terminal")
}

/// Gives the terminal back, once; later calls do nothing. Errors are ignored:
/// on a hangup there is no terminal left to write to, and the rest must run.
pub fn restore() {
    let mut taken = TAKEN.lock().unwrap_or_else(PoisonError::into_inner);
    if !*taken {
        return;
    }
    *taken = false;
    // Holding stdout keeps the UI thread from drawing over the main screen
    // after it comes back (a signal exits with the lock still held).
    let mut out = stdout().lock();
    let _ = write_restore(&mut out);
    let _ = disable_raw_mode();
}

/// The escape sequences that undo `take`'s: mouse reporting off, colours
/// reset, the main screen back, the cursor shown.
pub fn write_restore(out: &mut impl Write) -> io::Result<()> {
    queue!(
        out,
        DisableMouseCapture,
        ResetColor,
        LeaveAlternateScreen,
        Show
    )?;
    out.flush()
}

/// A thread that, on any of `SIGNALS`, restores the terminal and exits.
fn watch_signals() -> io::Result<()> {
    let mut signals = Signals::new(SIGNALS)?;
    std::thread::Builder::new()
        .name("raystep-signals".into())
        .spawn(move || {
            if let Some(signal) = signals.forever().next() {
                restore();
                std::process::exit(128 + signal);
            }
        })?;
    Ok(())
}

/// On a panic of the UI thread, restores the terminal before the message is
/// printed (on the main screen, where it stays). Render threads catch their
/// own panics and report them in the status line, so they stay silent here.
fn install_panic_hook() {
    let ui_thread = std::thread::current().id();
    let report = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if std::thread::current().id() == ui_thread {
            restore();
            report(info);
        }
    }));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_restore_sequence_undoes_every_mode_the_debugger_sets() {
        // Each private mode the setup turns on (`h`) must be turned off (`l`):
        // 1049 alternate screen; 1000, 1002, 1003, 1006 mouse reporting
        // (crossterm's EnableMouseCapture); 25 the cursor, which ratatui hides.
        let mut bytes = Vec::new();
        write_restore(&mut bytes).unwrap();
        let text = String::from_utf8(bytes).unwrap();
        for mode in ["1049", "1000", "1002", "1003", "1006"] {
            assert!(
                text.contains(&format!("\x1b[?{mode}l")),
                "{mode} in {text:?}"
            );
        }
        assert!(text.contains("\x1b[?25h"), "cursor shown in {text:?}");
    }
}
