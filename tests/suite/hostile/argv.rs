//! The command line is data too: clap quotes a bad argument verbatim
//! (`unexpected argument '--…'`, `invalid value '…' for '--pixel'`), so a
//! flag or value holding ESC, BEL, a C1 control, DEL or U+FFFF reached the
//! terminal raw (issue 27, item 4, for argv). raystep spells them as it
//! spells names (`crate::printable`: `\u{1b}`), keeps clap's exit code 2,
//! and a non-UTF-8 argument is never echoed as its raw bytes.

use std::ffi::OsString;
use std::os::unix::ffi::OsStringExt;
use std::process::{Command, Output};

/// The hostile characters, and how raystep spells each (lower-case hex, as
/// Rust's `escape_unicode`: ESC is 0x1B, BEL 7, U+0085 a C1 control, DEL
/// 0x7F, U+FFFF a noncharacter).
const HOSTILE: [(&str, &str); 5] = [
    ("\u{1b}[31m", r"\u{1b}[31m"),
    ("\u{7}", r"\u{7}"),
    ("\u{85}", r"\u{85}"),
    ("\u{7f}", r"\u{7f}"),
    ("\u{ffff}", r"\u{ffff}"),
];

/// raystep run with `args`, its stderr a pipe; with `colour`, as on a
/// colour terminal. On a pipe clap's own writer (anstream) strips escape
/// sequences and controls itself, but a terminal got them raw, clap's
/// colours around them: `CLICOLOR_FORCE=1` makes clap write as it does to
/// a terminal, and there raystep must write no control character at all
/// (its escaped message is plain text, without clap's colours).
fn raystep_os(args: &[OsString], colour: bool) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_raystep"));
    command.args(args).current_dir(env!("CARGO_MANIFEST_DIR"));
    command.env_remove("CLICOLOR_FORCE").env_remove("NO_COLOR");
    if colour {
        command.env("CLICOLOR_FORCE", "1");
    }
    command.output().expect("raystep runs")
}

/// The characters of `bytes` (lossily decoded, so bytes that are not UTF-8
/// show as U+FFFD, which is harmless) that no terminal should get raw:
/// C0 controls but the line break, DEL, C1 controls, U+FFFE and U+FFFF;
/// and whether `bytes` is UTF-8 at all.
fn raw_controls(bytes: &[u8]) -> (Vec<char>, bool) {
    let text = String::from_utf8_lossy(bytes);
    let bad = text
        .chars()
        .filter(|&c| c != '\n')
        .filter(|&c| c.is_control() || c == '\u{fffe}' || c == '\u{ffff}')
        .collect();
    (bad, std::str::from_utf8(bytes).is_ok())
}

/// raystep refuses `args` with status 2, on a pipe and on a colour
/// terminal alike, naming the bad argument as `spelt` and writing no raw
/// control character.
fn assert_escaped(args: &[OsString], spelt: &str) {
    for colour in [false, true] {
        let output = raystep_os(args, colour);
        let (bad, utf8) = raw_controls(&output.stderr);
        let stderr = String::from_utf8_lossy(&output.stderr);
        let what = format!("{args:?} (colour {colour})");
        assert!(bad.is_empty(), "{what}: raw {bad:?} in {stderr}");
        assert!(utf8, "{what}: stderr is not UTF-8: {stderr}");
        assert!(stderr.contains(spelt), "{what}: no {spelt} in {stderr}");
        assert_eq!(output.status.code(), Some(2), "{what}: {stderr}");
        assert!(output.stdout.is_empty(), "{what}");
    }
}

#[test]
fn an_unknown_flag_or_a_bad_value_is_quoted_escaped() {
    for (raw, spelt) in HOSTILE {
        // An unknown flag: clap's "unexpected argument '--x…' found".
        let flag = format!("--x{raw}");
        assert_escaped(
            &["render".into(), "scenes/glass.toml".into(), flag.into()],
            spelt,
        );
        // A bad value: clap's "invalid value '1,…' for '--pixel <X,Y>'".
        let value = format!("1,{raw}");
        assert_escaped(
            &[
                "inspect".into(),
                "scenes/glass.toml".into(),
                "--pixel".into(),
                value.into(),
            ],
            spelt,
        );
        // An unknown command: the first word taken as the debugger's scene
        // would be a file; two words are "unexpected argument".
        let word = format!("render{raw}");
        assert_escaped(&[word.clone().into(), word.into()], spelt);
    }
}

#[test]
fn an_argument_that_is_not_utf8_never_reaches_the_terminal_as_bytes() {
    // "--x" then 0xFF 0x1B: not UTF-8, and an ESC behind it. clap reads a
    // flag lossily (0xFF as U+FFFD); the ESC must still be spelt out.
    let flag = OsString::from_vec(b"--x\xff\x1b[31m".to_vec());
    assert_escaped(
        &["render".into(), "scenes/glass.toml".into(), flag],
        r"\u{1b}[31m",
    );
    // A --pixel value clap reads as a String: clap refuses it as invalid
    // UTF-8, exit 2, with no raw byte (the ESC included) on stderr.
    let value = OsString::from_vec(b"1,\xff\x1b".to_vec());
    let args = [
        "inspect".into(),
        "scenes/glass.toml".into(),
        "--pixel".into(),
        value,
    ];
    for colour in [false, true] {
        let output = raystep_os(&args, colour);
        let (bad, utf8) = raw_controls(&output.stderr);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            bad.is_empty() && utf8,
            "colour {colour}: raw {bad:?} in {stderr}"
        );
        assert!(
            stderr.contains("invalid UTF-8"),
            "colour {colour}: {stderr}"
        );
        assert_eq!(output.status.code(), Some(2), "{stderr}");
    }
}

#[test]
fn help_still_exits_0_on_stdout_with_a_hostile_argument_beside_it() {
    // clap prints --help to stdout with status 0 whatever else argv holds;
    // the escaped path keeps both (the help names no argument).
    let args = ["render".into(), "--help".into(), "\u{1b}[31m".into()];
    let output = raystep_os(&args, true);
    let (bad, _) = raw_controls(&output.stdout);
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(bad.is_empty(), "{bad:?}");
    assert!(String::from_utf8_lossy(&output.stdout).contains("Usage: raystep render"));
}
