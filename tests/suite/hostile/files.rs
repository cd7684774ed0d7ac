//! Outputs aimed at inputs, inputs that are not regular files, readers
//! past their size caps, and a teacher's files in REPORT/.
//!
//! Issue 27, items 1 to 3: every output of a command is checked against
//! every file the command reads (the scene, each mesh and MTL it reads, the
//! student's image, the ray log, the assignment, a submission), however
//! spelt, before anything is written; a FIFO or a device given as any
//! input is refused at once, never opened for a blocking read; a file over
//! its reader's cap is refused from its length with both numbers said; and
//! the debugger reloads beside its keys, so a watched scene replaced by a
//! FIFO never freezes it. Issue 41, section 2: standard input is an input
//! too; the outputs of one run never collide; of a previous REPORT/ only
//! what raystep wrote is replaced, a teacher's own files kept. Every run
//! has a deadline: a regression fails here instead of hanging the tests.

use std::ffi::CString;
use std::fs::{self, File};
use std::os::unix::ffi::OsStrExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::mpsc::channel;
use std::time::{Duration, Instant};

use raystep::tui::{Action, App};

/// Long enough for a busy machine; a refusal takes milliseconds.
const DEADLINE: Duration = Duration::from_secs(30);

/// What a run of raystep ended with.
pub(super) struct Ended {
    code: Option<i32>,
    stderr: String,
}

/// `raystep ARGS` run in `dir` with no terminal, killed if it has not
/// ended by `DEADLINE` (and the test failed: it hung).
pub(super) fn run(dir: &Path, args: &[&str]) -> Ended {
    run_reading(dir, args, Stdio::null())
}

/// As `run`, with `stdin` as standard input.
fn run_reading(dir: &Path, args: &[&str], stdin: impl Into<Stdio>) -> Ended {
    let stderr_path = dir.join(".stderr");
    let mut child = Command::new(env!("CARGO_BIN_EXE_raystep"))
        .args(args)
        .current_dir(dir)
        .stdin(stdin)
        .stdout(Stdio::null())
        .stderr(File::create(&stderr_path).unwrap())
        .spawn()
        .expect("raystep runs");
    let started = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if started.elapsed() > DEADLINE {
            let _ = child.kill();
            let _ = child.wait();
            panic!("raystep {args:?} still ran after {DEADLINE:?}: it hung");
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    Ended {
        code: status.code(),
        stderr: fs::read_to_string(&stderr_path).unwrap(),
    }
}

/// Asserts that the run was refused (exit 1) saying `words`.
pub(super) fn refused(ended: &Ended, words: &str) {
    assert_eq!(ended.code, Some(1), "{}", ended.stderr);
    assert!(ended.stderr.contains("error: "), "{}", ended.stderr);
    assert!(ended.stderr.contains(words), "{}", ended.stderr);
}

pub(super) fn mkfifo(path: &Path) {
    let name = CString::new(path.as_os_str().as_bytes()).unwrap();
    assert_eq!(unsafe { libc::mkfifo(name.as_ptr(), 0o600) }, 0);
}

/// A folder holding the Cornell box (its scene, OBJ and MTL), an 8 x 8
/// render of it as "yours.png", a ray log of one of its pixels, and an
/// assignment with a student's folder handing that render in.
fn cornell() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cornell");
    for name in ["cornell.toml", "cornell.obj", "cornell.mtl"] {
        fs::copy(scenes.join(name), dir.path().join(name)).unwrap();
    }
    let rendered = run(
        dir.path(),
        &["render", "cornell.toml", "--size", "8x8", "-o", "yours.png"],
    );
    assert_eq!(rendered.code, Some(0), "{}", rendered.stderr);
    let log = Command::new(env!("CARGO_BIN_EXE_raystep"))
        .args(["inspect", "cornell.toml", "--size", "8x8", "--pixel", "4,4"])
        .args(["--format", "raylog"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    fs::write(dir.path().join("rays.jsonl"), log.stdout).unwrap();
    fs::write(
        dir.path().join("a.toml"),
        "title = \"t\"\n[[scene]]\nfile = \"cornell.toml\"\nsubmit = \"c.png\"\npoints = 1\nsize = [8, 8]\n",
    )
    .unwrap();
    fs::create_dir(dir.path().join("ada")).unwrap();
    fs::copy(dir.path().join("yours.png"), dir.path().join("ada/c.png")).unwrap();
    dir
}

/// Every file in `dir`, with its bytes, to show nothing was touched.
fn contents(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut files: Vec<_> = fs::read_dir(dir)
        .unwrap()
        .flatten()
        .filter(|e| e.file_type().unwrap().is_file() && e.file_name() != ".stderr")
        .map(|e| (e.path(), fs::read(e.path()).unwrap()))
        .collect();
    files.sort();
    files
}

#[test]
fn diagram_takes_no_diff_against_so_it_cannot_write_over_it() {
    // The case: `-o o.toml --diff-against o.toml` once replaced
    // o.toml by the figure.
    let dir = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/glass.toml");
    fs::copy(&scene, dir.path().join("o.toml")).unwrap();
    let before = fs::read(dir.path().join("o.toml")).unwrap();
    let scene = scene.to_str().unwrap();
    let ended = run(
        dir.path(),
        &[
            "diagram",
            scene,
            "--pixel",
            "72,45",
            "-o",
            "o.toml",
            "--diff-against",
            "o.toml",
        ],
    );
    assert_eq!(ended.code, Some(2), "a bad command line: {}", ended.stderr);
    assert!(
        ended.stderr.contains("diagram takes no --diff-against"),
        "{}",
        ended.stderr
    );
    assert_eq!(fs::read(dir.path().join("o.toml")).unwrap(), before);
}

#[test]
fn no_command_writes_over_a_mesh_or_mtl_its_scene_reads() {
    let dir = cornell();
    let d = dir.path();
    fs::hard_link(d.join("cornell.obj"), d.join("hard.png")).unwrap();
    std::os::unix::fs::symlink("cornell.mtl", d.join("link.svg")).unwrap();
    let before = contents(d);
    let size = ["--size", "8x8"];
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            [&["render", "cornell.toml", "-o", "cornell.obj"][..], &size].concat(),
            "cannot write cornell.obj: it is a file the scene reads, cornell.obj",
        ),
        (
            [
                &["render", "cornell.toml", "-o", "./x/../cornell.mtl"][..],
                &size,
            ]
            .concat(),
            "cannot write ./x/../cornell.mtl: it is a file the scene reads, cornell.mtl",
        ),
        (
            [
                &[
                    "diagram",
                    "cornell.toml",
                    "--pixel",
                    "4,4",
                    "-o",
                    "link.svg",
                ][..],
                &size,
            ]
            .concat(),
            "cannot write link.svg: it is a file the scene reads, cornell.mtl",
        ),
        (
            vec!["compare", "cornell.toml", "yours.png", "-o", "hard.png"],
            "cannot write hard.png: it is a file the scene reads, cornell.obj",
        ),
        (
            vec![
                "grade",
                "a.toml",
                "--submission",
                "ada",
                "--gradescope",
                "cornell.obj",
            ],
            "cannot write cornell.obj: it is a file the scene reads, cornell.obj",
        ),
    ];
    fs::create_dir(d.join("x")).unwrap();
    for (args, words) in cases {
        let ended = run(d, &args);
        refused(&ended, words);
        assert_eq!(contents(d), before, "{args:?} changed a file");
    }
}

#[test]
fn no_command_writes_over_any_other_input() {
    let dir = cornell();
    let d = dir.path();
    std::os::unix::fs::symlink("yours.png", d.join("link.png")).unwrap();
    let before = contents(d);
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec![
                "render",
                "./cornell.toml",
                "--size",
                "8x8",
                "-o",
                "cornell.toml",
            ],
            "cannot write cornell.toml: it is the scene file ./cornell.toml",
        ),
        (
            vec![
                "diagram",
                "cornell.toml",
                "--size",
                "8x8",
                "--pixel",
                "4,4",
                "-o",
                "./cornell.toml",
            ],
            "it is the scene file cornell.toml",
        ),
        (
            vec!["compare", "cornell.toml", "yours.png", "-o", "link.png"],
            "cannot write link.png: it is your image yours.png",
        ),
        (
            vec![
                "compare",
                "cornell.toml",
                "--size",
                "8x8",
                "--rays",
                "rays.jsonl",
                "-o",
                "./rays.jsonl",
            ],
            "it is your ray log rays.jsonl",
        ),
        (
            vec![
                "grade",
                "a.toml",
                "--submission",
                "ada",
                "--prairielearn",
                "a.toml",
            ],
            "cannot write a.toml: it is the assignment a.toml",
        ),
        (
            vec![
                "grade",
                "a.toml",
                "--submission",
                "ada",
                "--gradescope",
                "ada/c.png",
            ],
            "cannot write ada/c.png: it is the submission",
        ),
    ];
    for (args, words) in cases {
        let ended = run(d, &args);
        refused(&ended, words);
        assert_eq!(contents(d), before, "{args:?} changed a file");
    }
}

#[test]
fn compare_never_writes_over_the_ray_log_it_reads_from_standard_input() {
    // Issue 41: `compare SCENE IMG --rays - -o LOG < LOG` replaced the log
    // by the error map: standard input is an input too, by any name.
    let dir = cornell();
    let d = dir.path();
    fs::hard_link(d.join("rays.jsonl"), d.join("hard.png")).unwrap();
    std::os::unix::fs::symlink("rays.jsonl", d.join("link.png")).unwrap();
    let before = contents(d);
    for out in ["rays.jsonl", "hard.png", "./link.png"] {
        let log = File::open(d.join("rays.jsonl")).unwrap();
        let args = [
            "compare",
            "cornell.toml",
            "yours.png",
            "--rays",
            "-",
            "-o",
            out,
        ];
        refused(
            &run_reading(d, &args, log),
            &format!("cannot write {out}: it is your ray log, read from standard input"),
        );
        assert_eq!(contents(d), before, "{out} changed a file");
    }
    // Any other file is written as before, the log read from stdin.
    let log = File::open(d.join("rays.jsonl")).unwrap();
    let args = [
        "compare",
        "cornell.toml",
        "yours.png",
        "--rays",
        "-",
        "-o",
        "map.png",
    ];
    let ended = run_reading(d, &args, log);
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    let map = image::open(d.join("map.png")).unwrap();
    assert_eq!((map.width(), map.height()), (8, 8));
}

/// Every entry under `dir` but raystep's stderr, relative (folders with a
/// `/`), with its bytes, where it links to, or nothing for a folder.
fn tree(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut found = Vec::new();
    let mut stack = vec![dir.to_owned()];
    while let Some(folder) = stack.pop() {
        for entry in fs::read_dir(&folder).unwrap() {
            let path = entry.unwrap().path();
            let name = path.strip_prefix(dir).unwrap().to_str().unwrap().to_owned();
            let kind = fs::symlink_metadata(&path).unwrap().file_type();
            if name == ".stderr" {
                continue;
            } else if kind.is_dir() {
                found.push((format!("{name}/"), Vec::new()));
                stack.push(path);
            } else if kind.is_symlink() {
                let to = fs::read_link(&path).unwrap();
                found.push((name, to.as_os_str().as_bytes().to_vec()));
            } else {
                found.push((name, fs::read(&path).unwrap()));
            }
        }
    }
    found.sort();
    found
}

/// `cornell()` with a class beside it: ada and bob, each handing in the
/// render, graded into report/.
fn graded_class() -> tempfile::TempDir {
    let dir = cornell();
    let d = dir.path();
    for student in ["ada", "bob"] {
        fs::create_dir_all(d.join("class").join(student)).unwrap();
        fs::copy(
            d.join("yours.png"),
            d.join("class").join(student).join("c.png"),
        )
        .unwrap();
    }
    let ended = run(d, &["grade", "a.toml", "class", "-o", "report"]);
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    dir
}

/// The names of the hidden folders raystep made beside the report.
fn hidden_folders(d: &Path) -> Vec<String> {
    (fs::read_dir(d).unwrap())
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|name| name.starts_with(".raystep"))
        .collect()
}

#[test]
fn a_teachers_files_in_a_previous_report_are_kept_and_only_raysteps_replaced() {
    // Issue 41: a previous REPORT/ into which the teacher saved notes.txt
    // or a folder was replaced whole, and those files were gone.
    let dir = graded_class();
    let d = dir.path();
    let report = d.join("report");
    assert!(report.join("students/bob.html").exists());
    fs::write(report.join("notes.txt"), "bob: late, see email").unwrap();
    fs::create_dir_all(report.join("comments/week 4")).unwrap();
    fs::write(report.join("comments/week 4/ada.txt"), "good").unwrap();
    fs::write(report.join("images/ada/remark.txt"), "shadow acne?").unwrap();
    fs::create_dir(report.join("empty")).unwrap();
    std::os::unix::fs::symlink("grades.csv", report.join("latest.csv")).unwrap();
    let teachers = [
        ("comments/", &b""[..]),
        ("comments/week 4/", b""),
        ("comments/week 4/ada.txt", b"good"),
        ("empty/", b""),
        ("images/ada/remark.txt", b"shadow acne?"),
        ("latest.csv", b"grades.csv"),
        ("notes.txt", b"bob: late, see email"),
    ];
    // Bob leaves the class: his pages and images were raystep's, and go.
    fs::remove_dir_all(d.join("class/bob")).unwrap();
    let ended = run(d, &["grade", "a.toml", "class", "-o", "report"]);
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    let after = tree(&report);
    for (name, bytes) in teachers {
        assert!(
            after.contains(&(name.to_string(), bytes.to_vec())),
            "{name} was not kept: {after:?}"
        );
    }
    assert!(!report.join("students/bob.html").exists());
    assert!(!report.join("images/bob").exists());
    let grades = fs::read_to_string(report.join("grades.csv")).unwrap();
    assert!(
        grades.contains("ada") && !grades.contains("bob"),
        "{grades}"
    );
    assert_eq!(hidden_folders(d), Vec::<String>::new());
}

#[test]
fn a_changed_report_file_or_a_teachers_file_in_the_way_is_refused_untouched() {
    let dir = graded_class();
    let d = dir.path();
    let report = d.join("report");
    // grades.csv opened in a spreadsheet, a column of comments added.
    let mut grades = fs::read(report.join("grades.csv")).unwrap();
    let written = grades.clone();
    grades.extend_from_slice(b"comments: ada retakes\r\n");
    fs::write(report.join("grades.csv"), &grades).unwrap();
    let before = tree(&report);
    let ended = run(d, &["grade", "a.toml", "class", "-o", "report"]);
    refused(
        &ended,
        "cannot write the report into report: files in the way of the new report, which \
         raystep does not delete: grades.csv (changed since raystep wrote it); move them out \
         of the folder, or name another folder",
    );
    assert_eq!(tree(&report), before);
    // Put back as written, the report is replaced as before.
    fs::write(report.join("grades.csv"), &written).unwrap();
    let ended = run(d, &["grade", "a.toml", "class", "-o", "report"]);
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    // A page the teacher made where a new student's page goes.
    fs::create_dir(d.join("class/cy")).unwrap();
    fs::copy(d.join("yours.png"), d.join("class/cy/c.png")).unwrap();
    fs::write(report.join("students/cy.html"), "<p>cy: to do</p>").unwrap();
    let before = tree(&report);
    let ended = run(d, &["grade", "a.toml", "class", "-o", "report"]);
    refused(&ended, "students/cy.html (not written by raystep)");
    assert_eq!(tree(&report), before);
    assert_eq!(hidden_folders(d), Vec::<String>::new());
}

#[test]
fn the_results_files_never_collide_with_the_report_and_nothing_is_written() {
    // Issue 41: `--gradescope R/grades.json -o R` overwrote the report's
    // own grades.json; `--prairielearn R -o R` half-wrote.
    let dir = graded_class();
    let d = dir.path();
    let before = tree(d);
    fn one<'a>(extra: &[&'a str]) -> Vec<&'a str> {
        [&["grade", "a.toml", "--submission", "ada"][..], extra].concat()
    }
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            one(&["-o", "report", "--gradescope", "report/grades.json"]),
            "cannot write report/grades.json (--gradescope): it lies inside the report \
             folder report (-o), which raystep replaces whole",
        ),
        (
            one(&["-o", "new", "--prairielearn", "new"]),
            "cannot write new (--prairielearn): it is the report folder new (-o)",
        ),
        (
            one(&["-o", "new", "--gradescope", "new/results/r.json"]),
            "cannot write new/results/r.json (--gradescope): it lies inside the report folder new (-o)",
        ),
        (
            one(&["-o", "new/report", "--prairielearn", "./new"]),
            "cannot write ./new (--prairielearn): the report folder new/report (-o) lies inside it",
        ),
        (
            one(&[
                "--gradescope",
                "new/r.json",
                "--prairielearn",
                "new/./r.json",
            ]),
            "cannot write new/./r.json: it would be both the results of --gradescope and the \
             results of --prairielearn",
        ),
    ];
    for (args, words) in cases {
        refused(&run(d, &args), words);
        // Nothing written: no file, no folder made for one.
        let after = tree(d);
        let changed: Vec<&String> = (after.iter().filter(|e| !before.contains(e)))
            .chain(before.iter().filter(|e| !after.contains(e)))
            .map(|(name, _)| name)
            .collect();
        assert!(changed.is_empty(), "{args:?} changed {changed:?}");
    }
}

#[test]
fn a_fifo_given_as_any_input_is_refused_at_once() {
    let dir = cornell();
    let d = dir.path();
    for name in ["fifo.toml", "fifo.png", "fifo.jsonl", "fifo.obj"] {
        mkfifo(&d.join(name));
    }
    fs::write(
        d.join("fifo-mesh.toml"),
        fs::read_to_string(d.join("cornell.toml"))
            .unwrap()
            .replace("cornell.obj", "fifo.obj"),
    )
    .unwrap();
    let fifo = "it is a FIFO (a named pipe), not a regular file";
    let cases: Vec<(Vec<&str>, String)> = vec![
        (
            vec!["inspect", "fifo.toml", "--pixel", "1,1"],
            format!("cannot read fifo.toml: {fifo}"),
        ),
        (
            vec!["render", "fifo.toml", "-o", "out.png"],
            format!("cannot read fifo.toml: {fifo}"),
        ),
        (
            vec!["compare", "cornell.toml", "fifo.png"],
            format!("cannot read fifo.png: {fifo}"),
        ),
        (
            vec!["debug", "cornell.toml", "--compare", "fifo.png"],
            format!("cannot read fifo.png: {fifo}"),
        ),
        (
            vec!["cornell.toml", "--compare", "fifo.png"],
            format!("cannot read fifo.png: {fifo}"),
        ),
        (
            vec![
                "explain",
                "cornell.toml",
                "--pixel",
                "1,1",
                "--diff-against",
                "fifo.toml",
            ],
            format!("cannot read fifo.toml: {fifo}"),
        ),
        (
            vec!["compare", "cornell.toml", "--rays", "fifo.jsonl"],
            format!("cannot read the ray log fifo.jsonl: {fifo}"),
        ),
        (
            vec!["debug", "cornell.toml", "--rays", "fifo.jsonl"],
            format!("cannot read the ray log fifo.jsonl: {fifo}"),
        ),
        (
            vec!["inspect", "fifo-mesh.toml", "--pixel", "1,1"],
            format!("cannot read mesh file fifo.obj: {fifo}"),
        ),
        (
            vec!["grade", "fifo.toml", "--submission", "ada"],
            format!("cannot read the assignment fifo.toml: {fifo}"),
        ),
    ];
    for (args, words) in cases {
        let started = Instant::now();
        refused(&run(d, &args), &words);
        assert!(
            started.elapsed() < Duration::from_secs(10),
            "{args:?} took {:?}",
            started.elapsed()
        );
    }
}

#[test]
fn a_device_as_the_scene_is_refused_before_a_byte_is_read() {
    // Once read until memory ran out (2 GB, then "out of memory").
    let dir = tempfile::tempdir().unwrap();
    let ended = run(dir.path(), &["inspect", "/dev/zero", "--pixel", "1,1"]);
    refused(
        &ended,
        "cannot read /dev/zero: it is a character device, not a regular file",
    );
}

#[test]
fn a_file_over_its_cap_is_refused_with_its_length_and_the_cap() {
    let dir = cornell();
    let d = dir.path();
    // Sparse: as long as said, with no blocks written.
    let sparse = |name: &str, length: u64| {
        File::create(d.join(name)).unwrap().set_len(length).unwrap();
    };
    const MIB: u64 = 1 << 20;
    sparse("big.toml", 256 * MIB + 1);
    sparse("big.obj", 1024 * MIB + 1);
    sparse("big.png", 49 * MIB + 1);
    sparse("big.jsonl", 1024 * MIB + 1);
    sparse("big-assignment.toml", 16 * MIB + 1);
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["inspect", "big.toml", "--pixel", "1,1"],
            "cannot read big.toml: it is 268435457 bytes, more than the 256 MiB (268435456 bytes) a scene file may be",
        ),
        (
            vec!["render", "big.obj", "-o", "out.png"],
            "cannot read mesh file big.obj: it is 1073741825 bytes, more than the 1 GiB (1073741824 bytes) a mesh or MTL file may be",
        ),
        (
            vec!["compare", "cornell.toml", "big.png"],
            "cannot read big.png: it is 51380225 bytes, more than the 49 MiB (51380224 bytes) a student's PNG may be",
        ),
        (
            vec!["compare", "cornell.toml", "--rays", "big.jsonl"],
            "cannot read the ray log big.jsonl: it is 1073741825 bytes, more than the 1 GiB (1073741824 bytes) a ray log may be",
        ),
        (
            vec!["grade", "big-assignment.toml", "--submission", "ada"],
            "cannot read the assignment big-assignment.toml: it is 16777217 bytes, more than the 16 MiB (16777216 bytes) an assignment file may be",
        ),
    ];
    for (args, words) in cases {
        refused(&run(d, &args), words);
    }
}

#[test]
fn a_watched_scene_replaced_by_a_fifo_never_freezes_the_debugger() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.toml");
    fs::write(&path, include_str!("../../../scenes/seven-rays.toml")).unwrap();
    let (done, finished) = channel();
    let scene = path.clone();
    // The debugger's loop on a thread of the test's, so that a freeze is
    // seen as a deadline passed rather than a test that never ends.
    std::thread::spawn(move || {
        let mut app = App::open(Some(scene.clone()), false).unwrap().watching();
        std::thread::sleep(Duration::from_millis(100));
        fs::remove_file(&scene).unwrap();
        mkfifo(&scene);
        let started = Instant::now();
        let mut slowest = Duration::ZERO;
        while app.session().error().is_none() && started.elapsed() < DEADLINE {
            let tick = Instant::now();
            app.update(Action::Tick);
            slowest = slowest.max(tick.elapsed());
            std::thread::sleep(Duration::from_millis(20));
        }
        let error = app.session().error().map(str::to_owned);
        let quit = Instant::now();
        app.update(Action::Quit);
        let _ = done.send((error, slowest, quit.elapsed(), app.should_quit()));
    });
    let Ok((error, slowest, quitting, quit)) = finished.recv_timeout(DEADLINE * 2) else {
        // Free the frozen reader, if it is still waiting for a writer.
        let name = CString::new(path.as_os_str().as_bytes()).unwrap();
        unsafe { libc::close(libc::open(name.as_ptr(), libc::O_WRONLY | libc::O_NONBLOCK)) };
        panic!("the debugger froze on the FIFO");
    };
    let error = error.expect("the reload failed, with a banner");
    assert!(
        error.contains("it is a FIFO (a named pipe), not a regular file"),
        "{error}"
    );
    assert!(
        slowest < Duration::from_millis(100),
        "a tick took {slowest:?}"
    );
    assert!(
        quit && quitting < Duration::from_millis(100),
        "q took {quitting:?}"
    );
}
