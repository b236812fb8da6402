//! Test layer for the SJA1000 register block: several `Sja1000` on one
//! clock and one wired-AND bus, a Wishbone master per node, and a host
//! driver that performs the register sequences of the Linux `sja1000`
//! driver (drivers/net/can/sja1000/sja1000.c): `set_reset_mode`,
//! `set_normal_mode`, `chipset_init`, `set_bittiming`, `start`,
//! `start_xmit`, the interrupt handler with `sja1000_rx` and `sja1000_err`.
#![allow(dead_code)]

use canstar_controller::frame::Frame;
use canstar_controller::sja1000::*;
use canstar_hdl::drive;

/// BTR0/BTR1 used by the tests: BRP 0 (2 clocks per TQ), SJW 2,
/// TSEG1 6 TQ, TSEG2 3 TQ: 10 TQ = 20 clocks per bit.
pub const BTR0: u8 = 0x40;
pub const BTR1: u8 = 0x25;
pub const BIT: usize = 20;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CanState {
    Stopped,
    Active,
    Warning,
    Passive,
    BusOff,
}

/// Linux `CAN_CTRLMODE_*` flags used by the driver.
#[derive(Clone, Copy, Debug, Default)]
pub struct CtrlMode {
    pub one_shot: bool,
    pub loopback: bool,
    pub listen_only: bool,
    pub presume_ack: bool,
    pub berr_reporting: bool,
    pub triple: bool,
}

/// What the driver reported (the netdev statistics and error frames).
#[derive(Clone, Debug, Default)]
pub struct Drv {
    pub mode: CtrlMode,
    pub state: Option<CanState>,
    pub rx: Vec<Frame>,
    pub tx_packets: usize,
    pub tx_errors: usize,
    pub overruns: usize,
    pub ecc: Vec<u8>,
    pub alc: Vec<u8>,
    pub irqs: Vec<u8>,
    pub states: Vec<CanState>,
    pub wakeups: usize,
    pub tx_busy: bool,
    pub auto: bool,
    pub counters: (u8, u8),
}

/// Another device on the bus, clocked with the nodes (e.g. the slcan top):
/// `tx` is its bus output now, `step(bus)` runs one clock with `bus` as its
/// input.
pub trait Peer {
    fn tx(&self) -> bool;
    fn step(&mut self, bus: bool);
}

pub struct Net {
    pub nodes: Vec<Box<Sja1000>>,
    pub drv: Vec<Drv>,
    /// Per-node forced RX level (None: the bus).
    pub force: Vec<Option<bool>>,
    /// An extra driver on the bus (None: recessive).
    pub ext: Option<bool>,
    pub cycle: usize,
    pub int_seen: Vec<usize>,
    /// A device stepped with the nodes (None: none).
    pub peer: Option<Box<dyn Peer>>,
}

impl Net {
    pub fn new(n: usize) -> Net {
        Self::with_reset_timing(n, 0, 0)
    }

    /// `n` controllers whose hardware reset loads `btr0`/`btr1`.
    pub fn with_reset_timing(n: usize, btr0: u8, btr1: u8) -> Net {
        let mut nodes = Vec::new();
        for _ in 0..n {
            let mut u = Box::new(Sja1000::with_reset_timing(btr0, btr1));
            drive::init(&mut *u);
            u.rx.next = true;
            u.rst.next = true;
            drive::cycle(&mut *u);
            u.rst.next = false;
            drive::cycle(&mut *u);
            nodes.push(u);
        }
        Net {
            nodes,
            drv: vec![Drv::default(); n],
            force: vec![None; n],
            ext: None,
            cycle: 0,
            int_seen: vec![0; n],
            peer: None,
        }
    }

    pub fn bus(&self) -> bool {
        self.nodes.iter().all(|n| n.tx.val()) && self.ext.unwrap_or(true) && self.peer.as_ref().map_or(true, |p| p.tx())
    }

    /// One clock of every node (no interrupt service).
    pub fn step(&mut self) {
        let bus = self.bus();
        for (i, n) in self.nodes.iter_mut().enumerate() {
            n.rx.next = self.force[i].unwrap_or(bus);
        }
        for n in self.nodes.iter_mut() {
            drive::cycle(&mut **n);
        }
        if let Some(p) = self.peer.as_mut() {
            p.step(bus);
        }
        for i in 0..self.nodes.len() {
            if !self.nodes[i].int_n.val() {
                self.int_seen[i] += 1;
            }
        }
        self.cycle += 1;
    }

    /// One Wishbone access (two clocks).
    fn access(&mut self, i: usize, we: bool, addr: u8, val: u8) -> u8 {
        {
            let n = &mut self.nodes[i];
            n.wb_cyc.next = true;
            n.wb_stb.next = true;
            n.wb_we.next = we;
            n.wb_adr.next = (addr as u64).into();
            n.wb_dat_w.next = (val as u64).into();
        }
        self.step();
        assert!(self.nodes[i].wb_ack.val(), "no ack");
        let d = self.nodes[i].wb_dat_r.val().index() as u8;
        self.step();
        let n = &mut self.nodes[i];
        assert!(!n.wb_ack.val(), "ack longer than one clock");
        n.wb_cyc.next = false;
        n.wb_stb.next = false;
        n.wb_we.next = false;
        d
    }
    /// Writes on several nodes in the same clocks.
    pub fn wr_all(&mut self, ops: &[(usize, u8, u8)]) {
        for &(i, addr, val) in ops {
            let n = &mut self.nodes[i];
            n.wb_cyc.next = true;
            n.wb_stb.next = true;
            n.wb_we.next = true;
            n.wb_adr.next = (addr as u64).into();
            n.wb_dat_w.next = (val as u64).into();
        }
        self.step();
        self.step();
        for &(i, _, _) in ops {
            let n = &mut self.nodes[i];
            n.wb_cyc.next = false;
            n.wb_stb.next = false;
            n.wb_we.next = false;
        }
    }
    /// Load the TX buffer like `start_xmit` without the command.
    pub fn load(&mut self, i: usize, f: &Frame) {
        let mut fi = f.dlc & 0x0F;
        if f.rtr {
            fi |= FI_RTR;
        }
        let id = f.id;
        let mut bytes = vec![];
        if f.ide {
            fi |= FI_FF;
            bytes.extend([fi, (id >> 21) as u8, (id >> 13) as u8, (id >> 5) as u8, (id << 3) as u8]);
        } else {
            bytes.extend([fi, (id >> 3) as u8, (id << 5) as u8]);
        }
        bytes.extend(f.data.iter().copied());
        for (k, b) in bytes.iter().enumerate() {
            self.wr(i, REG_FI + k as u8, *b);
        }
    }
    pub fn wr(&mut self, i: usize, addr: u8, val: u8) {
        self.access(i, true, addr, val);
    }
    pub fn rd(&mut self, i: usize, addr: u8) -> u8 {
        self.access(i, false, addr, 0)
    }
    pub fn int(&self, i: usize) -> bool {
        !self.nodes[i].int_n.val()
    }

    /// Run `n` clocks, servicing interrupts of nodes whose driver is active.
    pub fn run(&mut self, n: usize) {
        let end = self.cycle + n;
        while self.cycle < end {
            self.step();
            self.service();
        }
    }
    pub fn service(&mut self) {
        for i in 0..self.nodes.len() {
            if self.drv[i].auto && self.int(i) {
                self.isr(i);
            }
        }
    }
    #[track_caller]
    pub fn run_until(&mut self, max: usize, mut pred: impl FnMut(&Net) -> bool) {
        let end = self.cycle + max;
        while self.cycle < end {
            self.step();
            self.service();
            if pred(self) {
                return;
            }
        }
        panic!("condition not reached within {max} cycles");
    }

    /// Run, reading SR every bit time, until `SR & mask == want`.
    #[track_caller]
    pub fn wait_sr(&mut self, i: usize, mask: u8, want: u8, max_bits: usize) {
        for _ in 0..max_bits {
            if self.rd(i, REG_SR) & mask == want {
                return;
            }
            self.run(BIT);
        }
        panic!("SR & {mask:#x} != {want:#x} within {max_bits} bits");
    }

    // ---------------------------------------------------------------
    // The Linux driver's register sequences.

    pub fn set_reset_mode(&mut self, i: usize) {
        let mut status = self.rd(i, REG_MOD);
        self.wr(i, REG_IER, 0);
        for _ in 0..100 {
            if status & MOD_RM != 0 {
                self.drv[i].state = Some(CanState::Stopped);
                return;
            }
            self.wr(i, REG_MOD, MOD_RM);
            self.run(10);
            status = self.rd(i, REG_MOD);
        }
        panic!("setting SJA1000 into reset mode failed");
    }

    pub fn set_normal_mode(&mut self, i: usize) {
        let mut status = self.rd(i, REG_MOD);
        let m = self.drv[i].mode;
        let mut mod_reg_val = 0;
        for _ in 0..100 {
            if status & MOD_RM == 0 {
                self.drv[i].state = Some(CanState::Active);
                let ier = if m.berr_reporting { 0xFF } else { !IRQ_BEI };
                self.wr(i, REG_IER, ier);
                return;
            }
            if m.listen_only {
                mod_reg_val |= MOD_LOM;
            }
            if m.presume_ack {
                mod_reg_val |= MOD_STM;
            }
            self.wr(i, REG_MOD, mod_reg_val);
            self.run(10);
            status = self.rd(i, REG_MOD);
        }
        panic!("setting SJA1000 into normal mode failed");
    }

    pub fn chipset_init(&mut self, i: usize) {
        self.wr(i, REG_CDR, 0x48 | CDR_PELICAN);
        for k in 0..4 {
            self.wr(i, REG_ACCC0 + k, 0x00);
        }
        for k in 0..4 {
            self.wr(i, REG_ACCM0 + k, 0xFF);
        }
        self.wr(i, REG_OCR, 0xDA | 0x02);
    }

    pub fn set_bittiming(&mut self, i: usize, btr0: u8, btr1: u8) {
        self.wr(i, REG_BTR0, btr0);
        self.wr(i, REG_BTR1, btr1 | if self.drv[i].mode.triple { 0x80 } else { 0 });
    }

    pub fn start(&mut self, i: usize) {
        if self.drv[i].state != Some(CanState::Stopped) {
            self.set_reset_mode(i);
        }
        if self.rd(i, REG_CDR) & CDR_PELICAN == 0 {
            self.chipset_init(i);
        }
        self.wr(i, REG_TXERR, 0);
        self.wr(i, REG_RXERR, 0);
        self.rd(i, REG_ECC);
        self.rd(i, REG_IR);
        self.set_normal_mode(i);
        self.drv[i].tx_busy = false;
    }

    /// `open`: reset mode, bit timing, start; interrupts serviced from now on.
    pub fn open(&mut self, i: usize, mode: CtrlMode) {
        self.drv[i].mode = mode;
        self.drv[i].auto = true;
        self.set_reset_mode(i);
        self.set_bittiming(i, BTR0, BTR1);
        self.start(i);
    }

    /// All nodes opened and integrated (11 recessive bits).
    pub fn opened(n: usize, mode: CtrlMode) -> Net {
        let mut net = Net::new(n);
        for i in 0..n {
            net.open(i, mode);
        }
        net.run(13 * BIT);
        net
    }

    pub fn xmit(&mut self, i: usize, f: &Frame) {
        assert!(!self.drv[i].tx_busy, "queue stopped");
        let mut fi = f.dlc & 0x0F;
        let id = f.id;
        if f.rtr {
            fi |= FI_RTR;
        }
        let dreg;
        if f.ide {
            fi |= FI_FF;
            dreg = REG_FI + 5;
            self.wr(i, REG_FI, fi);
            self.wr(i, REG_ID1, ((id & 0x1fe00000) >> 21) as u8);
            self.wr(i, REG_ID1 + 1, ((id & 0x001fe000) >> 13) as u8);
            self.wr(i, REG_ID1 + 2, ((id & 0x00001fe0) >> 5) as u8);
            self.wr(i, REG_ID1 + 3, ((id & 0x0000001f) << 3) as u8);
        } else {
            dreg = REG_FI + 3;
            self.wr(i, REG_FI, fi);
            self.wr(i, REG_ID1, ((id & 0x000007f8) >> 3) as u8);
            self.wr(i, REG_ID1 + 1, ((id & 0x00000007) << 5) as u8);
        }
        if !f.rtr {
            for (k, b) in f.data.iter().enumerate() {
                self.wr(i, dreg + k as u8, *b);
            }
        }
        let m = self.drv[i].mode;
        let mut cmd = 0;
        if m.one_shot {
            cmd |= CMD_AT;
        }
        if m.loopback {
            cmd |= CMD_SRR;
        } else {
            cmd |= CMD_TR;
        }
        self.drv[i].tx_busy = true;
        self.wr(i, REG_CMR, cmd);
    }

    /// `sja1000_rx`: read one message from the RX window and release it.
    pub fn rx_one(&mut self, i: usize) -> Frame {
        let fi = self.rd(i, REG_FI);
        let (id, dreg) = if fi & FI_FF != 0 {
            let id = ((self.rd(i, REG_ID1) as u32) << 21)
                | ((self.rd(i, REG_ID1 + 1) as u32) << 13)
                | ((self.rd(i, REG_ID1 + 2) as u32) << 5)
                | ((self.rd(i, REG_ID1 + 3) as u32) >> 3);
            (id, REG_FI + 5)
        } else {
            let id = ((self.rd(i, REG_ID1) as u32) << 3) | ((self.rd(i, REG_ID1 + 1) as u32) >> 5);
            (id, REG_FI + 3)
        };
        let dlc = fi & 0x0F;
        let f = if fi & FI_RTR != 0 {
            Frame::remote(fi & FI_FF != 0, id, dlc)
        } else {
            let n = (dlc as usize).min(8);
            let data: Vec<u8> = (0..n).map(|k| self.rd(i, dreg + k as u8)).collect();
            Frame::data(fi & FI_FF != 0, id, dlc, &data)
        };
        self.wr(i, REG_CMR, CMD_RRB);
        f
    }

    /// `sja1000_interrupt`.
    pub fn isr(&mut self, i: usize) {
        let mut n = 0;
        loop {
            let isrc = self.rd(i, REG_IR);
            if isrc == 0 || n >= 20 {
                break;
            }
            self.drv[i].irqs.push(isrc);
            let mut status = self.rd(i, REG_SR);
            if isrc & IRQ_WUI != 0 {
                self.drv[i].wakeups += 1;
            }
            if isrc & IRQ_TI != 0 {
                if self.drv[i].mode.one_shot && status & SR_TCS == 0 {
                    self.drv[i].tx_errors += 1;
                } else {
                    self.drv[i].tx_packets += 1;
                }
                self.drv[i].tx_busy = false;
            }
            if isrc & IRQ_RI != 0 {
                while status & SR_RBS != 0 {
                    let f = self.rx_one(i);
                    self.drv[i].rx.push(f);
                    status = self.rd(i, REG_SR);
                }
            }
            if isrc & (IRQ_DOI | IRQ_EI | IRQ_BEI | IRQ_EPI | IRQ_ALI) != 0 {
                self.err(i, isrc, status);
            }
            n += 1;
        }
    }

    /// `sja1000_err`.
    fn err(&mut self, i: usize, isrc: u8, status: u8) {
        let mut state = self.drv[i].state.unwrap_or(CanState::Stopped);
        if isrc & IRQ_DOI != 0 {
            self.drv[i].overruns += 1;
            self.wr(i, REG_CMR, CMD_CDO);
        }
        if isrc & IRQ_EI != 0 {
            state = if status & SR_BS != 0 {
                CanState::BusOff
            } else if status & SR_ES != 0 {
                CanState::Warning
            } else {
                CanState::Active
            };
        }
        if isrc & IRQ_BEI != 0 {
            let ecc = self.rd(i, REG_ECC);
            self.drv[i].ecc.push(ecc);
        }
        if isrc & IRQ_EPI != 0 {
            state = if state == CanState::Passive { CanState::Warning } else { CanState::Passive };
        }
        if isrc & IRQ_ALI != 0 {
            let alc = self.rd(i, REG_ALC);
            self.drv[i].alc.push(alc & 0x1F);
        }
        let tx = self.rd(i, REG_TXERR);
        let rx = self.rd(i, REG_RXERR);
        self.drv[i].counters = (tx, rx);
        if Some(state) != self.drv[i].state {
            self.drv[i].states.push(state);
            self.drv[i].state = Some(state);
        }
    }
}
