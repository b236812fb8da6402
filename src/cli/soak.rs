//! `canstar soak`: the fault-free soak of the reference two-hub network (hub.md A1).

use super::progress::Progress;
use anyhow::{Context, Result};
use canstar::output::OutputSet;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Frames in total (summed over the chunks).
    #[arg(long, default_value_t = 1_000_000)]
    frames: u64,
    /// Frames per chunk (one independent run with its own seed).
    #[arg(long, default_value_t = 2000)]
    chunk_frames: u32,
    /// Master seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Oscillator offset magnitude in ppm (every hub and controller +ppm or -ppm; default:
    /// the tolerance limit of the bit timing).
    #[arg(long)]
    ppm: Option<f64>,
    /// Add the legal events of healthy nodes: an error-passive controller, overload
    /// frames, a late joiner or a node switched off and on, in every chunk.
    #[arg(long)]
    events: bool,
    /// Node controllers at 14.74 MHz (same bit timing, half the simulation cost).
    #[arg(long, conflicts_with = "network")]
    fast: bool,
    /// Soak this network file (TOML, as `canstar sim` reads it; default: the reference
    /// network). Oscillator offsets, first transmitters and start times are set per chunk.
    #[arg(long)]
    network: Option<PathBuf>,
    /// Worker threads (default: available parallelism).
    #[arg(long)]
    jobs: Option<usize>,
    /// Run only shard i of n (`2/4`), or `auto` (from SLURM_ARRAY_TASK_ID/COUNT or LSB_JOBINDEX).
    #[arg(long)]
    shard: Option<String>,
    /// Write the chunk outcomes as JSON (merge shards with --merge).
    #[arg(long)]
    json: Option<PathBuf>,
    /// Combine JSON reports of soak shards and print the summary.
    #[arg(long, num_args = 1.., conflicts_with_all = ["shard"])]
    merge: Vec<PathBuf>,
    /// Run one chunk only (by index) and print it.
    #[arg(long, conflicts_with_all = ["shard", "merge"])]
    chunk: Option<u64>,
    /// With --chunk: write the chunk's run as VCD (every hub, link and controller, as
    /// `canstar sim` writes a network run), from bit --vcd-from for --vcd-bits bit times
    /// (a whole chunk is gigabytes).
    #[arg(long, requires = "chunk")]
    vcd: Option<PathBuf>,
    /// First bit time of the VCD (e.g. a few bits before a blame site).
    #[arg(long, requires = "vcd", default_value_t = 0)]
    vcd_from: u64,
    /// Length of the VCD window in bit times.
    #[arg(long, requires = "vcd", default_value_t = 200)]
    vcd_bits: u64,
}

pub fn run(a: Args) -> Result<()> {
    use canstar_recan::soak::{self, SoakReport, SoakSettings};
    // The output is reserved before any work.
    let mut set = OutputSet::new();
    if let Some(p) = &a.json {
        set.file(p)?;
    }
    if let Some(p) = &a.vcd {
        set.file(p)?;
    }
    if !a.merge.is_empty() {
        let mut all = SoakReport::default();
        for p in &a.merge {
            let text = canstar::input::read_text(p, canstar::input::MAX_JSON_BYTES)?;
            let r: SoakReport = serde_json::from_str(&text).with_context(|| format!("{} is not a soak report", p.display()))?;
            anyhow::ensure!(all.settings.is_none() || all.settings == r.settings, "{}: other soak settings", p.display());
            all.settings = r.settings;
            all.chunks.extend(r.chunks);
        }
        all.chunks.sort_by_key(|c| c.index);
        all.chunks.dedup_by_key(|c| c.index);
        if let Some(p) = &a.json {
            set.write(p, serde_json::to_string_pretty(&all)?)?;
        }
        set.commit()?;
        out!("{}", all.summary());
        if let Some(s) = &all.settings {
            if all.chunks.len() as u64 != s.chunks() {
                errln!("warning: {} of {} chunks present (shards missing)", all.chunks.len(), s.chunks());
            }
        }
        anyhow::ensure!(all.ok(), "blames, isolations or problems in the soak");
        return Ok(());
    }
    anyhow::ensure!(a.frames > 0 && a.chunk_frames > 0, "--frames and --chunk-frames must be at least 1");
    let network = match &a.network {
        Some(p) => {
            let text = canstar::input::read_text(p, canstar::input::MAX_TOML_BYTES)?;
            Some(canstar_recan::spec::NetworkSpec::from_toml(&text).map_err(|e| anyhow::anyhow!("{}: {e}", p.display()))?)
        }
        None => None,
    };
    let settings = SoakSettings { frames: a.frames, chunk_frames: a.chunk_frames, seed: a.seed, ppm: a.ppm, events: a.events, fast: a.fast, network };
    if let Some(w) = settings.network_spec().propagation_budget().warning() {
        errln!("warning: {}: {w}", a.network.as_ref().map_or("the reference network".into(), |p| p.display().to_string()));
    }
    if let Some(i) = a.chunk {
        let (spec, evs) = soak::chunk_spec(&settings, i);
        for e in &evs {
            outln!("event: {}", e.describe());
        }
        outln!(
            "oscillators: hubs {:?} ppm, controllers (A, B) {:?} ppm",
            spec.network.hubs.iter().map(|h| h.ppm).collect::<Vec<_>>(),
            spec.network.nodes.iter().map(|n| (n.a.ppm, n.b.ppm)).collect::<Vec<_>>()
        );
        let window = a.vcd.as_deref().and_then(|p| set.temp_of(p)).map(|p| (p, a.vcd_from, a.vcd_bits));
        let c = soak::run_chunk_vcd(&settings, i, window);
        let report = SoakReport { settings: Some(settings), chunks: vec![c.clone()] };
        if let Some(p) = &a.json {
            set.write(p, serde_json::to_string_pretty(&report)?)?;
        }
        set.commit()?;
        out!("{}", report.summary());
        anyhow::ensure!(c.clean(), "chunk {i} (seed {}) not clean", c.seed);
        return Ok(());
    }
    let shard = super::campaign::parse_shard(a.shard.as_deref())?;
    let plan = settings.plan(shard);
    let jobs = a.jobs.unwrap_or_else(|| std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1));
    let target: u64 = plan.len() as u64 * settings.chunk_frames as u64;
    let mut bar = Progress::new(target, "frames");
    let t0 = std::time::Instant::now();
    let (mut blames, mut isolations, mut done) = (0u64, 0usize, 0usize);
    let chunks = soak::execute(&settings, &plan, jobs, |c| {
        blames += c.blames;
        isolations += c.isolations.len();
        done += 1;
        if !c.clean() {
            bar.suspend(|| errln!("chunk {} seed {}: blames {} isolations {:?} {:?}", c.index, c.seed, c.blames, c.isolations, c.problems));
        }
        bar.set_message(format!("{done} of {} chunks, {blames} blames, {isolations} isolations", plan.len()));
        bar.set(done as u64 * settings.chunk_frames as u64);
    });
    bar.finish();
    let cycles: u64 = chunks.iter().map(|c| c.sim_cycles).sum();
    let report = SoakReport { settings: Some(settings), chunks };
    if let Some(p) = &a.json {
        set.write(p, serde_json::to_string_pretty(&report)?)?;
    }
    // The report of a finished soak is kept even when it found problems.
    set.commit()?;
    out!("{}", report.summary());
    let dt = t0.elapsed().as_secs_f64();
    errln!(
        "{} frames in {dt:.0} s ({:.1} frames/s, {:.0} simulated clock cycles/s, {jobs} jobs{})",
        report.frames(),
        report.frames() as f64 / dt.max(1e-9),
        cycles as f64 / dt.max(1e-9),
        shard.map_or(String::new(), |s| format!(", shard {s}"))
    );
    if let Some(p) = &a.json {
        errln!("wrote {}", p.display());
    }
    anyhow::ensure!(report.ok(), "blames, isolations or problems in the soak");
    Ok(())
}
