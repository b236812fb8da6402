//! The SJA1000 register block driven by the Linux driver's register
//! sequences, two or three nodes on one wired-AND bus.
mod sja1000_util;
use canstar_controller::frame::Frame;
use canstar_controller::sja1000::*;
use sja1000_util::*;

fn frames() -> Vec<Frame> {
    vec![
        Frame::std(0x123, &[1, 2, 3]),
        Frame::ext(0x1ABC_DEF5, &[0xDE, 0xAD, 0xBE, 0xEF, 0, 1, 2, 3]),
        Frame::remote(false, 0x7FF, 4),
        Frame::remote(true, 0x0000_0001, 15),
        Frame::std(0x000, &[]),
        Frame::data(false, 0x555, 12, &[9, 8, 7, 6, 5, 4, 3, 2]),
        Frame::data(true, 0x1555_5555, 9, &[0xFF; 8]),
    ]
}

#[test]
fn sja_reset_values_and_register_access() {
    let mut n = Net::new(1);
    assert_eq!(n.rd(0, REG_MOD), MOD_RM);
    assert_eq!(n.rd(0, REG_SR), 0x3C, "TS, RS, TCS, TBS after reset");
    assert_eq!(n.rd(0, REG_IR), 0);
    assert_eq!(n.rd(0, REG_EWL), 96);
    assert_eq!(n.rd(0, REG_CDR), 0);
    assert!(!n.int(0));
    // reset-mode registers read back
    for (a, v) in [(REG_BTR0, 0x43u8), (REG_BTR1, 0xA5), (REG_OCR, 0xDA), (REG_EWL, 17), (REG_RBSA, 0x2A)] {
        n.wr(0, a, v);
        assert_eq!(n.rd(0, a), v & if a == REG_RBSA { 0x3F } else { 0xFF });
    }
    for k in 0..8 {
        n.wr(0, REG_ACCC0 + k, 0x11 * k + 1);
    }
    for k in 0..8 {
        assert_eq!(n.rd(0, REG_ACCC0 + k), 0x11 * k + 1);
    }
    n.wr(0, REG_CDR, 0xFF);
    assert_eq!(n.rd(0, REG_CDR), 0xEF);
    // FIFO RAM and TX buffer are readable/writable in reset mode
    for k in 0..64u8 {
        n.wr(0, REG_RXFIFO + k, k ^ 0x5A);
    }
    for k in 0..64u8 {
        assert_eq!(n.rd(0, REG_RXFIFO + k), k ^ 0x5A);
    }
    for k in 0..13u8 {
        n.wr(0, REG_TXBUF + k, 0xC0 + k);
        assert_eq!(n.rd(0, REG_TXBUF + k), 0xC0 + k);
    }
    // address bit 7 is ignored
    assert_eq!(n.rd(0, 0x80 | REG_TXBUF), 0xC0);
    // operating mode: ACR/AMR locations are the TX buffer/RX window,
    // reset-mode-only registers are not writable
    n.wr(0, REG_MOD, 0);
    assert_eq!(n.rd(0, REG_MOD), 0);
    n.wr(0, REG_BTR0, 0x00);
    n.wr(0, REG_EWL, 0x99);
    assert_eq!(n.rd(0, REG_BTR0), 0x43);
    assert_eq!(n.rd(0, REG_EWL), 17);
    n.wr(0, REG_CDR, 0x00);
    assert_eq!(n.rd(0, REG_CDR), 0xE0, "only CD and clock-off writable in operating mode");
    n.wr(0, REG_FI, 0x12);
    assert_eq!(n.rd(0, REG_TXBUF), 0x12);
    // RX window = RAM from RBSA (0x2A)
    assert_eq!(n.rd(0, REG_FI), 0x2A ^ 0x5A);
    assert_eq!(n.rd(0, REG_FI + 12), (0x2A + 12) ^ 0x5A);
    // LOM/STM/AFM only change in reset mode
    n.wr(0, REG_MOD, MOD_LOM | MOD_STM | MOD_AFM);
    assert_eq!(n.rd(0, REG_MOD), 0);
    n.wr(0, REG_MOD, MOD_RM);
    n.wr(0, REG_MOD, MOD_RM | MOD_LOM | MOD_AFM);
    assert_eq!(n.rd(0, REG_MOD), MOD_RM | MOD_LOM | MOD_AFM);
    assert_eq!(n.rd(0, REG_ACCC0), 1);
}

#[test]
fn sja_linux_exchange_std_ext_remote() {
    let mut n = Net::opened(2, CtrlMode::default());
    assert_eq!(n.rd(0, REG_SR), SR_TBS | SR_TCS, "idle, bus-on, buffers free");
    let fs = frames();
    for (k, f) in fs.iter().enumerate() {
        let tx = k % 2;
        n.xmit(tx, f);
        n.run_until(200 * BIT, |n| !n.drv[tx].tx_busy && n.drv[1 - tx].rx.len() > k / 2);
        n.run(20 * BIT);
    }
    let mut got: Vec<Frame> = vec![];
    for k in 0..fs.len() {
        let rxer = 1 - k % 2;
        got.push(n.drv[rxer].rx[k / 2].clone());
    }
    assert_eq!(got, fs);
    assert_eq!(n.drv[0].tx_packets + n.drv[1].tx_packets, fs.len());
    for i in 0..2 {
        assert_eq!(n.rd(i, REG_RMC), 0);
        assert_eq!((n.rd(i, REG_TXERR), n.rd(i, REG_RXERR)), (0, 0));
        assert_eq!(n.drv[i].state, Some(CanState::Active));
        assert!(n.drv[i].ecc.is_empty());
    }
}
