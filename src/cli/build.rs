//! `canstar build`: an iCE40 bitstream of one role for one board, with the
//! PLL setting, the logic cells, fmax against the design clock and the command
//! that flashes it.

use anyhow::Result;
use canstar::build::{self, pll, roles, Request};
use canstar::config::Config;
use std::path::PathBuf;
use std::time::Duration;

#[derive(clap::Args)]
pub struct Args {
    /// What to build: hub (the ReCANcentrate hub, canstar_hub) or controller (the
    /// SJA1000-compatible controller, canstar_sja1000_board).
    role: String,
    /// The board: a built-in board name (`canstar boards`) or a board .toml file.
    #[arg(long)]
    board: String,
    /// TOML configuration file (default: the built-in defaults).
    #[arg(long)]
    config: Option<PathBuf>,
    /// Output folder: the files go to <OUT>/<board>/<role>/.
    #[arg(long, default_value = "build")]
    out: PathBuf,
    /// Place-and-route seeds to try, one after the other, until one meets the design clock.
    #[arg(long, default_value_t = 3)]
    seeds: u64,
    /// Kill a seed's nextpnr run after this many seconds without router progress.
    #[arg(long, default_value_t = 60)]
    stall: u64,
    /// Time limit of one seed's place and route, in seconds.
    #[arg(long, default_value_t = 900)]
    pnr_timeout: u64,
    /// Largest error of the PLL's design clock against the nominal one, in ppm.
    #[arg(long, default_value_t = pll::DEFAULT_TOLERANCE_PPM)]
    pll_tolerance_ppm: f64,
    /// Write the bitstream even when fmax is below the design clock.
    #[arg(long)]
    timing_allow_fail: bool,
}

pub fn run(a: Args) -> Result<()> {
    anyhow::ensure!((1..=100).contains(&a.seeds), "--seeds {}: must be 1 to 100", a.seeds);
    anyhow::ensure!((1..=86_400).contains(&a.stall), "--stall {}: must be 1 to 86400 seconds", a.stall);
    anyhow::ensure!((1..=604_800).contains(&a.pnr_timeout), "--pnr-timeout {}: must be 1 to 604800 seconds", a.pnr_timeout);
    anyhow::ensure!(
        a.pll_tolerance_ppm.is_finite() && (0.0..=100_000.0).contains(&a.pll_tolerance_ppm),
        "--pll-tolerance-ppm {:?}: must be 0 to 100000",
        a.pll_tolerance_ppm
    );
    let config = match &a.config {
        Some(p) => Config::load(p)?,
        None => Config::default(),
    };
    let req = Request {
        board: a.board,
        role: a.role,
        config,
        out: a.out,
        seeds: a.seeds,
        stall: Duration::from_secs(a.stall),
        timeout: Duration::from_secs(a.pnr_timeout),
        tolerance_ppm: a.pll_tolerance_ppm,
        timing_allow_fail: a.timing_allow_fail,
    };
    let plan = build::plan(&req)?;
    // nextpnr runs in a process group of its own, out of reach of the terminal's
    // Ctrl-C: kill it, then remove the staged outputs (this handler replaces the
    // output set's own, which does only the second).
    let _ = ctrlc::set_handler(|| {
        canstar::report::pnr::kill_running();
        canstar::output::abandon_and_exit(canstar::output::INTERRUPTED);
    });
    let (b, p) = (&plan.board, &plan.pll);
    errln!("{} on {} ({}): top {}", plan.role.name, b.name, b.description, plan.top);
    errln!(
        "PLL: {} MHz -> {:.6} MHz for a nominal {} MHz design clock ({:+.0} ppm, tolerance ±{} ppm): {}",
        b.clock.hz as f64 / 1e6,
        p.fout_hz() / 1e6,
        plan.design.clock_hz as f64 / 1e6,
        p.error_ppm(plan.design.clock_hz),
        req.tolerance_ppm,
        p.describe()
    );
    errln!("synthesising and placing {} ...", plan.top);
    let built = build::run(&plan, &req, &mut |r| errln!("  nextpnr-ice40 {}", r.describe()))?;
    outln!("role:      {} ({})", plan.role.name, roles::lookup(plan.role.name)?.what);
    outln!("board:     {} ({} {})", b.name, b.part, b.package.as_deref().unwrap_or(""));
    outln!(
        "PLL:       {:.6} MHz from {} MHz, {:+.0} ppm against the nominal {} MHz ({})",
        p.fout_hz() / 1e6,
        b.clock.hz as f64 / 1e6,
        p.error_ppm(plan.design.clock_hz),
        plan.design.clock_hz as f64 / 1e6,
        p.describe()
    );
    outln!("logic:     {} LC (seed {})", built.lc, built.seed);
    outln!(
        "timing:    fmax {:.2} MHz at the {:.6} MHz design clock: {}",
        built.fmax_mhz,
        built.clock_mhz,
        if built.timing_pass { "PASS" } else { "FAIL (written with --timing-allow-fail)" }
    );
    for f in &built.files {
        outln!("wrote {}", f.display());
    }
    outln!("flash:     iceprog {}", built.bin.display());
    Ok(())
}
