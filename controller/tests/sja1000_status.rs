//! The status register's TCS bit against the SJA1000 data sheet (PeliCAN
//! status register, note on TCS): it goes to 0 when TR or SRR is written and
//! stays 0 until a transmission succeeds. Read at the moments a driver reads
//! it: right after the command, during the frame, after completion, after an
//! abort and after bus-off; RS and TS during a frame and when idle.
mod sja1000_util;
use canstar_controller::frame::Frame;
use canstar_controller::sja1000::*;
use sja1000_util::*;

#[test]
fn tcs_clears_with_the_request_and_sets_on_success() {
    let mut n = Net::opened(2, CtrlMode::default());
    assert_eq!(n.rd(0, REG_SR) & (SR_TBS | SR_TCS), SR_TBS | SR_TCS, "TCS = 1 after reset");
    for k in 0..2u8 {
        n.xmit(0, &Frame::std(0x100 + k as u32, &[k]));
        // right after the command: TBS and TCS both 0
        assert_eq!(n.rd(0, REG_SR) & (SR_TBS | SR_TCS), 0, "request {k}: right after TR");
        // during the frame
        n.wait_sr(0, SR_TS, SR_TS, 50);
        assert_eq!(n.rd(0, REG_SR) & (SR_TBS | SR_TCS), 0, "request {k}: during the frame");
        // after completion
        n.run_until(400 * BIT, |n| !n.drv[0].tx_busy);
        assert_eq!(n.drv[0].tx_packets, k as usize + 1);
        assert_eq!(n.rd(0, REG_SR) & (SR_TBS | SR_TCS), SR_TBS | SR_TCS, "request {k}: completed");
    }
    // self reception (SRR) clears it the same way and sets it on success
    n.drv[0].mode.loopback = true;
    n.xmit(0, &Frame::std(0x222, &[9]));
    assert_eq!(n.rd(0, REG_SR) & SR_TCS, 0, "right after SRR");
    n.run_until(400 * BIT, |n| !n.drv[0].tx_busy);
    assert_eq!(n.rd(0, REG_SR) & SR_TCS, SR_TCS, "SRR completed");
}

#[test]
fn tcs_stays_clear_after_an_abort_and_after_bus_off() {
    // abort: node 1 in reset mode, node 0 retries without acknowledgement
    let mut n = Net::new(2);
    n.open(0, CtrlMode::default());
    n.run(13 * BIT);
    assert_eq!(n.rd(0, REG_SR) & SR_TCS, SR_TCS);
    n.xmit(0, &Frame::std(0x8, &[]));
    n.run(100 * BIT);
    assert_eq!(n.rd(0, REG_SR) & (SR_TBS | SR_TCS), 0, "pending, retrying");
    n.wr(0, REG_CMR, CMD_AT);
    n.run_until(200 * BIT, |n| !n.drv[0].tx_busy);
    assert_eq!(n.rd(0, REG_SR) & (SR_TBS | SR_TCS), SR_TBS, "aborted: released, not completed");
    n.run(50 * BIT);
    assert_eq!(n.rd(0, REG_SR) & SR_TCS, 0, "stays 0 until a transmission succeeds");

    // bus-off: node 0's receiver stuck recessive, every own dominant bit a bit error
    let mut n = Net::new(2);
    n.open(0, CtrlMode { berr_reporting: true, ..Default::default() });
    n.open(1, CtrlMode::default());
    n.run(13 * BIT);
    n.force[0] = Some(true);
    n.xmit(0, &Frame::std(0x321, &[0xAA]));
    n.run_until(5_000 * BIT, |n| n.drv[0].state == Some(CanState::BusOff));
    let sr = n.rd(0, REG_SR);
    assert_eq!(sr & (SR_BS | SR_TBS | SR_TCS), SR_BS | SR_TBS, "bus-off: SR {sr:#x}");
    n.force[0] = None;
    // the Linux restart (reset mode, counters 0, normal mode) keeps TCS 0 ...
    n.start(0);
    n.run(20 * BIT);
    assert_eq!(n.rd(0, REG_SR) & (SR_BS | SR_TCS), 0);
    // ... until the next transmission succeeds
    n.drv[0].tx_busy = false;
    n.xmit(0, &Frame::std(0x11, &[5]));
    n.run_until(400 * BIT, |n| !n.drv[0].tx_busy);
    assert_eq!(n.rd(0, REG_SR) & (SR_TBS | SR_TCS), SR_TBS | SR_TCS);
}

#[test]
fn rs_and_ts_follow_the_frame_and_both_are_0_when_idle() {
    let mut n = Net::opened(2, CtrlMode::default());
    // idle after integration: neither receiving nor transmitting
    for i in 0..2 {
        assert_eq!(n.rd(i, REG_SR) & (SR_RS | SR_TS), 0, "node {i} idle");
    }
    n.xmit(0, &Frame::std(0x3A5, &[1, 2, 3, 4]));
    // the transmitter shows TS from Start_Of_Frame, the receiver RS, never TS
    n.wait_sr(0, SR_TS, SR_TS, 50);
    n.run(10 * BIT);
    assert_eq!(n.rd(1, REG_SR) & (SR_RS | SR_TS), SR_RS, "receiver during the frame");
    assert_eq!(n.rd(0, REG_SR) & SR_TS, SR_TS, "transmitter during the frame");
    n.run_until(400 * BIT, |n| !n.drv[0].tx_busy);
    n.run(12 * BIT);
    for i in 0..2 {
        assert_eq!(n.rd(i, REG_SR) & (SR_RS | SR_TS), 0, "node {i} idle after the frame");
    }
    // reset mode: both 1 (waiting for bus idle), as in the 0x3C after reset
    n.set_reset_mode(1);
    assert_eq!(n.rd(1, REG_SR) & (SR_RS | SR_TS), SR_RS | SR_TS, "reset mode");
}
