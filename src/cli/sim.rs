//! `canstar sim`: a bus scenario file on the controller RTL, or a ReCANcentrate
//! network file.

use anyhow::{Context, Result};
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Scenario or network file.
    scenario: PathBuf,
    /// Network files: simulated time in ms.
    #[arg(long, default_value_t = 2.0)]
    ms: f64,
    /// Network files: seed of the clock phases.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Write a VCD of every signal and bus wire.
    #[arg(long)]
    vcd: Option<PathBuf>,
    /// Write the per-bit trace of every node (can-protocol.md §18).
    #[arg(long)]
    trace: Option<PathBuf>,
    /// Write the frames each node saw as a candump log (node i is can<i>).
    #[arg(long)]
    log: Option<PathBuf>,
    #[command(flatten)]
    engine: canstar::engine::EngineArg,
}

pub fn run(a: Args) -> Result<()> {
    let Args { scenario, ms, seed, vcd, trace, log, engine } = a;
    let engine = engine.engine;
    let text = std::fs::read_to_string(&scenario).with_context(|| format!("reading {}", scenario.display()))?;
    if canstar_recan::NetworkSpec::is_network_file(&text) {
        return network(&scenario, &text, ms, seed, vcd, trace, engine);
    }
    let sc = canstar_verify::scenario::Scenario::from_toml(&text).map_err(|e| anyhow::anyhow!("{}: {e}", scenario.display()))?;
    let opts = canstar_verify::scenario::RunOptions { vcd: vcd.clone(), trace: trace.is_some(), engine };
    let r = canstar_verify::scenario::run(&sc, &opts).map_err(|e| anyhow::anyhow!(e))?;
    if let Some(p) = &trace {
        std::fs::write(p, r.trace.join("\n") + "\n").with_context(|| format!("writing {}", p.display()))?;
    }
    if let Some(p) = &log {
        std::fs::write(p, r.candump.join("\n") + "\n").with_context(|| format!("writing {}", p.display()))?;
    }
    println!("{:<12} {:>5} {:>5} {:>6} {:>4} {:>4} {:>6}", "node", "sent", "recv", "errors", "TEC", "REC", "state");
    for n in &r.nodes {
        let st = ["active", "passive", "bus-off"].get(n.state as usize).copied().unwrap_or("?");
        println!(
            "{:<12} {:>5} {:>5} {:>6} {:>4} {:>4} {:>6}{}",
            n.name, n.sent, n.received, n.errors, n.tec, n.rec, st, if n.pending { "  (frames still pending)" } else { "" }
        );
    }
    for (what, p) in [("VCD", &vcd), ("trace", &trace), ("candump log", &log)] {
        if let Some(p) = p {
            println!("wrote {what} {}", p.display());
        }
    }
    Ok(())
}

/// `canstar sim` with a ReCANcentrate network file.
fn network(path: &std::path::Path, text: &str, ms: f64, seed: u64, vcd: Option<PathBuf>, trace: Option<PathBuf>, engine: canstar::engine::Engine) -> Result<()> {
    use canstar_recan::{run, NetworkSpec, RunSpec};
    let net = NetworkSpec::from_toml(text).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    let mut spec = RunSpec::new(net.clone(), seed, 0);
    spec.max_time_ps = Some((ms * 1e9).round() as u64);
    spec.vcd = vcd.clone();
    spec.trace = trace.is_some();
    spec.engine = engine;
    let r = run(&spec);
    if let Some(p) = &trace {
        std::fs::write(p, r.trace.join("\n") + "\n").with_context(|| format!("writing {}", p.display()))?;
    }
    println!("{} us simulated, {} frames delivered, {} clock cycles", r.end_ps / 1_000_000, r.delivered, r.sim_cycles);
    println!("{:<12} {:>9} {:>5} {:>4} {:>4} {:>4} {:>4}", "node", "delivered", "tx", "TEC.A", "REC.A", "TEC.B", "REC.B");
    for (k, n) in net.nodes.iter().enumerate() {
        let c = |c: usize| r.counters.iter().rev().find(|s| s.node == k && s.ctrl == c).map_or((0, 0), |s| (s.tec, s.rec));
        let tx = r.tx_ctrl[k].map_or("-", |t| ["A", "B"][t]);
        println!("{:<12} {:>9} {:>5} {:>5} {:>5} {:>5} {:>5}", n.name, r.delivered_per_node[k], tx, c(0).0, c(0).1, c(1).0, c(1).1);
    }
    for i in &r.isolated {
        println!("isolated {:?} at {:.1} us", i.what, i.t_ps as f64 / 1e6);
    }
    for (n, c, t) in &r.quarantined {
        println!("quarantined node {n} controller {} at {:.1} us", ["A", "B"][*c], *t as f64 / 1e6);
    }
    for f in &r.failures {
        println!("FAILED: {f}");
    }
    for (what, p) in [("VCD", &vcd), ("driver trace", &trace)] {
        if let Some(p) = p {
            println!("wrote {what} {}", p.display());
        }
    }
    if r.ok {
        Ok(())
    } else {
        anyhow::bail!("{} check(s) failed", r.failures.len())
    }
}

