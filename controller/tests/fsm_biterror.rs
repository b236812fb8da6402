//! The biterror program (conformance-tests.md §2) on the bit-level harness.
mod common;
use canstar_controller::frame::{frame_crc, BuildOptions, Frame};
use canstar_controller::fsm::*;
use common::*;

fn good_rx(b: &mut Bus, f: &Frame) {
    b.request(1, f);
    b.run_until(800, |b| b.nodes[1].tx_done.val());
    b.withdraw(1);
    b.run_idle(100);
    b.step();
}

#[test]
fn biterror_rx_program() {
    let (d, r) = (Ovr::StuckD, Ovr::StuckR);
    let mut b = Bus::integrated(2);
    let f = Frame::std(0x3D2, &[0x10, 0x20]);
    // rx_1: R at the ACK slot, R at the first bit of the AEF: +1 +8
    b.request(1, &f);
    b.force_at(0, Field::AckSlot, 1, r, 1);
    assert!(b.last(0).has(EV_BIT_ERR));
    b.force_at(0, Field::ActFlag, 1, r, 1);
    assert!(b.last(0).has(EV_BIT_ERR) && b.last(0).has(EV_AEF));
    b.run_until(40, |b| b.field(0) == Field::ErrDel);
    assert_eq!((b.rec(0), b.tec(1)), (9, 8), "rx_1");
    assert!(b.log[1].iter().any(|x| x.has(EV_FORM_ERR) && x.is(Field::AckDel, 1)));
    // rx_2 (retry): ACK stimulus, R at the 6th bit of the AEF: +9
    b.force_at(0, Field::AckSlot, 1, r, 1);
    b.force_at(0, Field::ActFlag, 6, r, 1);
    b.run_until(40, |b| b.field(0) == Field::ErrDel);
    assert_eq!(b.rec(0), 18, "rx_2");
    b.run_until(800, |b| b.nodes[1].tx_done.val());
    b.withdraw(1);
    assert_eq!(b.rec(0), 17);
    // rx_3: after that good frame: D at IM 1, R at OLF bit 1: +8
    b.force_at(0, Field::Inter, 1, d, 1);
    b.force_at(0, Field::OvlFlag, 1, r, 1);
    assert!(b.last(0).has(EV_BIT_ERR) && b.last(0).has(EV_AEF));
    b.run_until(40, |b| b.field(0) == Field::ErrDel);
    assert_eq!(b.rec(0), 25, "rx_3");
    // rx_4: D at IM 1, R at OLF bit 6: +8
    b.force_at(0, Field::Inter, 1, d, 1);
    b.force_at(0, Field::OvlFlag, 6, r, 1);
    b.run_until(40, |b| b.field(0) == Field::ErrDel);
    assert_eq!(b.rec(0), 33, "rx_4");
    b.run_idle(100);
    b.step();
    // towards the rx_5 precondition (REC 40..47): one rx_1-type error, good retry
    b.request(1, &f);
    b.force_at(0, Field::AckSlot, 1, r, 1);
    b.force_at(0, Field::ActFlag, 1, r, 1);
    b.run_until(800, |b| b.nodes[1].tx_done.val());
    b.withdraw(1);
    b.run_idle(100);
    b.step();
    assert_eq!(b.rec(0), 41);
    // rx_5: an AEF (ACK bit error, +1 -> 42), then R for 11 bits: +88 -> 130,
    // error-passive at the 11th, whose flag is still active
    b.request(1, &f);
    b.force_at(0, Field::AckSlot, 1, r, 1);
    assert_eq!(b.rec(0), 42);
    b.force_at(0, Field::ActFlag, 1, r, 11);
    assert!(b.last(0).has(EV_AEF));
    assert_eq!((b.rec(0), b.state(0)), (130, 1), "rx_5");
    b.run_until(20, |b| b.field(0) != Field::ActFlag || b.nodes[0].pos.val().index() > 6);
    assert!(b.log[0].iter().rev().take(6).all(|x| x.field == Field::ActFlag && !x.drv), "completed active flag");
    // the retry follows; rx_6: R at its ACK slot (saturated), D at PEF bit 1:
    // the equal-bit count restarts; N2 completes its frame
    let s6 = b.bit;
    b.force_at(0, Field::AckSlot, 1, r, 1);
    assert!(b.last(0).has(EV_BIT_ERR) && b.last(0).has(EV_PEF));
    b.force_at(0, Field::PasFlag, 1, d, 1);
    b.run_until(20, |b| b.field(0) == Field::ErrDel);
    let flag = b.log[0].iter().rev().filter(|x| x.field == Field::PasFlag).count();
    assert!(flag >= 7, "count restarted");
    assert_eq!(b.rec(0), 130, "rx_6");
    b.run_until(400, |b| !b.events(1, EV_TX_OK, s6).is_empty());
    b.withdraw(1);
    b.run_idle(100);
    b.step();
    // rx_7: next frame, a PEF of N1 (ACK stimulus), D at its 6th bit
    b.request(1, &Frame::std(0x3D3, &[0x30]));
    let s7 = b.bit;
    b.force_at(0, Field::AckSlot, 1, r, 1);
    b.force_at(0, Field::PasFlag, 6, d, 1);
    b.run_until(20, |b| b.field(0) == Field::ErrDel);
    assert_eq!(b.rec(0), 130, "rx_7");
    b.run_until(400, |b| !b.events(1, EV_TX_OK, s7).is_empty());
    b.withdraw(1);
    // rx_8: the Intermission after that error frame: D at IM 1, R at OLF 1: a PEF
    b.force_at(0, Field::Inter, 1, d, 1);
    b.force_at(0, Field::OvlFlag, 1, r, 1);
    assert!(b.last(0).has(EV_BIT_ERR) && b.last(0).has(EV_PEF));
    b.run_until(40, |b| b.field(0) == Field::ErrDel);
    assert_eq!(b.rec(0), 130, "rx_8");
    // rx_9: D at IM 1, R at OLF bit 6: PEF, unchanged
    b.force_at(0, Field::Inter, 1, d, 1);
    b.force_at(0, Field::OvlFlag, 6, r, 1);
    assert!(b.last(0).has(EV_PEF));
    assert_eq!((b.rec(0), b.state(0)), (130, 1), "rx_9");
    b.run_idle(200);
    // a good reception ends it: 127, error-active
    b.step();
    good_rx(&mut b, &Frame::std(0x100, &[]));
    assert_eq!((b.rec(0), b.state(0)), (127, 0));
}

#[test]
fn biterror_tx_program() {
    let (d, r) = (Ovr::StuckD, Ovr::StuckR);
    // one frame for all conditions: DLC 8 (bit 3 R, bit 0 D), byte 0 >= 0x80 and
    // even, CRC bit 14 = 1 and CRC bit 0 = 0
    let f = (0..=255u8)
        .map(|x| Frame::std(0x2B4, &[0x80 | (x & 0x7E), x, 0x11, 0x22, 0x33, 0x44, 0x55, 0x66]))
        .find(|f| {
            let c = frame_crc(f, BuildOptions::default());
            (c >> 14) & 1 == 1 && c & 1 == 0
        })
        .expect("frame");
    let mut b = Bus::integrated(2);
    let tec = std::cell::Cell::new(0u64);
    let step = |b: &mut Bus, name: &str, field: Field, pos: u8, o: Ovr, dt: u64, flag: usize| {
        b.force_at(0, field, pos, o, 1);
        let x = b.last(0).clone();
        assert!(x.has(EV_BIT_ERR) && x.has(flag), "{name}: {x:?}");
        tec.set(tec.get() + dt);
        assert_eq!(b.tec(0), tec.get(), "{name}");
    };
    b.request(0, &f);
    step(&mut b, "tx_1", Field::Sof, 1, r, 8, EV_AEF);
    b.run_until(40, |b| b.field(0) == Field::ErrDel);
    assert_eq!(b.rec(1), 1, "tx_1: N2 stuff error inside N1's flag");
    step(&mut b, "tx_2", Field::Resv, 1, r, 8, EV_AEF);
    step(&mut b, "tx_2b", Field::ActFlag, 1, r, 8, EV_AEF);
    step(&mut b, "tx_3", Field::Sof, 1, r, 8, EV_AEF);
    step(&mut b, "tx_3b", Field::ActFlag, 6, r, 8, EV_AEF);
    b.run_until(800, |b| b.nodes[0].tx_done.val());
    b.withdraw(0);
    tec.set(tec.get() - 1);
    // tx_4/5: after the good frame, D at IM 1 and R at OLF bit 1 / bit 6
    b.force_at(0, Field::Inter, 1, d, 1);
    step(&mut b, "tx_4", Field::OvlFlag, 1, r, 8, EV_AEF);
    b.force_at(0, Field::Inter, 1, d, 1);
    step(&mut b, "tx_5", Field::OvlFlag, 6, r, 8, EV_AEF);
    b.run_idle(100);
    b.step();
    b.request(0, &f);
    let fields = [
        ("DLC 1", Field::Dlc, 1, d),
        ("DLC 4", Field::Dlc, 4, r),
        ("Data 1", Field::Data, 1, d),
        ("Data 8", Field::Data, 8, r),
        ("CRC 1", Field::Crc, 1, d),
        ("CRC 15", Field::Crc, 15, r),
    ];
    for (name, field, pos, o) in fields {
        step(&mut b, name, field, pos, o, 8, EV_AEF);
    }
    assert_eq!(tec.get(), 103);
    // tx_12: an AEF (R at SOF: 111), then R for 3 bits inside it: 135, the last
    // flag is still active
    step(&mut b, "tx_12a", Field::Sof, 1, r, 8, EV_AEF);
    b.force_at(0, Field::ActFlag, 2, r, 3);
    tec.set(tec.get() + 24);
    assert_eq!((b.tec(0), b.state(0)), (tec.get(), 1), "tx_12");
    assert!(b.last(0).has(EV_AEF));
    // tx_13: R at SOF: PEF, suspend before the retry
    step(&mut b, "tx_13", Field::Sof, 1, r, 8, EV_PEF);
    b.run_until(100, |b| b.field(0) == Field::Sof);
    assert!(b.log[0].iter().rev().take(12).any(|x| x.field == Field::Suspend && x.pos == 8));
    // tx_14: R at r0, D at PEF bit 1; tx_15: D at PEF bit 6: no change
    step(&mut b, "tx_14", Field::Resv, 1, r, 8, EV_PEF);
    b.force_at(0, Field::PasFlag, 1, d, 1);
    b.force_at(0, Field::PasFlag, 6, d, 1);
    assert_eq!(b.tec(0), tec.get(), "tx_15");
    b.run_until(800, |b| b.nodes[0].tx_done.val());
    b.withdraw(0);
    tec.set(tec.get() - 1);
    // tx_16/17 (passive): D at IM 1, R at OLF bit 1 / 6: PEF
    b.force_at(0, Field::Inter, 1, d, 1);
    step(&mut b, "tx_16", Field::OvlFlag, 1, r, 8, EV_PEF);
    b.force_at(0, Field::Inter, 1, d, 1);
    step(&mut b, "tx_17", Field::OvlFlag, 6, r, 8, EV_PEF);
    b.run_idle(100);
    b.step();
    b.request(0, &f);
    for (name, field, pos, o) in fields {
        step(&mut b, name, field, pos, o, 8, EV_PEF);
    }
    assert_eq!((b.tec(0), b.state(0)), (tec.get(), 1));
    b.run_until(800, |b| b.nodes[0].tx_done.val());
    assert_eq!(b.tec(0), tec.get() - 1);
    assert_eq!(tec.get() - 1, 213);
}
