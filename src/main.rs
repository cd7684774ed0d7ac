use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = raystep::cli::parse_or_exit();
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
