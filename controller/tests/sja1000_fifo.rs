//! The 64-byte receive FIFO: message layout, RMC, RBSA, release, wrap
//! around, FIFO full and data overrun, RI as a level.
mod sja1000_util;
use canstar_controller::frame::Frame;
use canstar_controller::sja1000::*;
use sja1000_util::*;

fn send(n: &mut Net, f: &Frame) {
    n.xmit(0, f);
    n.run_until(400 * BIT, |n| !n.drv[0].tx_busy);
    n.run(4 * BIT);
}

#[test]
fn sja_fifo_layout_overrun_and_wrap() {
    let mut n = Net::opened(2, CtrlMode::default());
    // node 1's host does not service its interrupts
    n.drv[1].auto = false;
    // the raw message layout in the RX window
    send(&mut n, &Frame::data(false, 0x5A3, 10, &[1, 2, 3, 4, 5, 6, 7, 8]));
    assert!(n.int(1), "RI");
    assert_eq!(n.rd(1, REG_IR), IRQ_RI);
    assert_eq!(n.rd(1, REG_IR), IRQ_RI, "RI is a level, not cleared by reading IR");
    assert_eq!(n.rd(1, REG_RMC), 1);
    assert_eq!(n.rd(1, REG_RBSA), 0);
    let win: Vec<u8> = (0..11).map(|k| n.rd(1, REG_FI + k)).collect();
    assert_eq!(win, [0x0A, 0x5A3u32 >> 3, (0x5A3 & 7) << 5, 1, 2, 3, 4, 5, 6, 7, 8].iter().map(|x| *x as u8).collect::<Vec<_>>());
    // the same bytes in the FIFO RAM
    for k in 0..11 {
        assert_eq!(n.rd(1, REG_RXFIFO + k), win[k as usize]);
    }
    n.wr(1, REG_CMR, CMD_RRB);
    assert_eq!((n.rd(1, REG_RMC), n.rd(1, REG_RBSA)), (0, 11));
    assert_eq!(n.rd(1, REG_SR) & SR_RBS, 0);
    assert!(!n.int(1));
    // extended remote frame: 5 bytes, RTR in FI and ID4
    send(&mut n, &Frame::remote(true, 0x1234_5678, 3));
    let win: Vec<u8> = (0..5).map(|k| n.rd(1, REG_FI + k)).collect();
    assert_eq!(win, vec![0xC3, 0x91, 0xA2, 0xB3, 0xC4]);
    n.wr(1, REG_CMR, CMD_RRB);
    assert_eq!(n.rd(1, REG_RBSA), 16);
    // fill with 11-byte messages from RBSA 16: 5 fit (55 of 64 bytes), the 6th overruns
    let fs: Vec<Frame> = (0..7u8).map(|k| Frame::std(0x100 + k as u32, &[k; 8])).collect();
    for f in &fs[..5] {
        send(&mut n, f);
    }
    assert_eq!(n.rd(1, REG_RMC), 5);
    assert_eq!(n.rd(1, REG_SR) & SR_DOS, 0);
    send(&mut n, &fs[5]);
    assert_eq!(n.rd(1, REG_RMC), 5, "the message that does not fit is dropped");
    assert_eq!(n.rd(1, REG_SR) & (SR_DOS | SR_RBS), SR_DOS | SR_RBS);
    assert_eq!(n.rd(1, REG_IR), IRQ_DOI | IRQ_RI);
    assert_eq!(n.rd(1, REG_IR), IRQ_RI, "DOI cleared by the read");
    // a second overrun while DOS is set gives no new DOI
    send(&mut n, &fs[6]);
    assert_eq!(n.rd(1, REG_IR), IRQ_RI);
    // a 3-byte message still fits (9 bytes free)
    send(&mut n, &Frame::std(0x7, &[]));
    assert_eq!(n.rd(1, REG_RMC), 6);
    n.wr(1, REG_CMR, CMD_CDO);
    assert_eq!(n.rd(1, REG_SR) & SR_DOS, 0);
    // the driver reads them in order; messages wrap around the end of the RAM
    n.drv[1].auto = true;
    n.isr(1);
    let mut exp: Vec<Frame> = fs[..5].to_vec();
    exp.push(Frame::std(0x7, &[]));
    assert_eq!(n.drv[1].rx, exp);
    assert_eq!(n.rd(1, REG_RBSA), (16 + 55 + 3) % 64);
    // more traffic across the wrap
    let more: Vec<Frame> = (0..12u8).map(|k| Frame::data(k % 2 == 1, 0x3 + k as u32 * 77, k % 9, &[k ^ 0xA5; 8])).collect();
    for f in &more {
        send(&mut n, f);
    }
    assert_eq!(n.drv[1].rx[6..], more[..]);
    assert_eq!(n.drv[1].overruns, 0);
    assert_eq!(n.rd(1, REG_RMC), 0);
}

#[test]
fn sja_fifo_emptied_by_reset_mode_and_rbsa_write() {
    let mut n = Net::opened(2, CtrlMode::default());
    n.drv[1].auto = false;
    send(&mut n, &Frame::std(0x10, &[1]));
    send(&mut n, &Frame::std(0x11, &[2]));
    assert_eq!(n.rd(1, REG_RMC), 2);
    n.wr(1, REG_MOD, MOD_RM);
    assert_eq!((n.rd(1, REG_RMC), n.rd(1, REG_RBSA)), (0, 0), "reset mode empties the FIFO, RBSA kept");
    n.wr(1, REG_RBSA, 40);
    n.wr(1, REG_MOD, 0);
    n.run(13 * BIT);
    send(&mut n, &Frame::std(0x12, &[3, 4]));
    assert_eq!((n.rd(1, REG_RMC), n.rd(1, REG_RBSA)), (1, 40));
    assert_eq!(n.rd(1, REG_RXFIFO + 40), 0x02);
    assert_eq!(n.rx_one(1), Frame::std(0x12, &[3, 4]));
    assert_eq!(n.rd(1, REG_RBSA), 45);
}
