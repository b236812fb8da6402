//! The command line: one file per command, each with its clap arguments and the
//! printing of its results; the work itself is done by the library crates.

use anyhow::Result;
use clap::{Parser, Subcommand};

/// `println!` that ends the command quietly when standard output is closed.
macro_rules! outln {
    () => { $crate::cli::print::out(format_args!("\n")) };
    ($($t:tt)*) => { $crate::cli::print::out(format_args!("{}\n", format_args!($($t)*))) };
}

/// `print!` that ends the command quietly when standard output is closed.
macro_rules! out {
    ($($t:tt)*) => { $crate::cli::print::out(format_args!($($t)*)) };
}

/// `eprintln!` that ignores a closed standard error.
macro_rules! errln {
    ($($t:tt)*) => { $crate::cli::print::err(format_args!("{}\n", format_args!($($t)*))) };
}

pub mod print;
mod bench;
mod boards;
mod build;
mod campaign;
mod conformance;
mod fuzz;
mod generate;
mod progress;
mod report;
mod sim;
mod soak;

#[derive(Parser)]
#[command(name = "canstar", version, about = "CAN controller and CAN star hub RTL generator with a cycle simulator")]
pub struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Generate Verilog (and pin files) for a design, with defaults or from a TOML config.
    Generate(generate::Args),
    /// List the boards (FPGA family, part, clock, pin-file format, the designs each has a
    /// pinout for: hub, controller); given names or board .toml files, check and list those.
    Boards(boards::Args),
    /// Build an iCE40 bitstream of one role (hub, controller) for a board: Yosys, nextpnr-ice40
    /// (design clock from the board oscillator through the iCE40 PLL, timing checked at it) and
    /// icepack; writes <out>/<board>/<role>/<top>.bin and prints the iceprog command.
    Build(build::Args),
    /// Synthesise the generated designs and print a resource table (iCE40 cells, flip-flops,
    /// block RAMs and fmax with Yosys + nextpnr-ice40; Spartan-3 LUTs and flip-flops with Yosys).
    Report(report::Args),
    /// Simulate a bus scenario (TOML: nodes, bit timing, clock offsets, frames, interference),
    /// or a ReCANcentrate network file (top-level `[network]`, see examples/recancentrate.toml)
    /// running its test applications.
    Sim(sim::Args),
    /// Measure simulation throughput (simulated clock cycles per second).
    Bench(bench::Args),
    /// Randomised differential testing: RTL nodes in lock step with golden models on a bus with
    /// random traffic and receive-path disturbances; prints divergences and property violations.
    Fuzz(fuzz::Args),
    /// Run the Bosch conformance suite (conformance-tests.md) in the multi-node simulation:
    /// one line per program, a line with the simulation effort and throughput (clock cycles,
    /// bit times, wall time), then `N passed, M failed` counting steps.
    Conformance(conformance::Args),
    /// Fault campaigns on the ReCANcentrate system: every selected scenario class repeated
    /// with random injection instants, traffic phases and oscillator offsets; prints per class
    /// runs, passes, worst healthy TEC/REC, isolation latency and every failure with its seed.
    Campaign(campaign::Args),
    /// Fault-free soak of the reference two-hub network at full load with every oscillator at
    /// the tolerance limit (optionally with the legal events of healthy nodes); prints frames,
    /// blames, isolations and the worst TEC/REC.
    Soak(soak::Args),
}

/// Run the parsed command.
pub fn run(cli: Cli) -> Result<()> {
    match cli.cmd {
        Cmd::Generate(a) => generate::run(a),
        Cmd::Boards(a) => boards::run(a),
        Cmd::Build(a) => build::run(a),
        Cmd::Report(a) => report::run(a),
        Cmd::Sim(a) => sim::run(a),
        Cmd::Bench(a) => bench::run(a),
        Cmd::Fuzz(a) => fuzz::run(a),
        Cmd::Conformance(a) => conformance::run(a),
        Cmd::Campaign(a) => campaign::run(a),
        Cmd::Soak(a) => soak::run(a),
    }
}
