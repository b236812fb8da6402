//! `canstar`: generate CAN controller and CAN star hub RTL, and simulate it.

use anyhow::{Context, Result};
use canstar::config::Config;
use canstar::generate::{self, Target};
use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "canstar", version, about = "CAN controller and CAN star hub RTL generator with a cycle simulator")]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Generate Verilog (and pin files) for a design, with defaults or from a TOML config.
    Generate {
        /// What to generate.
        #[arg(value_enum, default_value = "all")]
        target: Target,
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
    },
    /// Synthesise the generated designs and print a resource table (iCE40 cells, flip-flops,
    /// block RAMs and fmax with Yosys + nextpnr-ice40; Spartan-3 LUTs and flip-flops with Yosys).
    Report {
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
    },
    /// Simulate a bus scenario (TOML: nodes, bit timing, clock offsets, frames, interference),
    /// or a ReCANcentrate network file (top-level `[network]`, see sim/examples/recancentrate.toml)
    /// running its test applications.
    Sim {
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
    },
    /// Measure simulation throughput (simulated clock cycles per second).
    Bench {
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
    },
    /// Randomised differential testing: RTL nodes in lock step with golden models on a bus with
    /// random traffic and receive-path disturbances; prints divergences and property violations.
    Fuzz {
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
    },
    /// Run the Bosch conformance suite (conformance-tests.md) in the multi-node simulation:
    /// one line per program, a line with the simulation effort and throughput (clock cycles,
    /// bit times, wall time), then `N passed, M failed` counting steps.
    Conformance {
        /// Run only this program (baudrate, biterror, btl, crc, dlc, emlcount, extd_id,
        /// formerr, idle, overload, stuffbit, stufferr, txarb).
        #[arg(long)]
        program: Option<String>,
        /// Write one VCD per program (`<program>.vcd`) into this directory.
        #[arg(long)]
        vcd: Option<PathBuf>,
        /// Run every node in lock step with its own golden model (can-protocol.md §19): print
        /// each divergence, and count them in the final line (`N passed, M failed, K divergences`).
        #[arg(long)]
        lockstep: bool,
    },
    /// Fault campaigns on the ReCANcentrate system: every selected scenario class repeated
    /// with random injection instants, traffic phases and oscillator offsets; prints per class
    /// runs, passes, worst healthy TEC/REC, isolation latency and every failure with its seed.
    Campaign(CampaignArgs),
}

#[derive(clap::Args)]
struct CampaignArgs {
    /// Classes to run: comma-separated names or globs (`pub*`, `flip-*-up-*`); see --list.
    #[arg(long, default_value = "*")]
    classes: String,
    /// Repetitions per class.
    #[arg(long, default_value_t = 100)]
    reps: u32,
    /// Master seed (each run's seed is derived from it, the class and the repetition).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Worker threads (default: available parallelism).
    #[arg(long)]
    jobs: Option<usize>,
    /// Run only shard i of n (1-based), e.g. `--shard 2/4`; merge the JSON files with --merge.
    #[arg(long)]
    shard: Option<String>,
    /// Write the per-run results as JSON.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Delay between the two faults of the double-* classes, in bit times.
    #[arg(long, default_value_t = canstar_sim::campaign::classes::DEFAULT_DOUBLE_DELAY_BITS)]
    double_delay_bits: u32,
    /// Run one run of this class only and print its details (with --run-seed or --rep).
    #[arg(long, conflicts_with_all = ["classes", "shard", "json"])]
    class: Option<String>,
    /// With --class: the run seed (as printed for a failure).
    #[arg(long, conflicts_with = "rep")]
    run_seed: Option<u64>,
    /// With --class: the repetition (its seed derived from --seed); default 0.
    #[arg(long)]
    rep: Option<u32>,
    /// With --class: write the VCD of the run.
    #[arg(long, requires = "class")]
    vcd: Option<PathBuf>,
    /// With --class: write an SVG of every controller's TEC/REC with isolations and quarantines.
    #[arg(long, requires = "class")]
    plot: Option<PathBuf>,
    /// Combine JSON reports (shards of one campaign) and print the table.
    #[arg(long, num_args = 1.., conflicts_with_all = ["class", "shard", "classes"])]
    merge: Vec<PathBuf>,
    /// List the scenario classes.
    #[arg(long)]
    list: bool,
}

/// The parent directory of an output file must exist (checked before any work).
fn check_output(p: &std::path::Path) -> Result<()> {
    if p.is_dir() {
        anyhow::bail!("{} is a directory", p.display());
    }
    if let Some(d) = p.parent() {
        if !d.as_os_str().is_empty() && !d.is_dir() {
            anyhow::bail!("cannot write {}: directory {} does not exist", p.display(), d.display());
        }
    }
    Ok(())
}

fn campaign_cmd(a: CampaignArgs) -> Result<()> {
    use canstar_sim::campaign::{self, report::CampaignReport, system, Settings, Shard};
    if a.list {
        for c in campaign::classes::catalogue() {
            println!("{}", c.name);
        }
        return Ok(());
    }
    for p in [&a.json, &a.vcd, &a.plot].into_iter().flatten() {
        check_output(p)?;
    }
    if !a.merge.is_empty() {
        let mut parts = vec![];
        for p in &a.merge {
            let text = std::fs::read_to_string(p).with_context(|| format!("reading {}", p.display()))?;
            parts.push(CampaignReport::from_json(&text, &p.display().to_string())?);
        }
        let m = CampaignReport::merge(&parts)?;
        print!("{}", m.table());
        if m.runs.len() != m.expected_runs() {
            eprintln!("warning: {} of {} runs of the campaign present (shards missing)", m.runs.len(), m.expected_runs());
        }
        if let Some(p) = &a.json {
            std::fs::write(p, m.to_json()).with_context(|| format!("writing {}", p.display()))?;
        }
        anyhow::ensure!(m.ok(), "{} failing run(s)", m.runs.iter().filter(|r| !r.pass).count());
        return Ok(());
    }
    let settings = Settings { seed: a.seed, reps: a.reps, double_delay_bits: a.double_delay_bits };
    if let Some(name) = &a.class {
        let class = campaign::class(name)?;
        let rep = a.rep.unwrap_or(0);
        let seed = a.run_seed.unwrap_or_else(|| campaign::run_seed(a.seed, &class.name, rep));
        let d = system::run_detailed(&class, rep, seed, &settings, a.vcd.clone());
        let o = &d.outcome;
        println!("{} seed {}: {}", o.class, o.seed, if o.pass { "PASS" } else { "FAIL" });
        for f in &o.faults {
            println!("  fault: {f}");
        }
        for i in &o.isolations {
            println!("  isolated: {i} (bit)");
        }
        for q in &o.quarantined {
            println!("  quarantined: {q}");
        }
        println!(
            "  worst healthy TEC/REC {} (sampled TEC {} REC {}), max retransmissions {}, duplicates {}, delivered {}, isolation latency {}",
            o.worst_healthy,
            o.worst_healthy_tec,
            o.worst_healthy_rec,
            o.max_retransmissions,
            o.duplicates,
            o.delivered,
            o.isolation_latency_bits.map_or("-".into(), |l| format!("{l} bits"))
        );
        for n in &o.notes {
            println!("  note: {n}");
        }
        for f in &o.failures {
            println!("  FAILURE: {f}");
        }
        if let Some(p) = &a.vcd {
            println!("wrote VCD {}", p.display());
        }
        if let Some(p) = &a.plot {
            std::fs::write(p, campaign::plot::svg(&d.plot)).with_context(|| format!("writing {}", p.display()))?;
            println!("wrote plot {}", p.display());
        }
        anyhow::ensure!(o.pass, "run failed (rerun: canstar campaign --class {} --run-seed {})", o.class, o.seed);
        return Ok(());
    }
    anyhow::ensure!(a.run_seed.is_none() && a.rep.is_none(), "--run-seed and --rep need --class");
    let classes = campaign::select(&a.classes)?;
    let shard = a.shard.as_deref().map(Shard::parse).transpose()?;
    anyhow::ensure!(a.reps > 0, "--reps must be at least 1");
    let plans = campaign::plan(&classes, &settings, shard);
    let jobs = a.jobs.unwrap_or_else(|| std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1));
    let bar = indicatif::ProgressBar::new(plans.len() as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} runs ({per_sec}, eta {eta}) {msg}")
            .unwrap()
            .progress_chars("=> "),
    );
    let t0 = std::time::Instant::now();
    let (mut done, mut failed, mut cycles) = (0usize, 0usize, 0u64);
    let total = plans.len();
    let outcomes = campaign::execute(&plans, jobs, |p| system::run_plan(p, &settings), |o| {
        done += 1;
        cycles += o.sim_cycles;
        if !o.pass {
            failed += 1;
            bar.suspend(|| eprintln!("FAIL {} rep {} seed {}: {}", o.class, o.rep, o.seed, o.failures.join("; ")));
        }
        bar.inc(1);
        bar.set_message(format!("{failed} failed"));
        if bar.is_hidden() && (done * 10 / total.max(1)) != ((done - 1) * 10 / total.max(1)) {
            eprintln!("{:.0} s: {done}/{total} runs, {failed} failed", t0.elapsed().as_secs_f64());
        }
    });
    bar.finish_and_clear();
    let dt = t0.elapsed().as_secs_f64();
    let report = CampaignReport::new(settings, &classes, shard, outcomes);
    print!("{}", report.table());
    eprintln!(
        "{total} runs in {dt:.1} s ({:.2} runs/s, {:.0} simulated clock cycles/s, {jobs} jobs{})",
        total as f64 / dt.max(1e-9),
        cycles as f64 / dt.max(1e-9),
        shard.map_or(String::new(), |s| format!(", shard {s}"))
    );
    if let Some(p) = &a.json {
        std::fs::write(p, report.to_json()).with_context(|| format!("writing {}", p.display()))?;
        eprintln!("wrote {}", p.display());
    }
    anyhow::ensure!(report.ok(), "{failed} failing run(s)");
    Ok(())
}

/// `canstar sim` with a ReCANcentrate network file.
fn network_sim(path: &std::path::Path, text: &str, ms: f64, seed: u64, vcd: Option<PathBuf>, trace: Option<PathBuf>) -> Result<()> {
    use canstar_sim::recan::{run, NetworkSpec, RunSpec};
    let net = NetworkSpec::from_toml(text).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    let mut spec = RunSpec::new(net.clone(), seed, 0);
    spec.max_time_ps = Some((ms * 1e9).round() as u64);
    spec.vcd = vcd.clone();
    spec.trace = trace.is_some();
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

#[allow(clippy::too_many_arguments)]
fn fuzz_cmd(
    frames: u64,
    seed: u64,
    per_run: usize,
    jobs: Option<usize>,
    run_seed: Option<u64>,
    disturb: bool,
    vcd_dir: PathBuf,
    max_failures: usize,
) -> Result<()> {
    use canstar_sim::fuzz::{self, RunOptions, RunReport};
    let opts = RunOptions { frames: per_run, disturb, vcd_dir: Some(vcd_dir) };
    let show = |r: &RunReport| {
        println!(
            "run seed {} ({:#x}): {} nodes, {} frames, {} sent, {} errors, worst state {}",
            r.seed, r.seed, r.nodes, r.frames, r.sent, r.errors, ["error-active", "error-passive", "bus-off"][r.worst_state.min(2) as usize]
        );
        if let Some(d) = &r.divergence {
            println!("{d}");
        }
        if let Some(v) = &r.vcd {
            println!("  VCD of the divergence window: {}", v.display());
        }
        for v in &r.violations {
            println!("  property violation: {v}");
        }
    };
    if let Some(s) = run_seed {
        let r = fuzz::run_seed(s, &opts);
        show(&r);
        anyhow::ensure!(r.ok(), "run seed {s} failed");
        return Ok(());
    }
    let jobs = jobs.unwrap_or_else(|| std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1));
    let bar = indicatif::ProgressBar::new(frames);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} frames ({per_sec}, eta {eta}) {msg}")
            .unwrap()
            .progress_chars("=> "),
    );
    let t0 = std::time::Instant::now();
    let s = fuzz::fuzz(frames, seed, &opts, jobs, max_failures, |s, r| {
        bar.set_position(s.frames);
        let div = s.failures.iter().filter(|f| f.divergence.is_some()).count();
        let viol: usize = s.failures.iter().map(|f| f.violations.len()).sum();
        bar.set_message(format!("runs {} divergences {div} violations {viol}", s.runs));
        if !r.ok() {
            bar.suspend(|| show(r));
        }
        if bar.is_hidden() && s.runs % 20 == 0 {
            let dt = t0.elapsed().as_secs_f64();
            eprintln!(
                "{:.0} s: {} frames, {} runs, {:.1} frames/s, divergences {div}, violations {viol}, passive runs {}, bus-off runs {}",
                dt, s.frames, s.runs, s.frames as f64 / dt, s.passive_runs, s.busoff_runs
            );
        }
    });
    bar.finish();
    let dt = t0.elapsed().as_secs_f64();
    let div = s.failures.iter().filter(|f| f.divergence.is_some()).count();
    let viol: usize = s.failures.iter().map(|f| f.violations.len()).sum();
    println!(
        "{} frames in {} runs ({} sent, {} errors, {} runs reached error-passive, {} bus-off), {} bits compared in lock step",
        s.frames, s.runs, s.sent, s.errors, s.passive_runs, s.busoff_runs, s.bits
    );
    println!(
        "{:.1} s: {:.1} frames/s, {:.0} simulated clock cycles/s, {} jobs",
        dt,
        s.frames as f64 / dt,
        s.cycles as f64 / dt,
        jobs
    );
    println!(
        "longest dominant run driven by one node: {} bits (bound {} for its flag restarts)",
        s.max_dom_run.0, s.max_dom_run.1
    );
    println!("divergences: {div}, property violations: {viol}");
    for f in &s.failures {
        println!("  failing run seed {} (rerun: canstar fuzz --run-seed {} --per-run {})", f.seed, f.seed, f.frames);
    }
    anyhow::ensure!(s.failures.is_empty(), "{} failing run(s)", s.failures.len());
    Ok(())
}

fn run(cli: Cli) -> Result<()> {
    match cli.cmd {
        Cmd::Generate { target, config, board, out, constraints, check } => {
            let cfg = match &config {
                Some(p) => Config::load(p)?,
                None => Config::default(),
            };
            let arts = generate::render(target, &cfg, board.as_deref())?;
            if check {
                let bad = generate::check(&arts, &out, &constraints);
                if !bad.is_empty() {
                    for b in &bad {
                        eprintln!("out of date: {}", b.display());
                    }
                    anyhow::bail!("{} generated file(s) differ from `canstar generate` output; run it and commit", bad.len());
                }
                println!("{} generated file(s) up to date", arts.len());
            } else {
                let written = generate::write(&arts, &out, &constraints).context("writing generated files")?;
                for w in &written {
                    println!("wrote {}", w.display());
                }
            }
            Ok(())
        }
        Cmd::Report { config, freq, design, pnr_timeout } => {
            let cfg = match &config {
                Some(p) => Config::load(p)?,
                None => Config::default(),
            };
            let designs = canstar::designs::report_designs(&cfg)?;
            if let Some(unknown) = design.iter().find(|d| !designs.iter().any(|(n, _, _)| n == *d)) {
                let known: Vec<&str> = designs.iter().map(|(n, _, _)| n.as_str()).collect();
                anyhow::bail!("unknown design {unknown:?} (known: {})", known.join(", "));
            }
            let mut rows = vec![];
            for (name, verilog, top) in designs {
                if !design.is_empty() && !design.contains(&name) {
                    continue;
                }
                eprintln!("synthesising {name} ...");
                rows.push(canstar::report::measure(&name, &verilog, &top, freq, pnr_timeout)?);
            }
            println!("{}", canstar::report::table(&rows));
            println!("\ntools: {}", canstar::report::tool_versions());
            Ok(())
        }
        Cmd::Sim { scenario, ms, seed, vcd, trace, log } => {
            let text = std::fs::read_to_string(&scenario).with_context(|| format!("reading {}", scenario.display()))?;
            if canstar_sim::recan::NetworkSpec::is_network_file(&text) {
                return network_sim(&scenario, &text, ms, seed, vcd, trace);
            }
            let sc = canstar_sim::scenario::Scenario::from_toml(&text).map_err(|e| anyhow::anyhow!("{}: {e}", scenario.display()))?;
            let opts = canstar_sim::scenario::RunOptions { vcd: vcd.clone(), trace: trace.is_some() };
            let r = canstar_sim::scenario::run(&sc, &opts).map_err(|e| anyhow::anyhow!(e))?;
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
        Cmd::Bench { cycles, nodes, vcd: Some(path), signals, seed } => {
            let n = nodes.first().copied().unwrap_or(2);
            let c = cycles.min(200_000);
            canstar::designs::bench_vcd(&path, n, c, signals.as_deref(), seed)?;
            println!("wrote {} ({n} bit-timing instances on a bus, {c} cycles each)", path.display());
            Ok(())
        }
        Cmd::Bench { cycles, nodes, vcd: None, .. } => canstar::designs::bench(cycles, &nodes),
        Cmd::Fuzz { frames, seed, per_run, jobs, run_seed, no_disturb, vcd_dir, max_failures } => {
            fuzz_cmd(frames, seed, per_run, jobs, run_seed, !no_disturb, vcd_dir, max_failures)
        }
        Cmd::Campaign(a) => campaign_cmd(a),
        Cmd::Conformance { program, vcd, lockstep } => {
            let (_, failed, divergences) =
                canstar_sim::conformance::run_cli_with(program.as_deref(), vcd.as_deref(), lockstep, &mut std::io::stdout())?;
            if failed > 0 || divergences > 0 {
                anyhow::bail!("{failed} conformance step(s) failed, {divergences} lock-step divergence(s)");
            }
            Ok(())
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
