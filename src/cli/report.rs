//! `canstar report`: synthesis and place-and-route figures of every design.

use anyhow::Result;
use canstar::config::Config;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// TOML configuration file.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Clock frequency nextpnr is asked to meet, in MHz.
    #[arg(long, default_value_t = 50.0)]
    freq: f64,
    /// Only these designs (comma-separated top names, e.g. canstar_can_core,canstar_hub).
    #[arg(long, value_delimiter = ',')]
    design: Vec<String>,
    /// Time limit for place and route of one design, in seconds (0: synthesis only).
    #[arg(long, default_value_t = 900)]
    pnr_timeout: u64,
}

pub fn run(a: Args) -> Result<()> {
    anyhow::ensure!(a.freq.is_finite() && a.freq > 0.0 && a.freq <= 1000.0, "--freq {:?}: must be a frequency in MHz above 0 and at most 1000", a.freq);
    let cfg = match &a.config {
        Some(p) => Config::load(p)?,
        None => Config::default(),
    };
    let designs = canstar::designs::report_designs(&cfg)?;
    if let Some(unknown) = a.design.iter().find(|d| !designs.iter().any(|(n, _, _)| n == *d)) {
        let known: Vec<&str> = designs.iter().map(|(n, _, _)| n.as_str()).collect();
        anyhow::bail!("unknown design {unknown:?} (known: {})", known.join(", "));
    }
    let mut rows = vec![];
    for (name, verilog, top) in designs {
        if !a.design.is_empty() && !a.design.contains(&name) {
            continue;
        }
        errln!("synthesising {name} ...");
        rows.push(canstar::report::measure(&name, &verilog, &top, a.freq, a.pnr_timeout)?);
    }
    outln!("{}", canstar::report::table(&rows));
    outln!("\ntools: {}", canstar::report::tool_versions());
    Ok(())
}
