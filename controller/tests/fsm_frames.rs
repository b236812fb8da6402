//! Frame exchange on the bit-level harness (CanFsm only).
mod common;
use canstar_controller::frame::{self, BuildOptions, Frame};
use canstar_controller::fsm::*;
use common::*;

fn send_and_check(b: &mut Bus, tx: usize, f: &Frame) {
    let start = b.bit;
    b.request(tx, f);
    b.run_until(400, |b| b.nodes[tx].tx_done.val());
    b.withdraw(tx);
    b.run_idle(50);
    // bus bits between SOF and EOF 7 match the builder
    let sof = b.log[tx].iter().position(|r| r.bit >= start && r.has(EV_SOF)).unwrap();
    let expect = frame::bus_bits(f, BuildOptions::default(), true);
    let got: Vec<bool> = b.bus_log[sof..sof + expect.len()].to_vec();
    let exp_lv: Vec<bool> = expect.iter().map(|x| x.level).collect();
    assert_eq!(got, exp_lv, "bus bits of {f:?}");
    // field/pos/stuff annotations of the transmitter match the builder
    for (k, e) in expect.iter().enumerate() {
        let r = &b.log[tx][sof + k];
        assert_eq!((r.field, r.pos, r.stuff), (e.field, e.pos, e.stuff), "bit {k} of {f:?}");
    }
    for i in 0..b.nodes.len() {
        if i != tx {
            assert_eq!(b.rx[i].last(), Some(f), "node {i} delivery");
        }
        assert_eq!((b.tec(i), b.rec(i)), (0, 0), "node {i} counters");
        assert!(b.events(i, EV_BIT_ERR, start).is_empty());
    }
}

#[test]
fn all_kinds_of_frames_between_two_nodes() {
    let mut b = Bus::integrated(2);
    let mut n = 0;
    for dlc in 0..16u8 {
        for &ide in &[false, true] {
            let id = if ide { 0x1234567 ^ (dlc as u32 * 0x10101) } else { 0x5A5 ^ dlc as u32 };
            let data: Vec<u8> = (0..8).map(|k| (k as u8 * 37) ^ (dlc * 11)).collect();
            let f = Frame::data(ide, id & if ide { 0x1FFF_FFFF } else { 0x7FF }, dlc, &data);
            send_and_check(&mut b, n % 2, &f);
            let r = Frame::remote(ide, f.id, dlc);
            send_and_check(&mut b, (n + 1) % 2, &r);
            n += 1;
        }
    }
    assert_eq!(b.rx[0].len() + b.rx[1].len(), 64);
}

#[test]
fn heavy_stuffing_frames() {
    let mut b = Bus::integrated(3);
    let frames = [
        Frame::std(0x000, &[0; 8]),
        Frame::std(0x7FF, &[0xFF; 8]),
        Frame::ext(0, &[0; 8]),
        Frame::ext(0x1FFF_FFFF, &[0xFF; 8]),
        Frame::std(0x0F0, &[0x0F, 0x83, 0xE0, 0xF8, 0x3E]),
        Frame::remote(true, 0x1F07C1F, 15),
    ];
    for (k, f) in frames.iter().enumerate() {
        assert!(frame::stuff_count(f) > 0);
        send_and_check(&mut b, k % 3, f);
    }
}
