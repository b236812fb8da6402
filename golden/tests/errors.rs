//! Error detection and signalling (can-protocol.md §5, §9, §10, §13) on the golden bus.

mod util;
use canstar_golden::{Field, FaultState, Frame, Role, RxOverride};
use util::*;

use RxOverride::{StuckDominant as Dom, StuckRecessive as Rec};

/// formerr_rx_1: `D!` at the receiver's CRC_Delimiter: FORM_ERR, AEF from the ACK slot; the
/// transmitter flags one bit later, so the first bit after the receiver's flag is `D`: +9.
#[test]
fn formerr_rx_1_plus_9_pattern_rec_9_then_8_after_good_retry() {
    let mut b = idle_bus(2);
    b.nodes[1].request(std1(0x321));
    let r = force_at(&mut b, 0, Role::Rx, Field::CrcDelimiter, 1, false, Dom, 1);
    assert!(r[0][0].has("FORM_ERR") && r[0][0].has("AEF"));
    assert_eq!(r[0][0].rec, 1);
    let o = b.run_until(20, |o| o[0].has("DAF=1")).unwrap();
    assert_eq!(o[0].rec, 9);
    assert!(b.history[1].iter().rev().take(20).any(|o| o.has("FORM_ERR") && o.label.field == Field::AckDelimiter));
    assert_eq!(b.nodes[1].tec(), 8);
    run_to_tx_ok(&mut b, 1, 300);
    assert_eq!(b.nodes[0].rec(), 8);
    assert_eq!(b.nodes[1].tec(), 7);
}

/// biterror_rx_1: `R!` at the receiver's own dominant ACK bit (+1), then `R!` at bit 1 of its
/// AEF (+8, new flag): Δ REC +9.
#[test]
fn biterror_rx_1_ack_bit_error_then_flag_bit_error_rec_9() {
    let mut b = idle_bus(2);
    b.nodes[1].request(std1(0x0F0));
    let r = force_at(&mut b, 0, Role::Rx, Field::AckSlot, 1, false, Rec, 1);
    assert!(r[0][0].has("BIT_ERR") && r[0][0].has("AEF"));
    assert_eq!(r[0][0].rec, 1);
    let r = force_at(&mut b, 0, Role::Rx, Field::ActiveErrorFlag, 1, false, Rec, 1);
    assert!(r[0][0].has("BIT_ERR") && r[0][0].has("AEF"));
    assert_eq!(r[0][0].rec, 9);
    // The restarted flag starts at position 1 again and is completed.
    assert_eq!(b.nodes[0].label().field, Field::ActiveErrorFlag);
    assert_eq!(b.nodes[0].label().pos, 1);
    run_to_tx_ok(&mut b, 1, 300);
    assert_eq!(b.nodes[0].rec(), 8, "nothing more counted, then -1");
}

/// biterror_tx_2: `R!` at the transmitter's r0 (+8, AEF), then `R!` at AEF bit 1 (+8, new
/// AEF): Δ TEC +16.
#[test]
fn biterror_tx_2_r0_then_flag_bit_error_tec_16() {
    let mut b = idle_bus(2);
    b.nodes[0].request(std1(0x155));
    let r = force_at(&mut b, 0, Role::Tx, Field::ReservedBits, 1, false, Rec, 1);
    assert!(r[0][0].has("BIT_ERR"));
    assert_eq!(r[0][0].tec, 8);
    let r = force_at(&mut b, 0, Role::Tx, Field::ActiveErrorFlag, 1, false, Rec, 1);
    assert!(r[0][0].has("BIT_ERR") && r[0][0].has("AEF"));
    assert_eq!(r[0][0].tec, 16);
    run_to_tx_ok(&mut b, 0, 300);
    assert_eq!(b.nodes[0].tec(), 15);
    assert_eq!(b.nodes[1].rec(), 0, "receiver: +1 for the stuff error, -1 for the retry");
}

/// biterror_tx_1: `R!` at SOF: BIT_ERR, AEF, TEC +8; the receiver gets a stuff error inside
/// the flag (REC +1).
#[test]
fn biterror_tx_1_sof_bit_error_receiver_stuff_error() {
    let mut b = idle_bus(2);
    b.nodes[0].request(std1(0x155));
    let start = b.bit;
    let r = force_at(&mut b, 0, Role::Tx, Field::StartOfFrame, 1, false, Rec, 1);
    assert!(r[0][0].has("BIT_ERR") && r[0][0].has("AEF"));
    assert_eq!(r[0][0].tec, 8);
    let o = b.run_until(20, |o| o[1].has("STUFF_ERR")).unwrap();
    assert_eq!(o[1].rec, 1);
    assert_eq!(count(&b, 1, start, "SOF"), 1);
}

/// formerr_tx_10 / §13.3: 16 `D` bits after a transmitter's AEF: +8 at the 8th and 16th, no
/// first-bit rule for transmitters.
#[test]
fn formerr_tx_10_sixteen_dominant_after_aef_tec_plus_16() {
    let mut b = idle_bus(2);
    b.nodes[0].request(Frame::std_data(0x155, 0, &[]));
    let r = force_at(&mut b, 0, Role::Tx, Field::Identifier, 2, false, Rec, 1);
    assert!(r[0][0].has("BIT_ERR"));
    assert_eq!(r[0][0].tec, 8);
    let r = force_at(&mut b, 0, Role::Tx, Field::ActiveErrorFlag, 7, false, Dom, 16);
    let tec: Vec<u16> = r.iter().map(|o| o[0].tec).collect();
    assert_eq!(tec[0..7], [8; 7]);
    assert_eq!(tec[7..15], [16; 8]);
    assert_eq!(tec[15], 24);
    assert!(r[7][0].has("DAF=8") && r[15][0].has("DAF=16"));
}

/// formerr_rx_10/11: a receiver's form error (+1), `D` first bit after its AEF (+8), and the
/// 8th and 16th `D` (+8 each): +25.
#[test]
fn formerr_rx_10_11_receiver_first_bit_and_every_8th_plus_25() {
    let mut b = idle_bus(2);
    b.nodes[1].request(std1(0x0AA));
    let r = force_at(&mut b, 0, Role::Rx, Field::CrcDelimiter, 1, false, Dom, 1);
    assert_eq!(r[0][0].rec, 1);
    b.nodes[1].withdraw();
    let r = force_at(&mut b, 0, Role::Rx, Field::ActiveErrorFlag, 7, false, Dom, 16);
    assert_eq!(r[0][0].rec, 9);
    assert_eq!(r[6][0].rec, 9);
    assert_eq!(r[7][0].rec, 17);
    assert_eq!(r[15][0].rec, 25);
}

/// Overload flag: no first-bit penalty for a receiver, the every-8th rule applies
/// (formerr_rx_8/9).
#[test]
fn formerr_rx_8_9_dominant_after_overload_flag_only_every_8th() {
    let mut b = idle_bus(2);
    b.nodes[1].request(std1(0x0AA));
    force_at(&mut b, 0, Role::Rx, Field::CrcDelimiter, 1, false, Dom, 1);
    b.nodes[1].withdraw();
    let r = force_at(&mut b, 0, Role::Rx, Field::ErrorDelimiter, 8, false, Dom, 1);
    assert!(r[0][0].has("OVL") && r[0][0].has("OLF"));
    let before = b.nodes[0].rec();
    let r = force_at(&mut b, 0, Role::Rx, Field::OverloadFlag, 7, false, Dom, 16);
    assert_eq!(r[0][0].rec, before, "no +8 for the first bit after an overload flag");
    assert_eq!(r[7][0].rec, before + 8);
    assert_eq!(r[15][0].rec, before + 16);
}

/// A receiver with a CRC error does not acknowledge and flags after ACK_Delimiter (crc_rx_1):
/// `R!` at its r0 changes its CRC; the transmitter gets an ACK error (+8); Δ REC +1.
#[test]
fn crc_rx_1_crc_error_no_ack_flag_after_ack_delimiter() {
    let mut b = idle_bus(2);
    // r0 between two dominant bits and a recessive DLC bit 1: flipping r0 at the receiver
    // changes no stuff position, only the CRC.
    b.nodes[1].request(Frame::std_data(0x123, 8, &[0x55; 8]));
    force_at(&mut b, 0, Role::Rx, Field::ReservedBits, 1, false, Rec, 1);
    assert!(b.run_to(0, Role::Rx, Field::AckSlot, 1, false, 100));
    assert!(b.nodes[0].drive(), "no ACK from a CRC-error receiver");
    let o = b.step();
    assert!(o[1].has("ACK_ERR") && o[1].has("AEF"));
    assert_eq!(o[1].tec, 8);
    let o = b.step();
    assert_eq!(o[0].label.field, Field::AckDelimiter);
    assert!(o[0].has("CRC_ERR") && o[0].has("AEF") && !o[0].has("FORM_ERR"));
    assert_eq!(o[0].rec, 1);
    b.run(8);
    assert_eq!(b.nodes[0].rec(), 1);
    run_to_tx_ok(&mut b, 1, 300);
    assert_eq!(b.nodes[0].rec(), 0);
}

/// A CRC error without any other disturbance (bit flipped at the receiver only, chosen so no
/// run of five changes): CRC_ERR at ACK_Delimiter, AEF from EOF 1.
#[test]
fn crc_error_flag_starts_after_ack_delimiter() {
    let f = Frame::std_data(0x555, 1, &[0xAA]);
    let mut b = idle_bus(2);
    b.nodes[1].request(f);
    // Data_Field 4 of 0xAA: alternating levels, a flip creates no run of five.
    force_at(&mut b, 0, Role::Rx, Field::DataField, 4, false, RxOverride::Invert, 1);
    let o = b.run_until(40, |o| o[0].events.iter().any(is_error)).unwrap();
    assert!(o[0].has("CRC_ERR") && o[0].has("AEF"));
    assert_eq!(o[0].label.field, Field::AckDelimiter);
}

/// stufferr_2 / EXC2: an `R` stuff bit inside arbitration read `D` by both nodes: the
/// transmitter gets a stuff error without TEC change, the receiver +1, no penalty after the
/// coinciding flags.
#[test]
fn stufferr_2_stuff_error_in_arbitration_exc2_tec_0_rec_1() {
    let f = find_frame(std_frames(), |b| stuff_after(b, Field::Identifier, 4, R));
    let mut b = idle_bus(2);
    b.nodes[0].request(f);
    assert!(b.run_to(0, Role::Tx, Field::Identifier, 4, true, 100));
    let r = force_many(&mut b, &[0, 1], Dom, 1);
    assert!(r[0][0].has("STUFF_ERR") && r[0][0].has("EXC2") && r[0][0].has("AEF"));
    assert!(r[0][1].has("STUFF_ERR"));
    b.nodes[0].withdraw();
    assert!(b.run_to_idle(60));
    assert_eq!(b.nodes[0].tec(), 0);
    assert_eq!(b.nodes[1].rec(), 1);
}

/// stufferr_3: `R` stuff bit after an extended frame's RTR read `D`: outside arbitration, +8.
#[test]
fn stufferr_3_stuff_after_ext_rtr_is_outside_arbitration_tec_8_rec_1() {
    let f = find_frame(ext_frames(), |b| stuff_after(b, Field::RtrBit, 1, R));
    let mut b = idle_bus(2);
    b.nodes[0].request(f);
    assert!(b.run_to(0, Role::Tx, Field::RtrBit, 1, true, 100));
    let r = force_many(&mut b, &[0, 1], Dom, 1);
    assert!(r[0][0].has("STUFF_ERR") && !r[0][0].has("EXC2"));
    assert_eq!(r[0][0].tec, 8);
    assert_eq!(r[0][1].rec, 1);
    b.nodes[0].withdraw();
    assert!(b.run_to_idle(60));
    assert_eq!((b.nodes[0].tec(), b.nodes[1].rec()), (8, 1));
}

/// stufferr_1: `D` stuff bit read `R` by both: transmitter BIT_ERR +8, receiver STUFF_ERR +1.
#[test]
fn stufferr_1_dominant_stuff_bit_read_recessive_bit_error_8_stuff_error_1() {
    let f = find_frame(std_frames(), |b| stuff_after(b, Field::Identifier, 8, D));
    let mut b = idle_bus(2);
    b.nodes[0].request(f);
    assert!(b.run_to(0, Role::Tx, Field::Identifier, 8, true, 100));
    let r = force_many(&mut b, &[0, 1], Rec, 1);
    assert!(r[0][0].has("BIT_ERR"));
    assert!(r[0][1].has("STUFF_ERR"));
    b.nodes[0].withdraw();
    assert!(b.run_to_idle(60));
    assert_eq!((b.nodes[0].tec(), b.nodes[1].rec()), (8, 1));
}

/// Stuff errors after DLC, data and CRC (stufferr_5..16 kind), both roles: +8 / +1.
#[test]
fn stufferr_outside_arbitration_all_fields_tec_8_rec_1() {
    let cases: Vec<(Field, u16, bool)> = vec![
        (Field::DataLengthCode, 4, D),
        (Field::DataLengthCode, 4, R),
        (Field::DataField, 8, D),
        (Field::DataField, 8, R),
        (Field::CrcSequence, 15, R),
        (Field::CrcSequence, 15, D),
    ];
    for (field, pos, lvl) in cases {
        let cands = (0..0x800u32).step_by(7).flat_map(|id| {
            (0..=15u8).flat_map(move |dlc| {
                [0x00u8, 0xFF, 0x0F, 0xF0, 0x55, 0x3C, 0x81, 0x7E, 0x1F, 0xE0]
                    .into_iter()
                    .map(move |d| Frame::std_data(id, dlc, &vec![d; dlc.min(8) as usize]))
            })
        });
        let f = try_find_frame(cands, |b| stuff_after(b, field, pos, lvl))
            .unwrap_or_else(|| panic!("no frame for {field:?} {pos} {lvl}"));
        let mut b = idle_bus(2);
        b.nodes[0].request(f.clone());
        assert!(b.run_to(0, Role::Tx, field, pos as u32, true, 200));
        let r = force_many(&mut b, &[0, 1], if lvl { Dom } else { Rec }, 1);
        assert!(r[0][0].has(if lvl { "STUFF_ERR" } else { "BIT_ERR" }), "{field:?} {pos} {lvl}");
        assert!(r[0][1].has("STUFF_ERR"), "{field:?} {pos} {lvl}");
        b.nodes[0].withdraw();
        assert!(b.run_to_idle(60));
        assert_eq!((b.nodes[0].tec(), b.nodes[1].rec()), (8, 1), "{field:?} {pos} {lvl} {f:?}");
        assert_eq!(b.nodes[0].state(), FaultState::ErrorActive);
    }
}
