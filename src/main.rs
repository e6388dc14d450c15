use clap::Parser;
use std::process::ExitCode;

/// mimalloc, with each block charged to the service job whose thread allocated it (the
/// service's per-job memory limit; outside a job the count is one thread-local read).
#[global_allocator]
static ALLOCATOR: tetrafoil::service::memory::Counting<mimalloc::MiMalloc> =
    tetrafoil::service::memory::Counting(mimalloc::MiMalloc);

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
