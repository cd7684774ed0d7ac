use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = raystep::cli::Cli::parse();
    if let Err(usage) = cli.check_combinations() {
        usage.exit();
    }
    match raystep::cli::run(cli) {
        Ok(code) => code,
        Err(error) => {
            // A name quoted in the message may hold control characters.
            let message = format!("{error:#}");
            eprintln!("error: {}", raystep::printable::printable_text(&message));
            ExitCode::FAILURE
        }
    }
}
