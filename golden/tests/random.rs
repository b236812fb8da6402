//! Randomised robustness of the golden model: random traffic and random receive-path
//! disturbances on 3 nodes. Checks the can-protocol.md §13 invariants at every bit, and that the bus
//! returns to error-free operation once the disturbances stop.

#![allow(clippy::needless_range_loop)]

mod util;
use canstar_golden::{FaultState, Frame, RxOverride};
use std::collections::HashMap;
use util::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn random_frame(rng: &mut ChaCha8Rng) -> Frame {
    let ide = rng.gen_bool(0.4);
    let rtr = rng.gen_bool(0.2);
    let dlc = rng.gen_range(0..16u8);
    let id = if ide { rng.gen_range(0..1u32 << 29) } else { rng.gen_range(0..1u32 << 11) };
    let data: Vec<u8> = if rtr { vec![] } else { (0..dlc.min(8)).map(|_| rng.gen()).collect() };
    Frame { ide, id, rtr, dlc, data }
}

#[test]
fn random_disturbances_keep_invariants_and_bus_recovers() {
    let mut seen: HashMap<String, usize> = HashMap::new();
    for seed in 0..12u64 {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut b = idle_bus(3);
        let mut hold = [0u32; 3];
        for _ in 0..25_000 {
            for n in 0..3 {
                if !b.nodes[n].pending() && rng.gen_bool(0.01) {
                    b.nodes[n].request(random_frame(&mut rng));
                }
                if hold[n] > 0 {
                    hold[n] -= 1;
                    if hold[n] == 0 {
                        b.overrides[n] = RxOverride::None;
                    }
                } else if rng.gen_bool(0.004) {
                    b.overrides[n] = [RxOverride::Invert, RxOverride::StuckDominant, RxOverride::StuckRecessive][rng.gen_range(0..3)];
                    hold[n] = rng.gen_range(1..20);
                }
            }
            let outs = b.step();
            for (n, o) in outs.iter().enumerate() {
                for e in &o.events {
                    let t = e.token();
                    let t = t.split('=').next().unwrap().to_string();
                    *seen.entry(t).or_default() += 1;
                }
                assert!(o.rec <= 135, "seed {seed} node {n}");
                assert!(o.tec <= 263, "seed {seed} node {n}");
                let expect = if o.tec > 255 {
                    FaultState::BusOff
                } else if o.tec >= 128 || o.rec >= 128 {
                    FaultState::ErrorPassive
                } else {
                    FaultState::ErrorActive
                };
                assert_eq!(o.state, expect, "seed {seed} node {n}");
                if o.state == FaultState::BusOff {
                    assert!(o.next_drive);
                }
            }
        }
        // Quiet bus: every node leaves bus-off and integrates again; then each node's frame
        // reaches both others.
        b.overrides = vec![RxOverride::None; 3];
        for n in 0..3 {
            b.nodes[n].withdraw();
        }
        b.run(128 * 11 + 2000);
        for n in 0..3 {
            assert_ne!(b.nodes[n].state(), FaultState::BusOff, "seed {seed}");
        }
        for tx in 0..3 {
            let f = random_frame(&mut rng);
            let s = b.bit;
            b.nodes[tx].request(f.clone());
            run_to_tx_ok(&mut b, tx, 400);
            assert!(b.run_to_idle(40));
            for rx in (0..3).filter(|&r| r != tx) {
                assert_eq!(delivered(&b, rx, s), vec![f.clone()], "seed {seed}");
            }
            for n in 0..3 {
                assert!(!b.since(n, s).iter().any(|o| o.events.iter().any(is_error)), "seed {seed}");
            }
        }
    }
    // The disturbances reached every kind of situation.
    for t in [
        "SOF", "ARB_LOST", "BIT_ERR", "STUFF_ERR", "CRC_ERR", "FORM_ERR", "ACK_ERR", "AEF", "PEF", "OLF", "OVL", "DAF",
        "TX_OK", "RX_OK", "EXC1", "EXC2", "TO_EP", "TO_EA", "TO_BO", "RUN", "RECOVERED", "WARN", "WARN_CLR",
    ] {
        assert!(seen.get(t).copied().unwrap_or(0) > 0, "token {t} never seen: {seen:?}");
    }
}
