//! Tests of the input synchroniser and the edge detector (`canstar_hdl::sync`): Rust
//! simulation, and (ignored without the tools) the Verilog flow: lint, Yosys, co-simulation.

mod util;
use util::*;

// ---------------------------------------------------------------- Synchroniser

fn check_synchroniser(depth: usize, seed: u64) {
    let mut u = Synchroniser::new(depth);
    assert_eq!(u.latency(), depth);
    drive::init(&mut u);
    assert!(u.q.val(), "power-up value must be 1 (recessive)");
    let mut rng = flow::rng(seed);
    let d_seq = runs(&mut rng, 5000, 6);
    let mut stages = vec![true; depth];
    for (i, &d) in d_seq.iter().enumerate() {
        let reset = rng.gen_bool(0.02);
        u.d.next = d;
        u.reset.next = reset;
        drive::settle(&mut u);
        assert_eq!(u.q.val(), stages[depth - 1], "cycle {i} before edge");
        drive::cycle(&mut u);
        if reset {
            stages.iter_mut().for_each(|s| *s = true);
        } else {
            stages.insert(0, d);
            stages.pop();
        }
        assert_eq!(u.q.val(), stages[depth - 1], "cycle {i} after edge");
    }
}

#[test]
fn synchroniser_depth1_delays_by_one() {
    check_synchroniser(1, 11);
}

#[test]
fn synchroniser_depth2_delays_by_two() {
    check_synchroniser(2, 12);
}

#[test]
fn synchroniser_explicit_latency_and_reset() {
    let mut u = Synchroniser::default();
    assert_eq!(u.latency(), 2);
    drive::init(&mut u);
    u.d.next = false;
    drive::cycle(&mut u);
    assert!(u.q.val(), "one clock is not enough with 2 stages");
    drive::cycle(&mut u);
    assert!(!u.q.val(), "dominant after 2 clocks");
    // A reset sets every stage back to 1 at once.
    u.reset.next = true;
    drive::cycle(&mut u);
    assert!(u.q.val());
    u.reset.next = false;
    drive::cycle(&mut u);
    assert!(u.q.val(), "the second stage was reset too");
    drive::cycle(&mut u);
    assert!(!u.q.val());
}

#[test]
#[should_panic(expected = "depth must be 1 or 2")]
fn synchroniser_rejects_depth_0() {
    let _ = Synchroniser::new(0);
}

#[test]
#[should_panic(expected = "depth must be 1 or 2")]
fn synchroniser_rejects_depth_3() {
    let _ = Synchroniser::new(3);
}

// ---------------------------------------------------------------- EdgeDetector

#[test]
fn edge_detector_power_up_sees_dominant_as_fall() {
    let mut u = EdgeDetector::default();
    drive::init(&mut u);
    assert!(u.prev.val());
    u.d.next = false;
    drive::settle(&mut u);
    assert!(u.fall.val() && !u.rise.val(), "previous value after power-up is 1");
    u.d.next = true;
    drive::settle(&mut u);
    assert!(!u.fall.val() && !u.rise.val());
}

#[test]
fn edge_detector_matches_model() {
    let mut u = EdgeDetector::default();
    drive::init(&mut u);
    let mut rng = flow::rng(21);
    let d_seq = runs(&mut rng, 5000, 4);
    let mut prev = true;
    let (mut falls, mut rises) = (0, 0);
    for (i, &d) in d_seq.iter().enumerate() {
        let reset = rng.gen_bool(0.03);
        u.d.next = d;
        u.reset.next = reset;
        drive::settle(&mut u);
        assert_eq!(u.fall.val(), prev && !d, "fall, cycle {i}");
        assert_eq!(u.rise.val(), !prev && d, "rise, cycle {i}");
        assert_eq!(u.prev.val(), prev, "prev, cycle {i}");
        falls += u.fall.val() as usize;
        rises += u.rise.val() as usize;
        drive::cycle(&mut u);
        prev = if reset { true } else { d };
    }
    assert!(falls > 500 && rises > 500);
}


// ---------------------------------------------------------------- Verilog flow

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn synchroniser_depth1_verilog_flow() {
    sync_flow(1, 101);
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn synchroniser_depth2_verilog_flow() {
    sync_flow(2, 102);
}

fn sync_flow(depth: usize, seed: u64) {
    let mut u = Synchroniser::new(depth);
    let mut d = true;
    let (synth, cs) = flow::full_check(&mut u, &format!("synchroniser{depth}"), FLOW_CYCLES, seed, |u, rng, _| {
        if rng.gen_bool(0.25) {
            d = !d;
        }
        u.d.next = d;
        u.reset.next = rng.gen_bool(0.002);
    })
    .expect("flow");
    assert_eq!(cs.cycles, FLOW_CYCLES);
    assert!(synth.cells > 0);
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn edge_detector_verilog_flow() {
    let mut u = EdgeDetector::default();
    let mut d = true;
    let (synth, cs) = flow::full_check(&mut u, "edge_detector", FLOW_CYCLES, 103, |u, rng, _| {
        if rng.gen_bool(0.2) {
            d = !d;
        }
        u.d.next = d;
        u.reset.next = rng.gen_bool(0.002);
    })
    .expect("flow");
    assert_eq!(cs.cycles, FLOW_CYCLES);
    assert!(synth.cells > 0);
}
