//! Throughput benchmark of the kernel: simulated clock cycles per second.
//!
//! [`bench()`] measures (a) one node alone and (b) `bus_nodes` nodes sharing a
//! bus. A node is whatever the factory builds (a [`Component`] reading its
//! input 0 = RX, no outputs used), wrapped in a [`PatternNode`] that drives
//! the node's TX with a pseudo-random bit pattern changing at bit boundaries.
//! The default node is [`EdgeCounter`]; to benchmark another block, pass
//! another factory, e.g.
//! `|i, clk| HdlComponent::new(&format!("n{i}"), clk, BitTiming::default(), 1, 0, |b, v| b.rx.next = v[0], |_, _| {})`.

use std::time::Instant;

use rust_hdl::prelude::*;

use crate::bus::{Bus, NodeDelays};
use crate::{ClockSpec, Component, HdlComponent, Io, Sim};

/// A small clocked block: two-flip-flop synchroniser on `rx`, counter of
/// the synchronised level's edges.
#[derive(LogicBlock, Default)]
pub struct EdgeCounter {
    pub clock: Signal<In, Clock>,
    pub rx: Signal<In, Bit>,
    /// Number of edges seen (wraps).
    pub edges: Signal<Out, Bits<8>>,
    /// The synchronised level.
    pub level: Signal<Out, Bit>,
    sync0: DFF<Bit>,
    sync1: DFF<Bit>,
    cnt: DFF<Bits<8>>,
}

impl Logic for EdgeCounter {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, sync0, sync1, cnt);
        self.sync0.d.next = self.rx.val();
        self.sync1.d.next = self.sync0.q.val();
        if self.sync0.q.val() != self.sync1.q.val() {
            self.cnt.d.next = self.cnt.q.val() + 1;
        }
        self.edges.next = self.cnt.q.val();
        self.level.next = self.sync1.q.val();
    }
}

canstar_hdl::impl_clocked!(EdgeCounter);

/// The default benchmark node: an [`EdgeCounter`] with input 0 = RX, no outputs.
pub fn edge_counter_node(i: usize, clock: ClockSpec) -> HdlComponent<EdgeCounter> {
    HdlComponent::new(&format!("node{i}"), clock, EdgeCounter::default(), 1, 0, |b, v| b.rx.next = v[0], |_, _| {})
}

/// Wraps a node: forwards input 0 (RX) to the inner component and drives
/// output 0 (TX) with a pseudo-random pattern (an LFSR; a bit is dominant
/// with probability 1/4) that changes every `cycles_per_bit` clock cycles.
pub struct PatternNode<C: Component> {
    pub inner: C,
    cycles_per_bit: u32,
    count: u32,
    lfsr: u32,
}

impl<C: Component> PatternNode<C> {
    pub fn new(inner: C, cycles_per_bit: u32, seed: u32) -> Self {
        PatternNode { inner, cycles_per_bit: cycles_per_bit.max(1), count: 0, lfsr: seed | 1 }
    }
    fn next_bit(&mut self) -> bool {
        let mut r = false;
        for _ in 0..2 {
            // 32-bit Galois LFSR, taps 32,22,2,1
            let lsb = self.lfsr & 1;
            self.lfsr >>= 1;
            if lsb != 0 {
                self.lfsr ^= 0x8020_0003;
            }
            r |= lsb != 0;
        }
        r
    }
}

impl<C: Component> Component for PatternNode<C> {
    fn name(&self) -> &str {
        self.inner.name()
    }
    fn clock(&self) -> ClockSpec {
        self.inner.clock()
    }
    fn tick(&mut self, io: &mut Io<'_>) {
        self.inner.tick(&mut io.sub(0..1, 0..0));
        if self.count == 0 {
            let b = self.next_bit();
            io.set_output(0, b);
        }
        self.count += 1;
        if self.count == self.cycles_per_bit {
            self.count = 0;
        }
    }
    fn probe(&self, probe: &mut dyn Probe) {
        self.inner.probe(probe)
    }
}

/// Benchmark parameters.
#[derive(Clone, Debug)]
pub struct BenchConfig {
    /// Nominal clock period (default 25 000 ps = 40 MHz).
    pub period_ps: u64,
    /// Clock cycles per bit of the TX pattern (default 40 = 1 Mbit/s at 40 MHz).
    pub cycles_per_bit: u32,
    /// Cycles simulated for the single node.
    pub single_cycles: u64,
    /// Nodes on the shared bus.
    pub bus_nodes: usize,
    /// Cycles simulated per bus node.
    pub bus_cycles_per_node: u64,
    /// Node clocks get offsets spread over `[-ppm_spread, +ppm_spread]`.
    pub ppm_spread: f64,
    /// Delays of every node.
    pub delays: NodeDelays,
    pub seed: u64,
}

impl Default for BenchConfig {
    fn default() -> Self {
        BenchConfig {
            period_ps: 25_000,
            cycles_per_bit: 40,
            single_cycles: 1_000_000,
            bus_nodes: 8,
            bus_cycles_per_node: 200_000,
            ppm_spread: 100.0,
            delays: NodeDelays { tx_dom: 40_000, tx_rec: 60_000, rx_dom: 30_000, rx_rec: 30_000 },
            seed: 1,
        }
    }
}

/// Benchmark results (wall-clock dependent: report, never assert).
#[derive(Clone, Debug, PartialEq)]
pub struct BenchReport {
    pub single_cycles: u64,
    pub single_secs: f64,
    /// (a) clock cycles per second of one node alone.
    pub single_cycles_per_sec: f64,
    pub bus_nodes: usize,
    /// Total cycles of all bus nodes.
    pub bus_cycles: u64,
    pub bus_secs: f64,
    /// (b) clock cycles per second summed over all bus nodes.
    pub bus_cycles_per_sec: f64,
    /// (b) per node: simulated cycles of one node per second.
    pub bus_node_cycles_per_sec: f64,
    /// Simulated time of the bus run in ps.
    pub bus_sim_ps: u64,
}

impl std::fmt::Display for BenchReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(
            f,
            "single node: {} cycles in {:.3} s = {:.0} cycles/s",
            self.single_cycles, self.single_secs, self.single_cycles_per_sec
        )?;
        write!(
            f,
            "{} nodes on a bus: {} cycles in {:.3} s = {:.0} cycles/s total, {:.0} cycles/s per node",
            self.bus_nodes, self.bus_cycles, self.bus_secs, self.bus_cycles_per_sec, self.bus_node_cycles_per_sec
        )
    }
}

/// The benchmark bus: `n` nodes built by `factory(index, clock)`, each
/// wrapped in a [`PatternNode`], on a bus with `cfg.delays`, clocks spread
/// over `[-ppm_spread, +ppm_spread]` with random phases. Not yet run.
pub fn build_bus<C: Component>(cfg: &BenchConfig, n: usize, factory: &mut impl FnMut(usize, ClockSpec) -> C) -> Sim {
    let mut sim = Sim::new(cfg.seed);
    let bus = Bus::uniform(&mut sim, "bus", n, cfg.delays);
    for (i, node) in bus.nodes.iter().enumerate() {
        let ppm = if n > 1 { -cfg.ppm_spread + 2.0 * cfg.ppm_spread * i as f64 / (n - 1) as f64 } else { 0.0 };
        let clk = sim.random_phase_clock(cfg.period_ps, ppm);
        let inner = factory(i, clk);
        sim.add(PatternNode::new(inner, cfg.cycles_per_bit, 0x1234_5678 ^ (i as u32 * 0x9e37_79b9)), &[node.rx], &[node.tx]);
    }
    sim
}

fn run_bus<C: Component>(
    cfg: &BenchConfig,
    n: usize,
    cycles_per_node: u64,
    factory: &mut impl FnMut(usize, ClockSpec) -> C,
) -> (Sim, f64) {
    let mut sim = build_bus(cfg, n, factory);
    let end = (cfg.period_ps * cycles_per_node).saturating_sub(1);
    let t0 = Instant::now();
    sim.run_until(end);
    (sim, t0.elapsed().as_secs_f64())
}

/// Run the benchmark with nodes built by `factory(index, clock)`.
pub fn bench<C: Component>(cfg: &BenchConfig, mut factory: impl FnMut(usize, ClockSpec) -> C) -> BenchReport {
    let (s1, t1) = run_bus(cfg, 1, cfg.single_cycles, &mut factory);
    let (sn, tn) = run_bus(cfg, cfg.bus_nodes, cfg.bus_cycles_per_node, &mut factory);
    let c1 = s1.total_cycles();
    let cn = sn.total_cycles();
    let t1 = t1.max(1e-9);
    let tn = tn.max(1e-9);
    BenchReport {
        single_cycles: c1,
        single_secs: t1,
        single_cycles_per_sec: c1 as f64 / t1,
        bus_nodes: cfg.bus_nodes,
        bus_cycles: cn,
        bus_secs: tn,
        bus_cycles_per_sec: cn as f64 / tn,
        bus_node_cycles_per_sec: cn as f64 / tn / cfg.bus_nodes.max(1) as f64,
        bus_sim_ps: sn.now(),
    }
}

/// [`bench()`] with the default [`EdgeCounter`] node.
pub fn bench_default(cfg: &BenchConfig) -> BenchReport {
    bench(cfg, edge_counter_node)
}
