//! Arbitration, error detection and error signalling on
//! the bit-level harness (CanFsm only). Expected values from can-protocol.md
//! §7–§14 and conformance-tests.md.
mod common;
use canstar_controller::frame::Frame;
use canstar_controller::fsm::*;
use common::*;

fn good_exchange(b: &mut Bus, tx: usize, f: &Frame) {
    b.request(tx, f);
    b.run_until(400, |b| b.nodes[tx].tx_done.val());
    b.withdraw(tx);
    b.run_idle(60);
}

#[test]
fn arbitration_three_nodes_ext_vs_std_same_base() {
    let mut b = Bus::integrated(3);
    let base = 0x2A5;
    let f_std_data = Frame::std(base, &[1]);
    let f_ext = Frame::ext((base << 18) | 0x1234, &[2]);
    let f_std_remote = Frame::remote(false, base, 1);
    b.request(0, &f_ext);
    b.request(1, &f_std_remote);
    b.request(2, &f_std_data);
    let start = b.bit;
    // all three start in the same bit; the standard data frame wins at RTR/SRR
    b.run_until(2000, |b| b.rx[1].len() + b.rx[0].len() + b.rx[2].len() >= 6);
    for i in 0..3 {
        b.withdraw(i);
    }
    b.run_idle(100);
    // delivery order at node 0: std data (node 2), std remote (node 1)
    assert_eq!(b.rx[0], vec![f_std_data.clone(), f_std_remote.clone()]);
    assert_eq!(b.rx[1], vec![f_std_data.clone(), f_ext.clone()]);
    assert_eq!(b.rx[2], vec![f_std_remote.clone(), f_ext.clone()]);
    // node 0 (ext) loses at SRR (bit 12) against the dominant RTR of node 2
    let l0 = b.events(0, EV_ARB_LOST, start);
    assert_eq!(l0[0].field, Field::Srr);
    // node 1 (std remote) loses at RTR against the data frame
    let l1 = b.events(1, EV_ARB_LOST, start);
    assert_eq!(l1[0].field, Field::Rtr);
    // second round: node 0 (ext) loses at IDE against node 1 (std remote)
    assert_eq!(l0[1].field, Field::Ide);
    for i in 0..3 {
        assert_eq!((b.tec(i), b.rec(i)), (0, 0));
        assert!(b.events(i, EV_BIT_ERR, start).is_empty() && b.events(i, EV_STUFF_ERR, start).is_empty());
    }
}

#[test]
fn arbitration_on_identifier_bits() {
    let mut b = Bus::integrated(3);
    // 0x100 vs 0x0C0 vs 0x080: node 2 (0x080) wins; node 0 loses at ID 3 (bit 8),
    // node 1 at ID 5 (bit 6)
    b.request(0, &Frame::std(0x100, &[]));
    b.request(1, &Frame::std(0x0C0, &[]));
    b.request(2, &Frame::std(0x080, &[]));
    let start = b.bit;
    b.run_until(1000, |b| b.rx[2].len() == 2);
    let l0 = b.events(0, EV_ARB_LOST, start);
    assert!(l0[0].is(Field::Ident, 3), "{:?}", l0[0]);
    let l1 = b.events(1, EV_ARB_LOST, start);
    assert!(l1[0].is(Field::Ident, 5), "{:?}", l1[0]);
    // the loser drives recessive from the next bit on (its read-back matches the winner)
    let k = l0[0].bit + 1;
    assert!(b.log[0][k].drv);
    assert_eq!(b.nodes[1].arb_lost_pos.val().index(), 5);
    assert_eq!(b.rx[0].first().unwrap().id, 0x080);
    assert_eq!(b.rx[2], vec![Frame::std(0x0C0, &[]), Frame::std(0x100, &[])]);
}

#[test]
fn ack_error_alone_on_the_bus_then_passive_exception_1() {
    let mut b = Bus::integrated(1);
    b.request(0, &Frame::std(0x123, &[0xAA]));
    let mut tecs = vec![];
    for _ in 0..18 {
        let s = b.bit;
        b.run_until(400, |b| b.nodes[0].error.val());
        let r = b.last(0).clone();
        assert!(r.has(EV_ACK_ERR) && r.is(Field::AckSlot, 1), "{r:?}");
        tecs.push(r.tec);
        if r.tec < 128 || tecs.len() < 17 {
            assert!(r.has(if tecs.len() <= 16 { EV_AEF } else { EV_PEF }), "{r:?}");
        }
        let _ = s;
    }
    let expect: Vec<u64> = (1..=16).map(|k| 8 * k).chain([128, 128]).collect();
    assert_eq!(tecs, expect);
    // the passive flag without dominant bits applies exception 1, and a suspend
    // precedes the retry
    let s = b.bit;
    b.run_until(400, |b| b.nodes[0].error.val());
    assert!(!b.events(0, EV_EXC1, s).is_empty());
    assert!(b.log[0][s..].iter().any(|r| r.field == Field::Suspend && r.pos == 8));
    assert_eq!(b.tec(0), 128);
    assert_eq!(b.state(0), 1);
}

#[test]
fn self_test_mode_needs_no_ack() {
    let mut b = Bus::integrated(1);
    b.nodes[0].self_test.next = true;
    b.request(0, &Frame::ext(0x1ABCDEF, &[1, 2, 3]));
    b.run_until(400, |b| b.nodes[0].tx_done.val());
    assert_eq!(b.tec(0), 0);
}

#[test]
fn bit_error_on_tx_at_various_fields() {
    // (field, pos, forced level, frame) with the transmitted level opposite to the force
    let f = Frame::std(0x0F5, &[0x81, 0x7E]);
    let cases: Vec<(Field, u8, Ovr)> = vec![
        (Field::Sof, 1, Ovr::StuckR),
        (Field::Ident, 1, Ovr::StuckR),     // ID bit 10 of 0x0F5 is 0
        (Field::Rtr, 1, Ovr::StuckR),       // data frame: RTR dominant
        (Field::Ide, 1, Ovr::StuckR),
        (Field::Resv, 1, Ovr::StuckR),
        (Field::Dlc, 3, Ovr::StuckD),       // DLC 2 = 0010: bit 3 recessive
        (Field::Data, 1, Ovr::StuckD),      // 0x81 MSB recessive
        (Field::Data, 2, Ovr::StuckR),
        (Field::Crc, 15, Ovr::Invert),
    ];
    for (field, pos, o) in cases {
        let mut b = Bus::integrated(2);
        b.request(0, &f);
        b.force_at(0, field, pos, o, 1);
        let r = b.last(0).clone();
        assert!(r.has(EV_BIT_ERR) && r.has(EV_AEF), "{field:?} {pos}: {r:?}");
        assert!(r.is(field, pos), "{r:?}");
        assert_eq!(r.tec, 8, "{field:?}");
        // the active flag follows
        b.step();
        assert_eq!(b.last(0).field, Field::ActFlag);
        assert!(!b.last(0).drv);
        b.withdraw(0);
        b.run_idle(100);
        // the receiver saw an error in the flag (stuff or form): REC 1
        assert_eq!(b.rec(1), 1, "{field:?}");
    }
}

#[test]
fn stuff_error_at_receiver_gives_plus_9() {
    let mut b = Bus::integrated(2);
    // SOF and ID 1..4 dominant: an R stuff bit follows ID 4
    let f = Frame::std(0x012, &[0x55]);
    b.request(1, &f);
    b.run_to_stuff(0, Field::Ident, 4, 100);
    let s = b.bit;
    b.force_bit(0, Ovr::StuckD);
    let r = b.last(0).clone();
    assert!(r.has(EV_STUFF_ERR) && r.stuff && r.has(EV_AEF), "{r:?}");
    assert_eq!(r.rec, 1);
    b.run_until(50, |b| b.field(0) == Field::ErrDel);
    assert_eq!(b.rec(0), 9);
    // the transmitter reads the flag as a dominant bit where it sends a
    // recessive identifier bit (ID 7 of 0x012): it loses arbitration, then
    // sees a stuff error as a receiver
    assert!(!b.events(1, EV_ARB_LOST, s).is_empty());
    assert_eq!((b.tec(1), b.rec(1)), (0, 1));
    // after the successful retry REC decrements
    b.run_until(400, |b| b.nodes[1].tx_done.val());
    b.withdraw(1);
    b.run_idle(50);
    assert_eq!((b.tec(1), b.rec(0), b.rec(1)), (0, 8, 1));
    assert_eq!(b.rx[0], vec![f]);
}

#[test]
fn stuff_error_in_arbitration_exception_2_and_outside() {
    // stufferr_2: R stuff bit after ID 4 (SOF, ID 1..4 dominant), forced D at both nodes
    let mut b = Bus::integrated(2);
    b.request(0, &Frame::std(0x01F, &[]));
    b.run_to_stuff(0, Field::Ident, 4, 100);
    b.ovr = vec![Ovr::StuckD, Ovr::StuckD];
    b.step();
    b.ovr = vec![Ovr::None, Ovr::None];
    let r = b.last(0).clone();
    assert!(r.has(EV_STUFF_ERR) && r.has(EV_EXC2), "{r:?}");
    assert_eq!(r.tec, 0);
    assert_eq!(b.last(1).rec, 1);
    b.withdraw(0);
    b.run_idle(100);
    assert_eq!((b.tec(0), b.rec(1)), (0, 1));
    // stufferr_3: R stuff bit after the RTR of an extended frame: +8
    let mut b = Bus::integrated(2);
    // extension ending in 1111 + RTR 0 ... choose ext id with last 4 bits 0 and data RTR 0 -> 5 D bits end at RTR
    let f = Frame::ext(0x0AAAAAB0, &[]);
    b.request(0, &f);
    b.run_to_stuff(0, Field::Rtr, 1, 200);
    b.ovr = vec![Ovr::StuckD, Ovr::StuckD];
    b.step();
    b.ovr = vec![Ovr::None, Ovr::None];
    let r = b.last(0).clone();
    assert!(r.has(EV_STUFF_ERR) && !r.has(EV_EXC2), "{r:?}");
    assert_eq!(r.tec, 8);
}

#[test]
fn overload_on_dominant_intermission_bits() {
    for pos in [1u8, 2] {
        let mut b = Bus::integrated(2);
        good_exchange(&mut b, 1, &Frame::std(0x100, &[1]));
        b.request(1, &Frame::std(0x101, &[2]));
        b.run_until(400, |b| b.nodes[1].tx_done.val());
        b.withdraw(1);
        let s = b.bit;
        b.force_at(0, Field::Inter, pos, Ovr::StuckD, 1);
        let r = b.last(0).clone();

        assert!(r.has(EV_OVL) && r.has(EV_OLF), "{r:?}");
        b.step();
        assert_eq!(b.last(0).field, Field::OvlFlag);
        b.run_idle(60);
        if pos == 1 {
            // node 1 answers with its own overload flag; no counter changes
            assert!(b.log[1][s..].iter().any(|r| r.has(EV_OLF)));
            assert_eq!((b.tec(1), b.rec(0), b.tec(0), b.rec(1)), (0, 0, 0, 0));
        } else {
            // node 0's flag starts in node 1's third intermission bit: a SOF
            // for node 1, which then sees a stuff error; node 0 tolerates
            // the dominant bits after its overload flag
            assert!(b.log[1][s..].iter().any(|r| r.has(EV_SOF) && r.field == Field::Inter));
            assert_eq!((b.rec(1), b.rec(0), b.tec(0)), (1, 0, 0));
        }
    }
}

#[test]
fn receiver_last_eof_bit_rule_and_transmitter_eof7() {
    // receiver: D at EOF 7 -> frame delivered, REC unchanged, overload
    let mut b = Bus::integrated(2);
    good_exchange(&mut b, 1, &Frame::std(0x100, &[1]));
    assert_eq!(b.rx[0].len(), 1);
    let f = Frame::std(0x200, &[9, 8]);
    b.request(1, &Frame::std(0x7F0, &[]));
    b.run_until(400, |b| b.nodes[1].tx_done.val());
    b.withdraw(1);
    b.run_idle(60);
    b.request(1, &f);
    b.force_at(0, Field::Eof, 7, Ovr::StuckD, 1);
    let r = b.last(0).clone();
    assert!(r.has(EV_RX_OK) && r.has(EV_OVL) && r.has(EV_OLF), "{r:?}");
    assert_eq!(b.rx[0].last(), Some(&f));
    b.withdraw(1);
    b.run_idle(60);
    assert_eq!((b.rec(0), b.tec(1)), (0, 0));
    // transmitter: D at EOF 7 is a form error, +8, retransmission; the receiver
    // delivers the frame twice
    let mut b = Bus::integrated(2);
    let f = Frame::std(0x300, &[7]);
    b.request(0, &f);
    b.force_at(0, Field::Eof, 7, Ovr::StuckD, 1);
    let r = b.last(0).clone();
    assert!(r.has(EV_FORM_ERR) && r.has(EV_AEF) && r.tec == 8, "{r:?}");
    b.run_until(400, |b| b.nodes[0].tx_done.val());
    b.withdraw(0);
    b.run_idle(60);
    assert_eq!(b.rx[1], vec![f.clone(), f]);
    assert_eq!(b.tec(0), 7);
}

#[test]
fn ack_slot_bit_error_at_receiver_gives_plus_9() {
    let mut b = Bus::integrated(2);
    b.request(1, &Frame::std(0x155, &[0xC3]));
    b.force_at(0, Field::AckSlot, 1, Ovr::StuckR, 1);
    let r = b.last(0).clone();
    assert!(r.has(EV_BIT_ERR) && r.rec == 1, "{r:?}");
    b.run_until(40, |b| b.field(0) == Field::ErrDel);
    assert_eq!(b.rec(0), 9);
    // the transmitter saw a form error at ACK_Delimiter
    assert!(b.log[1].iter().any(|r| r.has(EV_FORM_ERR) && r.is(Field::AckDel, 1)));
    assert_eq!(b.tec(1), 8);
}

#[test]
fn crc_error_signalled_after_ack_delimiter() {
    let mut b = Bus::integrated(3);
    // a frame with a recessive CRC bit whose flip does not touch stuffing
    let (f, bits, k) = (0..64u8)
        .find_map(|d| {
            let f = Frame::std(0x3C5, &[0x12, d]);
            let bits = canstar_controller::frame::bus_bits(&f, Default::default(), true);
            let k = (1..bits.len() - 1).find(|&k| {
            let left = bits[..k].iter().rev().take_while(|b| !b.level).count();
            let right = bits[k + 1..].iter().take_while(|b| !b.level && b.field == Field::Crc).count();
            bits[k].field == Field::Crc
                && !bits[k].stuff
                && bits[k].level
                && !bits[k - 1].level
                && !bits[k + 1].level
                && left + right < 4
            })?;
            Some((f, bits, k))
        })
        .expect("suitable CRC bit");
    b.request(1, &f);
    b.force_at(0, Field::Crc, bits[k].pos, Ovr::StuckD, 1);
    b.run_until(20, |b| b.nodes[0].error.val());
    let r = b.last(0).clone();
    assert!(r.has(EV_CRC_ERR) && r.is(Field::AckDel, 1), "{r:?}");
    // node 0 sent no ACK
    assert!(b.log[0].iter().rev().find(|r| r.field == Field::AckSlot).unwrap().drv);
    b.run_until(40, |b| b.field(0) == Field::ErrDel);
    // the other nodes see node 0's flag at End_Of_Frame 1 (form error) and
    // flag one bit later: +1 and +8 for node 0
    assert_eq!(b.rec(0), 9);
    for i in 1..3 {
        assert!(b.log[i].iter().any(|r| r.has(EV_FORM_ERR) && r.is(Field::Eof, 1)));
    }
    b.run_until(400, |b| b.nodes[1].tx_done.val());
    b.withdraw(1);
    b.run_idle(50);
    assert_eq!(b.rx[0], vec![f.clone()]);
    assert_eq!(b.rx[2], vec![f]);
}

#[test]
fn form_error_at_crc_delimiter_and_dominant_bits_after_flag() {
    let mut b = Bus::integrated(2);
    b.request(1, &Frame::std(0x0AA, &[]));
    b.force_at(0, Field::CrcDel, 1, Ovr::StuckD, 1);
    assert!(b.last(0).has(EV_FORM_ERR));
    b.run_until(40, |b| b.field(0) == Field::ErrDel);
    assert_eq!(b.rec(0), 9);
    b.withdraw(1);
    b.run_idle(60);
    // 16 dominant bits after an active error flag of a receiver: +8 (first), +8 (8th), +8 (16th)
    b.request(1, &Frame::std(0x0AA, &[]));
    b.force_at(0, Field::CrcDel, 1, Ovr::StuckD, 1);
    let r0 = b.rec(0);
    assert_eq!(r0, 10);
    b.run_until(20, |b| b.field(0) == Field::ActFlag && b.nodes[0].pos.val().index() == 7);
    b.ovr[0] = Ovr::StuckD;
    b.run(16);
    b.ovr[0] = Ovr::None;
    assert_eq!(b.rec(0), r0 + 24);
    let dafs = b.log[0].iter().rev().take(20).filter(|r| r.has(EV_DAF)).count();
    assert_eq!(dafs, 16);
}

#[test]
fn dominant_third_intermission_bit_is_sof_for_pending_transmitter() {
    let mut b = Bus::integrated(2);
    good_exchange(&mut b, 1, &Frame::std(0x100, &[1]));
    b.request(1, &Frame::std(0x101, &[2]));
    b.run_until(400, |b| b.nodes[1].tx_done.val());
    b.withdraw(1);
    let f = Frame::std(0x555, &[0x5A]);
    b.request(0, &f);
    b.run_to(0, Field::Inter, 3, 20);
    b.ovr = vec![Ovr::StuckD, Ovr::StuckD];
    b.step();
    b.ovr = vec![Ovr::None, Ovr::None];
    assert!(b.last(0).has(EV_SOF) && b.last(1).has(EV_SOF));
    b.step();
    // node 0 continues with Identifier 1 as transmitter, without its own SOF
    assert!(b.last(0).is(Field::Ident, 1) && b.last(0).role_tx);
    b.run_until(300, |b| b.nodes[0].tx_done.val());
    b.withdraw(0);
    b.run_idle(50);
    assert_eq!(b.rx[1].last(), Some(&f));
}

#[test]
fn integration_needs_11_recessive_bits() {
    let mut b = Bus::new(1);
    b.run(9);
    b.force_bit(0, Ovr::StuckD); // D at Wait_For_Bus_Idle 9 (after the reset bit)
    b.run(10);
    assert_eq!(b.field(0), Field::WaitIdle);
    b.step();
    assert_eq!(b.field(0), Field::Idle);
    assert!(b.last(0).has(EV_INTEGRATED));
}

#[test]
fn single_shot_does_not_retry() {
    let mut b = Bus::integrated(1);
    b.nodes[0].single_shot.next = true;
    b.request(0, &Frame::std(0x123, &[]));
    b.run(300);
    let sofs = b.log[0].iter().filter(|r| r.has(EV_SOF)).count();
    assert_eq!(sofs, 1);
    assert_eq!(b.tec(0), 8);
}

#[test]
fn listen_only_node_receives_silently() {
    let mut b = Bus::integrated(3);
    b.nodes[2].listen_only.next = true;
    let f = Frame::ext(0x1555AAA, &[1, 2, 3, 4]);
    good_exchange(&mut b, 0, &f);
    assert_eq!(b.rx[2], vec![f.clone()]);
    assert!(b.log[2].iter().all(|r| r.drv), "a listen-only node never drives dominant");
    // an error seen only by the listen-only node: its flag (typed as usual) is
    // not driven, so it is no bit error; counters frozen
    b.request(0, &f);
    b.force_at(2, Field::CrcDel, 1, Ovr::StuckD, 1);
    assert!(b.last(2).has(EV_FORM_ERR) && b.last(2).has(EV_AEF));
    b.run(8);
    assert!(b.log[2].iter().rev().take(8).all(|r| !r.has(EV_BIT_ERR)));
    b.run_until(400, |b| b.nodes[0].tx_done.val());
    b.withdraw(0);
    b.run_idle(60);
    assert_eq!((b.rec(2), b.tec(2)), (0, 0));
    assert!(b.log[2].iter().all(|r| r.drv));
    assert_eq!(b.rx[1].len(), 2);
    // no transmission while listening only
    b.request(2, &Frame::std(0x001, &[]));
    b.run(300);
    assert!(b.log[2].iter().all(|r| r.drv));
    assert!(b.rx[0].is_empty());
}

#[test]
fn arbitration_lost_in_extension_and_at_extended_rtr() {
    let mut b = Bus::integrated(2);
    // same base, extension differs first at Ex_Identifier 5 (bit 13)
    let e0 = (0x155 << 18) | 0x3_0000 | (1 << 13);
    let e1 = (0x155 << 18) | 0x3_0000;
    b.request(0, &Frame::ext(e0, &[]));
    b.request(1, &Frame::ext(e1, &[]));
    b.run_until(400, |b| b.nodes[1].tx_done.val());
    b.withdraw(1);
    let l = b.events(0, EV_ARB_LOST, 0);
    assert!(l[0].is(Field::ExIdent, 5), "{:?}", l[0]);
    assert_eq!(b.nodes[0].arb_lost_pos.val().index(), 13 + 5);
    b.run_until(400, |b| b.nodes[0].tx_done.val());
    b.withdraw(0);
    b.run_idle(50);
    // extended remote vs extended data, same id: loss at the extended RTR
    b.request(0, &Frame::remote(true, e1, 2));
    b.request(1, &Frame::ext(e1, &[1, 2]));
    b.run_until(400, |b| b.nodes[1].tx_done.val());
    b.withdraw(1);
    let l = b.events(0, EV_ARB_LOST, 0);
    assert!(l[1].is(Field::Rtr, 1), "{:?}", l[1]);
    assert_eq!(b.nodes[0].arb_lost_pos.val().index(), 32);
    b.run_until(400, |b| b.nodes[0].tx_done.val());
    assert_eq!(b.rx[1], vec![Frame::ext(e0, &[]), Frame::remote(true, e1, 2)]);
    assert_eq!((b.tec(0), b.rec(0), b.tec(1), b.rec(1)), (0, 0, 0, 0));
}

#[test]
fn dominant_srr_and_recessive_reserved_bits_are_accepted() {
    use canstar_controller::frame::{bus_bits, BuildOptions};
    // a scripted transmitter: node 0 reads the script through its override
    let cases = [
        (Frame::ext(0x0A40A5A5, &[0x12]), BuildOptions { srr: false, r1: false, r0: false }),
        (Frame::ext(0x0A42A5A5, &[]), BuildOptions { srr: false, r1: true, r0: true }),
        (Frame::ext(0x1234567, &[1, 2, 3]), BuildOptions { srr: true, r1: true, r0: false }),
        (Frame::std(0x28F, &[5]), BuildOptions { srr: true, r1: false, r0: true }),
        (Frame::remote(false, 0x290, 3), BuildOptions { srr: true, r1: false, r0: true }),
    ];
    let mut b = Bus::integrated(1);
    for (f, o) in cases {
        let bits = bus_bits(&f, o, true);
        for bb in &bits {
            b.ovr[0] = if bb.level { Ovr::StuckR } else { Ovr::StuckD };
            b.step();
            if bb.field == Field::AckSlot {
                assert!(!b.last(0).drv, "node 0 acknowledges {f:?}");
            }
        }
        b.ovr[0] = Ovr::None;
        b.run(4);
        assert_eq!(b.rx[0].last(), Some(&f));
        assert_eq!(b.rec(0), 0);
        assert!(b.log[0].iter().all(|r| !r.has(EV_AEF) && !r.has(EV_PEF)));
    }
}
