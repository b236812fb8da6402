//! The overload program (conformance-tests.md §10) on the bit-level harness.
mod common;
use canstar_controller::frame::Frame;
use canstar_controller::fsm::*;
use common::*;

fn ovl(b: &Bus, name: &str) {
    let x = b.last(0);
    assert!(x.has(EV_OVL) && x.has(EV_OLF), "{name}: {x:?}");
}

fn both_at(b: &mut Bus, f: Field, pos: u8, o: Ovr) {
    b.run_to(0, f, pos, 800);
    b.ovr = vec![o, o];
    b.step();
    b.ovr = vec![Ovr::None, Ovr::None];
}

#[test]
fn overload_rx_program() {
    let d = Ovr::StuckD;
    let mut b = Bus::integrated(2);
    let f = Frame::std(0x5C3, &[1, 2, 3]);
    b.request(1, &f);
    b.force_at(0, Field::Eof, 7, d, 1);
    ovl(&b, "rx_1a");
    assert_eq!(b.rx[0], vec![f.clone()]);
    b.withdraw(1);
    b.force_at(0, Field::OvlDel, 8, d, 1);
    ovl(&b, "rx_1b");
    b.force_at(0, Field::Inter, 1, d, 1);
    ovl(&b, "rx_1c");
    b.force_at(0, Field::Inter, 2, d, 1);
    ovl(&b, "rx_1d");
    b.run_idle(200);
    assert_eq!((b.tec(0), b.rec(0)), (0, 0));
    // rx_2: N2 has a request; both forced D at Intermission 3 (after a frame)
    b.request(1, &Frame::std(0x111, &[]));
    b.run_until(400, |b| b.nodes[1].tx_done.val());
    b.withdraw(1);
    b.step(); // the request handshake: tx_req low for a clock after tx_done
    let f2 = Frame::std(0x6A6, &[0x77]);
    b.request(1, &f2);
    both_at(&mut b, Field::Inter, 3, d);
    assert!(b.last(0).has(EV_SOF) && b.last(1).has(EV_SOF));
    assert!(b.nodes[1].role.val() && !b.nodes[0].role.val());
    b.run_until(400, |b| b.nodes[1].tx_done.val());
    b.withdraw(1);
    b.run_idle(100);
    assert_eq!(b.rx[0].last(), Some(&f2));
    // (N2 took N1's rx_1d overload flag in its third intermission bit as a
    // SOF and saw a stuff error: its REC is 1)
    assert_eq!((b.tec(0), b.rec(0), b.tec(1), b.rec(1)), (0, 0, 0, 1));
    // rx_3: after an error frame (ACK bit error), D at Error_Delimiter 8
    b.request(1, &Frame::std(0x222, &[5]));
    b.force_at(0, Field::AckSlot, 1, Ovr::StuckR, 1);
    b.force_at(0, Field::ErrDel, 8, d, 1);
    ovl(&b, "rx_3");
    b.run_until(400, |b| b.nodes[1].tx_done.val());
    b.withdraw(1);
}

#[test]
fn overload_tx_program() {
    let (d, r) = (Ovr::StuckD, Ovr::StuckR);
    let mut b = Bus::integrated(2);
    let f = Frame::std(0x067, &[9]); // ID 4 dominant (tx_3)
    b.request(0, &f);
    b.run_until(400, |b| b.nodes[0].tx_done.val());
    b.withdraw(0);
    b.force_at(0, Field::Inter, 1, d, 1);
    ovl(&b, "tx_1a");
    b.force_at(0, Field::OvlDel, 8, d, 1);
    ovl(&b, "tx_1b");
    b.force_at(0, Field::Inter, 2, d, 1);
    ovl(&b, "tx_1c");
    assert_eq!(b.tec(0), 0);
    b.run_idle(200);
    // tx_2: N1 has a request; both forced D at Intermission 3
    b.request(0, &f);
    b.run_until(400, |b| b.nodes[0].tx_done.val());
    b.withdraw(0);
    b.step(); // the request handshake: tx_req low for a clock after tx_done
    let f2 = Frame::std(0x066, &[8]);
    b.request(0, &f2);
    both_at(&mut b, Field::Inter, 3, d);
    assert!(b.nodes[0].role.val());
    assert_eq!(b.field(0), Field::Ident);
    b.run_until(400, |b| b.nodes[0].tx_done.val());
    b.withdraw(0);
    b.run_idle(100);
    assert_eq!(b.rx[1].last(), Some(&f2));
    assert_eq!(b.tec(0), 0);
    // tx_3: R at Identifier 4 (dominant): BIT_ERR, AEF, +8; tx_4: D at Error_Delimiter 8: OLF
    b.request(0, &f);
    b.force_at(0, Field::Ident, 4, r, 1);
    assert!(b.last(0).has(EV_BIT_ERR) && b.last(0).has(EV_AEF));
    assert_eq!(b.tec(0), 8);
    b.force_at(0, Field::ErrDel, 8, d, 1);
    ovl(&b, "tx_4");
    assert_eq!(b.tec(0), 8);
}
