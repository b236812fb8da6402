//! Randomised robustness on the bit-level harness: three nodes with random
//! requests and random receive-path disturbances. Invariants: only frames
//! that some node requested are delivered, counters stay in range and agree
//! with the error state, and once the disturbances stop every request is
//! completed and the bus returns to idle.
#![allow(clippy::needless_range_loop)]
mod common;
use canstar_controller::frame::Frame;
use canstar_controller::fsm::*;
use common::stim::random_frame;
use common::*;
use rand::{Rng, SeedableRng};
use std::collections::HashSet;

#[test]
fn random_traffic_with_disturbances() {
    for seed in 0..6u64 {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let mut b = Bus::integrated(3);
        let mut sent: HashSet<Frame> = HashSet::new();
        let mut want: Vec<Option<Frame>> = vec![None; 3];
        let mut done = [0usize; 3];
        let rate = [0.0, 0.002, 0.01][seed as usize % 3];
        for bit in 0..40_000 {
            for i in 0..3 {
                // (the handshake needs tx_req low for a clock after tx_done)
                if want[i].is_none() && !b.nodes[i].tx_done.val() && bit < 35_000 && rng.gen_bool(0.01) {
                    // unique identifiers per node avoid two nodes sending the same id
                    let mut f = random_frame(&mut rng);
                    f.id = (f.id & !3) | i as u32;
                    sent.insert(f.clone());
                    b.request(i, &f);
                    want[i] = Some(f);
                }
                b.ovr[i] = if bit < 30_000 && rng.gen_bool(rate) {
                    [Ovr::StuckD, Ovr::StuckR, Ovr::Invert][rng.gen_range(0..3)]
                } else {
                    Ovr::None
                };
            }
            b.step();
            for i in 0..3 {
                if b.nodes[i].tx_done.val() {
                    b.withdraw(i);
                    want[i] = None;
                    done[i] += 1;
                }
                let (t, r, s) = (b.tec(i), b.rec(i), b.state(i));
                assert!(t <= 263 && r <= 135, "seed {seed} node {i}: tec {t} rec {r}");
                let exp = if t > 255 { 2 } else if t >= 128 || r >= 128 { 1 } else { 0 };
                assert_eq!(s, exp, "seed {seed} node {i}");
                // bus-off nodes: let them recover but stop asking
                if s == 2 {
                    b.withdraw(i);
                    want[i] = None;
                }
            }
        }
        for i in 0..3 {
            for f in &b.rx[i] {
                assert!(sent.contains(f), "seed {seed}: node {i} delivered a frame nobody sent: {f:?}");
            }
            assert!(want[i].is_none(), "seed {seed}: node {i} still has a pending request");
            assert_eq!(b.field(i), Field::Idle, "seed {seed}: node {i}");
        }
        if rate == 0.0 {
            // an undisturbed bus: no error at all, every frame delivered everywhere else
            for i in 0..3 {
                assert!(b.log[i].iter().all(|r| !r.has(EV_AEF) && !r.has(EV_PEF)), "seed {seed}");
                assert_eq!((b.tec(i), b.rec(i)), (0, 0));
                let others: usize = (0..3).filter(|&j| j != i).map(|j| done[j]).sum();
                assert_eq!(b.rx[i].len(), others, "seed {seed} node {i}");
            }
        }
        let min = if rate == 0.0 { 200 } else { 20 };
        assert!(done.iter().sum::<usize>() > min, "seed {seed}: {done:?}");
    }
}
