//! The crc program (conformance-tests.md §4, rx_1 and tx_1 .. tx_8) on the
//! bit-level harness.
mod common;
use canstar_controller::frame::Frame;
use canstar_controller::fsm::*;
use common::*;

#[test]
fn crc_rx_1() {
    let mut b = Bus::integrated(2);
    let f = Frame::std(0x2F0, &[0x11, 0x22]);
    b.request(1, &f);
    b.force_at(0, Field::Resv, 1, Ovr::StuckR, 1);
    b.run_to(0, Field::AckSlot, 1, 200);
    b.step();
    assert!(b.last(0).drv, "no ACK from a receiver with a CRC error");
    b.step();
    let x = b.last(0).clone();
    assert!(x.is(Field::AckDel, 1) && x.has(EV_CRC_ERR) && !x.has(EV_FORM_ERR) && x.has(EV_AEF), "{x:?}");
    assert!(b.log[1].iter().any(|r| r.has(EV_ACK_ERR)));
    b.run_until(30, |b| b.field(0) == Field::ErrDel);
    assert_eq!((b.rec(0), b.tec(1)), (1, 8));
    b.run_until(800, |b| b.nodes[1].tx_done.val());
    b.withdraw(1);
    b.run_idle(100);
    assert_eq!((b.rec(0), b.tec(1)), (0, 7));
    assert_eq!(b.rx[0], vec![f]);
}

#[test]
fn crc_tx_program() {
    let (d, r) = (Ovr::StuckD, Ovr::StuckR);
    let mut b = Bus::integrated(2);
    let f = Frame::std(0x0F3, &[0x5A]);
    b.ovr[1] = r; // N2 sees an idle bus: no acknowledgement
    b.request(0, &f);
    // tx_1
    b.run_until(400, |b| b.nodes[0].error.val());
    assert!(b.last(0).has(EV_ACK_ERR) && b.last(0).has(EV_AEF));
    assert_eq!(b.tec(0), 8, "tx_1");
    b.run_until(30, |b| b.field(0) == Field::ErrDel);
    // tx_2: ACK error, then R at the flag for 14 bits from AEF bit 2
    b.run_until(400, |b| b.nodes[0].error.val());
    assert_eq!(b.tec(0), 16);
    b.force_at(0, Field::ActFlag, 2, r, 14);
    assert_eq!(b.tec(0), 128, "tx_2");
    assert_eq!(b.last(0).field, Field::ActFlag);
    assert!(b.last(0).has(EV_AEF), "the flag after the last error is still active");
    // tx_3: retry after suspend: ACK error, PEF without D: EXC1
    b.run_until(400, |b| b.nodes[0].error.val());
    assert!(b.last(0).has(EV_PEF));
    assert!(b.log[0].iter().rev().take(120).any(|x| x.field == Field::Suspend));
    b.run_until(30, |b| b.field(0) == Field::ErrDel);
    assert!(b.log[0].iter().rev().take(10).any(|x| x.has(EV_EXC1)));
    assert_eq!(b.tec(0), 128, "tx_3");
    // tx_4: N2 acknowledges again: success, 127, error-active
    b.ovr[1] = Ovr::None;
    b.run_until(400, |b| b.nodes[0].tx_done.val());
    b.withdraw(0);
    b.run_idle(100);
    assert_eq!((b.tec(0), b.state(0)), (127, 0), "tx_4");
    // tx_5: new frame, R at Identifier 2 (dominant): AEF, 135, passive
    let f5 = Frame::std(0x0F4, &[0xA5]);
    b.request(0, &f5);
    b.force_at(0, Field::Ident, 2, r, 1);
    assert!(b.last(0).has(EV_BIT_ERR) && b.last(0).has(EV_AEF));
    assert_eq!((b.tec(0), b.state(0)), (135, 1), "tx_5");
    // tx_6: retry with N2 deaf: ACK error, PEF (EXC1), then 113 D after the flag: +8 x 14.
    // N2 is made deaf while it is idle (during N1's suspend), so that it never
    // sends a flag it cannot read back.
    b.run_until(100, |b| b.field(0) == Field::Suspend && b.field(1) == Field::Idle);
    b.ovr[1] = r;
    b.run_until(400, |b| b.nodes[0].error.val());
    assert!(b.last(0).has(EV_ACK_ERR) && b.last(0).has(EV_PEF));
    b.force_at(0, Field::PasFlag, 7, d, 113);
    assert_eq!(b.tec(0), 247, "tx_6");
    // tx_7: ACK error, PEF, D at PEF bit 2: +8
    b.run_until(600, |b| b.nodes[0].error.val());
    assert!(b.last(0).has(EV_ACK_ERR));
    b.force_at(0, Field::PasFlag, 2, d, 1);
    assert_eq!((b.tec(0), b.state(0)), (255, 1), "tx_7");
    // tx_8: the same with D at PEF bit 6: 263, bus-off
    b.run_until(600, |b| b.nodes[0].error.val());
    b.force_at(0, Field::PasFlag, 6, d, 1);
    assert_eq!((b.tec(0), b.state(0)), (263, 2), "tx_8");
}
