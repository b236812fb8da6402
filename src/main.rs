//! `canstar`: generate CAN controller and CAN star hub RTL, and simulate it.

use anyhow::{Context, Result};
use canstar::config::Config;
use canstar::generate::{self, Target};
use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "canstar", version, about = "CAN controller and CAN star hub RTL generator with a cycle simulator")]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Generate Verilog (and pin files) for a design, with defaults or from a TOML config.
    Generate {
        /// What to generate.
        #[arg(value_enum, default_value = "all")]
        target: Target,
        /// TOML configuration file (unknown keys and impossible values are errors).
        #[arg(long)]
        config: Option<PathBuf>,
        /// Output directory for Verilog.
        #[arg(long, default_value = "verilog-out")]
        out: PathBuf,
        /// Output directory for pin constraint files.
        #[arg(long, default_value = "constraints")]
        constraints: PathBuf,
        /// Do not write; fail if the files on disk differ from what would be generated.
        #[arg(long)]
        check: bool,
    },
    /// Synthesise the generated designs and print a resource table (iCE40 cells, flip-flops,
    /// block RAMs and fmax with Yosys + nextpnr-ice40; Spartan-3 LUTs and flip-flops with Yosys).
    Report {
        /// TOML configuration file.
        #[arg(long)]
        config: Option<PathBuf>,
        /// Clock frequency nextpnr is asked to meet, in MHz.
        #[arg(long, default_value_t = 50.0)]
        freq: f64,
    },
    /// Measure simulation throughput (simulated clock cycles per second).
    Bench {
        /// Simulated clock cycles per measurement.
        #[arg(long, default_value_t = 2_000_000)]
        cycles: u64,
        /// Node counts for the shared-bus measurement.
        #[arg(long, value_delimiter = ',', default_value = "2,5,10")]
        nodes: Vec<usize>,
        /// Instead of measuring, write a VCD of the first node count's bus (all signals of every instance and every bus wire).
        #[arg(long)]
        vcd: Option<PathBuf>,
        /// With --vcd: dump only these signals (hierarchical names or prefixes, `name*` globs), comma separated.
        #[arg(long, value_delimiter = ',')]
        signals: Option<Vec<String>>,
        /// Seed (clock phases) for the --vcd run.
        #[arg(long, default_value_t = 1)]
        seed: u64,
    },
    /// Run the Bosch conformance suite (conformance-tests.md) in the multi-node simulation:
    /// one line per program, then `N passed, M failed` counting steps.
    Conformance {
        /// Run only this program (baudrate, biterror, btl, crc, dlc, emlcount, extd_id,
        /// formerr, idle, overload, stuffbit, stufferr, txarb).
        #[arg(long)]
        program: Option<String>,
        /// Write one VCD per program (`<program>.vcd`) into this directory.
        #[arg(long)]
        vcd: Option<PathBuf>,
    },
}

fn run(cli: Cli) -> Result<()> {
    match cli.cmd {
        Cmd::Generate { target, config, out, constraints, check } => {
            let cfg = match &config {
                Some(p) => Config::load(p)?,
                None => Config::default(),
            };
            let arts = generate::render(target, &cfg)?;
            if check {
                let bad = generate::check(&arts, &out, &constraints);
                if !bad.is_empty() {
                    for b in &bad {
                        eprintln!("out of date: {}", b.display());
                    }
                    anyhow::bail!("{} generated file(s) differ from `canstar generate` output; run it and commit", bad.len());
                }
                println!("{} generated file(s) up to date", arts.len());
            } else {
                let written = generate::write(&arts, &out, &constraints).context("writing generated files")?;
                for w in &written {
                    println!("wrote {}", w.display());
                }
            }
            Ok(())
        }
        Cmd::Report { config, freq } => {
            let cfg = match &config {
                Some(p) => Config::load(p)?,
                None => Config::default(),
            };
            let mut rows = vec![];
            for (name, verilog, top) in canstar::designs::report_designs(&cfg)? {
                eprintln!("synthesising {name} ...");
                rows.push(canstar::report::measure(&name, &verilog, &top, freq)?);
            }
            println!("{}", canstar::report::table(&rows));
            println!("\ntools: {}", canstar::report::tool_versions());
            Ok(())
        }
        Cmd::Bench { cycles, nodes, vcd: Some(path), signals, seed } => {
            let n = nodes.first().copied().unwrap_or(2);
            let c = cycles.min(200_000);
            canstar::designs::bench_vcd(&path, n, c, signals.as_deref(), seed)?;
            println!("wrote {} ({n} bit-timing instances on a bus, {c} cycles each)", path.display());
            Ok(())
        }
        Cmd::Bench { cycles, nodes, vcd: None, .. } => canstar::designs::bench(cycles, &nodes),
        Cmd::Conformance { program, vcd } => {
            let (_, failed) = canstar_sim::conformance::run_cli(program.as_deref(), vcd.as_deref(), &mut std::io::stdout())?;
            if failed > 0 {
                anyhow::bail!("{failed} conformance step(s) failed");
            }
            Ok(())
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
