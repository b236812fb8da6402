//! Randomised differential testing (short fixed-seed version of `canstar fuzz`).
use canstar_verify::fuzz::{fuzz, run_seed, RunOptions};

#[test]
fn fixed_seed_fuzz_has_no_divergence_or_violation() {
    let opts = RunOptions { frames: 16, disturb: true, vcd_dir: Some(std::env::temp_dir()), ..Default::default() };
    let s = fuzz(200, 20251121, &opts, 2, 3, |s, r| {
        eprintln!(
            "run {} seed {:#x}: {} nodes, {} frames, sent {}, errors {}, worst state {}, ok {}",
            s.runs, r.seed, r.nodes, r.frames, r.sent, r.errors, r.worst_state, r.ok()
        )
    });
    for f in &s.failures {
        eprintln!("FAILED seed {:#x}: {:?}", f.seed, f.violations);
        if let Some(d) = &f.divergence {
            eprintln!("{d}");
        }
    }
    assert!(s.failures.is_empty(), "{} failing runs", s.failures.len());
    assert!(s.frames >= 200);
    // the disturbances did something
    assert!(s.errors > 0 && s.passive_runs > 0, "{s:?}");
}

#[test]
fn runs_are_reproducible_from_their_seed() {
    let opts = RunOptions { frames: 6, ..Default::default() };
    let a = run_seed(77, &opts);
    let b = run_seed(77, &opts);
    assert_eq!((a.sim_ps, a.cycles, a.sent, a.errors, a.bits), (b.sim_ps, b.cycles, b.sent, b.errors, b.bits));
    assert!(a.ok(), "{:?} {:?}", a.violations, a.divergence);
}

#[test]
fn the_divergence_window_vcd_has_dut_and_golden_signals() {
    let opts = RunOptions { frames: 2, disturb: false, vcd_dir: None, ..Default::default() };
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("w.vcd");
    canstar_verify::fuzz::write_window_vcd(5, &opts, &path, 300_000_000).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    for name in ["golden", "n1", "n2", "dbg_sample", "level"] {
        assert!(text.contains(name), "no {name} in the VCD header");
    }
    // a window, not the whole run: starts 60 bits before the instant
    let first_ts = text.lines().find(|l| l.starts_with('#')).unwrap();
    let t0: u64 = first_ts[1..].parse().unwrap();
    assert!((300_000_000 - 60 * 2_500_000..=300_000_000).contains(&t0), "first timestamp {t0}");
}
