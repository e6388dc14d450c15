use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = tetrafoil::cli::Cli::parse();
    match tetrafoil::cli::run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
