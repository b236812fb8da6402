//! Arbitration between golden nodes (can-protocol.md §7, conformance extd_id_arb, baudrate).

#![allow(clippy::needless_range_loop)]

mod util;
use canstar_golden::{Event, Field, Frame, FrameVariant, GoldenBus};
use util::*;

/// Both frames requested in the same Bus_Idle bit; runs until both are sent. Returns the
/// (field, position) at which node 0 lost arbitration, if it did.
fn contest(f0: Frame, v0: FrameVariant, f1: Frame, v1: FrameVariant) -> (GoldenBus, Option<(Field, u32)>) {
    let mut b = idle_bus(2);
    let start = b.bit;
    b.nodes[0].request_variant(f0.clone(), v0);
    b.nodes[1].request_variant(f1.clone(), v1);
    let mut done = [false; 2];
    while !(done[0] && done[1]) {
        let o = b.step();
        for n in 0..2 {
            done[n] |= o[n].has("TX_OK");
        }
        assert!(b.bit - start < 600, "contest did not finish");
    }
    assert!(b.run_to_idle(20));
    let lost = b.since(0, start).iter().find_map(|o| {
        o.events.iter().find_map(|e| if let Event::ArbLost(p) = e { Some((o.label.field, *p)) } else { None })
    });
    // Both delivered at the other node, nothing else, no errors, counters 0.
    assert_eq!(delivered(&b, 1, start), vec![f0]);
    assert_eq!(delivered(&b, 0, start), vec![f1]);
    for n in 0..2 {
        assert!(!b.since(n, start).iter().any(|o| o.events.iter().any(is_error)));
        assert_eq!((b.nodes[n].tec(), b.nodes[n].rec()), (0, 0));
    }
    (b, lost)
}

const N: FrameVariant = FrameVariant { srr_dominant: false, r1_recessive: false, r0_recessive: false };
const SRR_D: FrameVariant = FrameVariant { srr_dominant: true, r1_recessive: false, r0_recessive: false };

#[test]
fn lower_identifier_wins_loser_loses_at_first_differing_id_bit() {
    // 0x123 = 001 0010 0011, 0x127 = 001 0010 0111: first difference at ID bit 2 -> position 9.
    let (_, lost) = contest(Frame::std_data(0x127, 1, &[1]), N, Frame::std_data(0x123, 1, &[2]), N);
    assert_eq!(lost, Some((Field::Identifier, 9)));
}

#[test]
fn extd_id_arb_1_std_remote_loses_to_std_data_at_rtr() {
    let (_, lost) = contest(Frame::std_remote(0x2A5, 0), N, Frame::std_data(0x2A5, 0, &[]), N);
    assert_eq!(lost, Some((Field::RtrBit, 1)));
}

#[test]
fn extd_id_arb_2_std_remote_loses_to_dominant_srr_at_rtr_and_ext_frame_is_delivered() {
    let (_, lost) = contest(Frame::std_remote(0x2A5, 0), N, Frame::ext_data(0x2A5 << 18 | 0x1234, 0, &[]), SRR_D);
    assert_eq!(lost, Some((Field::RtrBit, 1)));
}

#[test]
fn extd_id_arb_3_ext_loses_to_std_data_at_srr() {
    let (_, lost) = contest(Frame::ext_data(0x2A5 << 18, 0, &[]), N, Frame::std_data(0x2A5, 0, &[]), N);
    assert_eq!(lost, Some((Field::SrrBit, 1)));
}

#[test]
fn extd_id_arb_4_ext_loses_to_std_remote_at_ide() {
    let (_, lost) = contest(Frame::ext_remote(0x2A5 << 18 | 7, 0), N, Frame::std_remote(0x2A5, 0), N);
    assert_eq!(lost, Some((Field::IdeBit, 1)));
}

#[test]
fn extd_id_arb_5_ext_loses_at_first_differing_extension_bit() {
    // extensions 0x1000 (bit 12 set) vs 0x0FFF: differ first at extension bit 12 -> position 6.
    let (_, lost) = contest(Frame::ext_data(0x111 << 18 | 0x1000, 0, &[]), N, Frame::ext_data(0x111 << 18 | 0x0FFF, 0, &[]), N);
    assert_eq!(lost, Some((Field::ExIdentifier, 6)));
}

#[test]
fn extd_id_arb_6_ext_remote_loses_to_ext_data_at_rtr() {
    let (_, lost) = contest(Frame::ext_remote(0x0ABC_DEF0, 2), N, Frame::ext_data(0x0ABC_DEF0, 2, &[3, 4]), N);
    assert_eq!(lost, Some((Field::RtrBit, 1)));
}

#[test]
fn extd_id_arb_7_ext_loses_to_dominant_srr_at_srr() {
    let (_, lost) = contest(Frame::ext_data(0x333 << 18 | 5, 0, &[]), N, Frame::ext_data(0x333 << 18 | 5, 0, &[]), SRR_D);
    assert_eq!(lost, Some((Field::SrrBit, 1)));
}

/// Three nodes request in the same bit: frames follow in identifier order, each loser shows
/// ARB_LOST, keeps its request and retries; every frame is delivered at both other nodes.
#[test]
fn three_nodes_frames_in_priority_order_all_delivered() {
    let frames = [Frame::std_data(0x300, 2, &[1, 2]), Frame::ext_data(0x100 << 18 | 9, 1, &[3]), Frame::std_remote(0x100, 4)];
    let mut b = idle_bus(3);
    let start = b.bit;
    for n in 0..3 {
        b.nodes[n].request(frames[n].clone());
    }
    let mut order = Vec::new();
    while order.len() < 3 {
        let o = b.step();
        for n in 0..3 {
            if o[n].has("TX_OK") {
                order.push(n);
            }
        }
        assert!(b.bit - start < 1000);
    }
    // std remote 0x100 beats ext with base 0x100 (at IDE); 0x300 last.
    assert_eq!(order, vec![2, 1, 0]);
    assert_eq!(count(&b, 0, start, "ARB_LOST"), 2);
    assert_eq!(count(&b, 1, start, "ARB_LOST"), 1);
    assert_eq!(count(&b, 2, start, "ARB_LOST"), 0);
    for n in 0..3 {
        let got = delivered(&b, n, start);
        let want: Vec<Frame> = order.iter().filter(|&&k| k != n).map(|&k| frames[k].clone()).collect();
        assert_eq!(got, want, "node {n}");
        assert_eq!((b.nodes[n].tec(), b.nodes[n].rec()), (0, 0));
        assert!(!b.since(n, start).iter().any(|o| o.events.iter().any(is_error)));
    }
}

/// std data X beats ext X (lost at SRR) and std data X beats std remote X.
#[test]
fn three_nodes_std_data_beats_remote_and_ext_same_base() {
    let frames = [Frame::ext_data(0x0AB << 18, 0, &[]), Frame::std_remote(0x0AB, 0), Frame::std_data(0x0AB, 0, &[])];
    let mut b = idle_bus(3);
    let start = b.bit;
    for n in 0..3 {
        b.nodes[n].request(frames[n].clone());
    }
    let o = b.run_until(300, |o| o.iter().any(|x| x.has("TX_OK"))).unwrap();
    assert!(o[2].has("TX_OK"));
    let lost_at = |n: usize| {
        b.since(n, start).iter().find(|o| o.has("ARB_LOST")).map(|o| o.label.field)
    };
    assert_eq!(lost_at(0), Some(Field::SrrBit));
    assert_eq!(lost_at(1), Some(Field::RtrBit));
}
