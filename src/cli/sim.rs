//! `canstar sim`: a bus scenario file on the controller RTL, or a ReCANcentrate
//! network file.

use super::progress::Progress;
use anyhow::{anyhow, bail, Result};
use canstar::output::OutputSet;
use std::path::{Path, PathBuf};

#[derive(clap::Args)]
pub struct Args {
    /// Scenario or network file.
    scenario: PathBuf,
    /// Simulated time in ms (network files: default 2; scenario files: stop
    /// earlier than the file's duration_us).
    #[arg(long, allow_negative_numbers = true)]
    ms: Option<f64>,
    /// Seed of the clock phases (network files: default 1; scenario files:
    /// replaces the file's `seed`).
    #[arg(long)]
    seed: Option<u64>,
    /// Write a VCD of every signal and bus wire.
    #[arg(long)]
    vcd: Option<PathBuf>,
    /// Write the per-bit trace of every node (can-protocol.md §18; network
    /// files: the drivers' routine log).
    #[arg(long)]
    trace: Option<PathBuf>,
    /// Scenario files: write the frames each node saw as a candump log (node i is can<i>).
    #[arg(long)]
    log: Option<PathBuf>,
    #[command(flatten)]
    engine: canstar::engine::EngineArg,
}

/// Longest simulated time `--ms` accepts (one hour).
const MAX_MS: f64 = 3_600_000.0;

/// `--ms` in picoseconds: finite, positive, at most [`MAX_MS`].
fn ms_to_ps(ms: f64) -> Result<u64> {
    if !(ms.is_finite() && ms > 0.0 && ms <= MAX_MS) {
        bail!("--ms {ms:?}: the simulated time must be a number of milliseconds above 0 and at most {MAX_MS}");
    }
    Ok(((ms * 1e9).round() as u64).max(1))
}

/// Reserve the optional outputs (before any simulation starts).
fn reserve(set: &mut OutputSet, paths: &[&Option<PathBuf>]) -> Result<()> {
    for p in paths.iter().copied().flatten() {
        set.file(p)?;
    }
    Ok(())
}

fn tmp(set: &OutputSet, p: &Option<PathBuf>) -> Option<PathBuf> {
    p.as_deref().and_then(|p| set.temp_of(p)).map(Path::to_path_buf)
}

pub fn run(a: Args) -> Result<()> {
    let text = canstar::input::read_toml(&a.scenario)?;
    let until_ps = a.ms.map(ms_to_ps).transpose()?;
    if canstar_recan::NetworkSpec::is_network_file(&text) {
        return network(&a, &text, until_ps);
    }
    let mut sc = canstar_verify::scenario::Scenario::from_toml(&text).map_err(|e| anyhow!("{}: {e}", a.scenario.display()))?;
    if let Some(s) = a.seed {
        sc.seed = s;
    }
    let mut set = OutputSet::new();
    reserve(&mut set, &[&a.vcd, &a.trace, &a.log])?;
    let opts = canstar_verify::scenario::RunOptions { vcd: tmp(&set, &a.vcd), trace: a.trace.is_some(), until_ps, engine: a.engine.engine };
    let r = canstar_verify::scenario::run(&sc, &opts).map_err(|e| anyhow!(e))?;
    if let Some(p) = &a.trace {
        set.write(p, r.trace.join("\n") + "\n")?;
    }
    if let Some(p) = &a.log {
        set.write(p, r.candump.join("\n") + "\n")?;
    }
    set.commit()?;
    outln!("{:<12} {:>5} {:>5} {:>6} {:>4} {:>4} {:>6}", "node", "sent", "recv", "errors", "TEC", "REC", "state");
    for n in &r.nodes {
        let st = ["active", "passive", "bus-off"].get(n.state as usize).copied().unwrap_or("?");
        outln!(
            "{:<12} {:>5} {:>5} {:>6} {:>4} {:>4} {:>6}{}",
            n.name,
            n.sent,
            n.received,
            n.errors,
            n.tec,
            n.rec,
            st,
            if n.pending { "  (frames still pending)" } else { "" }
        );
    }
    for (what, p) in [("VCD", &a.vcd), ("trace", &a.trace), ("candump log", &a.log)] {
        if let Some(p) = p {
            outln!("wrote {what} {}", p.display());
        }
    }
    Ok(())
}

/// `canstar sim` with a ReCANcentrate network file.
fn network(a: &Args, text: &str, until_ps: Option<u64>) -> Result<()> {
    use canstar_recan::{run_observed, NetworkSpec, RunSpec};
    let path = &a.scenario;
    let net = NetworkSpec::from_toml(text).map_err(|e| anyhow!("{}: {e}", path.display()))?;
    if a.log.is_some() {
        bail!("--log: {} is a network file; the candump log is written for bus scenario files only", path.display());
    }
    let mut set = OutputSet::new();
    reserve(&mut set, &[&a.vcd, &a.trace])?;
    let budget = net.propagation_budget();
    outln!("{}", budget.describe(&net));
    if let Some(w) = budget.warning() {
        errln!("warning: {}: {w}", path.display());
    }
    let mut spec = RunSpec::new(net.clone(), a.seed.unwrap_or(1), 0);
    spec.max_time_ps = Some(until_ps.unwrap_or(2_000_000_000));
    spec.vcd = tmp(&set, &a.vcd);
    spec.trace = a.trace.is_some();
    spec.engine = a.engine.engine;
    let mut bar: Option<Progress> = None;
    let r = run_observed(&spec, &mut |now, limit| {
        let b = bar.get_or_insert_with(|| Progress::new(limit / 1_000_000, "us simulated"));
        b.set(now / 1_000_000);
    });
    if let Some(b) = &bar {
        b.finish();
    }
    if let Some(e) = &r.vcd_error {
        bail!("{e}");
    }
    if let Some(p) = &a.trace {
        set.write(p, r.trace.join("\n") + "\n")?;
    }
    // The outputs of a finished run are kept even when its checks fail.
    set.commit()?;
    outln!("{} us simulated, {} frames delivered, {} clock cycles", r.end_ps / 1_000_000, r.delivered, r.sim_cycles);
    outln!(
        "{:<12} {:>9} {:>3} {:>5} {:>5} {:>5} {:>5} {:>9} {:>9}",
        "node", "delivered", "tx", "TEC.A", "REC.A", "TEC.B", "REC.B", "max A", "max B"
    );
    for (k, n) in net.nodes.iter().enumerate() {
        let c = |c: usize| r.counters.iter().rev().find(|s| s.node == k && s.ctrl == c).map_or((0, 0), |s| (s.tec, s.rec));
        let m = |c: usize| r.max_tec_rec.get(k).map_or("-".to_string(), |m| format!("{}/{}", m[c].0, m[c].1));
        let tx = r.tx_ctrl[k].map_or("-", |t| ["A", "B"][t]);
        outln!(
            "{:<12} {:>9} {:>3} {:>5} {:>5} {:>5} {:>5} {:>9} {:>9}",
            n.name,
            r.delivered_per_node[k],
            tx,
            c(0).0,
            c(0).1,
            c(1).0,
            c(1).1,
            m(0),
            m(1)
        );
    }
    outln!("(TEC/REC: at the end; max A, max B: highest TEC/REC of controller A and B during the run)");
    for (h, (fin, max)) in r.final_bic.iter().zip(&r.max_bic).enumerate() {
        let ports: Vec<String> = fin.iter().zip(max).map(|(f, m)| format!("{f}/{m}")).collect();
        outln!("hub {h} blame counters (BIC) per port, at the end/highest: {}", ports.join(" "));
    }
    outln!("{} isolation(s), {} quarantine(s)", r.isolated.len(), r.quarantined.len());
    for i in &r.isolated {
        outln!("isolated {:?} at {:.1} us", i.what, i.t_ps as f64 / 1e6);
    }
    for (n, c, t) in &r.quarantined {
        outln!("quarantined node {n} controller {} at {:.1} us", ["A", "B"][*c], *t as f64 / 1e6);
    }
    for f in &r.failures {
        outln!("FAILED: {f}");
    }
    for (what, p) in [("VCD", &a.vcd), ("driver trace", &a.trace)] {
        if let Some(p) = p {
            outln!("wrote {what} {}", p.display());
        }
    }
    if r.ok {
        Ok(())
    } else {
        bail!("{} check(s) failed", r.failures.len())
    }
}
