//! Error signalling and fault confinement on the bit-level harness (CanFsm only):
//! error-passive flags and suspend transmission, the warning limit, bus-off and
//! recovery, flag restarts and counter exceptions. Expected values from
//! can-protocol.md §7–§14 and conformance-tests.md.
mod common;
use canstar_controller::frame::Frame;
use canstar_controller::fsm::*;
use common::*;

#[test]
fn error_passive_flags_and_suspend() {
    let mut b = Bus::integrated(2);
    let f = Frame::std(0x555, &[0x11]);
    b.request(0, &f);
    // 16 bit errors at SOF: TEC 128, error-passive
    for k in 1..=16 {
        b.force_at(0, Field::Sof, 1, Ovr::StuckR, 1);
        let r = b.last(0).clone();
        assert_eq!(r.tec, 8 * k);
        assert!(r.has(EV_AEF), "the error that makes the node passive is still signalled actively");
    }
    assert_eq!(b.state(0), 1);
    b.force_at(0, Field::Sof, 1, Ovr::StuckR, 1);
    let s = b.bit;
    let r = b.last(0).clone();
    assert!(r.has(EV_PEF) && r.tec == 136, "{r:?}");
    // passive flag: node drives recessive; the other node sees nothing wrong
    b.step();
    assert_eq!(b.last(0).field, Field::PasFlag);
    assert!(b.last(0).drv);
    // before the retry: intermission then 8 bits of suspend transmission
    b.run_until(100, |b| b.field(0) == Field::Sof);
    let susp: Vec<u8> = b.log[0][s..].iter().filter(|r| r.field == Field::Suspend).map(|r| r.pos).collect();
    assert_eq!(susp, (1..=8).collect::<Vec<u8>>());
    // the retry succeeds: TEC 135, still passive, suspend again after it
    b.run_until(400, |b| b.nodes[0].tx_done.val());
    assert_eq!(b.tec(0), 135);
    b.withdraw(0);
    b.run_idle(50);
    assert!(b.log[0].iter().rev().take(20).any(|r| r.field == Field::Suspend));
    // the receiver got the frame (it also took the passive node's SOF errors: the
    // bus showed the SOF dominant, then the node's flag)
    assert_eq!(b.rx[1].last(), Some(&f));
}

#[test]
fn error_warning_at_96() {
    let mut b = Bus::integrated(2);
    b.request(0, &Frame::std(0x555, &[]));
    for k in 1..=12 {
        b.force_at(0, Field::Sof, 1, Ovr::StuckR, 1);
        assert_eq!(b.nodes[0].err_warn.val(), k >= 12, "tec {}", b.tec(0));
    }
}

#[test]
fn bus_off_and_automatic_recovery() {
    let mut b = Bus::integrated(1);
    b.request(0, &Frame::std(0x321, &[]));
    b.ovr[0] = Ovr::StuckR;
    b.run_until(20_000, |b| b.state(0) == 2);
    assert!(b.tec(0) > 255);
    assert_eq!(b.field(0), Field::BusOff);
    let entry = b.bit;
    b.withdraw(0);
    b.ovr[0] = Ovr::None;
    // a dominant bit at run bit 9 restarts the run
    b.run(8);
    b.force_bit(0, Ovr::StuckD);
    assert_eq!(b.nodes[0].runs.val().index(), 0);
    b.run_until(128 * 11 + 20, |b| b.state(0) == 0);
    let r = b.last(0).clone();
    assert!(r.has(EV_RECOVERED));
    assert_eq!(r.bit - entry + 1, 128 * 11 + 9, "128 runs of 11 after the 9 bits of the broken run");
    assert_eq!((b.tec(0), b.rec(0)), (0, 0));
    b.step();
    assert_eq!(b.field(0), Field::Idle);
    // TX recessive throughout bus-off
    assert!(b.log[0][entry..].iter().all(|r| r.drv));
}

#[test]
fn bus_off_host_started_recovery() {
    let mut b = Bus::integrated(1);
    b.nodes[0].host_recovery.next = true;
    b.request(0, &Frame::std(0x321, &[]));
    b.ovr[0] = Ovr::StuckR;
    b.run_until(20_000, |b| b.state(0) == 2);
    b.ovr[0] = Ovr::None;
    b.withdraw(0);
    b.run(3000);
    assert_eq!(b.state(0), 2, "no recovery without the host");
    b.nodes[0].recover.next = true;
    b.step();
    b.nodes[0].recover.next = false;
    b.run_until(128 * 11 + 30, |b| b.state(0) == 0);
}

#[test]
fn bit_errors_in_active_flag_restart_it_plus_8_each() {
    // biterror_tx_2 / rx_1: bit error, then R at flag bit 1: +8 +8
    let mut b = Bus::integrated(2);
    b.request(0, &Frame::std(0x0F5, &[0x81]));
    b.force_at(0, Field::Resv, 1, Ovr::StuckR, 1);
    assert_eq!(b.tec(0), 8);
    b.force_at(0, Field::ActFlag, 1, Ovr::StuckR, 1);
    let r = b.last(0).clone();
    assert!(r.has(EV_BIT_ERR) && r.has(EV_AEF) && r.is(Field::ActFlag, 1), "{r:?}");
    assert_eq!(r.tec, 16);
    b.force_at(0, Field::ActFlag, 6, Ovr::StuckR, 1);
    assert_eq!(b.tec(0), 24);
    b.step();
    assert!(b.last(0).is(Field::ActFlag, 1));
    // receiver: ACK bit error then a bit error at flag bit 1: +1 +8
    let mut b = Bus::integrated(2);
    b.request(1, &Frame::std(0x0F5, &[0x81]));
    b.force_at(0, Field::AckSlot, 1, Ovr::StuckR, 1);
    b.force_at(0, Field::ActFlag, 1, Ovr::StuckR, 1);
    assert_eq!(b.rec(0), 9);
}

#[test]
fn flag_restart_after_becoming_passive_is_passive() {
    // biterror_tx_12: R for 3 bits inside an active flag with TEC 104..111;
    // the last error makes the node passive, the flag it starts is still active
    let mut b = Bus::integrated(2);
    b.request(0, &Frame::std(0x0F5, &[]));
    for _ in 0..13 {
        b.force_at(0, Field::Sof, 1, Ovr::StuckR, 1);
    }
    assert_eq!(b.tec(0), 104);
    b.run_to(0, Field::ActFlag, 2, 10);
    b.ovr[0] = Ovr::StuckR;
    b.run(3);
    b.ovr[0] = Ovr::None;
    let r = b.last(0).clone();
    assert_eq!(r.tec, 128);
    assert!(r.has(EV_AEF), "rule 9: typed from the state before the increment");
    b.step();
    assert_eq!(b.last(0).field, Field::ActFlag);
    // a further bit error in that flag restarts it as a passive flag (C14)
    b.force_bit(0, Ovr::StuckR);
    let r = b.last(0).clone();
    assert!(r.has(EV_PEF) && r.tec == 136, "{r:?}");
}

#[test]
fn passive_flag_dominant_bits_restart_the_count() {
    // alone on the bus: ACK errors make the node passive, then a bit error at SOF
    let mut b = Bus::integrated(1);
    b.request(0, &Frame::std(0x0F5, &[]));
    b.run_until(10_000, |b| b.state(0) == 1);
    b.force_at(0, Field::Sof, 1, Ovr::StuckR, 1);
    assert!(b.last(0).has(EV_PEF));
    let t = b.tec(0);
    // D at PEF bit 3: equal-bit count restarts, no counter change
    b.force_at(0, Field::PasFlag, 3, Ovr::StuckD, 1);
    b.run_until(20, |b| b.field(0) != Field::PasFlag);
    // flag bits: 1,2 R; 3 D; 4..9 R (6 equal); position 10 is the first R
    // after the flag (Error_Delimiter position 1, still counted under the flag)
    let flag: Vec<u8> = b.log[0].iter().rev().take(14).filter(|r| r.field == Field::PasFlag).map(|r| r.pos).collect();
    assert_eq!(flag.len(), 10, "{flag:?}");
    assert_eq!(b.field(0), Field::ErrDel);
    assert_eq!(b.nodes[0].pos.val().index(), 2);
    assert_eq!(b.tec(0), t);
}

#[test]
fn exception_1_not_met_adds_8_once() {
    // crc_tx_7: passive ACK error, D at PEF bit 2 -> +8 at that bit
    let mut b = Bus::integrated(1);
    b.request(0, &Frame::std(0x0F5, &[]));
    b.run_until(10_000, |b| b.state(0) == 1);
    assert_eq!(b.tec(0), 128);
    b.run_until(400, |b| b.nodes[0].error.val());
    assert!(b.last(0).has(EV_ACK_ERR) && b.last(0).has(EV_PEF));
    assert_eq!(b.tec(0), 128);
    b.step();
    b.force_bit(0, Ovr::StuckD); // PEF bit 2
    assert_eq!(b.tec(0), 136);
    b.force_bit(0, Ovr::StuckD); // no second +8
    assert_eq!(b.tec(0), 136);
    // transmitter: 8th consecutive dominant bit after its flag +8, no first-bit rule
    b.run_until(30, |b| b.field(0) == Field::PasFlag && b.nodes[0].pos.val().index() > 8 && b.log[0].last().unwrap().smp);
    b.run_until(30, |b| b.field(0) != Field::PasFlag);
    assert_eq!(b.tec(0), 136);
}

#[test]
fn receiver_passive_rec_saturates_and_returns_to_127() {
    let mut b = Bus::integrated(2);
    // CRC-delimiter form errors: +9 each -> 15 of them give 135 -> passive
    b.request(1, &Frame::std(0x0AA, &[]));
    for k in 1..=15 {
        b.force_at(0, Field::CrcDel, 1, Ovr::StuckD, 1);
        b.run_until(40, |b| b.field(0) == Field::ErrDel);
        assert_eq!(b.rec(0), 9 * k);
    }
    b.withdraw(1);
    b.run_idle(60);
    let r = b.rec(0);
    assert_eq!(r, 135);
    assert_eq!(b.state(0), 1);
    // more errors: no further growth beyond saturation
    b.request(1, &Frame::std(0x0AA, &[]));
    b.force_at(0, Field::CrcDel, 1, Ovr::StuckD, 1);
    b.run_until(40, |b| b.field(0) == Field::ErrDel);
    assert_eq!(b.rec(0), r);
    // the retry is received: REC 127, error-active again
    b.run_until(300, |b| b.nodes[1].tx_done.val());
    b.withdraw(1);
    b.run_idle(60);
    assert_eq!(b.rec(0), 127);
    assert_eq!(b.state(0), 0);
}

#[test]
fn bus_off_mid_flag_stops_driving() {
    let mut b = Bus::integrated(2);
    b.request(0, &Frame::std(0x0F5, &[]));
    for _ in 0..31 {
        b.force_at(0, Field::Sof, 1, Ovr::StuckR, 1);
    }
    assert_eq!(b.tec(0), 248);
    b.force_at(0, Field::Sof, 1, Ovr::StuckR, 1);
    assert_eq!(b.tec(0), 256);
    b.step();
    assert_eq!(b.last(0).field, Field::BusOff);
    assert!(b.last(0).drv);
    assert_eq!(b.state(0), 2);
}
