//! `canstar generate`: Verilog and pin files.

use anyhow::{Context, Result};
use canstar::config::Config;
use canstar::generate::{self, Target};
use std::path::PathBuf;

/// What to generate (the command-line spelling of [`Target`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum TargetArg {
    /// The shared RTL blocks (CRC-15, stuffer, destuffer, bit timing, synchroniser), each as a standalone module.
    Blocks,
    /// The CAN controller: the core with its native interface, and the SJA1000-compatible Wishbone top.
    Controller,
    /// The star hubs (ReCANcentrate reference hub and CANcentrate) with pin files.
    Hub,
    /// Everything that exists (Verilog and pin files; with --check also the compiled models).
    All,
    /// The compiled simulation models (`models/src/generated/`, Rust written by canstar-rtlc
    /// from the RTL) of a source checkout: rewrites the stale ones.
    Models,
}

impl From<TargetArg> for Target {
    fn from(t: TargetArg) -> Self {
        match t {
            TargetArg::Blocks => Target::Blocks,
            TargetArg::Controller => Target::Controller,
            TargetArg::Hub => Target::Hub,
            TargetArg::All | TargetArg::Models => Target::All,
        }
    }
}

#[derive(clap::Args)]
pub struct Args {
    /// What to generate.
    #[arg(value_enum, default_value = "all")]
    target: TargetArg,
    /// TOML configuration file (unknown keys and impossible values are errors).
    #[arg(long)]
    config: Option<PathBuf>,
    /// Board for the pin files (built-in name, or a board .toml file); default: every built-in board.
    #[arg(long)]
    board: Option<String>,
    /// Output directory for Verilog.
    #[arg(long, default_value = "verilog-out")]
    out: PathBuf,
    /// Output directory for pin constraint files.
    #[arg(long, default_value = "constraints")]
    constraints: PathBuf,
    /// Do not write; fail if the files on disk differ from what would be generated.
    #[arg(long)]
    check: bool,
}

/// The compiled models of the source tree this binary was built from, if it is there.
fn models(bless: bool) -> Result<Option<canstar_models::registry::Stale>> {
    if !canstar_models::registry::generated_dir().is_dir() {
        return Ok(None);
    }
    canstar_models::registry::check(bless).map(Some).map_err(|e| anyhow::anyhow!("compiled models: {e}"))
}

pub fn run(a: Args) -> Result<()> {
    if a.target == TargetArg::Models {
        anyhow::ensure!(a.config.is_none() && a.board.is_none(), "`generate models` takes no --config or --board (the models serve every configuration of a shape)");
        match models(!a.check)? {
            None => anyhow::bail!("no source checkout at {}", canstar_models::registry::generated_dir().display()),
            Some(st) if a.check && !st.is_empty() => {
                for p in st.changed.iter().chain(&st.unregistered) {
                    eprintln!("out of date: {}", p.display());
                }
                anyhow::bail!("compiled models are stale; run `canstar generate models` and commit");
            }
            Some(st) => {
                for p in st.changed.iter() {
                    println!("{} {}", if a.check { "up to date:" } else { "wrote" }, p.display());
                }
                for p in st.unregistered.iter() {
                    println!("removed {}", p.display());
                }
                if st.is_empty() {
                    println!("compiled models up to date");
                }
            }
        }
        return Ok(());
    }
    let cfg = match &a.config {
        Some(p) => Config::load(p)?,
        None => Config::default(),
    };
    let arts = generate::render(a.target.into(), &cfg, a.board.as_deref())?;
    if a.check {
        let bad = generate::check(&arts, &a.out, &a.constraints);
        if !bad.is_empty() {
            for b in &bad {
                eprintln!("out of date: {}", b.display());
            }
            anyhow::bail!("{} generated file(s) differ from `canstar generate` output; run it and commit", bad.len());
        }
        println!("{} generated file(s) up to date", arts.len());
        if a.target == TargetArg::All {
            if let Some(st) = models(false)? {
                if !st.is_empty() {
                    for p in st.changed.iter().chain(&st.unregistered) {
                        eprintln!("out of date: {}", p.display());
                    }
                    anyhow::bail!("compiled models are stale; run `canstar generate models` and commit");
                }
                println!("compiled models up to date");
            }
        }
    } else {
        let written = generate::write(&arts, &a.out, &a.constraints).context("writing generated files")?;
        for w in &written {
            println!("wrote {}", w.display());
        }
    }
    Ok(())
}
