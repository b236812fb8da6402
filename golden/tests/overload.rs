//! Overload frames, interframe space and frame start (can-protocol.md §11, §12, C13, C15).

mod util;
use canstar_golden::{FaultState, Field, Frame, GoldenBus, Role, RxOverride};
use util::*;

use RxOverride::{StuckDominant as Dom, StuckRecessive as Rec};

/// Two nodes, N1 -> N2 good frame sent, stopped at N1's Intermission 1.
fn after_good_frame(tx: usize) -> GoldenBus {
    let mut b = idle_bus(2);
    b.nodes[tx].request(Frame::std_data(0x3C3, 2, &[0xDE, 0xAD]));
    run_to_tx_ok(&mut b, tx, 300);
    b
}

/// overload_tx_1a: `D!` at Tx_Intermission 1: OVL, OLF, TEC unchanged; N2 answers with its
/// own overload flag (it sees the flag at its Intermission 2).
#[test]
fn overload_tx_1a_dominant_intermission_1() {
    let mut b = after_good_frame(0);
    let r = force_at(&mut b, 0, Role::Tx, Field::Intermission, 1, false, Dom, 1);
    assert!(r[0][0].has("OVL") && r[0][0].has("OLF"));
    let o = b.step();
    assert!(o[1].has("OVL") && o[1].label.field == Field::Intermission && o[1].label.pos == 2);
    assert!(b.run_to_idle(40));
    assert_eq!((b.nodes[0].tec(), b.nodes[1].rec()), (0, 0));
    assert_eq!(count(&b, 0, 0, "OLF"), 1);
}

/// overload_rx_1d: `D!` at Rx_Intermission 2: OVL, OLF, counters unchanged.
#[test]
fn overload_rx_1d_dominant_intermission_2() {
    let mut b = after_good_frame(1);
    let r = force_at(&mut b, 0, Role::Rx, Field::Intermission, 2, false, Dom, 1);
    assert!(r[0][0].has("OVL") && r[0][0].has("OLF"));
    assert!(b.run_to_idle(40));
    assert_eq!((b.nodes[0].rec(), b.nodes[1].tec()), (0, 0));
}

/// formerr_rx_4 / overload_rx_1a (C13): `D!` at the receiver's End_Of_Frame 7: frame
/// delivered, overload frame; REC unchanged with the 1999 rule, − 1 with the ISO rule (ISO
/// 16845-1 7.6.16). Then overload_rx_1b: `D!` at
/// Overload_Delimiter 8: OVL, OLF again.
#[test]
fn formerr_rx_4_dominant_rec_ruleeiver_delivers_rec_unchanged_overload() {
    for iso in [false, true] {
        let mut b = if iso { idle_bus(2) } else { idle_bus_1999(2) };
        b.nodes[1].request(std1(0x111));
        force_at(&mut b, 0, Role::Rx, Field::CrcDelimiter, 1, false, Dom, 1);
        run_to_tx_ok(&mut b, 1, 300);
        assert_eq!(b.nodes[0].rec(), 8);
        assert!(b.run_to_idle(30));
        let f = Frame::std_data(0x222, 3, &[1, 2, 3]);
        b.nodes[1].request(f.clone());
        let r = force_at(&mut b, 0, Role::Rx, Field::EndOfFrame, 7, false, Dom, 1);
        assert_eq!(r[0][0].delivered(), Some(&f));
        assert!(r[0][0].has("OVL") && r[0][0].has("OLF") && !r[0][0].events.iter().any(|e| matches!(e, canstar_golden::Event::Error(_))));
        let rec = if iso { 7 } else { 8 };
        assert_eq!(r[0][0].rec, rec, "iso {iso}");
        assert!(r[0][1].has("TX_OK"), "the transmitter saw a recessive EOF 7");
        let r = force_at(&mut b, 0, Role::Rx, Field::OverloadDelimiter, 8, false, Dom, 1);
        assert!(r[0][0].has("OVL") && r[0][0].has("OLF"));
        assert!(b.run_to_idle(60));
        assert_eq!(b.nodes[0].rec(), rec);
        assert_eq!(b.nodes[1].tec(), 6, "8 from the form error, -1 per good frame");
    }
}

/// formerr_tx_4: `D!` at the transmitter's End_Of_Frame 7: FORM_ERR +8, retry; the receiver
/// delivered the first copy and delivers the retry too.
#[test]
fn formerr_tx_4_dominant_eof7_transmitter_form_error_receiver_delivers_twice() {
    let mut b = idle_bus(2);
    let f = Frame::ext_data(0x1ABCDEF, 1, &[7]);
    b.nodes[0].request(f.clone());
    let r = force_at(&mut b, 0, Role::Tx, Field::EndOfFrame, 7, false, Dom, 1);
    assert!(r[0][0].has("FORM_ERR") && r[0][0].has("AEF"));
    assert_eq!(r[0][0].tec, 8);
    assert_eq!(r[0][1].delivered(), Some(&f));
    run_to_tx_ok(&mut b, 0, 300);
    assert_eq!(delivered(&b, 1, 0), vec![f.clone(), f]);
    assert_eq!(b.nodes[0].tec(), 7);
    assert_eq!(b.nodes[1].rec(), 0, "overload at its Intermission 1 costs the receiver nothing");
}

/// overload_tx_4 / formerr_tx_5: `D!` at Error_Delimiter 8: OVL, OLF, TEC unchanged.
#[test]
fn overload_tx_4_dominant_error_delimiter_8() {
    let mut b = idle_bus(2);
    b.nodes[0].request(Frame::std_data(0x155, 0, &[]));
    force_at(&mut b, 0, Role::Tx, Field::Identifier, 4, false, Rec, 1);
    assert_eq!(b.nodes[0].tec(), 8);
    let r = force_at(&mut b, 0, Role::Tx, Field::ErrorDelimiter, 8, false, Dom, 1);
    assert!(r[0][0].has("OVL") && r[0][0].has("OLF"));
    assert_eq!(r[0][0].tec, 8);
}

/// emlcount_tx_11/12: OLF followed by 7 `D` bits: nothing; by 8: +8 at the 8th.
#[test]
fn emlcount_tx_11_12_dominant_after_overload_flag_7_free_8th_costs_8() {
    let mut b = idle_bus(2);
    b.nodes[0].request(Frame::std_data(0x155, 0, &[]));
    force_at(&mut b, 0, Role::Tx, Field::Identifier, 2, false, Rec, 1);
    let r = force_at(&mut b, 0, Role::Tx, Field::ErrorDelimiter, 8, false, Dom, 14);
    assert!(r[0][0].has("OVL"));
    assert!(r[13][0].has("DAF=7"));
    assert_eq!(r[13][0].tec, 8);
    let r = force_at(&mut b, 0, Role::Tx, Field::OverloadDelimiter, 8, false, Dom, 15);
    assert!(r[0][0].has("OVL") && r[14][0].has("DAF=8"));
    assert_eq!(r[13][0].tec, 8);
    assert_eq!(r[14][0].tec, 16);
}

/// overload_rx_2: N2 has a request pending; `N1+N2 D!` at Intermission 3: both take it as
/// SOF; N2 transmits from Identifier 1 without its own SOF, N1 delivers the frame.
#[test]
fn overload_rx_2_dominant_intermission_3_is_sof_pending_node_transmits() {
    let mut b = idle_bus(2);
    b.nodes[0].request(std1(0x400));
    b.run(20);
    let f = Frame::std_data(0x3FF, 2, &[0x42, 0x24]);
    b.nodes[1].request(f.clone());
    assert!(b.run_to(0, Role::Tx, Field::Intermission, 3, false, 300));
    let start = b.bit;
    let r = force_many(&mut b, &[0, 1], Dom, 1);
    assert!(r[0][0].has("SOF") && r[0][1].has("SOF"));
    assert_eq!(b.nodes[1].label().field, Field::Identifier);
    assert_eq!(b.nodes[1].label().role, Role::Tx);
    assert_eq!(b.nodes[1].label().pos, 1);
    assert_eq!(b.nodes[0].label().role, Role::Rx);
    run_to_tx_ok(&mut b, 1, 300);
    assert_eq!(delivered(&b, 0, start), vec![f]);
    assert_eq!(count(&b, 1, start, "SOF"), 1, "no own SOF sent");
    for n in 0..2 {
        assert!(!b.since(n, start).iter().any(|o| o.events.iter().any(is_error)));
    }
}

/// emlcount_tx_31 (C15): an error-passive former transmitter with a pending retry takes a
/// `D` Intermission 3 as another node's SOF and becomes a receiver; `D!` for 6 bits: the
/// 6th is a STUFF_ERR, REC 1, PEF; TEC unchanged.
#[test]
fn emlcount_tx_31_passive_former_transmitter_becomes_receiver_rec_1() {
    let mut b = idle_bus(2);
    b.overrides[1] = Rec;
    b.nodes[0].request(std1(0x0F0));
    for _ in 0..17 {
        b.run_until(300, |o| o[0].has("ACK_ERR")).unwrap();
    }
    assert_eq!(b.nodes[0].tec(), 128);
    assert_eq!(b.nodes[0].state(), FaultState::ErrorPassive);
    assert!(b.nodes[0].pending());
    let r = force_at(&mut b, 0, Role::Tx, Field::Intermission, 3, false, Dom, 6);
    assert!(r[0][0].has("SOF"));
    assert_eq!(r[1][0].label.role, Role::Rx);
    assert_eq!(r[1][0].label.field, Field::Identifier);
    assert!(r[5][0].has("STUFF_ERR") && r[5][0].has("PEF"));
    assert_eq!((r[5][0].rec, r[5][0].tec), (1, 128));
}

/// The same situation for an error-active former transmitter (overload_tx_2): it transmits.
#[test]
fn overload_tx_2_active_former_transmitter_takes_dominant_im3_as_own_sof() {
    let mut b = idle_bus(2);
    b.nodes[0].request(std1(0x0F0));
    run_to_tx_ok(&mut b, 0, 300);
    let f = Frame::std_data(0x0F1, 0, &[]);
    b.nodes[0].request(f.clone());
    let start = b.bit;
    force_at(&mut b, 0, Role::Tx, Field::Intermission, 3, false, Dom, 1);
    assert_eq!(b.nodes[0].label().role, Role::Tx);
    assert_eq!(b.nodes[0].label().field, Field::Identifier);
    run_to_tx_ok(&mut b, 0, 300);
    assert_eq!(delivered(&b, 1, start), vec![f]);
}

/// §12: a `D` during Suspend_Transmission is another node's SOF: the suspending node becomes
/// a receiver and delivers that frame, then retries.
#[test]
fn suspend_interrupted_by_foreign_sof_node_receives_then_retries() {
    let mut b = idle_bus(2);
    b.overrides[1] = Rec;
    b.nodes[0].request(std1(0x700));
    for _ in 0..16 {
        b.run_until(300, |o| o[0].has("ACK_ERR")).unwrap();
    }
    assert_eq!(b.nodes[0].state(), FaultState::ErrorPassive);
    assert!(b.run_to(0, Role::Tx, Field::SuspendTransmission, 3, false, 100));
    b.overrides[1] = RxOverride::None;
    let f = Frame::std_data(0x001, 1, &[9]);
    // N2 is idle (it read recessive all the time): it starts a frame now.
    b.nodes[1].request(f.clone());
    let start = b.bit;
    b.run_until(5, |o| o[0].has("SOF")).unwrap();
    assert_eq!(b.nodes[0].label().role, Role::Rx);
    run_to_tx_ok(&mut b, 1, 300);
    assert_eq!(delivered(&b, 0, start), vec![f]);
    run_to_tx_ok(&mut b, 0, 300);
    assert_eq!(b.nodes[0].tec(), 127);
}
