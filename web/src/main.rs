//! Prints every panel's check fingerprint, `name hex` a line: what the browser's must equal
//! (`cargo run -p odyn-web --features deterministic`; `scripts/browser.sh` compares).

use std::process::ExitCode;

fn main() -> ExitCode {
    match lab::fingerprints() {
        Ok(lines) => {
            for (name, fingerprint) in lines {
                println!("{name} {fingerprint}");
            }
            ExitCode::SUCCESS
        }
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}
