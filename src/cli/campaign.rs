//! `canstar campaign`: fault campaigns on the ReCANcentrate system.

use super::output::check_output;
use anyhow::{Context, Result};
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
    /// With --class: print every hub blame and every controller error of the run.
    #[arg(long, requires = "class")]
    events: bool,
    /// Combine JSON reports (shards of one campaign) and print the table.
    #[arg(long, num_args = 1.., conflicts_with_all = ["class", "shard", "classes"])]
    merge: Vec<PathBuf>,
    /// List the scenario classes.
    #[arg(long)]
    list: bool,
    /// Draw the sweep classes' isolation latency and worst healthy TEC/REC against the
    /// disturbance interval as SVG (with a campaign that ran `sweep-*` classes, or --merge).
    #[arg(long, conflicts_with = "class")]
    plot_sweep: Option<PathBuf>,
}

/// The sweep table and `--plot-sweep` of a finished campaign.
fn sweep_outputs(runs: &[canstar_recan::campaign::RunOutcome], plot: Option<&PathBuf>, title: &str) -> Result<()> {
    use canstar_recan::campaign::sweep;
    if runs.iter().any(|r| r.class.starts_with("sweep-")) {
        print!("{}", sweep::table(runs));
    }
    if let Some(p) = plot {
        std::fs::write(p, sweep::svg(runs, title)).with_context(|| format!("writing {}", p.display()))?;
        eprintln!("wrote sweep plot {}", p.display());
    }
    Ok(())
}

pub fn run(a: Args) -> Result<()> {
    use canstar_recan::campaign::{self, report::CampaignReport, system, Settings};
    if a.list {
        for c in campaign::classes::catalogue() {
            println!("{}", c.name);
        }
        return Ok(());
    }
    for p in [&a.json, &a.vcd, &a.plot, &a.plot_sweep].into_iter().flatten() {
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
        sweep_outputs(&m.runs, a.plot_sweep.as_ref(), &format!("canstar sweep campaign, {} runs (merged)", m.runs.len()))?;
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
        println!(
            "  shortest pulse on a healthy port input {:?}, on a sublink input {:?} (hub clocks)",
            o.min_pulse_healthy_port, o.min_pulse_sublink
        );
        if a.events {
            print_events(&d.result);
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
    let shard = parse_shard(a.shard.as_deref())?;
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
    sweep_outputs(&report.runs, a.plot_sweep.as_ref(), &format!("canstar sweep campaign, {} reps per class, seed {}", a.reps, a.seed))?;
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
        lines.push((i.t_ps, format!("isolated {:?}", i.what)));
    }
    lines.sort_by_key(|l| l.0);
    for (t, l) in lines {
        println!("  {:9.1} {l}", t as f64 / bit);
    }
}

/// `--shard` of `campaign` and `soak`: `i/n`, `auto` or `auto/n` (scheduler array job).
pub fn parse_shard(s: Option<&str>) -> Result<Option<canstar_recan::campaign::Shard>> {
    Ok(s.map(canstar_recan::campaign::Shard::parse_auto).transpose()?)
}
