//! The command line read, or the process ended with clap's message. clap
//! quotes the offending argument verbatim (`unexpected argument '…'`), so an
//! argument holding ESC, BEL, a C1 control, DEL, U+FFFE/U+FFFF (or bytes
//! that are not UTF-8) would reach the terminal raw: when one does, the
//! message is rendered without colours and spelt as `raystep_engine::printable`
//! spells names (`\u{1b}`). Exit codes stay clap's: 2 for a usage error,
//! 0 for `--help` and `--version` (which print to stdout).

use std::ffi::OsString;
use std::io::Write;

use clap::builder::Styles;
use clap::{CommandFactory, FromArgMatches};

use super::Cli;
use raystep_engine::printable::{printable_text, unprintable};

/// `Cli::parse()` and the flag combinations clap cannot check itself
/// (`Cli::check_combinations`), with argv escaped in any message.
pub fn parse_or_exit() -> Cli {
    let hostile = std::env::args_os().any(|a| hostile(&a));
    let mut command = Cli::command();
    if hostile {
        // No colours: the message is then plain text, the arguments in it
        // as given (clap's `StyledStr` shown with `Display` strips escape
        // sequences and controls, the argument's own ones too, so the
        // message would misquote it).
        command = command.styles(Styles::plain());
    }
    let parsed = (command.try_get_matches_from_mut(std::env::args_os()))
        .and_then(|mut matches| Cli::from_arg_matches_mut(&mut matches))
        .map_err(|error| error.format(&mut command));
    let cli = parsed.unwrap_or_else(|error| exit(error, hostile));
    if let Err(error) = cli.check_combinations() {
        // Its message is raystep's own, quoting no argument.
        error.exit();
    }
    cli
}

/// Whether an argument would carry a character no terminal should get raw
/// (`printable::unprintable`), or is not UTF-8 (shown lossily, but a
/// terminal must not be handed its bytes either).
pub(crate) fn hostile(argument: &OsString) -> bool {
    argument
        .to_str()
        .is_none_or(|text| text.contains(unprintable))
}

/// Prints `error` as clap would, spelt out when argv is `hostile` (the
/// error then comes from a command without styles), and exits with clap's
/// status.
fn exit(error: clap::Error, hostile: bool) -> ! {
    if !hostile {
        error.exit();
    }
    let text = error.render().ansi().to_string();
    let text = printable_text(&text);
    // A closed pipe is no reason to change the status.
    let _ = if error.use_stderr() {
        std::io::stderr().lock().write_all(text.as_bytes())
    } else {
        let mut out = std::io::stdout().lock();
        out.write_all(text.as_bytes()).and_then(|()| out.flush())
    };
    std::process::exit(error.exit_code())
}

#[cfg(test)]
mod tests {
    use std::os::unix::ffi::OsStringExt;

    use super::*;

    #[test]
    fn hostile_arguments() {
        // ESC, DEL, a C1 control (U+0085) and U+FFFF are unprintable; 0xFF
        // alone is not UTF-8; letters beyond ASCII are fine.
        for bad in ["a\u{1b}[31m", "\u{7f}", "\u{85}", "x\u{ffff}"] {
            assert!(hostile(&OsString::from(bad)), "{bad:?}");
        }
        assert!(hostile(&OsString::from_vec(vec![b'a', 0xff])));
        assert!(!hostile(&OsString::from("scène-漢.toml")));
    }
}
