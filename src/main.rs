use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = raystep::cli::Cli::parse();
    match raystep::cli::run(cli) {
        Ok(code) => code,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}
