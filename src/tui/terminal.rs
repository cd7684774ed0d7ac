//! Taking the terminal over and giving it back. Whatever ends the debugger
//! (quit, an error, a panic of the UI thread, or SIGTERM, SIGHUP, SIGINT or
//! SIGQUIT) leaves through `restore`, so the shell always gets back a cooked,
//! echoing terminal on its main screen, cursor shown, mouse reporting off.
//! A stop (Ctrl+Z, or SIGTSTP from the shell or `kill`) goes through
//! `suspend`, which gives the terminal back the same way, stops, and takes
//! it again when continued; the main loop then redraws the whole screen.
//!
//! Signals are handled on a thread of their own rather than by the event
//! loop: the loop may be blocked in a read or a long draw, and the
//! terminal must come back at once whatever it is doing.

use std::io::{self, Stdout, Write, stdout};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, OnceLock, PoisonError};

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
use signal_hook::consts::{SIGCONT, SIGHUP, SIGINT, SIGQUIT, SIGTERM, SIGTSTP};
use signal_hook::iterator::Signals;

/// The signals that end the debugger; each exits with 128 + its number,
/// as a shell reports a process killed by it.
pub(crate) const SIGNALS: [i32; 4] = [SIGTERM, SIGHUP, SIGINT, SIGQUIT];

/// Whether the terminal is ours to give back. The lock also makes a restore
/// that is under way finish before a second one (a signal during quit) exits.
static TAKEN: Mutex<bool> = Mutex::new(false);

/// Set when the process was continued after a stop: the screen must be
/// redrawn whole (`continued` reads and clears it).
static CONTINUED: AtomicBool = AtomicBool::new(false);

/// Set by `suspend` just before it stops the process: the SIGCONT that
/// continues it needs nothing more, `suspend` takes the terminal again.
static OWN_STOP: AtomicBool = AtomicBool::new(false);

/// Whether the terminal is in our modes now, for `give_back_unlocked`.
static IN_OUR_MODES: AtomicBool = AtomicBool::new(false);

/// The terminal's modes before `take`, for `give_back_unlocked`.
static MODES_BEFORE: OnceLock<libc::termios> = OnceLock::new();

/// What `write_restore` writes, as bytes: crossterm's DisableMouseCapture,
/// ResetColor, LeaveAlternateScreen and Show.
const RESTORE_BYTES: &[u8] =
    b"\x1b[?1006l\x1b[?1015l\x1b[?1003l\x1b[?1002l\x1b[?1000l\x1b[0m\x1b[?1049l\x1b[?25h";

/// Gives the terminal back without allocating or taking a lock: for the
/// binary's out-of-memory path (an allocation refused under `ulimit -v`
/// ends the process there, and the lock `restore` takes may be held by
/// the thread that ran out). Does nothing unless the terminal is in our
/// modes.
pub fn give_back_unlocked() {
    if !IN_OUR_MODES.swap(false, Ordering::SeqCst) {
        return;
    }
    // SAFETY: a write of a constant buffer, and tcsetattr with the modes
    // tcgetattr read before `take`.
    unsafe {
        libc::write(
            libc::STDOUT_FILENO,
            RESTORE_BYTES.as_ptr().cast(),
            RESTORE_BYTES.len(),
        );
        if let Some(modes) = MODES_BEFORE.get() {
            libc::tcsetattr(libc::STDIN_FILENO, libc::TCSANOW, modes);
        }
    }
}

/// Raw mode, the alternate screen and mouse capture, with the signal thread
/// and the panic hook that undo them.
pub(crate) fn take() -> Result<Terminal<CrosstermBackend<Stdout>>> {
    // Signals first: from the moment raw mode is on, any of them restores it.
    watch_signals().context("cannot watch for signals")?;
    install_panic_hook();
    {
        let mut taken = TAKEN.lock().unwrap_or_else(PoisonError::into_inner);
        *taken = true;
        // SAFETY: tcgetattr on a descriptor with a valid termios to fill.
        unsafe {
            let mut modes: libc::termios = std::mem::zeroed();
            if libc::tcgetattr(libc::STDIN_FILENO, &mut modes) == 0 {
                let _ = MODES_BEFORE.set(modes);
            }
        }
        enter(&mut stdout()).context("cannot set up the terminal")?;
    }
    Terminal::new(CrosstermBackend::new(stdout())).context("cannot set up the terminal")
}

/// Gives the terminal back, once; later calls do nothing. Errors are ignored:
/// on a hangup there is no terminal left to write to, and the rest must run.
pub(crate) fn restore() {
    let mut taken = TAKEN.lock().unwrap_or_else(PoisonError::into_inner);
    if !*taken {
        return;
    }
    *taken = false;
    // Holding stdout keeps the UI thread from drawing over the main screen
    // after it comes back (a signal exits with the lock still held).
    let mut out = stdout().lock();
    leave(&mut out);
}

/// Raw mode, the alternate screen and mouse capture.
fn enter(out: &mut impl Write) -> io::Result<()> {
    IN_OUR_MODES.store(true, Ordering::SeqCst);
    enable_raw_mode()?;
    execute!(out, EnterAlternateScreen, EnableMouseCapture)
}

/// `enter` undone.
fn leave(out: &mut impl Write) {
    IN_OUR_MODES.store(false, Ordering::SeqCst);
    let _ = write_restore(out);
    let _ = disable_raw_mode();
}

/// Ctrl+Z or SIGTSTP: gives the terminal back as `restore` does, stops the
/// process as SIGTSTP's default action would (the shell says "Stopped"),
/// and when continued takes the terminal again and asks for a redraw. The
/// app's state is untouched; background renders stop with the process and
/// go on after.
///
/// Continued in the background (`bg`), setting the terminal's modes stops
/// the process again (SIGTTOU, "Stopped (tty output)") until `fg`: it
/// neither hangs nor spins, and nothing is drawn over the shell meanwhile,
/// as stdout stays locked until the terminal is ours again.
pub(crate) fn suspend() {
    let taken = TAKEN.lock().unwrap_or_else(PoisonError::into_inner);
    if !*taken {
        return;
    }
    let mut out = stdout().lock();
    leave(&mut out);
    OWN_STOP.store(true, Ordering::SeqCst);
    stop();
    let _ = enter(&mut out);
    CONTINUED.store(true, Ordering::SeqCst);
}

/// Stops the process with SIGTSTP's default action, and returns once it is
/// continued. The handler signal-hook installed is set aside meanwhile and
/// put back as it was. In an orphaned process group (no job-control shell
/// that could continue it, as when a terminal emulator or tmux runs the
/// debugger directly) the kernel discards the signal: no stop, no hang.
fn stop() {
    // SAFETY: sigaction and raise with valid pointers; the action read back
    // is the one put back.
    unsafe {
        let mut default: libc::sigaction = std::mem::zeroed();
        default.sa_sigaction = libc::SIG_DFL;
        let mut installed: libc::sigaction = std::mem::zeroed();
        libc::sigaction(SIGTSTP, &default, &mut installed);
        // A signal to this thread: the stop happens before `raise` returns.
        libc::raise(SIGTSTP);
        libc::sigaction(SIGTSTP, &installed, std::ptr::null_mut());
    }
}

/// What a SIGCONT asks of the terminal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum OnContinue {
    /// `suspend` stopped us and takes the terminal again itself.
    Nothing,
    /// Still raw, but a stop we could not see (SIGSTOP) let the shell write
    /// on the screen ("Stopped", its prompt): draw it all again.
    Redraw,
    /// The shell set its own modes while we were stopped: set ours again.
    Retake,
}

/// The answer to a SIGCONT, from whether the terminal is back in cooked mode
/// and whether the stop was `suspend`'s own.
fn on_continue(cooked: bool, own_stop: bool) -> OnContinue {
    match (cooked, own_stop) {
        (true, _) => OnContinue::Retake,
        (false, true) => OnContinue::Nothing,
        (false, false) => OnContinue::Redraw,
    }
}

/// SIGCONT: after a stop `suspend` did not make (SIGSTOP, which cannot be
/// caught, so the terminal stayed raw in the shell's hands), makes sure the
/// modes are ours and asks for a redraw.
fn resume() {
    let taken = TAKEN.lock().unwrap_or_else(PoisonError::into_inner);
    if !*taken {
        return;
    }
    match on_continue(cooked(), OWN_STOP.swap(false, Ordering::SeqCst)) {
        OnContinue::Nothing => return,
        OnContinue::Redraw => {}
        OnContinue::Retake => {
            let mut out = stdout().lock();
            // crossterm remembers raw mode as on and would do nothing.
            let _ = disable_raw_mode();
            let _ = enter(&mut out);
        }
    }
    CONTINUED.store(true, Ordering::SeqCst);
}

/// Whether the terminal (stdin, which `run` checked is one) reads lines.
fn cooked() -> bool {
    // SAFETY: tcgetattr on a descriptor with a valid termios to fill.
    unsafe {
        let mut modes: libc::termios = std::mem::zeroed();
        libc::tcgetattr(libc::STDIN_FILENO, &mut modes) == 0 && modes.c_lflag & libc::ICANON != 0
    }
}

/// Whether the process was continued after a stop since the last call: the
/// screen must then be cleared and drawn whole.
pub(crate) fn continued() -> bool {
    CONTINUED.swap(false, Ordering::SeqCst)
}

/// The escape sequences that undo `take`'s: mouse reporting off, colours
/// reset, the main screen back, the cursor shown.
pub(crate) fn write_restore(out: &mut impl Write) -> io::Result<()> {
    queue!(
        out,
        DisableMouseCapture,
        ResetColor,
        LeaveAlternateScreen,
        Show
    )?;
    out.flush()
}

/// A thread that, on any of `SIGNALS`, restores the terminal and exits; on
/// SIGTSTP suspends, and on SIGCONT takes the terminal again if need be.
fn watch_signals() -> io::Result<()> {
    let mut signals = Signals::new(SIGNALS.iter().chain(&[SIGTSTP, SIGCONT]))?;
    std::thread::Builder::new()
        .name("raystep-signals".into())
        .spawn(move || {
            for signal in signals.forever() {
                match signal {
                    SIGTSTP => suspend(),
                    SIGCONT => resume(),
                    _ => {
                        restore();
                        std::process::exit(128 + signal);
                    }
                }
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

    #[test]
    fn the_restore_without_allocating_writes_the_same_bytes() {
        let mut bytes = Vec::new();
        write_restore(&mut bytes).unwrap();
        assert_eq!(bytes, RESTORE_BYTES);
    }

    #[test]
    fn a_continue_retakes_a_cooked_terminal_and_redraws_after_a_stop_not_ours() {
        // Cooked again: the shell set its modes, whoever stopped us.
        assert_eq!(on_continue(true, true), OnContinue::Retake);
        assert_eq!(on_continue(true, false), OnContinue::Retake);
        // Raw after our own stop: `suspend` already took it back.
        assert_eq!(on_continue(false, true), OnContinue::Nothing);
        // Raw after SIGSTOP: the modes are ours, the screen maybe not.
        assert_eq!(on_continue(false, false), OnContinue::Redraw);
    }
}
