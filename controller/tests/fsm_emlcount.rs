//! The second half of the emlcount transmitter program (conformance-tests.md
//! §6, steps tx_19 .. tx_37) on the bit-level harness: N1 transmits, N2
//! receives, all forcing at N1. Counter values are the manual's (or derived
//! ones from the plan).
mod common;
use canstar_controller::frame::Frame;
use canstar_controller::fsm::*;
use common::*;

fn check(b: &Bus, name: &str, tec: u64, rec: u64, st: u64) {
    assert_eq!((b.tec(0), b.rec(0), b.state(0)), (tec, rec, st), "{name}");
}

#[test]
fn emlcount_tx_19_to_37() {
    let (d, r) = (Ovr::StuckD, Ovr::StuckR);
    let mut b = Bus::integrated(2);
    let f = Frame::std(0x2A5, &[0x12, 0x34]);
    // set-up: TEC 128 by 16 bit errors at SOF
    b.request(0, &f);
    for _ in 0..16 {
        b.force_at(0, Field::Sof, 1, r, 1);
    }
    check(&b, "setup", 128, 0, 1);
    // tx_19: one good frame -> 127, error-active
    b.run_until(800, |b| b.nodes[0].tx_done.val());
    b.withdraw(0);
    b.run_idle(80);
    check(&b, "tx_19", 127, 0, 0);
    b.request(0, &f);
    // tx_20: R at SOF: AEF, 135, passive
    b.force_at(0, Field::Sof, 1, r, 1);
    assert!(b.last(0).has(EV_AEF));
    check(&b, "tx_20", 135, 0, 1);
    // tx_21: R at SOF: PEF, 143
    b.force_at(0, Field::Sof, 1, r, 1);
    assert!(b.last(0).has(EV_PEF));
    check(&b, "tx_21", 143, 0, 1);
    // tx_22: D at ACK_Delimiter: PEF, 151
    b.force_at(0, Field::AckDel, 1, d, 1);
    assert!(b.last(0).has(EV_FORM_ERR) && b.last(0).has(EV_PEF));
    check(&b, "tx_22", 151, 0, 1);
    // tx_23: D at EOF 1 and 6 more bits: PEF completes on the 6 D bits, 159
    b.force_at(0, Field::Eof, 1, d, 7);
    check(&b, "tx_23", 159, 0, 1);
    // tx_24: D at EOF 7; D at PEF bit 3: 167, count restarts
    b.force_at(0, Field::Eof, 7, d, 1);
    check(&b, "tx_24a", 167, 0, 1);
    b.force_at(0, Field::PasFlag, 3, d, 1);
    check(&b, "tx_24", 167, 0, 1);
    // tx_25: D at Error_Delimiter 8 held through the OLF and 7 more: 167
    b.force_at(0, Field::ErrDel, 8, d, 1 + 6 + 7);
    check(&b, "tx_25", 167, 0, 1);
    // tx_26: D at Overload_Delimiter 8 held through OLF + 8: +8 -> 175
    b.force_at(0, Field::OvlDel, 8, d, 1 + 6 + 8);
    check(&b, "tx_26", 175, 0, 1);
    // tx_27: D at Overload_Delimiter 2: FORM_ERR, PEF, 183
    b.force_at(0, Field::OvlDel, 2, d, 1);
    assert!(b.last(0).has(EV_FORM_ERR) && b.last(0).has(EV_PEF));
    check(&b, "tx_27", 183, 0, 1);
    // tx_28: R at ACK slot (passive): ACK_ERR, PEF, no D in the flag: EXC1, 183
    b.force_at(0, Field::AckSlot, 1, r, 1);
    assert!(b.last(0).has(EV_ACK_ERR) && b.last(0).has(EV_PEF));
    b.run_until(20, |b| b.field(0) == Field::ErrDel);
    assert!(b.log[0].iter().rev().take(12).any(|x| x.has(EV_EXC1)));
    check(&b, "tx_28", 183, 0, 1);
    // tx_29: D at Error_Delimiter 2 (+8); then D for the 64 bits after the PEF: +8 x 8 -> 255
    b.force_at(0, Field::ErrDel, 2, d, 1);
    check(&b, "tx_29a", 191, 0, 1);
    b.run_to(0, Field::PasFlag, 7, 20);
    b.ovr[0] = d;
    b.run(64);
    b.ovr[0] = Ovr::None;
    check(&b, "tx_29", 255, 0, 1);
    // tx_30: D at Error_Delimiter 8: OVL, OLF, 255
    b.force_at(0, Field::ErrDel, 8, d, 1);
    assert!(b.last(0).has(EV_OVL));
    check(&b, "tx_30", 255, 0, 1);
    // tx_31: D at Tx_Intermission 3 and the next 5 bits: N1 (passive former
    // transmitter) becomes a receiver; the 6th D is a stuff error: REC 1, PEF
    b.run_to(0, Field::Inter, 3, 40);
    assert!(b.nodes[0].role.val());
    b.ovr[0] = d;
    b.step();
    assert!(b.last(0).has(EV_SOF));
    assert!(!b.nodes[0].role.val(), "C15: a receiver despite the pending request");
    b.run(5);
    b.ovr[0] = Ovr::None;
    assert!(b.last(0).has(EV_STUFF_ERR) && b.last(0).has(EV_PEF));
    check(&b, "tx_31", 255, 1, 1);
    // tx_32: D at the first bit after that PEF: +8 -> 9
    b.force_at(0, Field::PasFlag, 7, d, 1);
    check(&b, "tx_32", 255, 9, 1);
    // tx_33: D at Error_Delimiter 4: FORM_ERR, +1 -> 10, PEF
    b.force_at(0, Field::ErrDel, 4, d, 1);
    assert!(b.last(0).has(EV_FORM_ERR) && b.last(0).has(EV_PEF));
    check(&b, "tx_33", 255, 10, 1);
    // tx_34: D at the first bit after the PEF's 6 R bits: +8 -> 18
    b.force_at(0, Field::PasFlag, 7, d, 1);
    check(&b, "tx_34", 255, 18, 1);
    // tx_35: D at an Error_Delimiter bit held for the 6 PEF bits and 1 more:
    // +1 (form error), the PEF completes on 6 D, the next D +8 -> 27
    b.force_at(0, Field::ErrDel, 3, d, 1 + 6 + 1);
    check(&b, "tx_35", 255, 27, 1);
    // N1 then starts its pending retry (no suspend: it was a receiver)
    b.run_until(400, |b| b.nodes[0].tx_done.val());
    check(&b, "tx_35 retry", 254, 27, 1);
    // tx_36: D at Tx_Intermission 1 after that frame: OVL, OLF
    b.force_at(0, Field::Inter, 1, d, 1);
    assert!(b.last(0).has(EV_OVL) && b.last(0).has(EV_OLF));
    check(&b, "tx_36", 254, 27, 1);
    // tx_37: R at OLF bit 2: BIT_ERR +8 -> 262, bus-off
    b.force_at(0, Field::OvlFlag, 2, r, 1);
    assert!(b.last(0).has(EV_BIT_ERR));
    check(&b, "tx_37", 262, 27, 2);
    b.step();
    assert_eq!(b.last(0).field, Field::BusOff);
}
