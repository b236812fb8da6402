//! Cost of campaign runs (diagnostic, ignored: performance is never asserted).
//! `cargo test --release -p canstar-sim --test recan_cost -- --ignored --nocapture`
use canstar_recan::{published_scenario, run};

#[test]
#[ignore = "diagnostic: prints CPU time and simulated cycles per run"]
fn diag_cost_of_published_scenario_runs() {
    let mut total = 0.0;
    let mut cycles = 0u64;
    for n in 1..=21 {
        let (spec, _) = published_scenario(n, 1);
        let t = cpu_time();
        let r = run(&spec);
        let dt = cpu_time() - t;
        total += dt;
        cycles += r.sim_cycles;
        eprintln!("scenario {n:2}: {dt:.2} s CPU, {} cycles, {} frames, {:.0} us simulated", r.sim_cycles, r.delivered, r.end_ps as f64 / 1e6);
    }
    eprintln!("21 runs: {total:.1} s CPU, {:.2} s per run, {:.0} cycles/s", total / 21.0, cycles as f64 / total);
}

/// Process CPU time in seconds (wall time would count other processes on a shared machine).
fn cpu_time() -> f64 {
    let s = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let f: Vec<&str> = s.rsplit(')').next().unwrap_or("").split_whitespace().collect();
    let ticks = f.get(11).and_then(|x| x.parse::<f64>().ok()).unwrap_or(0.0) + f.get(12).and_then(|x| x.parse::<f64>().ok()).unwrap_or(0.0);
    ticks / 100.0
}
