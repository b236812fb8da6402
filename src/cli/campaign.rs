//! `canstar campaign`: fault campaigns on the ReCANcentrate system.

use super::progress::Progress;
use anyhow::Result;
use canstar::output::OutputSet;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
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
    /// Run only shard i of n (1-based), e.g. `--shard 2/4`, or `auto` / `auto/n` in a Slurm or
    /// LSF array job (index and count from SLURM_ARRAY_TASK_ID/COUNT or LSB_JOBINDEX); merge
    /// the JSON files with --merge.
    #[arg(long)]
    shard: Option<String>,
    /// Write the per-run results as JSON.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Write a JUnit XML report (one test case per class) for CI systems.
    #[arg(long, conflicts_with = "class")]
    junit: Option<PathBuf>,
    /// Delay between the two faults of the double-* classes, in bit times.
    #[arg(long, default_value_t = canstar_recan::campaign::classes::DEFAULT_DOUBLE_DELAY_BITS)]
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
    /// With --class: write the node drivers' routine log (tx, rx and qua routines,
    /// omissions, retransmissions) of the run.
    #[arg(long, requires = "class")]
    trace: Option<PathBuf>,
    /// With --class: print every hub blame and every controller error of the run.
    #[arg(long, requires = "class")]
    events: bool,
    /// Combine JSON reports of one configuration (shards of one campaign, or campaigns
    /// over different classes) and print the table.
    #[arg(long, num_args = 1.., conflicts_with_all = ["class", "shard", "classes"])]
    merge: Vec<PathBuf>,
    /// List the scenario classes.
    #[arg(long)]
    list: bool,
    /// Configure both hubs from the `[hub]` table of this TOML file (the format of
    /// `canstar generate --config`) instead of the reference hub; `ports` and `sublinks`
    /// must stay 3 and 2 (the campaign's network).
    #[arg(long, value_name = "TOML", conflicts_with = "merge")]
    hub_config: Option<PathBuf>,
    #[command(flatten)]
    engine: canstar::engine::EngineArg,
    /// Draw the sweep classes' isolation latency and worst healthy TEC/REC against the
    /// disturbance interval as SVG (with a campaign that ran `sweep-*` classes, or --merge).
    #[arg(long, conflicts_with = "class")]
    plot_sweep: Option<PathBuf>,
}

/// The sweep table of a finished campaign (empty without `sweep-*` runs); stages
/// its `--plot-sweep` SVG in `set`.
fn sweep_outputs(set: &OutputSet, runs: &[canstar_recan::campaign::RunOutcome], plot: Option<&PathBuf>, title: &str) -> Result<String> {
    use canstar_recan::campaign::sweep;
    if let Some(p) = plot {
        set.write(p, sweep::svg(runs, title))?;
    }
    Ok(if runs.iter().any(|r| r.class.starts_with("sweep-")) { sweep::table(runs) } else { String::new() })
}

pub fn run(a: Args) -> Result<()> {
    use canstar_recan::campaign::{self, report::CampaignReport, system, Settings};
    if a.list {
        for c in campaign::classes::catalogue() {
            outln!("{}", c.name);
        }
        return Ok(());
    }
    if a.class.is_none() {
        for (flag, p) in [("--vcd", &a.vcd), ("--plot", &a.plot), ("--trace", &a.trace)] {
            anyhow::ensure!(p.is_none(), "{flag} writes the details of one run: it needs --class");
        }
    }
    // Every output is reserved before any work.
    let mut set = OutputSet::new();
    for p in [&a.json, &a.junit, &a.vcd, &a.plot, &a.plot_sweep, &a.trace].into_iter().flatten() {
        set.file(p)?;
    }
    if !a.merge.is_empty() {
        let mut parts = vec![];
        for p in &a.merge {
            let text = canstar::input::read_text(p, canstar::input::MAX_JSON_BYTES)?;
            parts.push(CampaignReport::from_json(&text, &p.display().to_string())?);
        }
        let m = CampaignReport::merge(&parts)?;
        let sweep_table = sweep_outputs(&set, &m.runs, a.plot_sweep.as_ref(), &format!("canstar sweep campaign, {} runs (merged)", m.runs.len()))?;
        if let Some(p) = &a.json {
            set.write(p, m.to_json())?;
        }
        if let Some(p) = &a.junit {
            set.write(p, campaign::junit::xml(&m))?;
        }
        set.commit()?;
        out!("{}", m.table());
        out!("{sweep_table}");
        if m.runs.len() != m.expected_runs() {
            errln!("warning: {} of {} runs of the campaign present (shards missing)", m.runs.len(), m.expected_runs());
        }
        anyhow::ensure!(m.ok(), "{} failing run(s)", m.runs.iter().filter(|r| !r.pass).count());
        return Ok(());
    }
    let hub = a.hub_config.as_deref().map(campaign_hub).transpose()?;
    let settings = Settings { seed: a.seed, reps: a.reps, double_delay_bits: a.double_delay_bits, engine: a.engine.engine, hub };
    if let Some(name) = &a.class {
        let class = campaign::class(name)?;
        let rep = a.rep.unwrap_or(0);
        let seed = a.run_seed.unwrap_or_else(|| campaign::run_seed(a.seed, &class.name, rep));
        let vcd_tmp = a.vcd.as_deref().and_then(|p| set.temp_of(p)).map(|p| p.to_path_buf());
        let d = system::run_detailed(&class, rep, seed, &settings, vcd_tmp, a.trace.is_some());
        if let Some(e) = &d.result.vcd_error {
            anyhow::bail!("{e}");
        }
        if let Some(p) = &a.plot {
            set.write(p, campaign::plot::svg(&d.plot))?;
        }
        if let Some(p) = &a.trace {
            set.write(p, d.result.trace.join("\n") + "\n")?;
        }
        // The outputs of a finished run are kept even when it fails its checks.
        set.commit()?;
        let o = &d.outcome;
        outln!("{} seed {}: {}", o.class, o.seed, if o.pass { "PASS" } else { "FAIL" });
        for f in &o.faults {
            outln!("  fault: {f}");
        }
        for i in &o.isolations {
            outln!("  isolated: {i}");
        }
        for q in &o.quarantined {
            outln!("  quarantined: {q}");
        }
        outln!(
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
            outln!("  note: {n}");
        }
        outln!(
            "  shortest pulse on a healthy port input {:?}, on a sublink input {:?} (hub clocks)",
            o.min_pulse_healthy_port, o.min_pulse_sublink
        );
        if a.events {
            print_events(&d.result);
        }
        for f in &o.failures {
            outln!("  FAILURE: {f}");
        }
        if let Some(p) = &a.vcd {
            outln!("wrote VCD {}", p.display());
        }
        if let Some(p) = &a.plot {
            outln!("wrote plot {}", p.display());
        }
        if let Some(p) = &a.trace {
            outln!("wrote driver trace {}", p.display());
        }
        anyhow::ensure!(o.pass, "run failed (rerun: canstar campaign --class {} --run-seed {})", o.class, o.seed);
        return Ok(());
    }
    anyhow::ensure!(a.run_seed.is_none() && a.rep.is_none(), "--run-seed and --rep need --class");
    let classes = campaign::select(&a.classes)?;
    let shard = parse_shard(a.shard.as_deref())?;
    anyhow::ensure!(a.reps > 0, "--reps must be at least 1");
    anyhow::ensure!(a.jobs != Some(0), "--jobs must be at least 1");
    let plans = campaign::plan(&classes, &settings, shard);
    let jobs = a.jobs.unwrap_or_else(|| std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1));
    let mut bar = Progress::new(plans.len() as u64, "runs");
    let t0 = std::time::Instant::now();
    let (mut failed, mut cycles) = (0usize, 0u64);
    let total = plans.len();
    let outcomes = campaign::execute(&plans, jobs, |p| system::run_plan(p, &settings), |o| {
        cycles += o.sim_cycles;
        if !o.pass {
            failed += 1;
            bar.suspend(|| errln!("FAIL {} rep {} seed {}: {}", o.class, o.rep, o.seed, o.failures.join("; ")));
        }
        bar.set_message(format!("{failed} failed"));
        bar.inc();
    });
    bar.finish();
    let dt = t0.elapsed().as_secs_f64();
    let report = CampaignReport::new(settings, &classes, shard, outcomes);
    if let Some(p) = &a.json {
        set.write(p, report.to_json())?;
    }
    if let Some(p) = &a.junit {
        set.write(p, campaign::junit::xml(&report))?;
    }
    let sweep_table = sweep_outputs(&set, &report.runs, a.plot_sweep.as_ref(), &format!("canstar sweep campaign, {} reps per class, seed {}", a.reps, a.seed))?;
    // The report of a finished campaign is kept even when runs failed.
    set.commit()?;
    out!("{}", report.table());
    out!("{sweep_table}");
    errln!(
        "{total} runs in {dt:.1} s ({:.2} runs/s, {:.0} simulated clock cycles/s, {jobs} jobs{})",
        total as f64 / dt.max(1e-9),
        cycles as f64 / dt.max(1e-9),
        shard.map_or(String::new(), |s| format!(", shard {s}"))
    );
    if let Some(p) = &a.json {
        errln!("wrote {}", p.display());
    }
    anyhow::ensure!(report.ok(), "{failed} failing run(s)");
    Ok(())
}


/// The `[hub]` table of a configuration file for the campaign's network (its hubs'
/// ports and interlinks, from the network itself); errors name the file and the key.
fn campaign_hub(p: &std::path::Path) -> Result<canstar_hub::config::HubConfig> {
    let c = canstar::config::Config::load(p)?;
    let net = canstar_recan::spec::NetworkSpec::fast().hub;
    for (key, v, want) in [("hub.ports", c.hub.ports, net.ports), ("hub.sublinks", c.hub.sublinks, net.sublinks)] {
        anyhow::ensure!(v == want, "{}: {key} = {v}: the campaign's network has {want} (remove the key)", p.display());
    }
    Ok(c.hub)
}

/// The hub blames and controller errors of one run, in time order (bit times).
fn print_events(r: &canstar_recan::RunResult) {
    use canstar_controller::fsm::Field as CField;
    use canstar_hub::frame_state::Field as HField;
    let bit = r.bit_time_ps.max(1) as f64;
    let mut lines: Vec<(u64, String)> = vec![];
    for &(h, t, u, f, p, c) in &r.blames {
        let how = if c { "blames" } else { "blames (suppressed)" };
        lines.push((t, format!("hub {h} {how} unit {u} in {:?} bit {p}", HField::from_code(f as u64))));
    }
    for &(h, t, u) in &r.glitches {
        lines.push((t, format!("hub {h} glitch on unit {u}")));
    }
    for &(t, k, c, tx, f) in &r.ctrl_errors {
        let field = CField::ALL.get(f as usize).map_or(format!("{f}"), |x| format!("{x:?}"));
        lines.push((t, format!("node {k} ctrl {} error ({}) in {field}", "AB".as_bytes()[c] as char, if tx { "tx" } else { "rx" })));
    }
    for i in &r.isolated {
        lines.push((i.t_ps, format!("isolated {:?} by {}", i.what, i.cause)));
    }
    lines.sort_by_key(|l| l.0);
    for (t, l) in lines {
        outln!("  {:9.1} {l}", t as f64 / bit);
    }
}

/// `--shard` of `campaign` and `soak`: `i/n`, `auto` or `auto/n` (scheduler array job).
pub fn parse_shard(s: Option<&str>) -> Result<Option<canstar_recan::campaign::Shard>> {
    Ok(s.map(canstar_recan::campaign::Shard::parse_auto).transpose()?)
}
