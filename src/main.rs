use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    slipfront::cli::main_with(slipfront::cli::Cli::parse())
}
