//! Fault confinement (can-protocol.md §13, §14, C11, C12, C14, C15, C18) on the golden bus.

mod util;
use canstar_golden::{Config, FaultState, Field, Frame, GoldenBus, GoldenNode, Role, RxOverride};
use util::*;

use RxOverride::{StuckDominant as Dom, StuckRecessive as Rec};

/// crc_tx_1..4: N2 never acknowledges (stuck `R`). ACK error +8; on the retry, ACK error +8 and
/// 14 bit errors in the flags: TEC 128, the last flag still active; suspend (8 bits) before the
/// next retry, which ends in ACK_ERR + PEF with EXC1 (TEC stays 128); with the ACK back the
/// frame succeeds: TEC 127, error-active.
#[test]
fn crc_tx_1_to_4_ack_errors_tec_128_exc1_then_127() {
    let mut b = idle_bus(2);
    b.overrides[1] = Rec;
    b.nodes[0].request(Frame::std_data(0x0F0, 1, &[0x81]));
    // crc_tx_1
    let o = b.run_until(200, |o| o[0].has("ACK_ERR")).unwrap();
    assert!(o[0].has("AEF"));
    assert_eq!(o[0].tec, 8);
    // crc_tx_2
    let o = b.run_until(200, |o| o[0].has("ACK_ERR")).unwrap();
    assert_eq!(o[0].tec, 16);
    let r = force_at(&mut b, 0, Role::Tx, Field::ActiveErrorFlag, 2, false, Rec, 14);
    assert!(r.iter().all(|o| o[0].has("BIT_ERR")));
    assert_eq!(r[13][0].tec, 128);
    assert!(r[13][0].has("TO_EP") && r[13][0].has("AEF"), "rule 9: the flag is still active");
    assert_eq!(r[12][0].state, FaultState::ErrorActive);
    // error delimiter, intermission, then 8 suspend bits before the retry's SOF
    let start = b.bit;
    b.run_until(40, |o| o[0].has("SOF")).unwrap();
    let susp: Vec<u32> = b.since(0, start).iter().filter(|o| o.label.field == Field::SuspendTransmission).map(|o| o.label.pos).collect();
    assert_eq!(susp, (1..=8).collect::<Vec<_>>());
    // crc_tx_3
    let o = b.run_until(200, |o| o[0].has("ACK_ERR")).unwrap();
    assert!(o[0].has("PEF") && !o[0].has("AEF"));
    assert_eq!(o[0].tec, 128);
    let o = b.run_until(10, |o| o[0].has("EXC1")).unwrap();
    assert_eq!(o[0].tec, 128);
    assert_eq!(o[0].label.field, Field::PassiveErrorFlag);
    assert_eq!(o[0].label.pos, 6);
    // crc_tx_4
    b.overrides[1] = RxOverride::None;
    let bit = run_to_tx_ok(&mut b, 0, 300);
    assert_eq!(b.nodes[0].tec(), 127);
    assert!(b.history[0][bit as usize].has("TO_EA"));
}

/// crc_tx_7: passive ACK error and a `D` at PEF bit 2: exception 1 not met, +8 at that bit.
#[test]
fn crc_tx_7_exc1_not_met_plus_8_at_first_dominant_in_flag() {
    let mut b = idle_bus(2);
    b.overrides[1] = Rec;
    b.nodes[0].request(Frame::std_data(0x0F0, 1, &[0x81]));
    // 16 active ACK errors: TEC 128
    for k in 1..=16u16 {
        let o = b.run_until(300, |o| o[0].has("ACK_ERR")).unwrap();
        assert_eq!(o[0].tec, 8 * k);
    }
    b.run_until(300, |o| o[0].has("ACK_ERR")).unwrap();
    assert_eq!(b.nodes[0].tec(), 128);
    let r = force_at(&mut b, 0, Role::Tx, Field::PassiveErrorFlag, 2, false, Dom, 1);
    assert_eq!(r[0][0].tec, 136);
    let o = b.run_until(12, |o| o[0].label.field == Field::ErrorDelimiter).unwrap();
    assert_eq!(o[0].tec, 136);
    assert_eq!(count(&b, 0, b.bit - 14, "EXC1"), 0);
}

fn bus_off_one_node() -> GoldenBus {
    let mut b = GoldenBus::new(1);
    assert!(b.run_to_idle(20));
    b.nodes[0].request(std1(0x100));
    b.overrides[0] = Rec;
    let o = b.run_until(5000, |o| o[0].has("TO_BO")).expect("bus-off");
    assert_eq!(o[0].tec, 256);
    assert_eq!(o[0].state, FaultState::BusOff);
    assert!(b.nodes[0].drive(), "drives nothing in bus-off");
    b.overrides[0] = RxOverride::None;
    b.nodes[0].withdraw();
    b
}

/// idle_5/7: permanent `R!`: bit errors, +8 each, passive at 128 (the flag of the crossing
/// error is active), suspend between retries, bus-off when TEC exceeds 255; then 128 runs of
/// 11 recessive bits recover the node (RUN=1..128, RECOVERED, TEC = REC = 0, EA).
#[test]
fn idle_7_bus_off_at_tec_256_and_recovery_after_128_runs_of_11() {
    let mut b = bus_off_one_node();
    let tec_at_bo = b.nodes[0].tec();
    let start = b.bit;
    for _ in 0..(128 * 11 - 1) {
        let o = b.step();
        assert_eq!(o[0].state, FaultState::BusOff);
        assert_eq!(o[0].tec, tec_at_bo, "TEC frozen");
        assert_eq!(o[0].label.field, Field::BusOff);
    }
    let o = b.step();
    assert!(o[0].has("RUN=128") && o[0].has("RECOVERED") && o[0].has("TO_EA"));
    assert_eq!((o[0].tec, o[0].rec, o[0].state), (0, 0, FaultState::ErrorActive));
    assert_eq!(count(&b, 0, start, "RECOVERED"), 1);
    let runs: Vec<String> = tokens(&b, 0, start).into_iter().filter(|t| t.starts_with("RUN=")).collect();
    assert_eq!(runs.len(), 128);
    assert_eq!(runs[0], "RUN=1");
    assert_eq!(b.nodes[0].label().field, Field::BusIdle);
}

/// idle_9..12: a `D` restarts only the current run; completed runs stay counted.
#[test]
fn idle_9_to_12_dominant_bits_restart_only_the_current_run() {
    let mut b = bus_off_one_node();
    // idle_9: D at run bit 9
    force_at(&mut b, 0, Role::None, Field::BusOff, 9, false, Dom, 1);
    assert_eq!(b.nodes[0].recovery_runs(), 0);
    // idle_10: D at run bit 11: not complete
    force_at(&mut b, 0, Role::None, Field::BusOff, 11, false, Dom, 1);
    assert_eq!(b.nodes[0].recovery_runs(), 0);
    // idle_11: one run completes, then D at bit 1 of the next
    b.run(11);
    assert_eq!(b.nodes[0].recovery_runs(), 1);
    let r = b.force(0, Dom, 1);
    assert_eq!(r[0][0].label.pos, 1);
    assert_eq!(b.nodes[0].recovery_runs(), 1);
    // idle_12: 126 more runs, then D at bit 10
    b.run(126 * 11);
    assert_eq!(b.nodes[0].recovery_runs(), 127);
    force_at(&mut b, 0, Role::None, Field::BusOff, 10, false, Dom, 1);
    assert_eq!(b.nodes[0].recovery_runs(), 127);
    b.run(10);
    assert_eq!(b.nodes[0].state(), FaultState::BusOff);
    let o = b.step();
    assert!(o[0].has("RECOVERED"));
    assert_eq!((b.nodes[0].tec(), b.nodes[0].rec()), (0, 0));
    // idle_13: D at Bus_Idle 12: SOF, receiver, stuff error, REC 1, AEF
    force_at(&mut b, 0, Role::None, Field::BusIdle, 12, false, Dom, 1);
    let o = b.run_until(10, |o| o[0].has("STUFF_ERR")).unwrap();
    assert!(o[0].has("AEF"));
    assert_eq!(o[0].rec, 1);
}

/// C18 option: with host-started recovery nothing is counted until `start_recovery`.
#[test]
fn host_started_recovery_waits_for_the_host() {
    let mut b = GoldenBus::with_nodes(vec![GoldenNode::new(Config { host_recovery: true, ..Default::default() })]);
    assert!(b.run_to_idle(20));
    b.nodes[0].request(std1(0x100));
    b.overrides[0] = Rec;
    b.run_until(5000, |o| o[0].has("TO_BO")).unwrap();
    b.overrides[0] = RxOverride::None;
    b.run(3000);
    assert_eq!(b.nodes[0].state(), FaultState::BusOff);
    assert_eq!(b.nodes[0].recovery_runs(), 0);
    b.nodes[0].start_recovery();
    b.run(128 * 11 - 1);
    assert_eq!(b.nodes[0].state(), FaultState::BusOff);
    let o = b.step();
    assert!(o[0].has("RECOVERED"));
    // The request stayed pending across bus-off (withdrawn here? no: still pending) -> SOF next.
    assert_eq!(b.nodes[0].label().field, Field::StartOfFrame);
}

/// Receiver REC to 121 with dominant bits after its flag, then (emlcount_rx_15, C14) a bit
/// error in an overload flag makes it passive (+8 -> 128) with the flag still active; a bit
/// error in that flag restarts it as a passive flag with REC unchanged (C12); 16 further `D`
/// bits after the passive flag add nothing; a good frame sets REC to 127 (C11, TO_EA); the
/// next one to 126.
#[test]
fn emlcount_rx_15_16_c14_flag_type_c12_saturation_c11_restore_127() {
    let mut b = idle_bus(2);
    b.nodes[1].request(std1(0x0AA));
    force_at(&mut b, 0, Role::Rx, Field::CrcDelimiter, 1, false, Dom, 1);
    b.nodes[1].withdraw();
    let r = force_at(&mut b, 0, Role::Rx, Field::ActiveErrorFlag, 7, false, Dom, 112);
    assert_eq!(r[111][0].rec, 121);
    assert!(r.iter().any(|o| o[0].has("WARN")));
    assert!(b.run_to_idle(40));
    b.nodes[1].request(std1(0x0AB));
    run_to_tx_ok(&mut b, 1, 300);
    assert_eq!(b.nodes[0].rec(), 120);
    let r = force_at(&mut b, 0, Role::Rx, Field::Intermission, 1, false, Dom, 1);
    assert!(r[0][0].has("OVL") && r[0][0].has("OLF"));
    let r = force_at(&mut b, 0, Role::Rx, Field::OverloadFlag, 1, false, Rec, 1);
    assert!(r[0][0].has("BIT_ERR") && r[0][0].has("TO_EP") && r[0][0].has("AEF"));
    assert_eq!(r[0][0].rec, 128);
    let r = force_at(&mut b, 0, Role::Rx, Field::ActiveErrorFlag, 1, false, Rec, 1);
    assert!(r[0][0].has("BIT_ERR") && r[0][0].has("PEF"));
    assert_eq!(r[0][0].rec, 128);
    // the PEF completes after 6 equal bits; then 16 D bits: no change while REC >= 128
    // (the flag may still be waiting for 6 equal bits at position 7: force long enough)
    let r = force_at(&mut b, 0, Role::Rx, Field::PassiveErrorFlag, 7, false, Dom, 30);
    assert!(r.iter().any(|o| o[0].has("DAF=1")) && r.iter().any(|o| o[0].has("DAF=16")));
    assert!(r.iter().all(|o| o[0].rec == 128));
    assert!(b.run_to_idle(40));
    b.nodes[1].request(std1(0x0AC));
    let bit = run_to_tx_ok(&mut b, 1, 300);
    let o = &b.history[0][bit as usize];
    assert_eq!(o.rec, 127);
    assert!(o.has("RX_OK"));
    // C13, ISO rule: the restore to 127 (and TO_EA) came at the ACK slot, 8 bits before
    // End_Of_Frame bit 7
    let ack = &b.history[0][bit as usize - 8];
    assert_eq!(ack.label.field, Field::AckSlot);
    assert!(ack.has("TO_EA") && ack.rec == 127, "{ack:?}");
    assert!(b.run_to_idle(20));
    b.nodes[1].request(std1(0x0AD));
    run_to_tx_ok(&mut b, 1, 300);
    assert_eq!(b.nodes[0].rec(), 126);
}

/// C12: REC stops at the first value above 127 (at most 135).
#[test]
fn rec_saturates_above_127_at_most_135() {
    let mut b = idle_bus(2);
    b.nodes[1].request(std1(0x0AA));
    force_at(&mut b, 0, Role::Rx, Field::CrcDelimiter, 1, false, Dom, 1);
    b.nodes[1].withdraw();
    let r = force_at(&mut b, 0, Role::Rx, Field::ActiveErrorFlag, 7, false, Dom, 200);
    let recs: Vec<u8> = r.iter().map(|o| o[0].rec).collect();
    assert_eq!(*recs.iter().max().unwrap(), 129);
    assert_eq!(recs[199], 129);
    assert_eq!(r.iter().filter(|o| o[0].has("TO_EP")).count(), 1);
}

/// idle_1/idle_2: integration needs 11 consecutive recessive bits; a `D` restarts the count.
#[test]
fn idle_1_2_integration_needs_11_recessive_bits() {
    let mut b = GoldenBus::new(1);
    force_at(&mut b, 0, Role::None, Field::WaitForBusIdle, 9, false, Dom, 1);
    assert!(b.nodes[0].integrating());
    force_at(&mut b, 0, Role::None, Field::WaitForBusIdle, 11, false, Dom, 1);
    assert!(b.nodes[0].integrating());
    b.run(10);
    assert!(b.nodes[0].integrating());
    assert_eq!(b.nodes[0].label().pos, 11);
    b.step();
    assert!(!b.nodes[0].integrating());
    assert_eq!(b.nodes[0].label().field, Field::BusIdle);
    assert_eq!(b.nodes[0].state(), FaultState::ErrorActive);
}

/// A node reset in the middle of a frame neither acknowledges, flags nor counts, and does
/// not deliver that frame; it integrates on the following idle bus.
#[test]
fn node_integrating_during_a_frame_stays_silent() {
    let mut b = idle_bus(3);
    b.nodes[0].request(Frame::std_data(0x7F, 8, &[0, 0, 0, 0, 0xFF, 0xFF, 0xFF, 0xFF]));
    b.run(5);
    b.nodes[2].reset();
    let start = b.bit;
    run_to_tx_ok(&mut b, 0, 300);
    assert!(b.since(2, start).iter().all(|o| o.drove));
    assert!(delivered(&b, 2, start).is_empty());
    assert_eq!(delivered(&b, 1, start).len(), 1);
    assert_eq!((b.nodes[2].tec(), b.nodes[2].rec()), (0, 0));
    assert!(b.run_to_idle(20));
    assert!(!b.nodes[2].integrating());
}

/// Error warning (C16): WARN when a counter reaches 96, WARN_CLR when both are below again.
#[test]
fn warning_set_at_96_and_cleared_below() {
    let mut b = idle_bus(2);
    b.overrides[1] = Rec;
    b.nodes[0].request(std1(0x55));
    for _ in 0..12 {
        b.run_until(300, |o| o[0].has("ACK_ERR")).unwrap();
    }
    assert_eq!(b.nodes[0].tec(), 96);
    assert!(b.nodes[0].warning());
    assert_eq!(count(&b, 0, 0, "WARN"), 1);
    b.overrides[1] = RxOverride::None;
    let bit = run_to_tx_ok(&mut b, 0, 300);
    assert!(b.history[0][bit as usize].has("WARN_CLR"));
    assert!(!b.nodes[0].warning());
}

/// emlcount_tx_23-like: a passive transmitter, `D!` at End_Of_Frame 1 and 6 more bits: FORM_ERR
/// +8, PEF completed by the 6 `D` bits, no other effect.
#[test]
fn emlcount_tx_23_passive_eof1_and_6_dominant_only_plus_8() {
    let mut b = idle_bus(2);
    b.overrides[1] = Rec;
    b.nodes[0].request(std1(0x0F0));
    for _ in 0..16 {
        b.run_until(300, |o| o[0].has("ACK_ERR")).unwrap();
    }
    b.overrides[1] = RxOverride::None;
    assert_eq!(b.nodes[0].tec(), 128);
    let r = force_at(&mut b, 0, Role::Tx, Field::EndOfFrame, 1, false, Dom, 7);
    assert!(r[0][0].has("FORM_ERR") && r[0][0].has("PEF"));
    assert!(r.iter().all(|o| o[0].tec == 136));
    assert!(!r.iter().any(|o| o[0].events.iter().any(|e| e.token().starts_with("DAF"))));
    let o = b.step();
    assert_eq!(o[0].label.field, Field::PassiveErrorFlag);
    assert_eq!(o[0].label.pos, 7, "first R after the flag: delimiter position 1, counted under the flag");
    assert_eq!(b.nodes[0].label().field, Field::ErrorDelimiter);
    assert_eq!(b.nodes[0].label().pos, 2);
}

/// emlcount_tx_35-like: N1 error-passive through TEC (REC low) and a receiver with a pending
/// retry. `D!` at Error_Delimiter 3 held for the 6 PEF bits and one more: FORM_ERR +1, the
/// PEF completes on 6 equal `D`, the next `D` is the first after the flag: +8. N1 was a
/// receiver, so it starts its pending retry after Intermission without a suspend.
#[test]
fn emlcount_tx_35_passive_receiver_form_error_plus_1_first_dominant_plus_8_no_suspend() {
    let mut b = idle_bus(2);
    b.overrides[1] = Rec;
    b.nodes[0].request(std1(0x700));
    for _ in 0..16 {
        b.run_until(300, |o| o[0].has("ACK_ERR")).unwrap();
    }
    assert_eq!((b.nodes[0].tec(), b.nodes[0].state()), (128, FaultState::ErrorPassive));
    assert!(b.run_to(0, Role::Tx, Field::SuspendTransmission, 2, false, 100));
    b.overrides[1] = RxOverride::None;
    b.nodes[1].request(std1(0x001));
    b.run_until(5, |o| o[0].has("SOF")).unwrap();
    assert_eq!(b.nodes[0].label().role, Role::Rx);
    let r = force_at(&mut b, 0, Role::Rx, Field::AckSlot, 1, false, Rec, 1);
    assert!(r[0][0].has("BIT_ERR") && r[0][0].has("PEF"));
    assert_eq!(r[0][0].rec, 1);
    let r = force_at(&mut b, 0, Role::Rx, Field::ErrorDelimiter, 3, false, Dom, 8);
    assert!(r[0][0].has("FORM_ERR") && r[0][0].has("PEF"));
    assert_eq!(r[0][0].rec, 2);
    assert!(r[1..7].iter().all(|o| o[0].rec == 2 && o[0].events.is_empty()));
    assert!(r[7][0].has("DAF=1"));
    assert_eq!(r[7][0].rec, 10);
    // then delimiter, intermission and the retry, no suspend
    let s = b.bit;
    b.run_until(40, |o| o[0].has("SOF")).unwrap();
    assert!(!b.since(0, s).iter().any(|o| o.label.field == Field::SuspendTransmission));
    assert_eq!(b.nodes[0].label().role, Role::Tx);
}
