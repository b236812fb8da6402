//! Published scenarios with randomised variants (injection instant and field, traffic
//! phase, oscillator offsets, initial tx controllers), as the campaign runs them.
use canstar_recan::{check, published_scenario, run};

fn sweep(scenarios: &[usize], seeds: std::ops::RangeInclusive<u64>) -> Vec<String> {
    let mut bad = Vec::new();
    for &n in scenarios {
        for seed in seeds.clone() {
            let (spec, exp) = published_scenario(n, seed);
            let t = std::time::Instant::now();
            let r = run(&spec);
            let f = check(&r, &exp);
            eprintln!(
                "scenario {n:2} seed {seed:3}: {} in {:.2}s ({} cycles, {} frames) fault {:?} at {:?} iso {:?} qua {:?} retx {}",
                if f.is_empty() { "ok  " } else { "FAIL" },
                t.elapsed().as_secs_f64(),
                r.sim_cycles,
                r.delivered,
                r.fault_resolved,
                r.fault_start_ps,
                r.isolated.iter().map(|i| (i.what, i.latency_bits)).collect::<Vec<_>>(),
                r.quarantined,
                r.max_retransmissions
            );
            if !f.is_empty() {
                bad.push(format!("scenario {n} seed {seed}: {f:?}"));
            }
        }
    }
    bad
}

#[test]
fn randomised_variants_of_some_scenarios_keep_their_outcome() {
    let bad = sweep(&[3, 7, 12, 18, 20], 1..=1);
    assert!(bad.is_empty(), "{bad:#?}");
}

#[test]
#[ignore = "long: every scenario with several seeds"]
fn long_randomised_variants_of_every_scenario() {
    let env = |k: &str, d: u64| std::env::var(k).ok().and_then(|s| s.parse().ok()).unwrap_or(d);
    let (first, seeds) = (env("RECAN_SEED0", 1), env("RECAN_SEEDS", 3));
    let bad = sweep(&(1..=21).collect::<Vec<_>>(), first..=first + seeds - 1);
    assert!(bad.is_empty(), "{bad:#?}");
}

/// `RECAN_ONE=n,seed cargo test --release --test recan_random -- --ignored diag_one_variant --nocapture`
#[test]
#[ignore = "diagnostic: one scenario variant with its driver trace"]
fn diag_one_variant() {
    let v: Vec<u64> = std::env::var("RECAN_ONE").unwrap_or("1,0".into()).split(',').map(|x| x.parse().unwrap()).collect();
    let (mut spec, exp) = published_scenario(v[0] as usize, v[1]);
    spec.trace = true;
    eprintln!("{:?}", spec.faults);
    let r = run(&spec);
    for l in &r.trace {
        eprintln!("{l}");
    }
    eprintln!("{r:?}");
    eprintln!("{:?}", check(&r, &exp));
}
