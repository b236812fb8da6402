//! Bus timing 0/1 with every field width of the SJA1000: BRP 0..63 (TQ =
//! 2·(BRP+1) clocks, up to 128), TSEG1 up to 16 TQ, TSEG2 1..8 TQ, observed
//! on the bus between two controllers: the transmitter's bit time and sample
//! point measured in clocks, and the frame received.
mod sja1000_util;
use canstar_controller::frame::Frame;
use canstar_controller::sja1000::*;
use sja1000_util::*;

/// (BTR0, BTR1, clocks per TQ, TQ per bit, sample point in TQ from the
/// start of the bit as the block applies it).
fn case(btr0: u8, btr1: u8) -> (usize, usize, usize) {
    let tq = 2 * ((btr0 & 0x3F) as usize + 1);
    let t1 = (btr1 & 0x0F) as usize + 1;
    let t2 = ((btr1 >> 4) & 7) as usize + 1;
    (tq, 1 + t1 + t2, 1 + t1)
}

/// Run one frame from node 0 to node 1 with `btr0`/`btr1` on both and check
/// the bit time (every interval between the transmitter's TX edges, SOF to
/// CRC delimiter, is a multiple of it, and single bits occur) and the sample
/// point (every sample strobe of the transmitter in that range lies
/// `sp` TQ after the start of its bit).
fn check(btr0: u8, btr1: u8, sp_tq: usize) {
    let (tq, ntq, _) = case(btr0, btr1);
    let bit = tq * ntq;
    let mut n = Net::new(2);
    for i in 0..2 {
        n.drv[i].auto = true;
        n.set_reset_mode(i);
        n.set_bittiming(i, btr0, btr1);
        n.start(i);
        assert_eq!((n.rd(i, REG_BTR0), n.rd(i, REG_BTR1)), (btr0, btr1));
        assert!(!n.nodes[i].core().cfg_err.val(), "accepted");
    }
    n.run(13 * bit);
    let f = Frame::std(0x555, &[0xA5]);
    n.xmit(0, &f);
    n.drv[0].auto = false;
    n.drv[1].auto = false;
    let start = n.cycle;
    let mut prev = n.nodes[0].tx.val();
    let mut last_edge: Option<usize> = None;
    let mut widths = vec![];
    let mut offsets = vec![];
    while !(n.int(0) && n.int(1)) {
        n.step();
        assert!(n.cycle - start < 120 * bit, "frame not done");
        let c = n.nodes[0].core();
        let field = c.dbg_field.val().index();
        let in_frame = (4..=14).contains(&field);
        let tx = n.nodes[0].tx.val();
        if tx != prev {
            if let (Some(l), true) = (last_edge, in_frame) {
                widths.push(n.cycle - l);
            }
            last_edge = if in_frame { Some(n.cycle) } else { None };
            prev = tx;
        }
        if c.dbg_sample.val() && in_frame {
            if let Some(l) = last_edge {
                offsets.push((n.cycle - l) % bit);
            }
        }
    }
    n.drv[0].auto = true;
    n.drv[1].auto = true;
    n.service();
    n.run(5 * bit);
    assert_eq!(n.drv[1].rx, vec![f], "received");
    assert_eq!(n.drv[0].tx_packets, 1);
    assert!(widths.len() > 10 && offsets.len() > 30, "{widths:?} {offsets:?}");
    assert!(widths.iter().all(|w| w % bit == 0), "BTR {btr0:#x}/{btr1:#x}: bit {bit} clocks, edges {widths:?}");
    assert!(widths.contains(&bit));
    assert!(
        offsets.iter().all(|&o| o == sp_tq * tq),
        "BTR {btr0:#x}/{btr1:#x}: sample point {} clocks expected, got {offsets:?}",
        sp_tq * tq
    );
}

#[test]
fn sja_timing_large_prescaler_and_tseg1_16() {
    // BRP 63 (128 clocks per TQ), TSEG1 16, TSEG2 3: 20 TQ, SP 17 TQ
    check(0x3F, 0x2F, 17);
}

#[test]
fn sja_timing_exact_settings() {
    // BRP 17 (36 clocks), SJW 3, TSEG1 16, TSEG2 8: 25 TQ, SP 17
    check(0x91, 0x7F, 17);
    // BRP 16 (34 clocks, beyond the old 5-bit prescaler), TSEG1 5, TSEG2 2
    check(0x10, 0x14, 6);
    // BRP 1, BTR1 0x1C (TSEG1 13, TSEG2 2): 16 TQ, SP 87.5 %, now exact
    check(0x01, 0x1C, 14);
}

/// Settings that used to be approximations (PH2 was max(PH1, 2)) are exact.
#[test]
fn sja_timing_tseg2_1_and_short_tseg1_are_exact() {
    // 24 MHz, 500 kbit/s, 87.5 % (can-calc-bit-timing's choice for an
    // SJA1000 on 24 MHz): BRP 2 (6 clocks), TSEG1 6, TSEG2 1: 8 TQ, SP 7
    check(0x02, 0x05, 7);
    // BRP 32 (66 clocks), TSEG1 16, TSEG2 1: 18 TQ, SP 17
    check(0x20, 0x0F, 17);
    // TSEG1 <= TSEG2: TSEG1 6, TSEG2 6: 13 TQ, SP 7
    check(0x00, 0x55, 7);
}

#[test]
fn sja_timing_under_8_tq_is_rejected() {
    // TSEG1 3, TSEG2 2: 6 TQ; the core stays inert (TS = RS = 1, TX recessive)
    let mut n = Net::new(1);
    n.set_reset_mode(0);
    n.set_bittiming(0, 0x00, 0x12);
    n.start(0);
    assert!(n.nodes[0].core().cfg_err.val());
    n.wr(0, REG_FI, 0);
    n.wr(0, REG_FI + 1, 0x12);
    n.wr(0, REG_FI + 2, 0);
    n.wr(0, REG_CMR, CMD_TR);
    for _ in 0..400 {
        n.step();
        assert!(n.nodes[0].tx.val());
    }
    assert_eq!(n.rd(0, REG_SR) & (SR_TS | SR_RS | SR_TBS), SR_TS | SR_RS);
    // TSEG1 = 0 (a sample point 2 TQ after the bit start) is refused too
    n.set_reset_mode(0);
    n.set_bittiming(0, 0x00, 0x70);
    n.start(0);
    assert!(n.nodes[0].core().cfg_err.val());
}
