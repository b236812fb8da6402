//! The formerr program (conformance-tests.md §8) on the bit-level harness.
mod common;
use canstar_controller::frame::Frame;
use canstar_controller::fsm::*;
use common::*;

fn to_err_del(b: &mut Bus) {
    b.run_until(40, |b| matches!(b.field(0), Field::ErrDel | Field::OvlDel));
}

#[test]
fn formerr_rx_program() {
    let d = Ovr::StuckD;
    let mut b = Bus::integrated(2);
    let f = Frame::std(0x4C1, &[0xDE, 0xAD]);
    b.request(1, &f);
    let mut rec = 0;
    for (name, field, pos) in [("rx_1", Field::CrcDel, 1), ("rx_2", Field::AckDel, 1), ("rx_3", Field::Eof, 1)] {
        b.force_at(0, field, pos, d, 1);
        assert!(b.last(0).has(EV_FORM_ERR) && b.last(0).has(EV_AEF), "{name}");
        to_err_del(&mut b);
        rec += 9;
        assert_eq!(b.rec(0), rec, "{name}");
    }
    // rx_4: D at EOF 7 of the retry: delivered, OLF, unchanged
    b.force_at(0, Field::Eof, 7, d, 1);
    assert!(b.last(0).has(EV_OVL) && b.last(0).has(EV_RX_OK));
    b.withdraw(1);
    assert_eq!(b.rx[0], vec![f.clone()]);
    assert_eq!(b.rec(0), rec, "rx_4");
    // rx_5: D at Overload_Delimiter 8: OLF, unchanged
    b.force_at(0, Field::OvlDel, 8, d, 1);
    assert!(b.last(0).has(EV_OLF));
    assert_eq!(b.rec(0), rec, "rx_5");
    // rx_6: D at Overload_Delimiter 2: +9
    b.force_at(0, Field::OvlDel, 2, d, 1);
    assert!(b.last(0).has(EV_FORM_ERR));
    to_err_del(&mut b);
    rec += 9;
    assert_eq!(b.rec(0), rec, "rx_6");
    // rx_7: D at Error_Delimiter 2: +9
    b.force_at(0, Field::ErrDel, 2, d, 1);
    to_err_del(&mut b);
    rec += 9;
    assert_eq!(b.rec(0), rec, "rx_7");
    // rx_8: D at Error_Delimiter 8: OLF, unchanged
    b.force_at(0, Field::ErrDel, 8, d, 1);
    assert!(b.last(0).has(EV_OLF));
    assert_eq!(b.rec(0), rec, "rx_8");
    // rx_9: 16 D after that OLF: +8 at the 8th and 16th (no first-bit rule)
    b.force_at(0, Field::OvlFlag, 7, d, 16);
    rec += 16;
    assert_eq!(b.rec(0), rec, "rx_9");
    // rx_10: D at Overload_Delimiter 2: +1, and +8 for the dominant first bit
    // after the flag (N2 answers one bit later)
    b.force_at(0, Field::OvlDel, 2, d, 1);
    b.run_to(0, Field::ActFlag, 7, 10);
    // rx_11: 16 D after that AEF: the first is rx_10's first-bit +8, then the
    // 8th and 16th: +25 for rx_10 and rx_11 together
    b.ovr[0] = d;
    b.run(16);
    b.ovr[0] = Ovr::None;
    rec += 25;
    assert_eq!(b.rec(0), rec, "rx_10 + rx_11");
    assert_eq!(rec, 86);
}

/// C13, the ISO rule (`rec_iso` high, the core's default; the programs above run the
/// frame state machine with it low, the 1999 rule): the rx_4 step counts the reception,
/// REC − 1 (ISO 16845-1 7.6.16), frame delivered, overload frame as before.
#[test]
fn formerr_rx_4_with_the_iso_rule_decrements_rec() {
    let d = Ovr::StuckD;
    let mut b = Bus::integrated(2);
    for n in &mut b.nodes {
        n.rec_iso.next = true;
    }
    let f = Frame::std(0x4C1, &[0xDE, 0xAD]);
    b.request(1, &f);
    b.force_at(0, Field::CrcDel, 1, d, 1);
    to_err_del(&mut b);
    assert_eq!(b.rec(0), 9);
    b.force_at(0, Field::Eof, 7, d, 1);
    assert!(b.last(0).has(EV_OVL) && b.last(0).has(EV_RX_OK));
    b.withdraw(1);
    assert_eq!(b.rx[0], vec![f]);
    assert_eq!(b.rec(0), 8, "rx_4, ISO");
}

#[test]
fn formerr_tx_program() {
    let d = Ovr::StuckD;
    let mut b = Bus::integrated(2);
    let f = Frame::std(0x1C4, &[0xBE, 0xEF]);
    b.request(0, &f);
    let mut tec = 0;
    for (name, field, pos) in
        [("tx_1", Field::CrcDel, 1), ("tx_2", Field::AckDel, 1), ("tx_3", Field::Eof, 1), ("tx_4", Field::Eof, 7)]
    {
        b.force_at(0, field, pos, d, 1);
        assert!(b.last(0).has(EV_FORM_ERR) && b.last(0).has(EV_AEF), "{name}");
        tec += 8;
        assert_eq!(b.tec(0), tec, "{name}");
    }
    // tx_4: N2 saw a good frame and delivered it
    assert_eq!(b.rx[1], vec![f.clone()]);
    // tx_5: D at Error_Delimiter 8: OLF, unchanged
    b.force_at(0, Field::ErrDel, 8, d, 1);
    assert!(b.last(0).has(EV_OLF));
    // tx_6: D at Overload_Delimiter 8: OLF, unchanged
    b.force_at(0, Field::OvlDel, 8, d, 1);
    assert!(b.last(0).has(EV_OLF));
    assert_eq!(b.tec(0), tec, "tx_6");
    // tx_7: D at Overload_Delimiter 2: +8, AEF
    b.force_at(0, Field::OvlDel, 2, d, 1);
    assert!(b.last(0).has(EV_FORM_ERR) && b.last(0).has(EV_AEF));
    tec += 8;
    assert_eq!(b.tec(0), tec, "tx_7");
    // tx_8: D at Error_Delimiter 2: +8
    b.force_at(0, Field::ErrDel, 2, d, 1);
    tec += 8;
    assert_eq!(b.tec(0), tec, "tx_8");
    // tx_9: an OLF (D at Error_Delimiter 8), then 16 D after it: +16
    b.force_at(0, Field::ErrDel, 8, d, 1);
    b.force_at(0, Field::OvlFlag, 7, d, 16);
    tec += 16;
    assert_eq!(b.tec(0), tec, "tx_9");
    // tx_10: an AEF (D at Overload_Delimiter 2, +8), then 16 D after it: +16
    b.force_at(0, Field::OvlDel, 2, d, 1);
    tec += 8;
    b.force_at(0, Field::ActFlag, 7, d, 16);
    tec += 16;
    assert_eq!(b.tec(0), tec, "tx_10");
    // the retry succeeds; N2 delivers the frame a second time
    b.run_until(800, |b| b.nodes[0].tx_done.val());
    b.withdraw(0);
    b.run_idle(100);
    assert_eq!(b.tec(0), tec - 1);
    assert_eq!(b.rx[1], vec![f.clone(), f]);
}
