//! Clock-level lock-step (can-protocol.md §19) of `CanCore` against a golden
//! reference made of the bit timing's clock-exact model
//! (`canstar_hdl::btl::BtlCycleModel`) and the golden behavioural model of
//! canstar-sim, whose RX is the DUT's RX delayed by the synchroniser depth.
//! Three RTL cores share a wired-AND bus with random traffic and random
//! receive-path disturbances; every node is checked: TX and the sampled level on
//! every clock (with BRP 1 both edges must fall in the same cycle), the
//! sample strobe, TEC and REC at every sample point (REC exact up to 127),
//! and the delivered frames.
//!
//! The golden model is the `canstar-golden` crate (it depends on no RTL crate).
#![allow(dead_code, unused_imports, clippy::needless_range_loop, clippy::enum_variant_names)]
use canstar_golden as golden;
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

/// Timing fields (value - 1) with PH2 = max(PH1, 2).
fn fields(t: (u64, u64, u64, u64)) -> BtlConfig {
    BtlConfig::from_fields(t.0 as u32, t.1 as u32, t.2 as u32, t.2.max(1) as u32, t.3 as u32, false)
}

fn run(seed: u64, cfg: BtlConfig, delays: &[usize], rate: f64, cycles: usize) {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let n = 3;
    let mut b = CoreBus::with_config(n, delays, &cfg);
    // one reference per node, released from reset on the same clock as the DUT
    let mut btl: Vec<BtlCycleModel> = (0..n).map(|_| BtlCycleModel::new()).collect();
    let mut inp = BtlInputs::with_config(&cfg);
    inp.reset = true;
    for m in btl.iter_mut() {
        m.step(&inp);
        m.step(&inp);
    }
    inp.reset = false;
    let mut gold: Vec<golden::GoldenNode> = (0..n).map(|_| golden::GoldenNode::default()).collect();
    let mut rxq: Vec<VecDeque<bool>> = (0..n).map(|_| VecDeque::from(vec![true; SYNC_DEPTH])).collect();
    let bitc = (cfg.brp * cfg.ntq()) as usize;
    let mut want: Vec<Option<Frame>> = vec![None; n];
    let mut seen_rqst = vec![false; n];
    let mut gdel: Vec<Vec<Frame>> = vec![vec![]; n];
    let mut ovr_left = vec![0usize; n];
    let mut samples = 0;
    for cycle in 0..cycles {
        // stimulus: requests and disturbances (up to two bit times)
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
        // DUT outputs on this clock, then the clock edge
        let pre: Vec<(bool, bool, bool)> =
            b.nodes.iter().map(|d| (d.tx.val(), d.dbg_sample.val(), d.dbg_busmon.val())).collect();
        b.step();
        for i in 0..n {
            // the reference sees the RX this core saw on this clock, delayed by
            // the synchroniser
            rxq[i].push_back(b.nodes[i].rx.val());
            inp.rx = rxq[i].pop_front().unwrap();
            inp.drive = gold[i].drive();
            inp.hs_en = gold[i].hs_en();
            let pins = btl[i].step(&inp);
            let (dtx, dsmp, dbm) = pre[i];
            if dtx != pins.tx || dsmp != pins.sample || dbm != pins.busmon {
                panic!(
                    "seed {seed} node {i} cycle {cycle}: DUT tx/sample/busmon {}/{}/{} reference {}/{}/{}",
                    dtx as u8, dsmp as u8, dbm as u8, pins.tx as u8, pins.sample as u8, pins.busmon as u8
                );
            }
            if pins.sample {
                samples += 1;
                let o = gold[i].step(pins.busmon);
                if let Some(f) = o.delivered() {
                    gdel[i].push(cframe(f));
                }
                let (t0, r0) = (b.tec(i), b.rec(i));
                let rec_ok = if o.rec > 127 { r0 > 127 } else { r0 == o.rec as u64 };
                assert!(
                    t0 == o.tec as u64 && rec_ok,
                    "seed {seed} node {i} cycle {cycle}: DUT tec/rec {t0}/{r0} golden {}/{} at {:?}",
                    o.tec,
                    o.rec,
                    o.label
                );
                assert_eq!(b.rx[i], gdel[i], "seed {seed} node {i} cycle {cycle}: deliveries");
            }
            // the golden request follows the DUT's tx_rqst (§19.2)
            if b.nodes[i].dbg_tx_rqst.val() && !seen_rqst[i] {
                if let Some(f) = &want[i] {
                    gold[i].request(gframe(f));
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
        "seed {seed}: {samples} bits compared, deliveries {:?}, tec {:?} rec {:?}",
        gdel.iter().map(|v| v.len()).collect::<Vec<_>>(),
        (0..n).map(|i| b.tec(i)).collect::<Vec<_>>(),
        (0..n).map(|i| b.rec(i)).collect::<Vec<_>>()
    );
    assert!(samples > n * cycles / bitc / 2);
}

#[test]
fn core_lockstep_clean() {
    run(1, fields(T10_6_4), &[0, 0, 0], 0.0, 60_000);
}

/// Disturbances, and RX delays of 1 and 2 clocks at nodes 1 and 2 (with the
/// synchronisers the ACK of node 2 comes close to node 0's sample point, so
/// phase errors and resynchronisations occur).
#[test]
fn core_lockstep_disturbed() {
    for seed in 2..4 {
        run(seed, fields(T10_6_4), &[0, 1, 2], 0.0004, 60_000);
    }
    // T10/6/2 (the emlcount timing) and T10/8/1 at BRP 2
    run(4, fields((0, 0, 3, 1)), &[0, 1, 1], 0.0004, 60_000);
    run(5, fields((1, 4, 1, 0)), &[0, 1, 2], 0.0004, 60_000);
}

/// PH2 = 1 TQ at the shortest TQ that allows it (2 clocks: the transmit
/// point is 2 clocks after the sample point's tick, the bit-stream logic's
/// whole information processing time), and PH2 != PH1: the core equals the
/// golden reference on every clock, with disturbances and RX delays that
/// make restarts right after the sample point (IPT = 1 TQ, no postponement).
#[test]
fn core_lockstep_ph2_settings() {
    // 8 TQ of 2 clocks, SP 7 (the 87.5 % of 24 MHz / 500 kbit/s, scaled), SJW 1 and 4
    run(6, BtlConfig::new(2, 1, 5, 1).with_ph2(1), &[0, 1, 2], 0.0004, 60_000);
    run(7, BtlConfig::new(2, 2, 4, 4).with_ph2(1), &[0, 1, 3], 0.0004, 60_000);
    // PH2 > PH1 and PH2 < PH1 with PH2 >= 2
    run(8, BtlConfig::new(1, 2, 2, 2).with_ph2(5), &[0, 1, 2], 0.0004, 60_000);
    run(9, BtlConfig::new(3, 3, 6, 3).with_ph2(3), &[0, 2, 5], 0.0004, 60_000);
}
