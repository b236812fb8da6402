//! Test-only CAN stimulus for the hub: frames (the controller crate's frame builder), a plain-Rust reference frame
//! tracker (the frame state C that the real frame monitor will provide) and simple
//! node models, all driving a `HubCore` bit by bit.
#![allow(dead_code, clippy::too_many_arguments, clippy::needless_range_loop, clippy::nonminimal_bool, clippy::type_complexity)]

use canstar_controller::frame::{self, crc15, BuildOptions, Frame as CanFrame};
use canstar_hdl::drive;
use canstar_hdl::drive::Clocked;
use canstar_hub::frame_state::Field;
use canstar_hub::config::HubConfig;
use canstar_hub::{hub::HubCore, top::Hub};

mod nodes;
mod tracker;
pub use nodes::*;
pub use tracker::*;

/// What the harness needs from a hub: [`HubCore`] (frame state from the reference
/// tracker) or [`Hub`] (frame state from its own monitor, the CAN controller).
pub trait Dut: Clocked {
    fn build(cfg: &HubConfig) -> Self;
    fn set_rx(&mut self, i: usize, v: bool);
    fn set_reh_rx(&mut self, j: usize, v: bool);
    fn n_reh(&self) -> usize;
    fn tx_val(&self, i: usize) -> bool;
    fn bt_val(&self) -> bool;
    fn blame(&self) -> bool;
    fn set_rst_n(&mut self, v: bool);
    fn set_inject(&mut self, v: bool);
    /// Sets the monitor inputs (HubCore) or ignores them (Hub).
    fn set_monitor(&mut self, sample: bool, bit_start: bool, field: Field, pos: usize, crc_ok: bool, error: bool, frame_ok: bool);
    fn isolated(&self) -> Vec<bool>;
    fn silent(&self) -> Vec<bool>;
    fn sub_isolated(&self) -> Vec<bool>;
    fn bic(&self) -> Vec<u64>;
    fn sub_bic(&self) -> Vec<u64>;
    fn dbc(&self) -> Vec<u64>;
    fn nack(&self) -> Vec<u64>;
    fn sub_dbc(&self) -> Vec<u64>;
    fn sub_rep(&self) -> Vec<u64>;
    fn efg_active(&self) -> bool;
    fn inject_active(&self) -> bool;
    fn frame_state(&self) -> u64;
}

macro_rules! common_dut {
    () => {
        fn set_rx(&mut self, i: usize, v: bool) {
            self.rx[i].next = v;
        }
        fn set_reh_rx(&mut self, j: usize, v: bool) {
            self.reh_rx[j].next = v;
        }
        fn n_reh(&self) -> usize {
            self.reh_rx.len()
        }
        fn tx_val(&self, i: usize) -> bool {
            self.tx[i].val()
        }
        fn set_rst_n(&mut self, v: bool) {
            self.rst_n.next = v;
        }
        fn set_inject(&mut self, v: bool) {
            self.inject_fault.next = v;
        }
        fn isolated(&self) -> Vec<bool> {
            self.isolated.iter().map(|s| s.val()).collect()
        }
        fn silent(&self) -> Vec<bool> {
            self.silent.iter().map(|s| s.val()).collect()
        }
        fn sub_isolated(&self) -> Vec<bool> {
            self.sub_isolated.iter().map(|s| s.val()).collect()
        }
        fn bic(&self) -> Vec<u64> {
            self.bic.iter().map(|s| s.val().index() as u64).collect()
        }
        fn sub_bic(&self) -> Vec<u64> {
            self.sub_bic.iter().map(|s| s.val().index() as u64).collect()
        }
        fn dbc(&self) -> Vec<u64> {
            self.dbc.iter().map(|s| s.val().index() as u64).collect()
        }
        fn nack(&self) -> Vec<u64> {
            self.nack.iter().map(|s| s.val().index() as u64).collect()
        }
        fn sub_dbc(&self) -> Vec<u64> {
            self.sub_dbc.iter().map(|s| s.val().index() as u64).collect()
        }
        fn sub_rep(&self) -> Vec<u64> {
            self.sub_rep.iter().map(|s| s.val().index() as u64).collect()
        }
        fn efg_active(&self) -> bool {
            self.efg_active.val()
        }
        fn inject_active(&self) -> bool {
            self.inject_active.val()
        }
        fn frame_state(&self) -> u64 {
            self.frame_state.val().index() as u64
        }
    };
}

impl Dut for HubCore {
    fn build(cfg: &HubConfig) -> Self {
        HubCore::new(cfg)
    }
    common_dut!();
    fn bt_val(&self) -> bool {
        self.bt.val()
    }
    fn blame(&self) -> bool {
        self.blame_any()
    }
    fn set_monitor(&mut self, sample: bool, bit_start: bool, field: Field, pos: usize, crc_ok: bool, error: bool, frame_ok: bool) {
        self.mon_sample.next = sample;
        self.mon_bit_start.next = bit_start;
        if sample {
            self.mon_field.next = field.code().into();
            self.mon_pos.next = (pos.min(15) as u64).into();
            self.mon_crc_ok.next = crc_ok;
        }
        self.mon_error.next = error;
        self.mon_frame_ok.next = frame_ok;
    }
}

impl Dut for Hub {
    fn build(cfg: &HubConfig) -> Self {
        Hub::new(cfg)
    }
    common_dut!();
    fn bt_val(&self) -> bool {
        self.core().bt.val()
    }
    fn blame(&self) -> bool {
        self.core().blame_any()
    }
    fn set_monitor(&mut self, _: bool, _: bool, _: Field, _: usize, _: bool, _: bool, _: bool) {}
}

pub const CLOCKS_PER_BIT: usize = 16;
pub const SAMPLE_CLOCK: usize = 12;

/// A frame a test node sends: the controller crate's [`CanFrame`] (read its fields
/// through `Deref`), optionally with a wrong CRC.
#[derive(Clone, Debug)]
pub struct Frame {
    pub can: CanFrame,
    /// Send a wrong CRC (once: a retransmission is correct).
    pub corrupt_crc: bool,
}

impl std::ops::Deref for Frame {
    type Target = CanFrame;
    fn deref(&self) -> &CanFrame {
        &self.can
    }
}

impl std::ops::DerefMut for Frame {
    fn deref_mut(&mut self) -> &mut CanFrame {
        &mut self.can
    }
}

impl Frame {
    pub fn std(id: u32, data: &[u8]) -> Frame {
        Frame { can: CanFrame::std(id, data), corrupt_crc: false }
    }
    pub fn ext(id: u32, data: &[u8]) -> Frame {
        Frame { can: CanFrame::ext(id, data), corrupt_crc: false }
    }
    pub fn remote(id: u32, ext: bool, dlc: u8) -> Frame {
        Frame { can: CanFrame::remote(ext, id, dlc), corrupt_crc: false }
    }
    /// Stuffed bits SOF .. end of CRC, then CRC delimiter, ACK slot (recessive),
    /// ACK delimiter, 7 EOF bits (the controller crate's frame builder).
    pub fn wire_bits(&self) -> Vec<bool> {
        let mut raw: Vec<bool> = frame::unstuffed(&self.can, BuildOptions::default()).iter().map(|b| b.level).collect();
        let crc = crc15(&raw) ^ (self.corrupt_crc as u16);
        raw.extend((0..15).rev().map(|k| (crc >> k) & 1 == 1));
        let mut out: Vec<bool> = frame::stuff(&raw).into_iter().map(|(b, _)| b).collect();
        out.extend([true; 10]);
        out
    }
}

/// A fault between a node and its hub pin (uplink) or between the hub pin and the node
/// (downlink): gets (bit index, value, tracker before the bit) and returns the new value.
pub type FaultMode = Box<dyn FnMut(usize, bool, &Tracker) -> bool>;
/// The value of incoming sublink j at bit b, given the nodes' own contributions of that
/// bit (before the faults on this hub's uplinks).
pub type SublinkFn = Box<dyn FnMut(usize, usize, &[bool], &Tracker) -> bool>;

/// The stimulus side of a hub test: nodes, faults, sublinks, reference tracker.
/// Works clock by clock on a `HubCore`, so that it can also drive a co-simulation.
pub struct Stim {
    pub tracker: Tracker,
    pub nodes: Vec<Node>,
    pub up_faults: Vec<Option<FaultMode>>,
    pub down_faults: Vec<Option<FaultMode>>,
    pub sublink: SublinkFn,
    pub bit: usize,
    pub log: Vec<BitLog>,
    pins: Vec<bool>,
    views: Vec<bool>,
    pending: Option<BitLog>,
}

#[derive(Clone, Debug)]
pub struct BitLog {
    pub bit: usize,
    pub field: Field,
    pub pos: usize,
    pub bt: bool,
    pub pins: Vec<bool>,
    pub ev: Event,
    pub efg: bool,
    pub blame: bool,
}

/// The healthy peer: its ANDC is the AND of the same nodes' contributions.
pub fn mirror_peer() -> SublinkFn {
    Box::new(|_, _, pins, _| pins.iter().all(|&p| p))
}

impl Stim {
    pub fn new(nodes: Vec<Node>) -> Stim {
        let n = nodes.len();
        Stim {
            tracker: Tracker::default(),
            nodes,
            up_faults: (0..n).map(|_| None).collect(),
            down_faults: (0..n).map(|_| None).collect(),
            sublink: mirror_peer(),
            bit: 0,
            log: vec![],
            pins: vec![true; n],
            views: vec![true; n],
            pending: None,
        }
    }

    fn finish_bit(&mut self) {
        if let Some(r) = self.pending.take() {
            for i in 0..self.nodes.len() {
                self.nodes[i].after(self.views[i], r.field, r.ev, &self.tracker);
            }
            self.bit += 1;
        }
    }

    /// Set the hub inputs for clock `k` (0..16) of the current bit. Settles the hub
    /// at the sample clock to read BT.
    pub fn at_clock<T: Dut>(&mut self, hub: &mut T, k: usize) {
        if k == 0 {
            self.finish_bit();
            let b = self.bit;
            let n = self.nodes.len();
            let mut own = vec![true; n];
            for i in 0..n {
                let c = self.nodes[i].contribution(&self.tracker);
                own[i] = c;
                self.pins[i] = match &mut self.up_faults[i] {
                    Some(f) => f(b, c, &self.tracker),
                    None => c,
                };
                hub.set_rx(i, self.pins[i]);
            }
            // the peer sees the nodes' own contributions (its links, not our faulty ones)
            for j in 0..hub.n_reh() {
                let v = (self.sublink)(b, j, &own, &self.tracker);
                hub.set_reh_rx(j, v);
            }
        }
        hub.set_monitor(false, k == 0, Field::Idle, 0, false, false, false);
        if k == SAMPLE_CLOCK {
            drive::settle(hub);
            let bt = hub.bt_val();
            let b = self.bit;
            for i in 0..self.nodes.len() {
                let v = hub.tx_val(i);
                self.views[i] = match &mut self.down_faults[i] {
                    Some(f) => f(b, v, &self.tracker),
                    None => v,
                };
            }
            let (field, pos) = self.tracker.classify(bt);
            let crc_ok = self.tracker.crc_ok;
            let ev = self.tracker.push(bt);
            hub.set_monitor(true, false, field, pos, crc_ok, ev.error, ev.frame_ok);
            drive::settle(hub);
            let r = BitLog { bit: b, field, pos, bt, pins: self.pins.clone(), ev, efg: hub.efg_active(), blame: false };
            self.log.push(r.clone());
            self.pending = Some(r);
        }
        // blames are seen when the (possibly delayed) monitor sample reaches the judges
        drive::settle(hub);
        if hub.blame() {
            if let Some(l) = self.log.last_mut() {
                l.blame = true;
            }
        }
    }
}

/// A [`HubCore`] driven by a [`Stim`] and the reference tracker.
pub type CoreNet = Net<HubCore>;
/// A complete [`Hub`] (its own frame monitor) driven by a [`Stim`].
pub type HubNet = Net<Hub>;

/// A hub driven by a [`Stim`].
pub struct Net<T: Dut = HubCore> {
    pub hub: T,
    pub stim: Stim,
    pub max_bic: Vec<u64>,
    pub max_sub_bic: Vec<u64>,
    pub efg_bits: usize,
}

/// One bit of clock-level stimulus on a [`HubCore`] as the frame monitor reports it:
/// port i is recessive at clock k iff `port(i, k)`, sublink j iff `sub(j, k)`; `error`:
/// the monitor detects an error at the sample.
pub fn monitor_bit(h: &mut HubCore, field: Field, pos: usize, error: bool, port: &dyn Fn(usize, usize) -> bool, sub: &dyn Fn(usize, usize) -> bool) {
    let (n, m) = (h.config().ports, h.config().sublinks);
    for k in 0..CLOCKS_PER_BIT {
        for i in 0..n {
            h.set_rx(i, port(i, k));
        }
        for j in 0..m {
            h.set_reh_rx(j, sub(j, k));
        }
        h.set_monitor(k == SAMPLE_CLOCK, k == 0, field, pos, false, error && k == SAMPLE_CLOCK, false);
        drive::cycle(h);
    }
}

pub fn reset_hub<T: Dut>(hub: &mut T) {
    drive::init(hub);
    hub.set_rst_n(false);
    hub.set_monitor(false, false, Field::Idle, 0, false, false, false);
    for _ in 0..4 {
        drive::cycle(hub);
    }
    hub.set_rst_n(true);
}

impl<T: Dut> Net<T> {
    pub fn new(cfg: &HubConfig, nodes: Vec<Node>) -> Net<T> {
        assert_eq!(nodes.len(), cfg.ports);
        let mut hub = T::build(cfg);
        for i in 0..cfg.ports {
            hub.set_rx(i, true);
        }
        for j in 0..cfg.sublinks {
            hub.set_reh_rx(j, true);
        }
        reset_hub(&mut hub);
        let mut net = Net { hub, stim: Stim::new(nodes), max_bic: vec![0; cfg.ports], max_sub_bic: vec![0; cfg.sublinks], efg_bits: 0 };
        // 12 idle bits first: a frame monitor integrates after 11 recessive bits
        let queues: Vec<_> = net.stim.nodes.iter_mut().map(|n| std::mem::take(&mut n.queue)).collect();
        net.run(12);
        for (n, q) in net.stim.nodes.iter_mut().zip(queues) {
            n.queue = q;
        }
        net
    }

    /// Simulate one bit (16 clocks, sample at clock 12).
    pub fn step(&mut self) {
        for k in 0..CLOCKS_PER_BIT {
            self.stim.at_clock(&mut self.hub, k);
            drive::cycle(&mut self.hub);
            if k == SAMPLE_CLOCK + 1 {
                for (m, b) in self.max_bic.iter_mut().zip(self.hub.bic()) {
                    *m = (*m).max(b);
                }
                for (m, b) in self.max_sub_bic.iter_mut().zip(self.hub.sub_bic()) {
                    *m = (*m).max(b);
                }
                if self.hub.efg_active() {
                    self.efg_bits += 1;
                }
            }
        }
    }

    pub fn run(&mut self, bits: usize) {
        for _ in 0..bits {
            self.step();
        }
    }

    pub fn nodes(&mut self) -> &mut Vec<Node> {
        &mut self.stim.nodes
    }

    pub fn run_until_idle(&mut self, max_bits: usize) {
        for _ in 0..max_bits {
            self.step();
            if self.stim.nodes.iter().all(|n| n.queue.is_empty()) && self.stim.tracker.ph == Ph::Idle {
                for _ in 0..5 {
                    self.step();
                }
                return;
            }
        }
        panic!("network did not drain within {max_bits} bits:\n{}", self.trace(self.stim.log.len().saturating_sub(200)));
    }

    pub fn isolated(&self) -> Vec<bool> {
        self.hub.isolated()
    }
    pub fn silent(&self) -> Vec<bool> {
        self.hub.silent()
    }
    pub fn sub_isolated(&self) -> Vec<bool> {
        self.hub.sub_isolated()
    }
    pub fn bic(&self) -> Vec<u64> {
        self.hub.bic()
    }
    pub fn errors(&self) -> usize {
        self.stim.log.iter().filter(|l| l.ev.error).count()
    }
    pub fn blames(&self) -> usize {
        self.stim.log.iter().filter(|l| l.blame).count()
    }
    pub fn frames_ok(&self) -> usize {
        self.stim.log.iter().filter(|l| l.ev.frame_ok).count()
    }
    /// The field sequence as a compact string (debug aid).
    pub fn trace(&self, from: usize) -> String {
        self.stim.log[from.min(self.stim.log.len())..]
            .iter()
            .map(|l| {
                let pins: String = l.pins.iter().map(|&p| if p { '1' } else { '0' }).collect();
                format!(
                    "{}:{:?}{}{}[{}]{}{}{} ",
                    l.bit,
                    l.field,
                    l.pos,
                    if l.bt { "r" } else { "D" },
                    pins,
                    if l.ev.error { "!" } else { "" },
                    if l.blame { "B" } else { "" },
                    if l.efg { "E" } else { "" }
                )
            })
            .collect()
    }
}
