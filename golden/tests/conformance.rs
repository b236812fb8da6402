//! Steps of conformance-tests.md re-created literally on the golden bus (expected values in
//! the test names). One-node programs (txarb, idle) run N1 alone.

mod util;
use canstar_golden::frame::frame_bits;
use canstar_golden::{FaultState, Field, Frame, FrameVariant, GoldenBus, Role, RxOverride};
use util::*;

use RxOverride::{StuckDominant as Dom, StuckRecessive as Rec};

fn alone() -> GoldenBus {
    let mut b = GoldenBus::new(1);
    assert!(b.run_to_idle(20));
    b
}

/// Run a txarb step: request `f`, force at N1's current bit (role Tx, field, pos, stuff) for
/// one bit, withdraw, run to idle. Returns (results of the forced bit, all results after).
fn txarb(f: Frame, field: Field, pos: u32, stuff: bool, o: RxOverride) -> (GoldenBus, u64) {
    let mut b = alone();
    b.nodes[0].request(f);
    let start = b.bit;
    assert!(b.run_to(0, Role::Tx, field, pos, stuff, 200), "{field:?} {pos}");
    b.force(0, o, 1);
    b.nodes[0].withdraw();
    assert!(b.run_to_idle(100));
    (b, start)
}

#[test]
fn txarb_1_arb_lost_at_id_2_stuff_error_after_id_7_rec_1() {
    let f = find_frame(std_frames(), |b| bit_at(b, Field::Identifier, 2) == R);
    let (b, s) = txarb(f, Field::Identifier, 2, false, Dom);
    let h = b.since(0, s);
    let lost = h.iter().find(|o| o.has("ARB_LOST")).unwrap();
    assert_eq!((lost.label.field, lost.label.pos), (Field::Identifier, 2));
    let se = h.iter().find(|o| o.has("STUFF_ERR")).unwrap();
    assert_eq!((se.label.role, se.label.field, se.label.pos, se.label.stuff), (Role::Rx, Field::Identifier, 7, true));
    assert!(se.has("AEF"));
    assert_eq!((b.nodes[0].tec(), b.nodes[0].rec()), (0, 1));
}

#[test]
fn txarb_2_bit_error_id_7_dominant_tec_8() {
    let f = find_frame(std_frames(), |b| bit_at(b, Field::Identifier, 7) == D);
    let (b, s) = txarb(f, Field::Identifier, 7, false, Rec);
    assert_eq!(count(&b, 0, s, "BIT_ERR"), 1);
    assert_eq!(count(&b, 0, s, "AEF"), 1);
    assert_eq!((b.nodes[0].tec(), b.nodes[0].rec()), (8, 0));
}

#[test]
fn txarb_3_remote_rtr_forced_d_arb_lost_reads_ext_stuff_error_after_ex_id_4_rec_1() {
    let f = Frame::std_remote(0x2A5, 0);
    let (b, s) = txarb(f, Field::RtrBit, 1, false, Dom);
    let h = b.since(0, s);
    assert!(h.iter().any(|o| o.has("ARB_LOST")));
    let se = h.iter().find(|o| o.has("STUFF_ERR")).unwrap();
    assert_eq!((se.label.field, se.label.pos, se.label.stuff), (Field::ExIdentifier, 4, true));
    assert_eq!((b.nodes[0].tec(), b.nodes[0].rec()), (0, 1));
}

#[test]
fn txarb_5_r_stuff_after_id_9_forced_d_stuff_err_exc2_tec_0() {
    let f = find_frame(std_frames(), |b| {
        stuff_after(b, Field::Identifier, 9, R) && (5..=9).all(|p| bit_at(b, Field::Identifier, p) == D)
    });
    let (b, s) = txarb(f, Field::Identifier, 9, true, Dom);
    let h = b.since(0, s);
    let e = h.iter().find(|o| o.has("STUFF_ERR")).unwrap();
    assert!(e.has("EXC2") && e.has("AEF"));
    assert_eq!((b.nodes[0].tec(), b.nodes[0].rec()), (0, 0));
}

#[test]
fn txarb_6_d_stuff_after_id_5_forced_r_bit_err_tec_8() {
    let f = find_frame(std_frames(), |b| stuff_after(b, Field::Identifier, 5, D));
    let (b, s) = txarb(f, Field::Identifier, 5, true, Rec);
    assert_eq!(count(&b, 0, s, "BIT_ERR"), 1);
    assert_eq!(b.nodes[0].tec(), 8);
}

#[test]
fn txarb_7_std_r_stuff_after_rtr_forced_d_stuff_err_exc2_tec_0() {
    let f = find_frame(std_frames(), |b| stuff_after(b, Field::RtrBit, 1, R));
    let (b, s) = txarb(f, Field::RtrBit, 1, true, Dom);
    assert_eq!(count(&b, 0, s, "STUFF_ERR"), 1);
    assert_eq!(count(&b, 0, s, "EXC2"), 1);
    assert_eq!(b.nodes[0].tec(), 0);
}

#[test]
fn txarb_9_ext_ide_forced_d_arb_lost_reads_std_remote_stuff_error_after_dlc_4_rec_1() {
    let f = find_frame(ext_frames(), |_| true);
    let (b, s) = txarb(f, Field::IdeBit, 1, false, Dom);
    let h = b.since(0, s);
    assert!(h.iter().any(|o| o.has("ARB_LOST") && o.label.field == Field::IdeBit));
    let se = h.iter().find(|o| o.has("STUFF_ERR")).unwrap();
    assert_eq!((se.label.field, se.label.pos, se.label.stuff), (Field::DataLengthCode, 4, true));
    assert_eq!((b.nodes[0].tec(), b.nodes[0].rec()), (0, 1));
}

#[test]
fn txarb_11_std_r_stuff_after_ide_forced_d_stuff_err_outside_tec_8() {
    let f = find_frame(std_frames(), |b| stuff_after(b, Field::IdeBit, 1, R));
    let (b, s) = txarb(f, Field::IdeBit, 1, true, Dom);
    assert_eq!(count(&b, 0, s, "STUFF_ERR"), 1);
    assert_eq!(count(&b, 0, s, "EXC2"), 0);
    assert_eq!(b.nodes[0].tec(), 8);
}

#[test]
fn txarb_15_ext_remote_rtr_forced_d_arb_lost_stuff_error_after_dlc_3_rec_1() {
    let f = Frame::ext_remote(0x0123_4567, 0);
    let (b, s) = txarb(f, Field::RtrBit, 1, false, Dom);
    let h = b.since(0, s);
    assert!(h.iter().any(|o| o.has("ARB_LOST")));
    let se = h.iter().find(|o| o.has("STUFF_ERR")).unwrap();
    assert_eq!((se.label.field, se.label.pos, se.label.stuff), (Field::DataLengthCode, 3, true));
    assert_eq!((b.nodes[0].tec(), b.nodes[0].rec()), (0, 1));
}

#[test]
fn txarb_17_ext_r_stuff_after_ex_id_15_forced_d_exc2_tec_0() {
    let f = find_frame(ext_frames(), |b| stuff_after(b, Field::ExIdentifier, 15, R));
    let (b, s) = txarb(f, Field::ExIdentifier, 15, true, Dom);
    assert_eq!(count(&b, 0, s, "EXC2"), 1);
    assert_eq!(b.nodes[0].tec(), 0);
}

#[test]
fn txarb_19_ext_r_stuff_after_rtr_forced_d_stuff_err_tec_8() {
    let f = find_frame(ext_frames(), |b| stuff_after(b, Field::RtrBit, 1, R));
    let (b, s) = txarb(f, Field::RtrBit, 1, true, Dom);
    assert_eq!(count(&b, 0, s, "STUFF_ERR"), 1);
    assert_eq!(count(&b, 0, s, "EXC2"), 0);
    assert_eq!(b.nodes[0].tec(), 8);
}

#[test]
fn txarb_20_ext_d_stuff_after_rtr_forced_r_bit_err_tec_8() {
    let remotes = (0..0x40000u32).map(|k| Frame::ext_remote(k.wrapping_mul(0x9E37) & 0x1FFF_FFFF, 0));
    let f = find_frame(remotes, |b| stuff_after(b, Field::RtrBit, 1, D));
    let (b, s) = txarb(f, Field::RtrBit, 1, true, Rec);
    assert_eq!(count(&b, 0, s, "BIT_ERR"), 1);
    assert_eq!(b.nodes[0].tec(), 8);
}

/// idle_3: `D!` at Bus_Idle 2: SOF, receiver; the bus stays `R`, so the 6th bit after SOF is
/// a STUFF_ERR: REC = 1, AEF. idle_4: with a request pending, `D!` at Intermission 3 is taken
/// as SOF and N1 continues as transmitter with Identifier 1.
#[test]
fn idle_3_dominant_bus_idle_2_stuff_error_rec_1_idle_4_im3_sof_transmitter() {
    let mut b = alone();
    let r = force_at(&mut b, 0, Role::None, Field::BusIdle, 2, false, Dom, 1);
    assert!(r[0][0].has("SOF"));
    let o = b.run_until(10, |o| o[0].has("STUFF_ERR")).unwrap();
    assert_eq!((o[0].label.field, o[0].label.pos, o[0].label.stuff), (Field::Identifier, 5, true));
    assert!(o[0].has("AEF"));
    assert_eq!(o[0].rec, 1);
    b.nodes[0].request(std1(0x7F0));
    let r = force_at(&mut b, 0, Role::Rx, Field::Intermission, 3, false, Dom, 1);
    assert!(r[0][0].has("SOF"));
    let l = b.nodes[0].label();
    assert_eq!((l.role, l.field, l.pos), (Role::Tx, Field::Identifier, 1));
}

/// biterror_tx_12: 3 bit errors in AEFs from TEC 104: +24 = 128; the last makes N1 passive
/// but the flag it starts is active and completed.
#[test]
fn biterror_tx_12_three_flag_bit_errors_from_104_to_128_last_flag_active() {
    let mut b = idle_bus(2);
    b.overrides[1] = Rec; // no ACK: 13 ACK errors take TEC to 104
    b.nodes[0].request(std1(0x0F0));
    for _ in 0..13 {
        b.run_until(300, |o| o[0].has("ACK_ERR")).unwrap();
    }
    assert_eq!(b.nodes[0].tec(), 104);
    let r = force_at(&mut b, 0, Role::Tx, Field::ActiveErrorFlag, 3, false, Rec, 3);
    assert_eq!(r.iter().map(|o| o[0].tec).collect::<Vec<_>>(), vec![112, 120, 128]);
    assert!(r[2][0].has("TO_EP") && r[2][0].has("AEF"));
    // the new flag is 6 dominant bits
    let r = b.force(0, RxOverride::None, 6);
    assert!(r.iter().all(|o| !o[0].drove));
    assert_eq!(b.nodes[0].state(), FaultState::ErrorPassive);
}

/// crc_tx_8 from TEC 255 (emlcount_tx_29/30 level): a passive ACK error with a `D` at PEF
/// bit 6: +8 = 263, bus-off (TO_BO).
#[test]
fn crc_tx_8_exc1_not_met_at_pef_6_tec_263_bus_off() {
    let mut b = idle_bus(2);
    b.overrides[1] = Rec;
    b.nodes[0].request(std1(0x0F0));
    for _ in 0..16 {
        b.run_until(300, |o| o[0].has("ACK_ERR")).unwrap();
    }
    // TEC 128: now 16 passive ACK errors with a D in the flag, +8 each -> 255 needs D forcing;
    // use 15 of them: 128 + 15*8 = 248, then one bit error (+8) on the next SOF: 256 > 255.
    // Instead reach 255 exactly: 127 is not a multiple of 8 away, so take the manual's route
    // to 255 via a success (-1) first.
    b.overrides[1] = RxOverride::None;
    run_to_tx_ok(&mut b, 0, 300);
    assert_eq!(b.nodes[0].tec(), 127);
    b.overrides[1] = Rec;
    b.nodes[0].request(std1(0x0F0));
    // active ACK error: 135 (passive); then passive ACK errors, each with a D at PEF bit 2
    b.run_until(300, |o| o[0].has("ACK_ERR")).unwrap();
    assert_eq!(b.nodes[0].tec(), 135);
    for k in 1..=15u16 {
        force_at(&mut b, 0, Role::Tx, Field::PassiveErrorFlag, 2, false, Dom, 1);
        assert_eq!(b.nodes[0].tec(), 135 + 8 * k);
    }
    assert_eq!(b.nodes[0].tec(), 255);
    assert_eq!(b.nodes[0].state(), FaultState::ErrorPassive);
    let o = b.run_until(300, |o| o[0].has("ACK_ERR")).unwrap();
    assert!(o[0].has("PEF"));
    let r = force_at(&mut b, 0, Role::Tx, Field::PassiveErrorFlag, 6, false, Dom, 1);
    assert!(r[0][0].has("TO_BO"));
    assert_eq!(r[0][0].tec, 263);
    assert!(b.nodes[0].drive());
}

/// extd_id_rx_1..10: the listed frames (with SRR `D` / r0 `R` variants) are delivered with
/// the right kind and identifier, and the stated stuff conditions around IDE hold.
#[test]
fn extd_id_rx_1_to_10_frames_delivered_and_conditions_hold() {
    let v0 = FrameVariant::default();
    let r0r = FrameVariant { r0_recessive: true, ..v0 };
    let srrd = FrameVariant { srr_dominant: true, ..v0 };
    let cases = [
        (Frame::std_remote(0x28F, 0), v0),
        (Frame::std_remote(0x28F, 0), r0r),
        (Frame::std_data(0x290, 0, &[]), v0),
        (Frame::std_data(0x290, 0, &[]), r0r),
        (Frame::std_data(0x288, 0, &[]), v0),
        (Frame::ext_data(0x0A0C_A5A5, 0, &[]), v0),
        (Frame::ext_data(0x0A3C_A5A5, 0, &[]), v0),
        (Frame::ext_data(0x0A3E_A5A5, 0, &[]), v0),
        (Frame::ext_data(0x0A40_A5A5, 0, &[]), srrd),
        (Frame::ext_data(0x0A42_A5A5, 0, &[]), srrd),
    ];
    // conditions of the table (stuff bit before / after IDE)
    let stuff_before_ide = |f: &Frame, v: FrameVariant| {
        let bits = frame_bits(f, v);
        let i = bits.iter().position(|x| x.field == Field::IdeBit).unwrap();
        (bits[i - 1].stuff.then_some(bits[i - 1].bit), bits[i + 1].stuff.then_some(bits[i + 1].bit))
    };
    assert_eq!(stuff_before_ide(&cases[0].0, v0).0, Some(D));
    assert_eq!(stuff_before_ide(&cases[2].0, v0).0, Some(R));
    assert_eq!(stuff_before_ide(&cases[4].0, v0).1, Some(R));
    assert_eq!(stuff_before_ide(&cases[5].0, v0).1, Some(D));
    assert_eq!(stuff_before_ide(&cases[6].0, v0).0, Some(D));
    assert_eq!(stuff_before_ide(&cases[8].0, srrd).0, Some(R));
    let mut b = idle_bus(2);
    for (k, (f, v)) in cases.into_iter().enumerate() {
        let s = b.bit;
        b.nodes[1].request_variant(f.clone(), v);
        run_to_tx_ok(&mut b, 1, 300);
        assert!(b.run_to_idle(20));
        assert_eq!(delivered(&b, 0, s), vec![f], "extd_id_rx_{}", k + 1);
    }
    assert_eq!((b.nodes[0].rec(), b.nodes[1].tec()), (0, 0));
}

/// emlcount_rx_4 (C13, the 1999 rule): `D!` at Rx_End_Of_Frame 7 and the 13 bits after it:
/// frame delivered, REC unchanged; OLF, then 7 `D` bits after it tolerated. With the ISO rule
/// (the default) REC goes to 8.
#[test]
fn emlcount_rx_4_eof7_and_13_more_dominant_rec_unchanged_9() {
    for iso in [false, true] {
        let mut b = if iso { idle_bus(2) } else { idle_bus_1999(2) };
        b.nodes[1].request(std1(0x00F));
        force_at(&mut b, 0, Role::Rx, Field::AckSlot, 1, false, Rec, 1);
        b.nodes[1].withdraw();
        assert!(b.run_to_idle(60));
        assert_eq!(b.nodes[0].rec(), 9, "+9 pattern (emlcount_rx_3 kind)");
        let f = std1(0x010);
        b.nodes[1].request(f.clone());
        let r = force_at(&mut b, 0, Role::Rx, Field::EndOfFrame, 7, false, Dom, 14);
        assert_eq!(r[0][0].delivered(), Some(&f));
        assert!(r[0][0].has("OLF"));
        assert!(r[13][0].has("DAF=7"));
        let rec = if iso { 8 } else { 9 };
        assert!(r.iter().all(|o| o[0].rec == rec), "iso {iso}");
    }
}
