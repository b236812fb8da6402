//! TXERR/RXERR written in reset mode (SJA1000 data sheet, registers TXERR and RXERR): the core
//! continues from the written values when reset mode is left; the error
//! state (warning, passive, bus-off) and its status bits and interrupts
//! follow from them then; 255 in TXERR is a CPU-driven bus-off; a TXERR write
//! while bus-off ends it; RXERR writes while bus-off have no effect.
mod sja1000_util;
use canstar_controller::frame::Frame;
use canstar_controller::sja1000::*;
use sja1000_util::*;

/// Two opened nodes; node 0's interrupts are serviced by the test itself.
fn pair() -> Net {
    let mut n = Net::opened(2, CtrlMode::default());
    n.drv[0].auto = false;
    n
}

/// Node 0 into reset mode with every interrupt enabled and IR cleared.
fn reset_mode_irq(n: &mut Net) {
    n.wr(0, REG_MOD, MOD_RM);
    n.wr(0, REG_IER, 0xFF);
    n.rd(0, REG_IR);
    assert!(!n.int(0));
}

fn core_state(n: &Net, i: usize) -> u64 {
    n.nodes[i].core().state.val().index() as u64
}

#[test]
fn sja_txerr_write_makes_error_passive() {
    let mut n = pair();
    reset_mode_irq(&mut n);
    n.wr(0, REG_TXERR, 130);
    assert_eq!(n.rd(0, REG_TXERR), 130);
    assert_eq!(core_state(&n, 0), 1, "the core is error-passive from the loaded value");
    assert_eq!(n.rd(0, REG_SR) & (SR_ES | SR_BS), 0, "status bits follow only when reset mode is left");
    assert!(!n.int(0));
    n.wr(0, REG_MOD, 0);
    assert_eq!(n.rd(0, REG_MOD) & MOD_RM, 0);
    assert_eq!(n.rd(0, REG_SR) & (SR_ES | SR_BS), SR_ES);
    assert_eq!(n.rd(0, REG_IR), IRQ_EI | IRQ_EPI, "warning and passive reached");
    assert_eq!(n.rd(0, REG_TXERR), 130);
    // error-passive behaviour: alone on the bus (node 1 in reset mode) the
    // ACK errors give passive flags, and TEC does not grow (exception 1)
    n.set_reset_mode(1);
    n.load(0, &Frame::std(0x65, &[1]));
    n.wr(0, REG_CMR, CMD_TR);
    n.run(300 * BIT);
    assert_eq!(n.rd(0, REG_TXERR), 130, "passive ACK errors do not count");
    let ecc = n.rd(0, REG_ECC);
    assert_eq!(ecc, ECC_OTHER | 0x19, "ACK error captured");
    assert_eq!(n.rd(0, REG_SR) & SR_TBS, 0, "still retrying");
    // with node 1 back the frame goes through: 129, then two more frames: 127,
    // error active again (EPI), still warning
    n.start(1);
    n.wait_sr(0, SR_TBS, SR_TBS, 400);
    n.run(20 * BIT);
    assert_eq!(n.rd(0, REG_TXERR), 129);
    n.rd(0, REG_IR);
    for k in 0..2u8 {
        n.load(0, &Frame::std(0x70 + k as u32, &[k]));
        n.wr(0, REG_CMR, CMD_TR);
        n.wait_sr(0, SR_TBS, SR_TBS, 400);
    }
    n.run(20 * BIT);
    assert_eq!(n.rd(0, REG_TXERR), 127);
    assert_eq!(core_state(&n, 0), 0);
    assert_eq!(n.rd(0, REG_IR) & (IRQ_EPI | IRQ_EI), IRQ_EPI, "back to error active, still warning");
    assert_eq!(n.rd(0, REG_SR) & SR_ES, SR_ES);
    assert_eq!(n.drv[1].rx.len(), 3);
}

#[test]
fn sja_rxerr_write_makes_error_passive() {
    let mut n = pair();
    reset_mode_irq(&mut n);
    n.wr(0, REG_RXERR, 128);
    assert_eq!(n.rd(0, REG_RXERR), 128);
    n.wr(0, REG_MOD, 0);
    assert_eq!(n.rd(0, REG_IR), IRQ_EI | IRQ_EPI);
    assert_eq!(core_state(&n, 0), 1);
    // a received frame brings REC to 127 (C11): error active again; the interrupt
    // (EPI) comes at the ACK slot (C13, ISO rule), RI 8 bits later at End_Of_Frame 7
    n.xmit(1, &Frame::std(0x123, &[9, 8]));
    n.run_until(400 * BIT, |n| n.int(0));
    n.run(10 * BIT);
    assert_eq!(n.rd(0, REG_RXERR), 127);
    assert_eq!(n.rd(0, REG_IR) & (IRQ_EPI | IRQ_RI), IRQ_EPI | IRQ_RI);
    assert_eq!(core_state(&n, 0), 0);
    assert_eq!(n.rx_one(0), Frame::std(0x123, &[9, 8]));
}

/// Node 0 after TXERR = 255 in reset mode and leaving reset mode: bus-off.
fn cpu_bus_off() -> Net {
    let mut n = pair();
    reset_mode_irq(&mut n);
    n.wr(0, REG_TXERR, 255);
    assert_eq!(n.rd(0, REG_TXERR), 255);
    assert_eq!(n.rd(0, REG_SR) & (SR_BS | SR_ES), 0, "no bus-off before reset mode is left");
    assert!(!n.int(0));
    n.wr(0, REG_MOD, 0);
    // the bus-off event: reset mode again, TXERR 127, RXERR 0, BS, ES, EI
    assert_eq!(n.rd(0, REG_MOD) & MOD_RM, MOD_RM, "bus-off sets reset mode");
    assert_eq!(n.rd(0, REG_SR) & (SR_BS | SR_ES), SR_BS | SR_ES);
    assert_eq!(n.rd(0, REG_IR), IRQ_EI);
    assert_eq!((n.rd(0, REG_TXERR), n.rd(0, REG_RXERR)), (127, 0));
    assert_eq!(core_state(&n, 0), 2);
    n
}

#[test]
fn sja_txerr_255_is_a_cpu_driven_bus_off() {
    let mut n = cpu_bus_off();
    // bus-off holds in reset mode: node 0 neither acknowledges nor counts
    n.run(100 * BIT);
    assert_eq!(n.rd(0, REG_TXERR), 127);
    assert_eq!(n.rd(0, REG_SR) & SR_BS, SR_BS);
    // clearing RM starts the recovery: 128 x 11 recessive bits, TXERR counts down
    n.wr(0, REG_MOD, 0);
    n.run(600 * BIT);
    let t = n.rd(0, REG_TXERR);
    assert!(t > 0 && t < 127, "TXERR during recovery {t}");
    assert_eq!(n.rd(0, REG_SR) & SR_BS, SR_BS);
    n.wait_sr(0, SR_BS, 0, 1_000);
    assert_eq!(n.rd(0, REG_SR) & (SR_BS | SR_ES), 0);
    assert_eq!(n.rd(0, REG_IR) & IRQ_EI, IRQ_EI);
    assert_eq!((n.rd(0, REG_TXERR), n.rd(0, REG_RXERR)), (0, 0));
    assert_eq!(core_state(&n, 0), 0);
    // and transmits again
    n.load(0, &Frame::std(0x42, &[4, 2]));
    n.wr(0, REG_CMR, CMD_TR);
    n.wait_sr(0, SR_TBS, SR_TBS, 400);
    n.run(20 * BIT);
    assert_eq!(n.drv[1].rx, vec![Frame::std(0x42, &[4, 2])]);
}

#[test]
fn sja_txerr_write_ends_bus_off() {
    let mut n = cpu_bus_off();
    // RXERR writes have no effect while bus-off
    n.wr(0, REG_RXERR, 50);
    assert_eq!(n.rd(0, REG_RXERR), 0);
    // a TXERR write (0..254) clears BS at once
    n.wr(0, REG_TXERR, 40);
    assert_eq!(n.rd(0, REG_SR) & SR_BS, 0);
    assert_eq!(n.rd(0, REG_MOD) & MOD_RM, MOD_RM, "still in reset mode");
    assert_eq!(n.rd(0, REG_TXERR), 40);
    assert_eq!(core_state(&n, 0), 0);
    n.wr(0, REG_RXERR, 3);
    assert_eq!(n.rd(0, REG_RXERR), 3, "writable again");
    n.rd(0, REG_IR);
    n.wr(0, REG_MOD, 0);
    assert_eq!(n.rd(0, REG_MOD) & MOD_RM, 0);
    assert_eq!(n.rd(0, REG_SR) & (SR_ES | SR_BS), 0);
    assert_eq!(n.rd(0, REG_IR), IRQ_EI, "ES cleared when reset mode was left");
    assert_eq!((n.rd(0, REG_TXERR), n.rd(0, REG_RXERR)), (40, 3));
    // only 11 recessive bits to wait, then a frame: TEC 39
    n.load(0, &Frame::std(0x43, &[]));
    n.wr(0, REG_CMR, CMD_TR);
    n.wait_sr(0, SR_TBS, SR_TBS, 100);
    n.run(20 * BIT);
    assert_eq!(n.rd(0, REG_TXERR), 39);
    assert_eq!(n.drv[1].rx, vec![Frame::std(0x43, &[])]);
}

#[test]
fn sja_linux_restart_after_cpu_bus_off() {
    // the driver's restart (reset mode, TXERR = RXERR = 0, normal mode) ends
    // the CPU-driven bus-off like an error-driven one
    let mut n = cpu_bus_off();
    n.drv[0].auto = true;
    n.drv[0].state = Some(CanState::BusOff);
    n.start(0);
    n.run(20 * BIT);
    assert_eq!(n.rd(0, REG_SR) & (SR_BS | SR_ES), 0);
    assert_eq!((n.rd(0, REG_TXERR), n.rd(0, REG_RXERR)), (0, 0));
    n.xmit(0, &Frame::std(0x44, &[1]));
    n.run_until(400 * BIT, |n| !n.drv[0].tx_busy);
    n.run(20 * BIT);
    assert_eq!(n.drv[1].rx, vec![Frame::std(0x44, &[1])]);
}

/// The counter-load port of `CanCore` the block uses, on its own: a load
/// with TEC >= 256 is a bus-off (Bus_Off field, automatic recovery after
/// 128 x 11 recessive bits), a load below 256 while bus-off leaves it for
/// the 11-bit integration, REC >= 128 is error-passive; outside reset too.
#[test]
fn core_counter_load_port() {
    use canstar_controller::core::CanCore;
    use canstar_hdl::drive;
    let mut c = CanCore::new();
    drive::init(&mut c);
    // 1 clock per TQ, PROP 1, PH1 4: 10 clocks per bit
    c.brp.next = 0u64.into();
    c.prop.next = 0u64.into();
    c.ph1.next = 3u64.into();
    c.ph2.next = 3u64.into();
    c.sjw.next = 0u64.into();
    c.rx.next = true;
    let clk = |c: &mut CanCore, k: usize| {
        for _ in 0..k {
            c.rx.next = c.tx.val();
            drive::cycle(c);
        }
    };
    // loaded under reset: kept when reset is released
    c.reset.next = true;
    c.cnt_load.next = true;
    c.tec_in.next = 300u64.into();
    c.rec_in.next = 5u64.into();
    clk(&mut c, 3);
    c.reset.next = false;
    c.cnt_load.next = false;
    clk(&mut c, 1);
    assert_eq!((c.tec.val().index(), c.rec.val().index(), c.state.val().index()), (300, 5, 2));
    clk(&mut c, 30);
    assert_eq!(c.dbg_field.val().index(), 3, "Bus_Off");
    assert!(c.tx.val(), "recessive while bus-off");
    // automatic recovery: 128 x 11 recessive bits
    clk(&mut c, 128 * 11 * 10 + 200);
    assert_eq!((c.tec.val().index(), c.rec.val().index(), c.state.val().index()), (0, 0, 0));
    // outside reset: bus-off again, then a load below 256 ends it
    c.cnt_load.next = true;
    c.tec_in.next = 256u64.into();
    c.rec_in.next = 0u64.into();
    clk(&mut c, 1);
    c.cnt_load.next = false;
    clk(&mut c, 40);
    assert_eq!((c.state.val().index(), c.dbg_field.val().index()), (2, 3));
    c.cnt_load.next = true;
    c.tec_in.next = 10u64.into();
    c.rec_in.next = 200u64.into();
    clk(&mut c, 1);
    c.cnt_load.next = false;
    clk(&mut c, 1);
    assert_eq!((c.tec.val().index(), c.rec.val().index(), c.state.val().index()), (10, 200, 1));
    assert_eq!(c.dbg_field.val().index(), 1, "Wait_For_Bus_Idle");
    clk(&mut c, 13 * 10);
    assert_eq!(c.dbg_field.val().index(), 2, "Bus_Idle after 11 recessive bits");
    assert_eq!((c.tec.val().index(), c.rec.val().index()), (10, 200));
}
