//! `canstar bench`: simulation throughput, or waveforms of the benchmark bus.

use anyhow::Result;
use canstar::output::OutputSet;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
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
        None => canstar::bench::bench(a.cycles, &a.nodes, &mut std::io::stdout()),
    }
}

/// Most bit-timing instances on the benchmark bus.
const MAX_NODES: usize = 1000;
