//! Headless Chromium for the report's tests: the DOM of a page after the
//! browser has parsed it (`--dump-dom`), or a screenshot. Debian's
//! `chromium`; `.ci/run` installs it when it is missing. Without it a test
//! is skipped with a note, unless CI is set: there it must run.

use std::fs::File;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Longer than a page of the report takes on a loaded 2-core machine
/// (a few seconds), short enough that a hung browser fails the test.
const TIMEOUT: Duration = Duration::from_secs(90);

pub struct Chromium {
    program: PathBuf,
}

/// The browser, or `None` after printing why `test` is skipped. With CI
/// set (and not `false` or `0`), a missing browser fails the test instead
/// (`super::program_or_skip`).
pub fn chromium_or_skip(test: &str) -> Option<Chromium> {
    let program = (super::on_path("chromium"))
        .or_else(|| super::on_path("chromium-browser"))
        .or_else(|| super::program_or_skip("chromium"));
    if program.is_none() {
        eprintln!("note: {test} skipped (apt-get install chromium)");
    }
    program.map(|program| Chromium { program })
}

impl Chromium {
    /// The browser's program, for a test that drives it itself.
    pub fn program(&self) -> &Path {
        &self.program
    }

    /// `page`'s DOM, serialised, after the browser loaded it from `file://`.
    pub fn dump_dom(&self, page: &Path) -> String {
        self.dump_dom_at(page, "")
    }

    /// As `dump_dom`, the page opened at `fragment` (`#sort=total`, or ""),
    /// after its scripts ran.
    pub fn dump_dom_at(&self, page: &Path, fragment: &str) -> String {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("dom.html");
        let url = format!("{}{fragment}", file_url(page));
        self.run(&["--dump-dom".to_string(), url], &out, dir.path());
        std::fs::read_to_string(out).unwrap()
    }

    /// A `width` x `height` screenshot of `page`, written to `png`.
    pub fn screenshot(&self, page: &Path, png: &Path, (width, height): (u32, u32)) {
        let dir = tempfile::tempdir().unwrap();
        let args = [
            format!("--screenshot={}", png.display()),
            format!("--window-size={width},{height}"),
            "--hide-scrollbars".to_string(),
            file_url(page),
        ];
        self.run(&args, &dir.path().join("stdout"), dir.path());
        assert!(png.is_file(), "no screenshot of {}", page.display());
    }

    /// Runs the browser with `args` after the flags that keep it from the
    /// network and from any profile, its stdout into `out`; it is killed,
    /// with every process it started, after `TIMEOUT`.
    fn run(&self, args: &[String], out: &Path, scratch: &Path) {
        let profile = scratch.join("profile");
        let errors = scratch.join("stderr");
        let mut child = Command::new(&self.program)
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--disable-background-networking",
                "--disable-component-update",
                "--disable-sync",
                "--no-first-run",
            ])
            .arg(format!("--user-data-dir={}", profile.display()))
            .args(args)
            .stdin(Stdio::null())
            .stdout(File::create(out).unwrap())
            .stderr(File::create(&errors).unwrap())
            // Its own process group, so that a timeout ends the renderer and
            // the zygote with it.
            .process_group(0)
            .spawn()
            .expect("chromium starts");
        let start = Instant::now();
        let status = loop {
            if let Some(status) = child.try_wait().unwrap() {
                break status;
            }
            if start.elapsed() > TIMEOUT {
                // SAFETY: kill(2) on the group this test started, by its id.
                unsafe { libc::kill(-(child.id() as i32), libc::SIGKILL) };
                let _ = child.wait();
                panic!("chromium took more than {TIMEOUT:?} on {args:?}");
            }
            std::thread::sleep(Duration::from_millis(50));
        };
        assert!(
            status.success(),
            "chromium failed ({status}) on {args:?}: {}",
            std::fs::read_to_string(errors).unwrap_or_default()
        );
    }
}

/// `file:///...` for `path`, made absolute, each byte outside the
/// unreserved set and `/` percent-encoded.
pub fn file_url(path: &Path) -> String {
    let absolute = std::path::absolute(path).unwrap();
    let mut url = String::from("file://");
    for byte in absolute.as_os_str().as_encoded_bytes() {
        if byte.is_ascii_alphanumeric() || b"-._~/".contains(byte) {
            url.push(*byte as char);
        } else {
            url.push_str(&format!("%{byte:02X}"));
        }
    }
    url
}
