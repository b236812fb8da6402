//! `canstar report`: synthesis and place-and-route figures of every design.

use anyhow::Result;
use canstar::config::Config;
use canstar::report::pnr::Pnr;
use std::path::PathBuf;
use std::time::Duration;

#[derive(clap::Args)]
pub struct Args {
    /// TOML configuration file.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Clock frequency nextpnr is asked to meet, in MHz (a design that misses it
    /// still gets its achieved fmax, marked in the table).
    #[arg(long, default_value_t = 50.0)]
    freq: f64,
    /// Only these designs (comma-separated top names, e.g. canstar_can_core,canstar_hub).
    #[arg(long, value_delimiter = ',')]
    design: Vec<String>,
    /// Place-and-route seeds per design (seeds 1..=N, one after the other); the
    /// table gives the best and the median fmax of the seeds that placed.
    #[arg(long, default_value_t = 3)]
    seeds: u64,
    /// Kill a seed's nextpnr run after this many seconds without progress (a new
    /// log line; in the router, fewer arcs left to route than ever before).
    #[arg(long, default_value_t = 60)]
    stall: u64,
    /// Time limit of one seed's place and route, in seconds (0: synthesis only).
    #[arg(long, default_value_t = 900)]
    pnr_timeout: u64,
}

pub fn run(a: Args) -> Result<()> {
    anyhow::ensure!(a.freq.is_finite() && a.freq > 0.0 && a.freq <= 1000.0, "--freq {:?}: must be a frequency in MHz above 0 and at most 1000", a.freq);
    anyhow::ensure!((1..=100).contains(&a.seeds), "--seeds {}: must be 1 to 100", a.seeds);
    anyhow::ensure!((1..=86_400).contains(&a.stall), "--stall {}: must be 1 to 86400 seconds", a.stall);
    anyhow::ensure!(a.pnr_timeout <= 86_400 * 7, "--pnr-timeout {}: must be at most 604800 seconds (0: synthesis only)", a.pnr_timeout);
    let cfg = match &a.config {
        Some(p) => Config::load(p)?,
        None => Config::default(),
    };
    let designs = canstar::designs::report_designs(&cfg)?;
    if let Some(unknown) = a.design.iter().find(|d| !designs.iter().any(|(n, _, _)| n == *d)) {
        let known: Vec<&str> = designs.iter().map(|(n, _, _)| n.as_str()).collect();
        anyhow::bail!("unknown design {unknown:?} (known: {})", known.join(", "));
    }
    let pnr = (a.pnr_timeout > 0).then(|| Pnr {
        program: "nextpnr-ice40".into(),
        freq_mhz: a.freq,
        stall: Duration::from_secs(a.stall),
        timeout: Duration::from_secs(a.pnr_timeout),
    });
    // nextpnr runs in a process group of its own, out of reach of the terminal's
    // Ctrl-C: kill it on the way out. (Fails only if a handler is installed,
    // which this command does not do elsewhere.)
    let _ = ctrlc::set_handler(|| {
        canstar::report::pnr::kill_running();
        std::process::exit(canstar::output::INTERRUPTED);
    });
    let mut rows = vec![];
    for (name, verilog, top) in designs {
        if !a.design.is_empty() && !a.design.contains(&name) {
            continue;
        }
        errln!("synthesising {name} ...");
        let mut on_run = |r: &canstar::report::pnr::SeedRun| errln!("  {name} {}", r.describe());
        rows.push(canstar::report::measure(&name, &verilog, &top, pnr.as_ref(), a.seeds, &mut on_run)?);
    }
    outln!("{}", canstar::report::table(&rows));
    outln!("\ntools: {}", canstar::report::tool_versions());
    Ok(())
}
