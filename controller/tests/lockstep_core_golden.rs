//! Clock-level lock-step (can-protocol.md §19) of `CanCore` against a golden
//! reference made of the bit timing's clock-exact model
//! (`canstar_hdl::btl::BtlCycleModel`) and the golden behavioural model of
//! canstar-sim, whose RX is the DUT's RX delayed by the synchroniser depth.
//! Three RTL cores share a wired-AND bus with random traffic and random
//! receive-path disturbances; node 0 is checked: TX and the sampled level on
//! every clock (with BRP 1 both edges must fall in the same cycle), the
//! sample strobe, TEC and REC at every sample point (REC exact up to 127),
//! and the delivered frames.
//!
//! The golden model's source is included by path (canstar-sim depends on
//! this crate).
#![allow(dead_code, unused_imports, clippy::needless_range_loop, clippy::enum_variant_names)]
#[path = "../../sim/src/golden/mod.rs"]
mod golden;
mod common;
use canstar_controller::core::{CanCore, SYNC_DEPTH};
use canstar_controller::frame::Frame;
use canstar_controller::fsm::*;
use canstar_hdl::btl::{BtlConfig, BtlCycleModel, BtlInputs};
use common::core_bus::*;
use common::stim::random_frame;
use common::Ovr;
use rand::{Rng, SeedableRng};
use std::collections::VecDeque;

fn gframe(f: &Frame) -> golden::Frame {
    golden::Frame { ide: f.ide, id: f.id, rtr: f.rtr, dlc: f.dlc, data: f.data.clone() }
}
fn cframe(f: &golden::Frame) -> Frame {
    Frame { ide: f.ide, id: f.id, rtr: f.rtr, dlc: f.dlc, data: f.data.clone() }
}

fn run(seed: u64, t: (u64, u64, u64, u64), delays: &[usize], rate: f64, cycles: usize) {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let n = 3;
    let mut b = CoreBus::with_timing(n, delays, t, false);
    // the reference of node 0: released from reset on the same clock as the DUT
    let cfg = BtlConfig::from_fields(t.0 as u32, t.1 as u32, t.2 as u32, t.3 as u32, false);
    let mut btl = BtlCycleModel::new();
    let mut inp = BtlInputs::with_config(&cfg);
    inp.reset = true;
    btl.step(&inp);
    btl.step(&inp);
    inp.reset = false;
    let mut gold = golden::GoldenNode::default();
    let mut rxq: VecDeque<bool> = VecDeque::from(vec![true; SYNC_DEPTH]);
    let bitc = (t.0 as usize + 1) * cfg.ntq() as usize;
    let mut want: Vec<Option<Frame>> = vec![None; n];
    let mut seen_rqst = vec![false; n];
    let mut gdel: Vec<Frame> = vec![];
    let mut ovr_left = vec![0usize; n];
    let mut samples = 0;
    for cycle in 0..cycles {
        // stimulus: requests and disturbances (whole bit times)
        for i in 0..n {
            if want[i].is_none() && !b.nodes[i].tx_done.val() && cycle > 20 * bitc && cycle + 400 * bitc < cycles && rng.gen_bool(0.002) {
                let mut f = random_frame(&mut rng);
                f.id = (f.id & !3) | i as u32;
                b.request(i, &f);
                want[i] = Some(f);
            }
            if ovr_left[i] > 0 {
                ovr_left[i] -= 1;
                if ovr_left[i] == 0 {
                    b.ovr[i] = Ovr::None;
                }
            } else if cycle > 20 * bitc && cycle + 400 * bitc < cycles && rng.gen_bool(rate) {
                b.ovr[i] = [Ovr::StuckD, Ovr::StuckR, Ovr::Invert][rng.gen_range(0..3)];
                ovr_left[i] = rng.gen_range(1..2 * bitc);
            }
        }
        // the level node 0 reads this clock (the harness applies the same)
        let bus = b.bus();
        let rx0 = match b.ovr[0] {
            Ovr::None => bus,
            Ovr::Invert => !bus,
            Ovr::StuckR => true,
            Ovr::StuckD => false,
        };
        // reference outputs on this clock
        rxq.push_back(rx0);
        inp.rx = rxq.pop_front().unwrap();
        inp.drive = gold.drive();
        inp.hs_en = gold.hs_en();
        let pins = btl.step(&inp);
        let d = &b.nodes[0];
        let (dtx, dsmp, dbm) = (d.tx.val(), d.dbg_sample.val(), d.dbg_busmon.val());
        if dtx != pins.tx || dsmp != pins.sample || dbm != pins.busmon {
            panic!(
                "seed {seed} cycle {cycle}: DUT tx/sample/busmon {}/{}/{} reference {}/{}/{}",
                dtx as u8, dsmp as u8, dbm as u8, pins.tx as u8, pins.sample as u8, pins.busmon as u8
            );
        }
        b.step();
        if pins.sample {
            samples += 1;
            let o = gold.step(pins.busmon);
            if let Some(f) = o.delivered() {
                gdel.push(cframe(f));
            }
            let (t0, r0) = (b.tec(0), b.rec(0));
            let rec_ok = if o.rec > 127 { r0 > 127 } else { r0 == o.rec as u64 };
            assert!(
                t0 == o.tec as u64 && rec_ok,
                "seed {seed} cycle {cycle}: DUT tec/rec {t0}/{r0} golden {}/{} at {:?}",
                o.tec,
                o.rec,
                o.label
            );
            assert_eq!(b.rx[0].len(), gdel.len(), "seed {seed} cycle {cycle}: deliveries");
            if let (Some(x), Some(y)) = (b.rx[0].last(), gdel.last()) {
                assert_eq!(x, y, "seed {seed}");
            }
        }
        for i in 0..n {
            if i == 0 && b.nodes[0].dbg_tx_rqst.val() && !seen_rqst[0] {
                if let Some(f) = &want[0] {
                    gold.request(gframe(f));
                }
            }
            seen_rqst[i] |= b.nodes[i].dbg_tx_rqst.val();
            if b.nodes[i].tx_done.val() {
                b.withdraw(i);
                want[i] = None;
                seen_rqst[i] = false;
            }
        }
    }
    eprintln!(
        "seed {seed}: {samples} bits compared, node 0 delivered {}, tec {} rec {}",
        gdel.len(),
        b.tec(0),
        b.rec(0)
    );
    assert!(samples > cycles / bitc / 2);
}

#[test]
fn core_lockstep_clean() {
    run(1, T10_6_4, &[0, 0, 0], 0.0, 60_000);
}

/// Disturbances, and RX delays of 1 and 2 clocks at nodes 1 and 2 (with the
/// synchronisers the ACK of node 2 comes close to node 0's sample point, so
/// phase errors and resynchronisations occur).
#[test]
fn core_lockstep_disturbed() {
    for seed in 2..4 {
        run(seed, T10_6_4, &[0, 1, 2], 0.0004, 60_000);
    }
    // T10/6/2 (the emlcount timing) and T10/8/1 at BRP 2
    run(4, (0, 0, 3, 1), &[0, 1, 1], 0.0004, 60_000);
    run(5, (1, 4, 1, 0), &[0, 1, 2], 0.0004, 60_000);
}
