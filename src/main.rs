//! `canstar`: generate CAN controller and CAN star hub RTL, and simulate it.
//! The commands live in `cli/`, one file each.

mod cli;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args = cli::Cli::parse();
    match cli::run(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if cli::print::is_broken_pipe(&e) => {
            canstar::output::abandon_and_exit(cli::print::CLOSED_STDOUT)
        }
        Err(e) => {
            cli::print::err(format_args!("error: {e:#}\n"));
            ExitCode::FAILURE
        }
    }
}
