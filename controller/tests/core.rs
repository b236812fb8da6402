//! CanCore (synchroniser + bit timing + frame state machine) on a
//! clock-level wired-AND bus.
mod common;
use canstar_controller::core::CanCore;
use canstar_controller::frame::{self, BuildOptions, Frame};
use canstar_controller::fsm::*;
use canstar_hdl::drive;
use common::core_bus::*;
use common::Ovr;

fn exchange(b: &mut CoreBus, tx: usize, f: &Frame) {
    b.request(tx, f);
    b.run_until(3000, |b| b.nodes[tx].tx_done.val());
    b.withdraw(tx);
    b.run_idle(200);
}

#[test]
fn core_frames_of_every_kind() {
    // node 1 sees the bus 1 clock late (a small propagation delay: with the
    // synchronisers and the registered TX the loop delay stays below the sample point)
    let mut b = CoreBus::integrated(2, &[0, 1]);
    let mut k = 0;
    for dlc in 0..16u8 {
        for &ide in &[false, true] {
            for &rtr in &[false, true] {
                let id = if ide { 0x0F0F0F0 ^ (dlc as u32 * 0x11111) } else { 0x0F0 ^ (dlc as u32 * 0x21) };
                let f = if rtr {
                    Frame::remote(ide, id, dlc)
                } else {
                    Frame::data(ide, id, dlc, &[0x00, 0xFF, 0x0F, 0xF0, dlc, 0x55, 0xAA, 0x00])
                };
                let tx = k % 2;
                let s = b.samples[1 - tx].len();
                exchange(&mut b, tx, &f);
                assert_eq!(b.rx[1 - tx].last(), Some(&f));
                // the receiver's sampled levels from the SOF on match the frame builder
                let exp: Vec<bool> = frame::bus_bits(&f, BuildOptions::default(), true).iter().map(|x| x.level).collect();
                let got = &b.samples[1 - tx][s..];
                let sof = got.iter().position(|x| !x).unwrap();
                assert_eq!(&got[sof..sof + exp.len()], &exp[..], "{f:?}");
                k += 1;
            }
        }
    }
    for i in 0..2 {
        assert_eq!((b.tec(i), b.rec(i)), (0, 0));
        assert!(b.events(i, EV_AEF).is_empty());
        assert_eq!(b.rx[i].len(), 32);
    }
}

#[test]
fn core_arbitration_three_nodes() {
    let mut b = CoreBus::integrated(3, &[0, 1, 1]);
    let base = 0x2A5;
    let f_std_data = Frame::std(base, &[1]);
    let f_ext = Frame::ext((base << 18) | 0x1234, &[2]);
    let f_std_remote = Frame::remote(false, base, 1);
    b.request(0, &f_ext);
    b.request(1, &f_std_remote);
    b.request(2, &f_std_data);
    b.run_until(20_000, |b| b.rx[0].len() + b.rx[1].len() + b.rx[2].len() >= 6);
    for i in 0..3 {
        b.withdraw(i);
    }
    b.run_idle(500);
    assert_eq!(b.rx[0], vec![f_std_data.clone(), f_std_remote.clone()]);
    assert_eq!(b.rx[1], vec![f_std_data.clone(), f_ext.clone()]);
    assert_eq!(b.rx[2], vec![f_std_remote.clone(), f_ext.clone()]);
    let l0 = b.events(0, EV_ARB_LOST);
    assert_eq!((l0[0].2, l0[1].2), (Field::Srr, Field::Ide));
    assert_eq!(b.events(1, EV_ARB_LOST)[0].2, Field::Rtr);
    for i in 0..3 {
        assert_eq!((b.tec(i), b.rec(i)), (0, 0));
    }
}

#[test]
fn core_ack_error_alone_and_tx_timing() {
    let mut b = CoreBus::integrated(1, &[]);
    let f = Frame::std(0x4A1, &[0xC3]);
    b.request(0, &f);
    b.run_until(3000, |b| b.nodes[0].error.val());
    let ek = b.nodes[0].err_kind.val().index();
    assert_eq!(ek, 1 << ERRK_ACK);
    assert_eq!(b.nodes[0].err_field.val().index() as u64, Field::AckSlot.code());
    assert!(b.nodes[0].err_tx.val());
    assert_eq!(b.tec(0), 8);
    // the node's own sampled bits from SOF to the ACK slot are the frame (nack)
    let exp: Vec<bool> = frame::bus_bits(&f, BuildOptions::default(), false).iter().map(|x| x.level).collect();
    let got = &b.samples[0];
    let sof = got.iter().position(|x| !x).unwrap();
    let n_ack = exp.len() - 9; // up to and including the ACK slot
    assert_eq!(&got[sof..sof + n_ack], &exp[..n_ack]);
    b.run_until(3000, |b| b.nodes[0].error.val());
    assert_eq!(b.tec(0), 16);
}

#[test]
fn core_bus_off_and_recovery() {
    let mut b = CoreBus::integrated(1, &[]);
    b.request(0, &Frame::std(0x001, &[]));
    b.ovr[0] = Ovr::StuckR;
    b.run_until(200_000, |b| b.state(0) == 2);
    b.withdraw(0);
    b.ovr[0] = Ovr::None;
    let t0 = b.cycle;
    assert!(b.tec(0) > 255);
    b.run_until(128 * 11 * 10 + 100, |b| b.state(0) == 0);
    let bits = (b.cycle - t0) as f64 / 10.0;
    assert!((bits - 128.0 * 11.0).abs() <= 2.0, "recovery took {bits} bits");
    assert_eq!((b.tec(0), b.rec(0)), (0, 0));
    assert!(!b.events(0, EV_RECOVERED).is_empty());
}

#[test]
fn core_overload_and_last_eof_bit() {
    let mut b = CoreBus::integrated(2, &[0, 1]);
    exchange(&mut b, 1, &Frame::std(0x111, &[1]));
    // force node 0's RX dominant during its End_Of_Frame bit 7
    let f = Frame::std(0x222, &[2, 3]);
    b.request(1, &f);
    b.run_until(3000, |b| b.field(0) == Field::Eof && b.nodes[0].dbg_pos.val().index() == 7);
    b.ovr[0] = Ovr::StuckD;
    b.run_until(20, |b| b.nodes[0].dbg_sample.val());
    b.step();
    b.ovr[0] = Ovr::None;
    b.withdraw(1);
    b.run_idle(500);
    assert_eq!(b.rx[0].last(), Some(&f));
    assert!(!b.events(0, EV_OLF).is_empty());
    assert!(!b.events(1, EV_OLF).is_empty(), "the transmitter answers in its intermission");
    for i in 0..2 {
        assert_eq!((b.tec(i), b.rec(i)), (0, 0));
    }
}

#[test]
fn core_config_error_holds_reset() {
    let mut c = CanCore::new();
    drive::init(&mut c);
    // PROP 1, PH1 1 -> NTQ = 1 + 1 + 1 + 2 = 5 < 8: rejected
    configure(&mut c, (0, 0, 0, 0));
    c.rx.next = true;
    c.reset.next = true;
    drive::cycle(&mut c);
    c.reset.next = false;
    c.tx_req.next = true;
    for k in 0..500 {
        c.rx.next = k % 7 != 0;
        drive::cycle(&mut c);
        assert!(c.cfg_err.val());
        assert!(c.tx.val());
        assert_eq!(c.dbg_field.val().index(), 0);
    }
}

#[test]
fn core_stuff_error_receiver_plus_9() {
    let mut b = CoreBus::integrated(2, &[]);
    let f = Frame::std(0x012, &[0x55]);
    b.request(1, &f);
    b.run_until(3000, |b| b.field(0) == Field::Ident && b.nodes[0].dbg_stuff.val());
    b.ovr[0] = Ovr::StuckD;
    b.run_until(20, |b| b.nodes[0].dbg_sample.val());
    b.step();
    b.ovr[0] = Ovr::None;
    let e = b.events(0, EV_STUFF_ERR);
    assert_eq!(e.len(), 1);
    assert!(e[0].4, "at a stuff bit");
    b.run_until(3000, |b| b.nodes[1].tx_done.val());
    b.withdraw(1);
    b.run_idle(500);
    assert_eq!(b.rx[0], vec![f]);
    assert_eq!(b.rec(0), 8, "+1 +8, then -1 for the good retry");
}

#[test]
fn core_trace_lines() {
    use canstar_controller::trace::BitTracer;
    let mut b = CoreBus::integrated(2, &[]);
    let mut tr = [BitTracer::new("D1"), BitTracer::new("D2")];
    let mut lines: [Vec<String>; 2] = [vec![], vec![]];
    let f = Frame::std(0x003, &[0xAB]);
    b.request(0, &f);
    let start = b.samples[0].len();
    for _ in 0..2000 {
        b.step();
        for i in 0..2 {
            lines[i].extend(tr[i].clock(b.cycle as u64 * 100, &*b.nodes[i]));
        }
        if b.nodes[0].tx_done.val() {
            b.withdraw(0);
        }
    }
    let bitlines = |i: usize| lines[i].iter().filter(|l| !l.contains("MSG")).count();
    // one bit line per sample strobe (after the first)
    assert!((bitlines(0) as i64 - (b.samples[0].len() - start) as i64).abs() <= 1);
    let l0 = lines[0].join("\n");
    let l1 = lines[1].join("\n");
    assert!(l0.contains("Tx_Start_Of_Frame") && l0.contains("TX_OK"), "{l0}");
    assert!(l1.contains("Rx_Identifier") && l1.contains("RX_OK"), "{l1}");
    assert!(l1.contains("MSG std data id=0x3 dlc=1 data=ab"), "{l1}");
    assert!(l0.lines().any(|l| l.contains("Tx_Identifier") && l.contains(" S ")), "stuff marker:\n{l0}");
}

/// baudrate_4 / 4b: a dominant spike seen by one idle node. Up to PROP + PH1
/// TQ long it is not sampled but hard-synchronises the node (its sample
/// points move to SP TQ after the spike's edge); one TQ longer it is a SOF.
#[test]
fn core_idle_spike_hard_sync_and_sof() {
    for len in 1..=7usize {
        let mut b = CoreBus::integrated(1, &[]);
        b.run(37); // an arbitrary phase
        let before = b.samples[0].len();
        let edge = b.cycle;
        b.ovr[0] = Ovr::StuckD;
        b.run(len);
        b.ovr[0] = Ovr::None;
        b.run(200);
        let sof = !b.events(0, EV_SOF).is_empty();
        assert_eq!(sof, len > 5, "spike of {len} TQ");
        if !sof {
            assert!(b.events(0, EV_AEF).is_empty());
            assert_eq!(b.field(0), Field::Idle);
            // the first sample after the edge is SP = 6 TQ after it (plus the
            // fixed RX latency): find the first bit record after the edge
            let first = b.bits[0].iter().find(|r| r.0 > edge).unwrap().0;
            assert_eq!(first - edge, 6 + CanCore::l_rx(canstar_controller::core::SYNC_DEPTH), "spike {len}");
        } else {
            assert_eq!(b.rec(0), 1, "a stuff error follows the SOF on a silent bus");
        }
        assert!(b.samples[0].len() > before);
    }
}

/// Other prescalers and timings, and triple sampling: frames of every kind
/// between two nodes with a small propagation delay.
#[test]
fn core_other_timings_and_triple_sampling() {
    // (fields value - 1, triple): T10/6/4 at BRP 4, T25/17/1, T10/8/1 at BRP 2, T10/6/2 triple
    let configs = [((3u64, 0u64, 3u64, 3u64), false), ((0, 7, 7, 0), false), ((1, 4, 1, 0), false), ((0, 0, 3, 1), true)];
    for (t, triple) in configs {
        let brp = t.0 as usize + 1;
        let ntq = 1 + (t.1 + 1) + (t.2 + 1) + (t.2 + 1).max(2);
        let bit = brp * ntq as usize;
        let mut b = CoreBus::with_timing(2, &[0, brp], t, triple);
        b.run(13 * bit);
        assert_eq!((b.field(0), b.field(1)), (Field::Idle, Field::Idle), "{t:?}");
        let frames = [
            Frame::std(0x000, &[0; 8]),
            Frame::ext(0x1FFF_FFFF, &[0xFF; 8]),
            Frame::remote(true, 0x0F0F0F0, 15),
            Frame::data(false, 0x555, 11, &[0x0F, 0xF0, 0x3C, 0xC3, 1, 2, 3, 4]),
        ];
        for (k, f) in frames.iter().enumerate() {
            let tx = k % 2;
            b.request(tx, f);
            b.run_until(200 * bit, |b| b.nodes[tx].tx_done.val());
            b.withdraw(tx);
            b.run_until(20 * bit, |b| b.field(0) == Field::Idle && b.field(1) == Field::Idle);
            assert_eq!(b.rx[1 - tx].last(), Some(f), "{t:?} {triple}");
        }
        for i in 0..2 {
            assert_eq!((b.tec(i), b.rec(i)), (0, 0), "{t:?} {triple}");
        }
    }
}

/// The error payload names the bit: a stuff error at the stuff bit after
/// Identifier 4 reports FIELD Identifier, POSITION 4, receiver.
#[test]
fn core_error_payload_of_a_stuff_bit() {
    let mut b = CoreBus::integrated(2, &[]);
    b.request(1, &Frame::std(0x012, &[0x55]));
    b.run_until(3000, |b| b.field(0) == Field::Ident && b.nodes[0].dbg_stuff.val());
    b.ovr[0] = Ovr::StuckD;
    b.run_until(30, |b| b.nodes[0].error.val());
    b.ovr[0] = Ovr::None;
    let n = &b.nodes[0];
    assert_eq!(n.err_kind.val().index(), 1 << ERRK_STUFF);
    assert_eq!(n.err_field.val().index() as u64, Field::Ident.code());
    assert_eq!(n.err_pos.val().index(), 4);
    assert!(!n.err_tx.val());
}
