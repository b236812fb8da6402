//! The SJA1000 top (Wishbone register block, RX FIFO memory, acceptance filters,
//! CAN core): compiled model against rust-hdl, every output every cycle, every atom
//! at checkpoints. Two controllers on a wired-AND bus, each with a host that runs a
//! driver-like register program at random: configuration in reset mode (filters,
//! counters, modes), transmissions (normal, single-shot, self-reception), interrupt
//! service with RX FIFO reads and releases, status and error-capture reads, and now
//! and then a write of a random register or a read of any address (FIFO window, TX
//! buffer). The bus is disturbed now and then.

use std::collections::VecDeque;

use canstar_controller::sja1000::*;
use canstar_models::generated::sja1000 as g;
use canstar_models::lockstep::Lockstep;
use canstar_rtlc::rt::Model;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

type Node = Lockstep<Sja1000, g::Sja1000>;

#[derive(Clone, Copy, Debug)]
enum Op {
    W(u8, u8),
    R(u8),
}

/// Input indices of the Wishbone and CAN ports.
struct Ix {
    rst: usize,
    cyc: usize,
    stb: usize,
    we: usize,
    adr: usize,
    dat: usize,
    rx: usize,
    ack: usize,
    dat_r: usize,
    tx: usize,
    int_n: usize,
}

impl Ix {
    fn of(m: &dyn Model) -> Ix {
        let i = |n: &str| m.input_index(n).unwrap_or_else(|| panic!("no input {n}"));
        let o = |n: &str| m.output_index(n).unwrap_or_else(|| panic!("no output {n}"));
        Ix { rst: i("rst"), cyc: i("wb_cyc"), stb: i("wb_stb"), we: i("wb_we"), adr: i("wb_adr"), dat: i("wb_dat_w"), rx: i("rx"), ack: o("wb_ack"), dat_r: o("wb_dat_r"), tx: o("tx"), int_n: o("int_n") }
    }
}

/// A host: a queue of register accesses, one Wishbone access (two clocks) at a time.
struct Host {
    v: Vec<u128>,
    ops: VecDeque<Op>,
    active: bool,
    gap: u32,
    reads: u64,
    last: Option<Op>,
    /// How often each interrupt bit was read set in IR.
    irq: [u64; 8],
}

impl Host {
    fn new(n_in: usize, ix: &Ix) -> Host {
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
    fn tick(&mut self, ix: &Ix, out: &[u128], rng: &mut ChaCha8Rng, cycle: u64) {
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

fn net(nodes_n: usize, cycles: u64, seed: u64) -> u64 {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut nodes: Vec<Node> = (0..nodes_n)
        .map(|i| {
            // power-up bit timing is a runtime constant of the model
            let b = if i == 0 { Sja1000::new() } else { Sja1000::with_reset_timing(0x40, 0x25) };
            Lockstep::new(b, g::Sja1000::from_instance, g::hdl_set_inputs, g::hdl_outputs).unwrap_or_else(|m| panic!("{m}"))
        })
        .collect();
    let ix = Ix::of(&nodes[0].model);
    let n_in = nodes[0].model.info().inputs.len();
    let mut hosts: Vec<Host> = (0..nodes_n).map(|_| Host::new(n_in, &ix)).collect();
    let mut flip = vec![0u32; nodes_n];
    let mut ints = 0;
    for c in 0..cycles {
        let bus = c == 0 || nodes.iter().all(|n| n.outputs()[ix.tx] != 0);
        for (i, n) in nodes.iter_mut().enumerate() {
            hosts[i].tick(&ix, n.outputs(), &mut rng, c);
            if flip[i] == 0 && rng.gen_bool(0.000_03) {
                flip[i] = rng.gen_range(1..40);
            }
            let lvl = if flip[i] > 0 {
                flip[i] -= 1;
                !bus
            } else {
                bus
            };
            hosts[i].v[ix.rx] = lvl as u128;
            n.step(&hosts[i].v).unwrap_or_else(|m| panic!("node {i}: {m}"));
            ints += (n.outputs()[ix.int_n] == 0) as u64;
        }
        if c % 100_000 == 99_999 {
            for (i, n) in nodes.iter_mut().enumerate() {
                n.compare_all().unwrap_or_else(|m| panic!("node {i}: {m}"));
            }
        }
    }
    for (i, n) in nodes.iter_mut().enumerate() {
        n.compare_all().unwrap_or_else(|m| panic!("node {i}: {m}"));
        let h = &hosts[i];
        eprintln!("node {i}: {} accesses, IR bits read set (RI TI EI DOI WUI EPI ALI BEI): {:?}", h.reads, h.irq);
        assert!(h.reads > 1000, "node {i}: only {} bus accesses", h.reads);
        for (b, what) in [(0, "receive"), (1, "transmit"), (2, "error warning"), (7, "bus error")] {
            assert!(h.irq[b] > 3, "node {i}: {what} interrupt seen {} times", h.irq[b]);
        }
    }
    ints
}

/// Two controllers, 500 000 clocks each (1 M controller-cycles).
#[test]
fn two_controllers_with_hosts() {
    let ints = net(2, 500_000, 21);
    assert!(ints > 1000, "interrupt line active for only {ints} clocks");
}
