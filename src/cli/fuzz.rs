//! `canstar fuzz`: randomised lock-step runs against the golden model.

use super::progress::Progress;
use anyhow::Result;
use canstar::output::OutputSet;
use std::path::{Path, PathBuf};

#[derive(clap::Args)]
pub struct Args {
    /// Frames to run in total.
    #[arg(long, default_value_t = 1000)]
    frames: u64,
    /// Master seed (run k uses a seed derived from it; failing runs print their own seed).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Frames per run.
    #[arg(long, default_value_t = 24)]
    per_run: usize,
    /// Worker threads (default: available parallelism).
    #[arg(long)]
    jobs: Option<usize>,
    /// Rerun only this run seed (as printed for a failure) and print its report.
    #[arg(long)]
    run_seed: Option<u64>,
    /// No receive-path disturbances.
    #[arg(long)]
    no_disturb: bool,
    /// Directory for the VCD written around a divergence.
    #[arg(long, default_value = ".")]
    vcd_dir: PathBuf,
    /// Stop after this many failing runs.
    #[arg(long, default_value_t = 5)]
    max_failures: usize,
    #[command(flatten)]
    engine: canstar::engine::EngineArg,
}

pub fn run(a: Args) -> Result<()> {
    anyhow::ensure!(a.frames >= 1, "--frames must be at least 1");
    anyhow::ensure!((1..=MAX_PER_RUN).contains(&a.per_run), "--per-run {} (must be 1..={MAX_PER_RUN})", a.per_run);
    anyhow::ensure!(a.jobs != Some(0), "--jobs must be at least 1");
    // The divergence VCDs are staged and moved into --vcd-dir at the end.
    let mut set = OutputSet::new();
    let stage = set.dir(&a.vcd_dir)?;
    let r = fuzz_cmd(a.frames, a.seed, a.per_run, a.jobs, a.run_seed, !a.no_disturb, &stage, &a.vcd_dir, a.max_failures, a.engine.engine);
    // VCDs of divergences found are kept even though the command fails.
    set.commit()?;
    r
}

/// Most frames in one run.
const MAX_PER_RUN: usize = 10_000;

#[allow(clippy::too_many_arguments)]
fn fuzz_cmd(
    frames: u64,
    seed: u64,
    per_run: usize,
    jobs: Option<usize>,
    run_seed: Option<u64>,
    disturb: bool,
    stage: &Path,
    vcd_dir: &Path,
    max_failures: usize,
    engine: canstar::engine::Engine,
) -> Result<()> {
    use canstar_verify::fuzz::{self, RunOptions, RunReport};
    let opts = RunOptions { frames: per_run, disturb, vcd_dir: Some(stage.to_path_buf()), engine };
    let show = |r: &RunReport| {
        outln!(
            "run seed {} ({:#x}): {} nodes, {} frames, {} sent, {} errors, worst state {}",
            r.seed, r.seed, r.nodes, r.frames, r.sent, r.errors, ["error-active", "error-passive", "bus-off"][r.worst_state.min(2) as usize]
        );
        if let Some(d) = &r.divergence {
            outln!("{d}");
        }
        if let Some(v) = r.vcd.as_ref().and_then(|v| v.file_name()) {
            outln!("  VCD of the divergence window: {}", vcd_dir.join(v).display());
        }
        for v in &r.violations {
            outln!("  property violation: {v}");
        }
    };
    if let Some(s) = run_seed {
        let r = fuzz::run_seed(s, &opts);
        show(&r);
        anyhow::ensure!(r.ok(), "run seed {s} failed");
        return Ok(());
    }
    let jobs = jobs.unwrap_or_else(|| std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1));
    let mut bar = Progress::new(frames, "frames");
    let t0 = std::time::Instant::now();
    let s = fuzz::fuzz(frames, seed, &opts, jobs, max_failures, |s, r| {
        let div = s.failures.iter().filter(|f| f.divergence.is_some()).count();
        let viol: usize = s.failures.iter().map(|f| f.violations.len()).sum();
        bar.set_message(format!("runs {} divergences {div} violations {viol}, passive runs {}, bus-off runs {}", s.runs, s.passive_runs, s.busoff_runs));
        bar.set(s.frames);
        if !r.ok() {
            bar.suspend(|| show(r));
        }
    });
    bar.finish();
    let dt = t0.elapsed().as_secs_f64().max(1e-9);
    let div = s.failures.iter().filter(|f| f.divergence.is_some()).count();
    let viol: usize = s.failures.iter().map(|f| f.violations.len()).sum();
    outln!(
        "{} frames in {} runs ({} sent, {} errors, {} runs reached error-passive, {} bus-off), {} bits compared in lock step",
        s.frames, s.runs, s.sent, s.errors, s.passive_runs, s.busoff_runs, s.bits
    );
    outln!(
        "{:.1} s: {:.1} frames/s, {:.0} simulated clock cycles/s, {} jobs",
        dt,
        s.frames as f64 / dt,
        s.cycles as f64 / dt,
        jobs
    );
    outln!(
        "longest dominant run driven by one node: {} bits (bound {} for its flag restarts)",
        s.max_dom_run.0, s.max_dom_run.1
    );
    outln!("divergences: {div}, property violations: {viol}");
    for f in &s.failures {
        outln!("  failing run seed {} (rerun: canstar fuzz --run-seed {} --per-run {})", f.seed, f.seed, f.frames);
    }
    anyhow::ensure!(s.failures.is_empty(), "{} failing run(s)", s.failures.len());
    Ok(())
}
