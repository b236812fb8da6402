//! Clock-level multi-node harness: several `CanCore` instances on one clock
//! and a wired-AND bus, with optional per-node receive override and RX delay.
#![allow(dead_code)]

use super::Ovr;
use canstar_controller::core::CanCore;
use canstar_controller::frame::Frame;
use canstar_controller::fsm::*;
use canstar_hdl::drive;
use canstar_hdl::timing::BtlConfig;
use std::collections::VecDeque;

/// Timing fields (value - 1): T10/6/4 = PROP 1, PH1 4, SJW 4, BRP 1.
pub const T10_6_4: (u64, u64, u64, u64) = (0, 0, 3, 3);

/// (cycle after the sample, event word, field, pos, stuff, tec, rec) of one bit.
pub type BitRec = (usize, u64, Field, u8, bool, u64, u64);

pub struct CoreBus {
    pub nodes: Vec<Box<CanCore>>,
    pub ovr: Vec<Ovr>,
    /// Extra RX delay in clocks per node.
    pub delay: Vec<VecDeque<bool>>,
    pub rx: Vec<Vec<Frame>>,
    /// Per node: (cycle, events word) of every processed bit.
    pub bits: Vec<Vec<BitRec>>,
    /// Per node: sampled levels at its sample strobes.
    pub samples: Vec<Vec<bool>>,
    pub cycle: usize,
    pending: Vec<Option<(Field, u8, bool)>>,
}

/// The timing of fields `t` (value - 1: brp, prop, ph1, sjw) with PH2 = max(PH1, 2).
pub fn fields_timing(t: (u64, u64, u64, u64), triple: bool) -> BtlConfig {
    let f = |x: u64| x as u32 + 1;
    BtlConfig { triple, ..BtlConfig::new(f(t.0), f(t.1), f(t.2), f(t.3)) }
}

pub fn configure(c: &mut CanCore, t: (u64, u64, u64, u64)) {
    c.set_timing(&fields_timing(t, false));
}

impl CoreBus {
    pub fn new(n: usize, delays: &[usize]) -> CoreBus {
        CoreBus::with_timing(n, delays, T10_6_4, false)
    }

    /// Nodes with timing fields `t` (value - 1; PH2 = max(PH1, 2)) and optional triple sampling.
    pub fn with_timing(n: usize, delays: &[usize], t: (u64, u64, u64, u64), triple: bool) -> CoreBus {
        CoreBus::with_config(n, delays, &fields_timing(t, triple))
    }

    /// Nodes with bit timing `cfg`.
    pub fn with_config(n: usize, delays: &[usize], cfg: &BtlConfig) -> CoreBus {
        let mut nodes = Vec::new();
        for _ in 0..n {
            let mut c = Box::new(CanCore::new());
            drive::init(&mut *c);
            c.set_timing(cfg);
            c.rx.next = true;
            c.reset.next = true;
            drive::cycle(&mut *c);
            drive::cycle(&mut *c);
            c.reset.next = false;
            nodes.push(c);
        }
        let delay = (0..n).map(|i| VecDeque::from(vec![true; *delays.get(i).unwrap_or(&0)])).collect();
        CoreBus {
            nodes,
            ovr: vec![Ovr::None; n],
            delay,
            rx: vec![vec![]; n],
            bits: vec![vec![]; n],
            samples: vec![vec![]; n],
            cycle: 0,
            pending: vec![None; n],
        }
    }

    /// Integrated nodes (reset, then more than 11 recessive bits).
    pub fn integrated(n: usize, delays: &[usize]) -> CoreBus {
        let mut b = CoreBus::new(n, delays);
        b.run(13 * 10);
        for i in 0..n {
            assert_eq!(b.field(i), Field::Idle, "node {i}");
        }
        b
    }

    pub fn field(&self, i: usize) -> Field {
        Field::from_code(self.nodes[i].dbg_field.val().index() as u64).unwrap()
    }
    pub fn tec(&self, i: usize) -> u64 {
        self.nodes[i].tec.val().index() as u64
    }
    pub fn rec(&self, i: usize) -> u64 {
        self.nodes[i].rec.val().index() as u64
    }
    pub fn state(&self, i: usize) -> u64 {
        self.nodes[i].state.val().index() as u64
    }
    pub fn request(&mut self, i: usize, f: &Frame) {
        let n = &mut self.nodes[i];
        n.tx_ide.next = f.ide;
        n.tx_rtr.next = f.rtr;
        n.tx_id.next = (f.id as u64).into();
        n.tx_dlc.next = (f.dlc as u64).into();
        n.tx_data.next = f.data_word().into();
        n.tx_req.next = true;
    }
    pub fn withdraw(&mut self, i: usize) {
        self.nodes[i].tx_req.next = false;
    }

    pub fn bus(&self) -> bool {
        self.nodes.iter().all(|n| n.tx.val())
    }

    pub fn step(&mut self) {
        let bus = self.bus();
        for i in 0..self.nodes.len() {
            self.delay[i].push_back(bus);
            let seen = self.delay[i].pop_front().unwrap();
            let lvl = match self.ovr[i] {
                Ovr::None => seen,
                Ovr::Invert => !seen,
                Ovr::StuckR => true,
                Ovr::StuckD => false,
            };
            let n = &mut self.nodes[i];
            n.rx.next = lvl;
            if n.dbg_sample.val() {
                self.samples[i].push(n.dbg_busmon.val());
                self.pending[i] = Some((
                    Field::from_code(n.dbg_field.val().index() as u64).unwrap(),
                    n.dbg_pos.val().index() as u8,
                    n.dbg_stuff.val(),
                ));
            }
        }
        for n in self.nodes.iter_mut() {
            drive::cycle(&mut **n);
        }
        self.cycle += 1;
        for i in 0..self.nodes.len() {
            let n = &self.nodes[i];
            let ev = n.dbg_events.val().index() as u64;
            if (ev >> EV_BIT) & 1 == 1 {
                let (f, p, s) = self.pending[i].take().expect("event word without a sample strobe");
                self.bits[i].push((self.cycle, ev, f, p, s, n.tec.val().index() as u64, n.rec.val().index() as u64));
            }
            if n.rx_valid.val() {
                self.rx[i].push(Frame::from_native(
                    n.rx_ide.val(),
                    n.rx_rtr.val(),
                    n.rx_id.val().index() as u32,
                    n.rx_dlc.val().index() as u8,
                    n.rx_data.val().to_u64(),
                ));
            }
        }
    }

    pub fn run(&mut self, cycles: usize) {
        for _ in 0..cycles {
            self.step();
        }
    }

    pub fn run_until(&mut self, max: usize, mut pred: impl FnMut(&CoreBus) -> bool) {
        for _ in 0..max {
            self.step();
            if pred(self) {
                return;
            }
        }
        panic!("condition not reached within {max} cycles");
    }

    pub fn run_idle(&mut self, max: usize) {
        self.run_until(max, |b| (0..b.nodes.len()).all(|i| b.field(i) == Field::Idle));
    }

    /// Events of node `i` having bit `ev`.
    pub fn events(&self, i: usize, ev: usize) -> Vec<BitRec> {
        self.bits[i].iter().filter(|r| (r.1 >> ev) & 1 == 1).cloned().collect()
    }
}
