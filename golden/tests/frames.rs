//! Frame builder, CRC and error-free delivery of every frame kind between two golden nodes.

mod util;
use canstar_golden::frame::{crc15, frame_bits, unstuffed_bits};
use canstar_golden::{Field, Frame, FrameVariant, GoldenBus, Role};
use util::*;

#[test]
fn crc15_check_value_123456789_is_0x059e() {
    let bits = b"123456789".iter().flat_map(|&c| (0..8).map(move |i| (c >> (7 - i)) & 1 == 1));
    assert_eq!(crc15(bits), 0x059E);
}

#[test]
fn crc15_matches_crc_crate_can_algorithm() {
    // crc::CRC_15_CAN works on bytes; compare on byte-aligned random-ish inputs.
    let c = crc::Crc::<u16>::new(&crc::CRC_15_CAN);
    for seed in 0u32..200 {
        let bytes: Vec<u8> = (0..(seed % 12)).map(|k| (seed.wrapping_mul(2654435761).wrapping_add(k * 97) >> 7) as u8).collect();
        let bits = bytes.iter().flat_map(|&c| (0..8).map(move |i| (c >> (7 - i)) & 1 == 1));
        assert_eq!(crc15(bits), c.checksum(&bytes), "bytes {bytes:?}");
    }
}

#[test]
fn unstuffed_lengths_44_plus_8n_and_64_plus_8n() {
    for n in 0..=8u8 {
        let d = vec![0u8; n as usize];
        // SOF..CRC plus delimiter, ACK, ACK delimiter, EOF (10 bits)
        assert_eq!(unstuffed_bits(&Frame::std_data(0x123, n, &d), FrameVariant::default()).len() + 10, 44 + 8 * n as usize);
        assert_eq!(unstuffed_bits(&Frame::ext_data(0x123, n, &d), FrameVariant::default()).len() + 10, 64 + 8 * n as usize);
    }
}

#[test]
fn stuffing_never_six_equal_bits_and_stuff_bits_marked() {
    for id in [0u32, 0x7FF, 0x555, 0x0F0] {
        let f = Frame::std_data(id, 8, &[0, 0xFF, 0, 0xFF, 0x0F, 0xF0, 0, 0]);
        let bits = frame_bits(&f, FrameVariant::default());
        let stuffed_end = bits.iter().position(|b| b.field == Field::CrcDelimiter).unwrap();
        let mut run = 0;
        let mut lvl = None;
        for b in &bits[..stuffed_end] {
            if Some(b.bit) == lvl {
                run += 1;
            } else {
                lvl = Some(b.bit);
                run = 1;
            }
            assert!(run <= 5);
        }
        assert!(bits.iter().any(|b| b.stuff));
        // A stuff bit repeats the field and position of the bit before it.
        for w in bits.windows(2) {
            if w[1].stuff {
                assert_eq!((w[0].field, w[0].pos), (w[1].field, w[1].pos));
                assert_ne!(w[0].bit, w[1].bit);
            }
        }
    }
}

#[test]
fn worst_case_lengths_135_and_160_bits() {
    // All-zero frames stuff the most (together with a suitable CRC); check the bound.
    let mut max_std = 0;
    let mut max_ext = 0;
    for id in 0..64u32 {
        let s = frame_bits(&Frame::std_data(id, 8, &[0; 8]), FrameVariant::default()).len() + 3;
        let e = frame_bits(&Frame::ext_data(id, 8, &[0; 8]), FrameVariant::default()).len() + 3;
        max_std = max_std.max(s);
        max_ext = max_ext.max(e);
    }
    assert!(max_std <= 135 && max_std > 120, "{max_std}");
    assert!(max_ext <= 160 && max_ext > 140, "{max_ext}");
}

fn all_frames() -> Vec<Frame> {
    let mut v = Vec::new();
    for dlc in 0..=15u8 {
        let n = dlc.min(8) as usize;
        let data: Vec<u8> = (0..n as u8).map(|k| k.wrapping_mul(37) ^ 0x5A ^ dlc).collect();
        v.push(Frame::std_data(0x100 + dlc as u32 * 7, dlc, &data));
        v.push(Frame::std_remote(0x7F0 - dlc as u32, dlc));
        v.push(Frame::ext_data(0x0A0C_A5A5 + dlc as u32 * 12345, dlc, &data));
        v.push(Frame::ext_remote(0x1FFF_FFFF - dlc as u32, dlc));
    }
    v
}

/// dlc_rx/dlc_tx: every frame kind (std/ext, data/remote, DLC 0..15) delivered exactly,
/// counters stay 0, no error or overload, and the bus carries exactly the built bit sequence
/// (ACK slot dominant from the receiver).
#[test]
fn every_frame_kind_delivered_counters_zero_and_wire_bits_match_builder() {
    for (tx, rx) in [(0usize, 1usize), (1, 0)] {
        let mut b = idle_bus(2);
        for f in all_frames() {
            let start = b.bit;
            b.nodes[tx].request(f.clone());
            // Record the bus from SOF to EOF 7.
            let mut wire = Vec::new();
            loop {
                let lvl = b.bus_level();
                let o = b.step();
                if !wire.is_empty() || o[tx].has("SOF") {
                    wire.push(lvl);
                }
                if o[tx].has("TX_OK") {
                    break;
                }
                assert!(b.bit - start < 400, "no TX_OK for {f:?}");
            }
            let mut expect: Vec<bool> = frame_bits(&f, FrameVariant::default()).iter().map(|x| x.bit).collect();
            let ack = frame_bits(&f, FrameVariant::default()).iter().position(|x| x.field == Field::AckSlot).unwrap();
            expect[ack] = D;
            assert_eq!(wire, expect, "wire bits of {f:?}");
            assert!(b.run_to_idle(20));
            assert_eq!(delivered(&b, rx, start), vec![f.clone()]);
            assert!(delivered(&b, tx, start).is_empty(), "own frames are not delivered (C19)");
            for n in 0..2 {
                assert!(!b.since(n, start).iter().any(|o| o.events.iter().any(is_error)), "error events for {f:?}");
                assert_eq!((b.nodes[n].tec(), b.nodes[n].rec()), (0, 0));
            }
        }
    }
}

/// Receivers accept SRR dominant and r1/r0 recessive in all combinations (C8, C9),
/// stuffbit_rx-style, with a golden test-only transmitter.
#[test]
fn srr_dominant_and_recessive_reserved_bits_are_accepted() {
    let cases = [
        (Frame::std_data(0x28F, 0, &[]), FrameVariant { r0_recessive: true, ..Default::default() }),
        (Frame::std_remote(0x28F, 0), FrameVariant { r0_recessive: true, ..Default::default() }),
        (Frame::ext_data(0x0A40_A5A5, 0, &[]), FrameVariant { srr_dominant: true, ..Default::default() }),
        (Frame::ext_data(0x0A42_A5A5, 2, &[1, 2]), FrameVariant { srr_dominant: true, r1_recessive: true, ..Default::default() }),
        (Frame::ext_data(0x1234, 1, &[9]), FrameVariant { r1_recessive: true, r0_recessive: false, ..Default::default() }),
        (Frame::ext_data(0x1234, 1, &[9]), FrameVariant { r1_recessive: false, r0_recessive: true, ..Default::default() }),
        (Frame::ext_remote(0x1234, 3), FrameVariant { r1_recessive: true, r0_recessive: true, ..Default::default() }),
    ];
    let mut b = idle_bus(2);
    for (f, v) in cases {
        let start = b.bit;
        b.nodes[1].request_variant(f.clone(), v);
        run_to_tx_ok(&mut b, 1, 300);
        assert!(b.run_to_idle(20));
        assert_eq!(delivered(&b, 0, start), vec![f.clone()], "{v:?}");
        assert_eq!(b.nodes[0].rec(), 0);
        assert_eq!(b.nodes[1].tec(), 0);
    }
}

/// Receivers label bit 12 RTR_Bit even in an extended frame; the transmitter labels it SRR_Bit.
#[test]
fn bit_12_labels_rtr_for_receiver_srr_for_extended_transmitter() {
    let mut b = idle_bus(2);
    b.nodes[0].request(Frame::ext_data(0x0155_5555, 0, &[]));
    let start = b.bit;
    run_to_tx_ok(&mut b, 0, 300);
    let tx12 = b.since(0, start).iter().find(|o| o.label.field == Field::SrrBit && !o.label.stuff).unwrap();
    assert_eq!(tx12.label.role, Role::Tx);
    let rx = b.since(1, start);
    assert!(rx.iter().any(|o| o.label.field == Field::RtrBit && o.label.role == Role::Rx));
    assert!(!rx.iter().any(|o| o.label.field == Field::SrrBit));
    assert_eq!(rx.iter().filter(|o| o.label.field == Field::RtrBit && !o.label.stuff).count(), 2);
}

#[test]
fn own_frame_not_delivered_and_single_node_gets_ack_error() {
    let mut b = GoldenBus::new(1);
    assert!(b.run_to_idle(20));
    b.nodes[0].request(std1(0x10));
    let o = b.run_until(200, |o| o[0].has("ACK_ERR")).expect("ACK error");
    assert_eq!(o[0].tec, 8);
    assert!(o[0].has("AEF"));
}
