//! The debugger gives the terminal back on SIGTERM, SIGHUP, SIGINT and
//! SIGQUIT, as it does on quit, and while stopped by Ctrl+Z or SIGTSTP: the
//! real binary runs in a pseudo-terminal, is signalled (or sent keys) once
//! its first screen is up, and then the pty's modes and the bytes it wrote
//! are checked.
#![cfg(unix)]

use std::fs::File;
use std::io::{Read, Write};
use std::os::fd::{AsRawFd, FromRawFd, OwnedFd};
use std::os::unix::process::CommandExt;
use std::process::{Child, Command, ExitStatus, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Generous: the machine running the tests may be busy building.
const PATIENCE: Duration = Duration::from_secs(30);
/// The pty's size.
const ROWS: u16 = 40;
const COLUMNS: u16 = 120;

/// Each private mode the debugger sets, as (set, reset) sequences: the
/// alternate screen, mouse reporting (crossterm's four modes) and the cursor,
/// which ratatui hides while drawing.
const MODES: [(&str, &str); 6] = [
    ("\x1b[?1049h", "\x1b[?1049l"),
    ("\x1b[?1000h", "\x1b[?1000l"),
    ("\x1b[?1002h", "\x1b[?1002l"),
    ("\x1b[?1003h", "\x1b[?1003l"),
    ("\x1b[?1006h", "\x1b[?1006l"),
    ("\x1b[?25l", "\x1b[?25h"),
];

/// The debugger in a fresh 120 x 40 pseudo-terminal, with what it wrote so far.
struct Session {
    child: Child,
    /// Our end of the terminal's side: its modes are the ones the shell gets back.
    tty: OwnedFd,
    /// The pty's other side, where typed keys go in.
    keyboard: File,
    output: Arc<Mutex<Vec<u8>>>,
}

/// How the debugger's process is placed, as whatever starts it would.
#[derive(Clone, Copy)]
enum Start {
    /// A new session whose controlling terminal is the pty, as under a
    /// terminal emulator.
    Session,
    /// A process group of its own in our session, as a job-control shell
    /// runs a job. Its group is then not orphaned (its parent, this test, is
    /// in another group of the same session), so the kernel carries out
    /// SIGTSTP's stop; in a new session it would discard it.
    Job,
    /// As `Session`, under an address-space limit of this many bytes
    /// (`ulimit -v`, an autograder's container), with two threads and two
    /// malloc arenas, so that a machine with many cores does not spend the
    /// limit on stacks and arenas.
    LimitedSession(u64),
}

impl Session {
    fn start(args: &[&str]) -> Session {
        Session::start_as(Start::Session, args)
    }

    fn start_as(start: Start, args: &[&str]) -> Session {
        let (master, tty) = open_pty(COLUMNS, ROWS);
        let stdio = || Stdio::from(tty.try_clone().unwrap());
        let mut command = Command::new(env!("CARGO_BIN_EXE_raystep"));
        command
            .args(args)
            .stdin(stdio())
            .stdout(stdio())
            .stderr(stdio());
        if let Start::LimitedSession(_) = start {
            command
                .env("RAYON_NUM_THREADS", "2")
                .env("MALLOC_ARENA_MAX", "2");
        }
        // SAFETY: only async-signal-safe calls between fork and exec.
        unsafe {
            command.pre_exec(move || {
                match start {
                    Start::Session | Start::LimitedSession(_) => {
                        libc::setsid();
                        libc::ioctl(0, libc::TIOCSCTTY, 0);
                    }
                    Start::Job => {
                        libc::setpgid(0, 0);
                    }
                }
                if let Start::LimitedSession(bytes) = start {
                    let limit = libc::rlimit {
                        rlim_cur: bytes,
                        rlim_max: bytes,
                    };
                    libc::setrlimit(libc::RLIMIT_AS, &limit);
                }
                Ok(())
            });
        }
        let child = command.spawn().expect("the debugger starts");
        let output = Arc::new(Mutex::new(Vec::new()));
        let sink = output.clone();
        let mut master = File::from(master);
        let keyboard = master.try_clone().unwrap();
        // Drains the pty so the debugger never blocks writing; ends with EIO
        // once every handle on the terminal's side is closed.
        std::thread::spawn(move || {
            let mut buffer = [0; 4096];
            while let Ok(n @ 1..) = master.read(&mut buffer) {
                sink.lock().unwrap().extend_from_slice(&buffer[..n]);
            }
        });
        Session {
            child,
            tty,
            keyboard,
            output,
        }
    }

    fn text(&self) -> String {
        String::from_utf8_lossy(&self.output.lock().unwrap()).into_owned()
    }

    /// The screen as a terminal shows it after everything written so far:
    /// ratatui sends only the cells that changed, so a title redrawn in
    /// part is whole only here, not in the byte stream.
    fn screen(&self) -> String {
        let size = |n| std::num::NonZeroU16::new(n).expect("a pty has rows and columns");
        let mut terminal = vt100::Parser::new(size(ROWS), size(COLUMNS), 0);
        terminal.process(&self.output.lock().unwrap());
        terminal.screen().contents()
    }

    /// Polls until the screen shows `what`; panics after `PATIENCE`.
    fn wait_for_screen(&self, what: &str) {
        let deadline = Instant::now() + PATIENCE;
        while !self.screen().contains(what) {
            assert!(Instant::now() < deadline, "no {what} on {}", self.screen());
            std::thread::sleep(Duration::from_millis(10));
        }
    }

    /// Polls until `done` holds for what was written; panics after `PATIENCE`.
    fn wait_for(&self, what: &str, done: impl Fn(&str) -> bool) {
        let deadline = Instant::now() + PATIENCE;
        while !done(&self.text()) {
            assert!(Instant::now() < deadline, "no {what} in {:?}", self.text());
            std::thread::sleep(Duration::from_millis(10));
        }
    }

    /// What was written after the first `from` bytes.
    fn text_from(&self, from: usize) -> String {
        String::from_utf8_lossy(&self.output.lock().unwrap()[from..]).into_owned()
    }

    /// Polls until `done` holds for what was written after the first `from`
    /// bytes; panics after `PATIENCE`.
    fn wait_for_from(&self, from: usize, what: &str, done: impl Fn(&str) -> bool) {
        let deadline = Instant::now() + PATIENCE;
        while !done(&self.text_from(from)) {
            let text = self.text_from(from);
            assert!(Instant::now() < deadline, "no {what} in {text:?}");
            std::thread::sleep(Duration::from_millis(10));
        }
    }

    fn written(&self) -> usize {
        self.output.lock().unwrap().len()
    }

    fn signal(&self, signal: i32) {
        // SAFETY: a plain kill(2) of our own child.
        assert_eq!(unsafe { libc::kill(self.child.id() as i32, signal) }, 0);
    }

    /// Waits until the child is stopped, and returns the signal that stopped it.
    fn wait_for_stop(&self) -> i32 {
        let deadline = Instant::now() + PATIENCE;
        loop {
            let mut status = 0;
            let pid = self.child.id() as i32;
            // SAFETY: waitpid on our own child; WNOHANG, so it never blocks,
            // and without WEXITED-only flags it reaps nothing but a stop.
            let found = unsafe { libc::waitpid(pid, &mut status, libc::WUNTRACED | libc::WNOHANG) };
            if found == pid && libc::WIFSTOPPED(status) {
                return libc::WSTOPSIG(status);
            }
            assert_eq!(found, 0, "the debugger ended instead: status {status:#x}");
            assert!(Instant::now() < deadline, "the debugger did not stop");
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// Polls until the terminal's (canonical input, echo) are `modes`.
    fn wait_for_modes(&self, what: &str, modes: (bool, bool)) {
        let deadline = Instant::now() + PATIENCE;
        while self.cooked_and_echo() != modes {
            assert!(Instant::now() < deadline, "not {what}");
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// Sets the terminal to cooked and echoing, as a shell does when it
    /// takes the terminal back from a stopped job.
    fn cook(&self) {
        let mut modes: libc::termios = unsafe { std::mem::zeroed() };
        // SAFETY: `tty` is an open terminal and `modes` a valid termios.
        unsafe {
            assert_eq!(libc::tcgetattr(self.tty.as_raw_fd(), &mut modes), 0);
            modes.c_lflag |= libc::ICANON | libc::ECHO | libc::ISIG;
            assert_eq!(
                libc::tcsetattr(self.tty.as_raw_fd(), libc::TCSANOW, &modes),
                0
            );
        }
    }

    fn wait_for_exit(&mut self) -> ExitStatus {
        let deadline = Instant::now() + PATIENCE;
        loop {
            if let Some(status) = self.child.try_wait().unwrap() {
                return status;
            }
            assert!(Instant::now() < deadline, "the debugger did not exit");
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// (canonical input, echo) on the terminal.
    fn cooked_and_echo(&self) -> (bool, bool) {
        let mut modes: libc::termios = unsafe { std::mem::zeroed() };
        // SAFETY: `tty` is an open terminal and `modes` a valid termios.
        assert_eq!(
            unsafe { libc::tcgetattr(self.tty.as_raw_fd(), &mut modes) },
            0
        );
        (
            modes.c_lflag & libc::ICANON != 0,
            modes.c_lflag & libc::ECHO != 0,
        )
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn open_pty(columns: u16, rows: u16) -> (OwnedFd, OwnedFd) {
    let size = libc::winsize {
        ws_row: rows,
        ws_col: columns,
        ws_xpixel: 0,
        ws_ypixel: 0,
    };
    let (mut master, mut tty) = (-1, -1);
    // SAFETY: valid out-pointers; on success both descriptors are ours.
    let status = unsafe {
        libc::openpty(
            &mut master,
            &mut tty,
            std::ptr::null_mut(),
            std::ptr::null(),
            &size,
        )
    };
    assert_eq!(status, 0, "cannot open a pseudo-terminal");
    unsafe { (OwnedFd::from_raw_fd(master), OwnedFd::from_raw_fd(tty)) }
}

/// Every mode set was reset after it was last set.
fn all_modes_reset(text: &str) -> bool {
    MODES
        .iter()
        .all(|(set, reset)| text.rfind(reset) > text.rfind(set))
}

/// Starts the debugger, waits for its first screen, sends `signal`, and
/// checks the exit code and the terminal it leaves.
fn signal_restores_the_terminal(signal: i32, args: &[&str]) {
    let mut session = Session::start(args);
    // The status line's key hints come with the first frame.
    session.wait_for("first screen", |text| {
        text.contains("\x1b[?1006h") && text.contains("help")
    });
    assert_eq!(
        session.cooked_and_echo(),
        (false, false),
        "raw while running"
    );
    assert!(MODES.iter().all(|(set, _)| session.text().contains(set)));

    let sent = Instant::now();
    // SAFETY: a plain kill(2) of our own child.
    assert_eq!(unsafe { libc::kill(session.child.id() as i32, signal) }, 0);
    let status = session.wait_for_exit();
    let took = sent.elapsed();

    assert_eq!(status.code(), Some(128 + signal), "{status:?}");
    assert_eq!(session.cooked_and_echo(), (true, true), "cooked after");
    session.wait_for("restore of every mode", all_modes_reset);
    eprintln!("signal {signal}: exit {took:?} after it was sent");
    // The signal thread restores and exits at once, whatever the UI is doing
    // (5 to 50 ms here); the bound is generous for a machine busy building.
    assert!(took < Duration::from_secs(8), "exit took {took:?}");
}

#[test]
fn sigterm_restores_the_terminal() {
    signal_restores_the_terminal(libc::SIGTERM, &[]);
}

#[test]
fn sighup_restores_the_terminal() {
    signal_restores_the_terminal(libc::SIGHUP, &[]);
}

#[test]
fn sigint_from_outside_restores_the_terminal() {
    // Ctrl+C in raw mode is a key (quit); `kill -INT` is the signal.
    signal_restores_the_terminal(libc::SIGINT, &[]);
}

#[test]
fn sigquit_restores_the_terminal() {
    signal_restores_the_terminal(libc::SIGQUIT, &[]);
}

#[test]
fn a_signal_during_a_long_render_restores_the_terminal_at_once() {
    // 8000 x 6000 pixels of the built-in scene: about 20 s of rendering on
    // two cores, under way when the first screen is up; the exit must not
    // wait for it (the bound below leaves room for a loaded machine).
    let dir = tempfile::tempdir().unwrap();
    let scene = raystep_engine::scene::builtin::TEXT
        .replace("width = 161", "width = 8000")
        .replace("height = 121", "height = 6000");
    let path = dir.path().join("big.toml");
    std::fs::write(&path, scene).unwrap();
    signal_restores_the_terminal(libc::SIGTERM, &[path.to_str().unwrap()]);
}

#[test]
fn running_out_of_memory_restores_the_terminal() {
    // Under a 430 MiB address-space limit the debugger takes the terminal
    // (it needs about 370 MiB of address space with two threads), then
    // asks for the image of an 8192 x 8192 scene: 8192² x 3 bytes =
    // 201,326,592 for the pixels alone, more than the limit leaves (it runs
    // whole under 510 MiB: measured with `ulimit -v` in tmux). The refused block ends it with a message and exit 1, and
    // the terminal must come back as on quit (before, the alternate
    // screen and raw mode stayed).
    let dir = tempfile::tempdir().unwrap();
    let scene = raystep_engine::scene::builtin::TEXT
        .replace("width = 161", "width = 8192")
        .replace("height = 121", "height = 8192");
    let path = dir.path().join("big.toml");
    std::fs::write(&path, scene).unwrap();
    let mut session =
        Session::start_as(Start::LimitedSession(430 << 20), &[path.to_str().unwrap()]);
    let status = session.wait_for_exit();
    assert_eq!(status.code(), Some(1), "{status:?}");
    assert_eq!(session.cooked_and_echo(), (true, true), "cooked after");
    session.wait_for("the terminal taken", |text| text.contains("\x1b[?1049h"));
    session.wait_for("restore of every mode", all_modes_reset);
    // The message comes after the restore, on the shell's screen.
    session.wait_for("the message", |text| {
        text.rfind("error: out of memory: a block of 201326592 bytes was refused")
            > text.rfind("\x1b[?1049l")
    });
}

#[test]
fn quit_restores_the_terminal_too() {
    let mut session = Session::start(&[]);
    session.wait_for("first screen", |text| {
        text.contains("\x1b[?1006h") && text.contains("help")
    });
    session.keyboard.write_all(b"q").unwrap();
    let status = session.wait_for_exit();
    assert_eq!(status.code(), Some(0), "{status:?}");
    assert_eq!(session.cooked_and_echo(), (true, true), "cooked after");
    session.wait_for("restore of every mode", all_modes_reset);
}

/// The image pane's title once `l` moved the cursor to pixel (81, 60) of
/// the built-in scene.
const PIXEL_81_60: &str = "Pixel (81, 60) rgb(102,113,144)";

/// Every mode the debugger sets, set again in `text`, and a whole screen
/// drawn after a clear: the image pane's title (which a redraw of changes
/// alone would not send again) with `title` in it, and the status line's keys.
fn retaken_and_redrawn(text: &str, title: &str) -> bool {
    let Some(clear) = text.find("\x1b[2J") else {
        return false;
    };
    MODES[..5].iter().all(|(set, _)| text.contains(set))
        && text[clear..].contains(title)
        && text[clear..].contains("help")
}

/// Starts the debugger as a job, moves the pixel cursor one to the right,
/// stops it with `stop`, and checks that it gave the terminal back before
/// stopping with `signal`; continues it and checks that the terminal is
/// taken again and the screen redrawn as it was; then quits with `q`.
fn stop_gives_the_terminal_back_until_continued(stop: impl Fn(&mut Session), signal: i32) {
    let mut session = Session::start_as(Start::Job, &[]);
    session.wait_for("first screen", |text| {
        text.contains("\x1b[?1006h") && text.contains("help")
    });
    // The built-in scene opens on pixel (80, 60): `l` moves it to (81, 60),
    // whose colour the title then shows (as seen on screen).
    session.keyboard.write_all(b"l").unwrap();
    session.wait_for_screen(PIXEL_81_60);
    assert_eq!(
        session.cooked_and_echo(),
        (false, false),
        "raw while running"
    );

    let before_stop = session.written();
    stop(&mut session);
    assert_eq!(session.wait_for_stop(), signal);
    assert_eq!(
        session.cooked_and_echo(),
        (true, true),
        "cooked while stopped"
    );
    // What it wrote before stopping may still be in the pty on its way to
    // the thread that drains it.
    session.wait_for("every mode given back", all_modes_reset);
    let given_back = session.text_from(before_stop);
    for (_, reset) in MODES {
        assert!(given_back.contains(reset), "{reset:?} in {given_back:?}");
    }

    let before_continue = session.written();
    session.signal(libc::SIGCONT);
    session.wait_for_modes("raw again", (false, false));
    session.wait_for_from(before_continue, "the screen again", |text| {
        retaken_and_redrawn(text, PIXEL_81_60)
    });

    session.keyboard.write_all(b"q").unwrap();
    let status = session.wait_for_exit();
    assert_eq!(status.code(), Some(0), "{status:?}");
    assert_eq!(session.cooked_and_echo(), (true, true), "cooked after");
    session.wait_for("restore of every mode", all_modes_reset);
}

#[test]
fn ctrl_z_suspends_with_the_terminal_given_back_and_fg_redraws() {
    // Raw mode turns ISIG off: Ctrl+Z arrives as the byte 0x1a, a key.
    let type_ctrl_z = |session: &mut Session| session.keyboard.write_all(b"\x1a").unwrap();
    stop_gives_the_terminal_back_until_continued(type_ctrl_z, libc::SIGTSTP);
}

#[test]
fn sigtstp_from_outside_suspends_the_same_way() {
    let kill_tstp = |session: &mut Session| session.signal(libc::SIGTSTP);
    stop_gives_the_terminal_back_until_continued(kill_tstp, libc::SIGTSTP);
}

#[test]
fn after_sigstop_and_a_shell_cooking_the_terminal_continue_takes_it_again() {
    // SIGSTOP cannot be caught: the terminal stays raw while stopped. A shell
    // then sets its own modes; SIGCONT must set the debugger's again.
    let mut session = Session::start_as(Start::Job, &[]);
    session.wait_for("first screen", |text| {
        text.contains("\x1b[?1006h") && text.contains("help")
    });
    session.signal(libc::SIGSTOP);
    assert_eq!(session.wait_for_stop(), libc::SIGSTOP);
    assert_eq!(session.cooked_and_echo(), (false, false), "untouched");
    session.cook();

    let before_continue = session.written();
    session.signal(libc::SIGCONT);
    session.wait_for_modes("raw again", (false, false));
    session.wait_for_from(before_continue, "the screen again", |text| {
        retaken_and_redrawn(text, "Pixel (80, 60) rgb(105,123,143)")
    });
    session.keyboard.write_all(b"q").unwrap();
    assert_eq!(session.wait_for_exit().code(), Some(0));
    assert_eq!(session.cooked_and_echo(), (true, true), "cooked after");
}

/// Issue 27: a watched scene replaced by a FIFO was once reloaded on the
/// thread that answers the keys, which then waited for a writer for ever.
/// Now the reload runs beside it: the banner says why the FIFO is refused,
/// and `q` ends the debugger at once.
#[test]
fn a_watched_scene_replaced_by_a_fifo_leaves_q_answered() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, include_str!("../scenes/seven-rays.toml")).unwrap();
    let mut session = Session::start(&[path.to_str().unwrap()]);
    session.wait_for("first screen", |text| {
        text.contains("\x1b[?1006h") && text.contains("help")
    });
    std::fs::remove_file(&path).unwrap();
    let name = std::ffi::CString::new(path.to_str().unwrap()).unwrap();
    // SAFETY: a plain mkfifo(3) of a path we own.
    assert_eq!(unsafe { libc::mkfifo(name.as_ptr(), 0o600) }, 0);
    session.wait_for_screen("FIFO (a named pipe)");
    let asked = Instant::now();
    session.keyboard.write_all(b"q").unwrap();
    let status = loop {
        if let Some(status) = session.child.try_wait().unwrap() {
            break status;
        }
        assert!(
            asked.elapsed() < Duration::from_secs(1),
            "q not answered within a second"
        );
        std::thread::sleep(Duration::from_millis(5));
    };
    assert_eq!(status.code(), Some(0), "{status:?}");
}
