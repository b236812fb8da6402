//! The environment of SJA1000 controllers under test: a wired-AND bus (disturbed now
//! and then) and, per controller, a host that runs a driver-like register program at
//! random through Wishbone: configuration in reset mode (filters, counters, modes),
//! transmissions (normal, single-shot, self-reception), interrupt service with RX
//! FIFO reads and releases, status and error-capture reads, and now and then a write
//! of a random register or a read of any address (FIFO window, TX buffer).
//!
//! Per clock: `inputs(i, out)` for every controller (its last outputs), then every
//! controller steps, then `advance(outs)` with the new outputs of all of them.

use std::collections::VecDeque;

use canstar_controller::sja1000::*;
use canstar_rtlc::rt::Model;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

#[derive(Clone, Copy, Debug)]
pub enum Op {
    W(u8, u8),
    R(u8),
}

/// Input indices of the Wishbone and CAN ports.
pub struct Ix {
    pub rst: usize,
    pub cyc: usize,
    pub stb: usize,
    pub we: usize,
    pub adr: usize,
    pub dat: usize,
    pub rx: usize,
    pub ack: usize,
    pub dat_r: usize,
    pub tx: usize,
    pub int_n: usize,
}

impl Ix {
    pub fn of(m: &dyn Model) -> Ix {
        let i = |n: &str| m.input_index(n).unwrap_or_else(|| panic!("no input {n}"));
        let o = |n: &str| m.output_index(n).unwrap_or_else(|| panic!("no output {n}"));
        Ix { rst: i("rst"), cyc: i("wb_cyc"), stb: i("wb_stb"), we: i("wb_we"), adr: i("wb_adr"), dat: i("wb_dat_w"), rx: i("rx"), ack: o("wb_ack"), dat_r: o("wb_dat_r"), tx: o("tx"), int_n: o("int_n") }
    }
}

/// A host: a queue of register accesses, one Wishbone access (two clocks) at a time.
pub struct Host {
    pub v: Vec<u128>,
    ops: VecDeque<Op>,
    active: bool,
    gap: u32,
    pub reads: u64,
    last: Option<Op>,
    /// How often each interrupt bit was read set in IR.
    pub irq: [u64; 8],
}

impl Host {
    pub fn new(n_in: usize, ix: &Ix) -> Host {
        let mut v = vec![0u128; n_in];
        v[ix.rst] = 1;
        v[ix.rx] = 1;
        let mut ops = VecDeque::new();
        // power-up configuration as the Linux driver does it
        ops.extend([
            Op::W(REG_MOD, MOD_RM),
            Op::W(REG_CDR, 0x48 | CDR_PELICAN),
            Op::W(REG_ACCC0, 0),
            Op::W(REG_ACCC0 + 1, 0),
            Op::W(REG_ACCC0 + 2, 0),
            Op::W(REG_ACCC0 + 3, 0),
            Op::W(REG_ACCM0, 0xff),
            Op::W(REG_ACCM0 + 1, 0xff),
            Op::W(REG_ACCM0 + 2, 0xff),
            Op::W(REG_ACCM0 + 3, 0xff),
            Op::W(REG_OCR, 0xda),
            Op::W(REG_BTR0, 0x40),
            Op::W(REG_BTR1, 0x25),
            Op::W(REG_IER, 0xff),
            Op::W(REG_MOD, 0),
        ]);
        Host { v, ops, active: false, gap: 0, reads: 0, last: None, irq: [0; 8] }
    }

    fn program(&mut self, rng: &mut ChaCha8Rng, int: bool) {
        let ops = &mut self.ops;
        let r = rng.gen_range(0..1000);
        if int && r < 600 {
            // interrupt service: IR, SR, one message from the FIFO window, release
            ops.extend([Op::R(REG_IR), Op::R(REG_SR), Op::R(REG_ECC), Op::R(REG_ALC), Op::R(REG_RMC)]);
            for k in 0..13 {
                ops.push_back(Op::R(REG_FI + k));
            }
            ops.push_back(Op::W(REG_CMR, CMD_RRB));
            if rng.gen_bool(0.1) {
                ops.push_back(Op::W(REG_CMR, CMD_CDO));
            }
        } else if r < 620 {
            // a transmission
            let ide = rng.gen_bool(0.4);
            let rtr = rng.gen_bool(0.1);
            let dlc = rng.gen_range(0..9u8);
            let mut fi = dlc | if ide { FI_FF } else { 0 } | if rtr { FI_RTR } else { 0 };
            if rng.gen_bool(0.05) {
                fi = rng.gen();
            }
            ops.push_back(Op::W(REG_FI, fi));
            for k in 1..13 {
                ops.push_back(Op::W(REG_FI + k, rng.gen()));
            }
            let cmd = match rng.gen_range(0..10) {
                0 => CMD_TR | CMD_AT,
                1 => CMD_SRR,
                2 => CMD_TR | CMD_SRR,
                _ => CMD_TR,
            };
            ops.push_back(Op::W(REG_CMR, cmd));
        } else if r < 630 {
            ops.extend([Op::R(REG_SR), Op::R(REG_TXERR), Op::R(REG_RXERR), Op::R(REG_RBSA), Op::R(REG_EWL)]);
        } else if r < 632 {
            // reconfiguration in reset mode: filters, counters, modes
            ops.push_back(Op::W(REG_MOD, MOD_RM));
            for k in 0..4 {
                ops.push_back(Op::W(REG_ACCC0 + k, rng.gen()));
                ops.push_back(Op::W(REG_ACCM0 + k, if rng.gen_bool(0.5) { 0xff } else { rng.gen() }));
            }
            if rng.gen_bool(0.3) {
                ops.push_back(Op::W(REG_TXERR, rng.gen()));
                ops.push_back(Op::W(REG_RXERR, rng.gen()));
            }
            ops.push_back(Op::W(REG_EWL, rng.gen()));
            for a in 0..rng.gen_range(0..6) {
                ops.push_back(Op::R(REG_RXFIFO + rng.gen_range(0..64u8) + a));
            }
            let mut m = 0;
            for (bit, p) in [(MOD_LOM, 0.1), (MOD_STM, 0.2), (MOD_AFM, 0.5)] {
                if rng.gen_bool(p) {
                    m |= bit;
                }
            }
            ops.push_back(Op::W(REG_MOD, m));
        } else if r < 634 {
            // any register, any value (bit timing and sleep left alone)
            let a = rng.gen_range(0..128u8);
            if a != REG_BTR0 && a != REG_BTR1 && a != REG_MOD {
                ops.push_back(Op::W(a, rng.gen()));
            }
            ops.push_back(Op::R(rng.gen_range(0..128)));
        } else if r < 640 {
            ops.push_back(Op::R(rng.gen_range(0..128)));
        }
    }

    /// Set the inputs for the next clock from the outputs of the last one.
    pub fn tick(&mut self, ix: &Ix, out: &[u128], rng: &mut ChaCha8Rng, cycle: u64) {
        self.v[ix.rst] = (cycle < 2 || rng.gen_bool(0.000_002)) as u128;
        if self.active {
            if out[ix.ack] != 0 {
                self.active = false;
                self.reads += 1;
                if let Some(Op::R(REG_IR)) = self.last {
                    for b in 0..8 {
                        self.irq[b] += (out[ix.dat_r] >> b) as u64 & 1;
                    }
                }
                self.v[ix.cyc] = 0;
                self.v[ix.stb] = 0;
                self.v[ix.we] = 0;
                self.gap = rng.gen_range(0..4);
            }
            return;
        }
        if self.gap > 0 {
            self.gap -= 1;
            return;
        }
        if self.ops.is_empty() {
            self.program(rng, out[ix.int_n] == 0);
        }
        if let Some(op) = self.ops.pop_front() {
            let (we, a, d) = match op {
                Op::W(a, d) => (1, a, d),
                Op::R(a) => (0, a, rng.gen()),
            };
            self.v[ix.cyc] = 1;
            self.v[ix.stb] = 1;
            self.v[ix.we] = we;
            self.v[ix.adr] = a as u128;
            self.v[ix.dat] = d as u128;
            self.active = true;
            self.last = Some(op);
        }
    }
}

pub struct SjaNet {
    pub ix: Ix,
    pub hosts: Vec<Host>,
    rng: ChaCha8Rng,
    flip: Vec<u32>,
    bus: bool,
    cycle: u64,
}

impl SjaNet {
    pub fn new(model: &dyn Model, n: usize, seed: u64) -> SjaNet {
        let ix = Ix::of(model);
        let n_in = model.info().inputs.len();
        let hosts = (0..n).map(|_| Host::new(n_in, &ix)).collect();
        SjaNet { ix, hosts, rng: ChaCha8Rng::seed_from_u64(seed), flip: vec![0; n], bus: true, cycle: 0 }
    }

    /// Controller `i`'s inputs for this clock from its last outputs.
    pub fn inputs(&mut self, i: usize, out: &[u128]) -> &[u128] {
        self.hosts[i].tick(&self.ix, out, &mut self.rng, self.cycle);
        if self.flip[i] == 0 && self.rng.gen_bool(0.000_03) {
            self.flip[i] = self.rng.gen_range(1..40);
        }
        let lvl = if self.flip[i] > 0 {
            self.flip[i] -= 1;
            !self.bus
        } else {
            self.bus
        };
        self.hosts[i].v[self.ix.rx] = lvl as u128;
        &self.hosts[i].v
    }

    /// After every controller's clock: the bus level for the next one.
    pub fn advance(&mut self, tx: impl Iterator<Item = bool>) {
        let mut bus = true;
        for t in tx {
            bus &= t;
        }
        self.bus = bus;
        self.cycle += 1;
    }
}
