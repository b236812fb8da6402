//! The peer guard's estimate of the peer's sublink counters (hub.md §5.20) in isolation.
use canstar_hdl::{drive, flow};
use canstar_hub::peer::PeerEstimate;
use rand::Rng;

fn fresh(on: bool, limit: u64, decay: u64) -> PeerEstimate {
    let mut p = PeerEstimate::new(on, limit, decay);
    drive::init(&mut p);
    p.reset.next = true;
    drive::cycle(&mut p);
    p.reset.next = false;
    p
}

/// One clock with a port charge of `inc` blames.
fn charge(p: &mut PeerEstimate, inc: u64) {
    p.inc.next = inc.into();
    drive::cycle(p);
    p.inc.next = 0.into();
}

/// `n` good frames (one strobe each, then a clock for the registered strobe).
fn good_frames(p: &mut PeerEstimate, n: usize) {
    for _ in 0..n {
        p.frame_ok.next = true;
        drive::cycle(p);
        p.frame_ok.next = false;
        drive::cycle(p);
    }
}

#[test]
fn estimate_adds_eight_per_blame_and_saturates() {
    let mut p = fresh(true, 56, 2);
    for (inc, est) in [(1, 8), (3, 32), (2, 48)] {
        charge(&mut p, inc);
        assert_eq!(p.est.val().index(), est, "after a step of {inc}");
    }
    assert!(!p.high.val());
    charge(&mut p, 1);
    assert!(p.high.val(), "56 reached");
    for _ in 0..20 {
        charge(&mut p, 3);
    }
    assert_eq!(p.est.val().index(), 255);
}

#[test]
fn estimate_decays_one_per_decay_good_frames_and_resets() {
    let mut p = fresh(true, 56, 2);
    charge(&mut p, 1);
    good_frames(&mut p, 1);
    assert_eq!(p.est.val().index(), 8);
    good_frames(&mut p, 1);
    assert_eq!(p.est.val().index(), 7);
    good_frames(&mut p, 14);
    assert_eq!(p.est.val().index(), 0);
    good_frames(&mut p, 4);
    assert_eq!(p.est.val().index(), 0, "no decay below 0");
    // a charge in the clock of the registered good frame wins over the decay
    charge(&mut p, 1);
    p.frame_ok.next = true;
    drive::cycle(&mut p);
    p.frame_ok.next = false;
    charge(&mut p, 1);
    assert_eq!(p.est.val().index(), 16);
    p.reset.next = true;
    drive::cycle(&mut p);
    assert_eq!(p.est.val().index(), 0);
}

#[test]
fn guard_off_is_never_high() {
    let mut p = fresh(false, 56, 2);
    for _ in 0..10 {
        charge(&mut p, 3);
    }
    assert!(p.est.val().index() >= 56 && !p.high.val());
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn peer_estimate_flow() {
    let mut p = PeerEstimate::new(true, 56, 2);
    flow::full_check(&mut p, "peer_estimate", 100_000, 24, |p: &mut PeerEstimate, rng, c| {
        p.reset.next = c < 2 || rng.gen_ratio(1, 20_000);
        p.inc.next = if rng.gen_ratio(1, 40) { rng.gen_range(1..4u64) } else { 0 }.into();
        p.frame_ok.next = c % 16 == 12 && rng.gen_ratio(1, 3);
    })
    .expect("peer estimate flow");
}
