//! Error handling through the SJA1000 registers: arbitration lost capture,
//! bus errors with error code capture, error warning, error passive,
//! bus-off and both restart paths, single shot.
mod sja1000_util;
use canstar_controller::frame::Frame;
use canstar_controller::sja1000::*;
use sja1000_util::*;

fn berr() -> CtrlMode {
    CtrlMode { berr_reporting: true, ..Default::default() }
}

/// Both nodes start the same SOF; `loser` must report ALI with `alc`.
fn arbitrate(a: &Frame, b: &Frame, loser: usize, alc: u8) {
    // node 2 holds the bus while both requests become pending, so that
    // nodes 0 and 1 start the same SOF after its intermission
    let mut n = Net::opened(3, CtrlMode::default());
    n.load(0, a);
    n.load(1, b);
    n.xmit(2, &Frame::std(0x7F0, &[0x55; 4]));
    n.run(20 * BIT);
    n.drv[0].tx_busy = true;
    n.drv[1].tx_busy = true;
    n.wr_all(&[(0, REG_CMR, CMD_TR), (1, REG_CMR, CMD_TR)]);
    n.run_until(600 * BIT, |n| !n.drv[0].tx_busy && !n.drv[1].tx_busy);
    assert_eq!(n.drv[2].tx_packets, 1);
    n.run(20 * BIT);
    assert_eq!(n.drv[loser].alc, vec![alc], "ALC of {a:?} vs {b:?}: {:?} {:x?}", n.drv[1].rx, n.drv[loser].irqs);
    assert!(n.drv[1 - loser].alc.is_empty());
    let first = Frame::std(0x7F0, &[0x55; 4]);
    assert_eq!(n.drv[1].rx, vec![first.clone(), a.clone()]);
    assert_eq!(n.drv[0].rx, vec![first.clone(), b.clone()]);
    let (w, l) = if loser == 0 { (b, a) } else { (a, b) };
    assert_eq!(n.drv[2].rx, vec![w.clone(), l.clone()], "the winner's frame first");
    // the winner's frame came first: the loser received it before sending its own
    assert!(n.drv[loser].irqs.iter().any(|i| i & IRQ_ALI != 0));
    for i in 0..2 {
        assert_eq!(n.drv[i].tx_packets, 1);
        assert_eq!(n.rd(i, REG_TXERR), 0);
    }
}

#[test]
fn sja_arbitration_lost_capture() {
    // identifier bit 11 (ID.18): code 10
    arbitrate(&Frame::std(0x123, &[1]), &Frame::std(0x122, &[2]), 0, 10);
    // identifier bit 1 (ID.28): code 0
    arbitrate(&Frame::std(0x400, &[]), &Frame::std(0x000, &[]), 0, 0);
    // standard data frame against standard remote frame, same id: RTR bit, code 11
    arbitrate(&Frame::remote(false, 0x2A5, 1), &Frame::std(0x2A5, &[7]), 0, 11);
    // extended against standard with the same base id: SRR, code 11
    arbitrate(&Frame::std(0x2A5, &[7]), &Frame::ext(0x2A5 << 18, &[8]), 1, 11);
    // extended against standard remote with the same base: IDE, code 12
    arbitrate(&Frame::remote(false, 0x2A5, 0), &Frame::ext(0x2A5 << 18, &[8]), 1, 12);
    // extended ids differing in ID.0: code 30; in ID.17: code 13
    arbitrate(&Frame::ext(0x1234_5678, &[1]), &Frame::ext(0x1234_5679, &[2]), 1, 30);
    arbitrate(&Frame::ext(0x0002_0000, &[1]), &Frame::ext(0x0000_0000, &[2]), 0, 13);
    // extended data against extended remote, same id: RTR, code 31
    arbitrate(&Frame::remote(true, 0x0ABC_DEF0, 2), &Frame::ext(0x0ABC_DEF0, &[1, 2]), 0, 31);
}

#[test]
fn sja_ack_errors_warning_passive_and_back() {
    let mut n = Net::new(2);
    n.open(0, berr());
    n.run(13 * BIT);
    // node 1 stays in reset mode: node 0 is alone and gets ACK errors
    n.xmit(0, &Frame::std(0x55, &[1, 2]));
    n.run_until(20_000 * BIT, |n| n.drv[0].state == Some(CanState::Passive));
    assert_eq!(n.drv[0].states, vec![CanState::Warning, CanState::Passive]);
    // ECC: other error (ACK), transmitting (DIR 0), segment ACK slot
    assert!(!n.drv[0].ecc.is_empty());
    for &e in &n.drv[0].ecc {
        assert_eq!(e, ECC_OTHER | 0x19, "ECC {e:#x}");
    }
    let tec = n.rd(0, REG_TXERR);
    assert_eq!(tec, 128, "exception 1 keeps TEC at 128 once passive");
    let sr = n.rd(0, REG_SR);
    assert_eq!(sr & (SR_ES | SR_BS | SR_TBS), SR_ES, "warning status, transmission pending");
    // node 1 joins: the frame is acknowledged, TEC 127: error active again (EPI)
    n.open(1, CtrlMode::default());
    n.run_until(400 * BIT, |n| n.drv[0].tx_packets == 1);
    n.run(20 * BIT);
    assert_eq!(n.drv[1].rx, vec![Frame::std(0x55, &[1, 2])]);
    assert_eq!(n.rd(0, REG_TXERR), 127);
    assert_eq!(n.drv[0].states, vec![CanState::Warning, CanState::Passive, CanState::Warning]);
    // 32 more frames bring TEC below the warning limit: EI, error active
    for k in 0..32u8 {
        n.xmit(0, &Frame::std(0x100 + k as u32, &[k]));
        n.run_until(400 * BIT, |n| !n.drv[0].tx_busy);
    }
    n.run(20 * BIT);
    assert_eq!(n.rd(0, REG_TXERR), 95);
    assert_eq!(n.drv[0].state, Some(CanState::Active));
    assert_eq!(n.rd(0, REG_SR) & SR_ES, 0);
    assert_eq!(n.drv[1].rx.len(), 33);
}

#[test]
fn sja_error_warning_limit_register() {
    let mut n = Net::new(1);
    n.open(0, berr());
    n.set_reset_mode(0);
    n.wr(0, REG_EWL, 16);
    assert_eq!(n.rd(0, REG_EWL), 16);
    n.set_normal_mode(0);
    n.run(13 * BIT);
    n.xmit(0, &Frame::std(0x55, &[]));
    n.run_until(2_000 * BIT, |n| n.drv[0].state == Some(CanState::Warning));
    assert_eq!(n.rd(0, REG_TXERR), 16, "EI at TEC = EWL");
}

#[test]
fn sja_single_shot_failure_and_abort() {
    let mut n = Net::new(2);
    n.open(0, CtrlMode { one_shot: true, berr_reporting: true, ..Default::default() });
    n.run(13 * BIT);
    n.xmit(0, &Frame::ext(0x1555_0000, &[1]));
    n.run_until(400 * BIT, |n| !n.drv[0].tx_busy);
    assert_eq!((n.drv[0].tx_errors, n.drv[0].tx_packets), (1, 0));
    assert_eq!(n.rd(0, REG_SR) & (SR_TBS | SR_TCS), SR_TBS, "released, not completed");
    n.run(200 * BIT);
    assert_eq!(n.rd(0, REG_TXERR), 8, "exactly one attempt");
    assert_eq!(n.drv[0].ecc.len(), 1);
    // single shot with a receiver: completes
    n.open(1, CtrlMode::default());
    n.run(13 * BIT);
    n.xmit(0, &Frame::std(0x7, &[1, 2, 3]));
    n.run_until(400 * BIT, |n| !n.drv[0].tx_busy);
    assert_eq!(n.drv[0].tx_packets, 1);
    assert_eq!(n.rd(0, REG_SR) & (SR_TBS | SR_TCS), SR_TBS | SR_TCS);
    // abort of a transmission that cannot start (node 1 in reset, node 0 retrying):
    // AT during the retries releases the buffer at the end of the attempt
    n.drv[0].mode.one_shot = false;
    n.set_reset_mode(1);
    n.xmit(0, &Frame::std(0x8, &[]));
    n.run(100 * BIT);
    assert_eq!(n.rd(0, REG_SR) & SR_TBS, 0);
    let tec0 = n.rd(0, REG_TXERR);
    assert!(tec0 > 8);
    n.wr(0, REG_CMR, CMD_AT);
    n.run_until(200 * BIT, |n| !n.drv[0].tx_busy);
    assert_eq!(n.rd(0, REG_SR) & (SR_TBS | SR_TCS), SR_TBS);
    let tec1 = n.rd(0, REG_TXERR);
    n.run(200 * BIT);
    assert_eq!(n.rd(0, REG_TXERR), tec1, "no attempt after the abort");
}

#[test]
fn sja_bus_off_restart_paths() {
    for path in 0..2 {
        let mut n = Net::new(2);
        n.open(0, berr());
        n.open(1, CtrlMode::default());
        n.run(13 * BIT);
        // node 0's receiver is stuck recessive: every own dominant bit is a bit error
        n.force[0] = Some(true);
        n.xmit(0, &Frame::std(0x321, &[0xAA]));
        n.run_until(5_000 * BIT, |n| n.drv[0].state == Some(CanState::BusOff));
        assert!(n.drv[0].states.contains(&CanState::Warning));
        assert!(n.drv[0].states.contains(&CanState::Passive));
        let sr = n.rd(0, REG_SR);
        assert_eq!(sr & (SR_BS | SR_ES | SR_TBS), SR_BS | SR_ES | SR_TBS, "SR {sr:#x}");
        assert_eq!(n.rd(0, REG_MOD) & MOD_RM, MOD_RM, "bus-off sets reset mode");
        assert_eq!((n.rd(0, REG_TXERR), n.rd(0, REG_RXERR)), (127, 0));
        assert!(n.drv[0].ecc.iter().all(|e| e & ECC_MASK == ECC_BIT && e & ECC_DIR == 0));
        n.force[0] = None;
        n.run(100 * BIT);
        assert_eq!(n.rd(0, REG_SR) & SR_BS, SR_BS, "stays bus-off in reset mode");
        n.drv[0].states.clear();
        if path == 0 {
            // Linux restart: TXERR/RXERR = 0 in reset mode, then normal mode
            n.start(0);
            n.run(20 * BIT);
            assert_eq!(n.rd(0, REG_SR) & (SR_BS | SR_ES), 0);
        } else {
            // clear RM only: 128 x 11 recessive bits, TXERR counts down
            n.wr(0, REG_MOD, 0);
            n.wr(0, REG_IER, 0xFF);
            n.run(600 * BIT);
            let t = n.rd(0, REG_TXERR);
            assert!(t < 127 && t > 0, "TXERR during recovery {t}");
            assert_eq!(n.rd(0, REG_SR) & SR_BS, SR_BS);
            n.run_until(1_000 * BIT, |n| n.drv[0].state == Some(CanState::Active));
            assert_eq!(n.rd(0, REG_SR) & (SR_BS | SR_ES), 0);
            assert_eq!(n.rd(0, REG_TXERR), 0);
        }
        // transmits again
        n.drv[0].tx_busy = false;
        n.xmit(0, &Frame::std(0x11, &[5]));
        n.run_until(400 * BIT, |n| !n.drv[0].tx_busy);
        n.run(20 * BIT);
        assert_eq!(n.drv[1].rx.last(), Some(&Frame::std(0x11, &[5])));
    }
}

#[test]
fn sja_bus_error_codes() {
    // a receiver that sees a stuff error: node 2 drives 6 dominant bits in node 0's frame
    let mut n = Net::new(2);
    n.open(0, berr());
    n.open(1, berr());
    n.run(13 * BIT);
    n.xmit(0, &Frame::std(0x7FF, &[0xFF; 8]));
    // inside the data field (all recessive, stuffed), jam the bus dominant for 8 bits
    n.run(40 * BIT);
    n.ext = Some(false);
    n.run(8 * BIT);
    n.ext = None;
    n.run_until(400 * BIT, |n| !n.drv[0].tx_busy);
    n.run(20 * BIT);
    // transmitter: bit error (it sent recessive), DIR = TX
    let e0 = n.drv[0].ecc[0];
    assert_eq!(e0 & (ECC_MASK | ECC_DIR), ECC_BIT, "tx ECC {e0:#x}");
    // receiver: stuff error while receiving
    let e1 = n.drv[1].ecc[0];
    assert_eq!(e1 & (ECC_MASK | ECC_DIR), ECC_STUFF | ECC_DIR, "rx ECC {e1:#x}");
    assert_eq!(e0 & ECC_SEG, 0x0A, "data field");
    assert_eq!(e1 & ECC_SEG, 0x0A, "data field");
    assert_eq!(n.drv[1].rx, vec![Frame::std(0x7FF, &[0xFF; 8])], "retransmitted");
    // ECC is frozen until read: a second error before reading is not captured
    assert_eq!(n.rd(0, REG_TXERR), 8 - 1);
}
