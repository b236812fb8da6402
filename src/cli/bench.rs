//! `canstar bench`: the simulation engines side by side (rust-hdl, compiled models,
//! Verilator, the kernel), the kernel on bit-timing instances (`--btl`), or waveforms
//! of the bit-timing benchmark bus (`--vcd`).

use anyhow::Result;
use canstar::output::OutputSet;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// The kernel benchmark on bit-timing instances (--cycles, --nodes) instead of the engines.
    #[arg(long)]
    btl: bool,
    /// Engines: skip the Verilator column.
    #[arg(long)]
    no_verilator: bool,
    /// Engines: clock cycles per node of the CanCore bus workloads.
    #[arg(long, default_value_t = 400_000)]
    core_cycles: u64,
    /// Engines: simulated time of the reference network, in ms.
    #[arg(long, default_value_t = 20.0)]
    network_ms: f64,
    /// --btl: simulated clock cycles per measurement.
    #[arg(long, default_value_t = 2_000_000)]
    cycles: u64,
    /// --btl: node counts for the shared-bus measurement.
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
}

pub fn run(a: Args) -> Result<()> {
    anyhow::ensure!(a.cycles > 0, "--cycles must be positive");
    anyhow::ensure!(
        !a.nodes.is_empty() && a.nodes.iter().all(|&n| (1..=MAX_NODES).contains(&n)),
        "--nodes: node counts must be 1..={MAX_NODES}"
    );
    match &a.vcd {
        Some(path) => {
            let mut set = OutputSet::new();
            let tmp = set.file(path)?;
            let n = a.nodes[0];
            let c = a.cycles.min(200_000);
            canstar::bench::bench_vcd(&tmp, n, c, a.signals.as_deref(), a.seed).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
            set.commit()?;
            outln!("wrote {} ({n} bit-timing instances on a bus, {c} cycles each)", path.display());
            Ok(())
        }
        None if a.btl => canstar::bench::bench(a.cycles, &a.nodes, &mut std::io::stdout()),
        None => {
            use canstar::bench::engines;
            let o = engines::Options {
                core_cycles: a.core_cycles,
                network_ps: (a.network_ms * 1e9).round() as u64,
                verilator: !a.no_verilator,
                ..Default::default()
            };
            anyhow::ensure!(o.core_cycles >= 1000 && o.network_ps >= 100_000_000, "--core-cycles must be at least 1000 and --network-ms at least 0.1");
            outln!("canstar bench: the same recorded inputs replayed into each engine; kernel = canstar_sim::Sim closed loop on the compiled models");
            for l in engines::table(&engines::measure(&o)).lines() {
                outln!("{l}");
            }
            Ok(())
        }
    }
}

/// Most bit-timing instances on the benchmark bus.
const MAX_NODES: usize = 1000;
