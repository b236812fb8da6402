//! A CAN node for the kernel: the RTL controller [`CanCore`] plus a small
//! host model (a transmit queue driving the native request interface, and a
//! log of everything the controller reports).
//!
//! Bind it with one input (RX) and one output (TX):
//!
//! ```
//! use canstar_controller::frame::Frame;
//! use canstar_sim::bus::{Bus, NodeDelays};
//! use canstar_verify::node::{CanNode, NodeConfig};
//! use canstar_sim::{ClockSpec, Sim};
//! let mut sim = Sim::new(1);
//! let bus = Bus::uniform(&mut sim, "bus", 2, NodeDelays::symmetric(0, 0));
//! let clock = ClockSpec::new(100_000); // 10 MHz: 1 Mbit/s with the default T10/6/4
//! let a = sim.add(CanNode::new(NodeConfig::named("n1"), clock), &[bus.nodes[0].rx], &[bus.nodes[0].tx]);
//! let b = sim.add(CanNode::new(NodeConfig::named("n2"), clock), &[bus.nodes[1].rx], &[bus.nodes[1].tx]);
//! sim.get_mut(a).request(Frame::std(0x123, &[1, 2]));
//! sim.run_for(200_000_000); // 200 us
//! assert_eq!(sim.get(b).received(), vec![Frame::std(0x123, &[1, 2])]);
//! ```
//!
//! The node holds the controller in reset for its first [`RESET_CYCLES`]
//! clocks (the timing fields are latched under reset), then releases it; the
//! controller integrates (11 recessive bits) before it may send.

use canstar_sim::{ClockSpec, Component, Io};
use canstar_controller::frame::Frame;
use canstar_controller::core::RecRule;
use canstar_controller::view::CoreView;
use canstar_controller::fsm::{Field, ERRK_ACK, ERRK_BIT, ERRK_CRC, ERRK_FORM, ERRK_STUFF};
use canstar_controller::trace::BitTracer;
use canstar_hdl::timing::BtlConfig;
use canstar_models::core_sim::CoreSim;
pub use canstar_models::Engine;
use rust_hdl::prelude::Probe;
use std::collections::VecDeque;

/// Clocks the controller is held in reset after power-up or [`CanNode::hard_reset`].
pub const RESET_CYCLES: u32 = 4;

/// Static configuration of a node (real values, not register encodings).
#[derive(Debug, Clone, PartialEq)]
pub struct NodeConfig {
    pub name: String,
    /// Bit timing (real values; [`NodeConfig::timing`] sets PH2 = max(PH1, 2),
    /// `BtlConfig::with_ph2` another PH2).
    pub timing: BtlConfig,
    pub listen_only: bool,
    pub self_test: bool,
    pub single_shot: bool,
    pub host_recovery: bool,
    /// RX synchroniser depth (1 or 2).
    pub sync_depth: usize,
    /// The bit at which a receiver counts a successful reception in REC (C13): ISO by
    /// default; the Bosch reference programs run with [`RecRule::Bosch1999`].
    pub rec_rule: RecRule,
    /// Simulation engine of the controller (compiled model by default).
    pub engine: Engine,
}

impl NodeConfig {
    /// Default timing T10/6/4 with BRP 1 (1 Mbit/s at a 100 ns clock).
    pub fn named(name: &str) -> Self {
        NodeConfig {
            name: name.to_string(),
            timing: BtlConfig::T10_6_4,
            listen_only: false,
            self_test: false,
            single_shot: false,
            host_recovery: false,
            sync_depth: canstar_controller::core::SYNC_DEPTH,
            rec_rule: RecRule::default(),
            engine: Engine::default(),
        }
    }
    /// The same node with bit timing `brp` clocks per TQ, PROP, PH1, SJW in TQ
    /// (triple sampling unchanged).
    pub fn timing(mut self, brp: u32, prop: u32, ph1: u32, sjw: u32) -> Self {
        self.timing = BtlConfig { triple: self.timing.triple, ..BtlConfig::new(brp, prop, ph1, sjw) };
        self
    }
    /// The same node on another simulation engine.
    pub fn engine(mut self, engine: Engine) -> Self {
        self.engine = engine;
        self
    }
}

/// Kind of a detected error.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorKind {
    Bit,
    Stuff,
    Crc,
    Form,
    Ack,
}

/// What the controller reported, as the host sees it.
#[derive(Debug, Clone, PartialEq)]
pub enum HostEvent {
    /// A frame of this node was sent successfully.
    TxDone(Frame),
    /// Arbitration lost at this arbitration-field position.
    ArbLost(u32),
    /// An error was detected (kinds, FIELD, POSITION, while transmitting).
    Error { kinds: Vec<ErrorKind>, field: Field, pos: u32, tx: bool },
    /// A frame was received.
    Rx(Frame),
}

/// A CAN node: the controller core ([`CoreSim`] on the configured engine) plus host model. See the module documentation.
pub struct CanNode {
    name: String,
    clock: ClockSpec,
    /// The controller RTL on its engine (read its outputs through
    /// [`CoreView`] between steps).
    pub core: CoreSim,
    cfg: NodeConfig,
    reset_left: u32,
    queue: VecDeque<Frame>,
    current: Option<Frame>,
    /// tx_req must be low for a clock between two requests.
    gap: bool,
    recover_pulse: bool,
    /// Counter values to load on the next clock (`cnt_load` for one clock).
    load: Option<(u32, u32)>,
    log: Vec<(u64, HostEvent)>,
    tracer: Option<BitTracer>,
    trace: Vec<(u64, String)>,
    cycles: u64,
}

impl CanNode {
    pub fn new(cfg: NodeConfig, clock: ClockSpec) -> Self {
        let core = CoreSim::with_rule(cfg.engine, cfg.sync_depth, cfg.rec_rule);
        let mut n = CanNode {
            name: cfg.name.clone(),
            clock,
            core,
            cfg,
            reset_left: RESET_CYCLES,
            queue: VecDeque::new(),
            current: None,
            gap: false,
            recover_pulse: false,
            load: None,
            log: vec![],
            tracer: None,
            trace: vec![],
            cycles: 0,
        };
        n.apply_config();
        n
    }

    fn apply_config(&mut self) {
        let c = &self.cfg;
        let f = |v: u32| v.saturating_sub(1) as u8;
        let i = &mut self.core.inp;
        i.brp = f(c.timing.brp);
        i.prop = f(c.timing.prop);
        i.ph1 = f(c.timing.ph1);
        i.ph2 = f(c.timing.ph2);
        i.sjw = f(c.timing.sjw);
        i.triple = c.timing.triple;
        i.listen_only = c.listen_only;
        i.self_test = c.self_test;
        i.single_shot = c.single_shot;
        i.host_recovery = c.host_recovery;
        i.cnt_load = false;
    }

    pub fn config(&self) -> &NodeConfig {
        &self.cfg
    }

    /// Queue a frame for transmission (sent in queue order, one at a time).
    pub fn request(&mut self, f: Frame) {
        self.queue.push_back(f);
    }

    /// Withdraw the frame being sent and drop the queue. An attempt in
    /// progress finishes; no further retry is made.
    pub fn withdraw(&mut self) {
        self.queue.clear();
        self.current = None;
    }

    /// Is a frame pending (queued or being sent)?
    pub fn pending(&self) -> bool {
        self.current.is_some() || !self.queue.is_empty()
    }

    /// Hardware reset: counters cleared, integration again. The queue stays.
    pub fn hard_reset(&mut self) {
        self.reset_left = RESET_CYCLES;
        self.current = None;
    }

    /// Load TEC and REC through the counter-load port (`cnt_load` high for
    /// the next clock, `tec_in` = `tec` (9 bits, 256 and above: bus-off),
    /// `rec_in` = `rec`): the values are visible after that clock.
    pub fn load_counters(&mut self, tec: u32, rec: u32) {
        assert!(tec < 512 && rec < 256, "counter values out of range: TEC {tec}, REC {rec}");
        self.load = Some((tec, rec));
    }

    /// Start bus-off recovery (only with `host_recovery`).
    pub fn start_recovery(&mut self) {
        self.recover_pulse = true;
    }

    /// Record the can-protocol.md §18 per-bit trace of this node under `label` (e.g. `D1`).
    pub fn enable_trace(&mut self, label: &str) {
        self.tracer = Some(BitTracer::new(label));
    }

    /// Trace lines recorded so far with the time (ps) they were completed.
    pub fn trace(&self) -> &[(u64, String)] {
        &self.trace
    }

    /// Everything the controller reported, with times in ps.
    pub fn log(&self) -> &[(u64, HostEvent)] {
        &self.log
    }

    /// Frames received, in order.
    pub fn received(&self) -> Vec<Frame> {
        self.log.iter().filter_map(|(_, e)| if let HostEvent::Rx(f) = e { Some(f.clone()) } else { None }).collect()
    }

    /// Frames sent successfully, in order.
    pub fn sent(&self) -> Vec<Frame> {
        self.log.iter().filter_map(|(_, e)| if let HostEvent::TxDone(f) = e { Some(f.clone()) } else { None }).collect()
    }

    /// Errors detected so far.
    pub fn errors(&self) -> usize {
        self.log.iter().filter(|(_, e)| matches!(e, HostEvent::Error { .. })).count()
    }

    pub fn tec(&self) -> u32 {
        self.core.tec_value()
    }
    pub fn rec(&self) -> u32 {
        self.core.rec_value()
    }
    /// 0 error-active, 1 error-passive, 2 bus-off.
    pub fn state(&self) -> u32 {
        self.core.state_value()
    }
    /// FIELD of the bit in progress (between sample points: of the next bit).
    pub fn field(&self) -> Field {
        self.core.field()
    }
    /// POSITION of the bit in progress.
    pub fn pos(&self) -> u32 {
        self.core.pos()
    }
    /// Clock cycles simulated.
    pub fn cycles(&self) -> u64 {
        self.cycles
    }
    /// Nominal bit time in ps.
    pub fn bit_time_ps(&self) -> u64 {
        self.clock.period_ps * self.cfg.timing.brp as u64 * self.cfg.timing.ntq() as u64
    }

    fn drive_request(&mut self) {
        if self.current.is_none() && !self.gap {
            self.current = self.queue.pop_front();
        }
        match (&self.current, self.gap) {
            (Some(f), false) => {
                let i = &mut self.core.inp;
                i.tx_req = true;
                i.tx_ide = f.ide;
                i.tx_rtr = f.rtr;
                i.tx_id = f.id;
                i.tx_dlc = f.dlc;
                i.tx_data = f.data_word();
            }
            _ => self.core.inp.tx_req = false,
        }
    }

    fn collect(&mut self, now: u64) {
        let c = &self.core;
        if c.tx_done() {
            if let Some(f) = self.current.take() {
                self.log.push((now, HostEvent::TxDone(f)));
            }
            self.gap = true;
        }
        if c.arb_lost() {
            self.log.push((now, HostEvent::ArbLost(c.arb_lost_pos())));
        }
        if c.error() {
            let k = c.err_kind() as usize;
            let kinds = [(ERRK_BIT, ErrorKind::Bit), (ERRK_STUFF, ErrorKind::Stuff), (ERRK_CRC, ErrorKind::Crc), (ERRK_FORM, ErrorKind::Form), (ERRK_ACK, ErrorKind::Ack)]
                .iter()
                .filter(|(b, _)| (k >> b) & 1 == 1)
                .map(|(_, e)| *e)
                .collect();
            self.log.push((
                now,
                HostEvent::Error {
                    kinds,
                    field: Field::from_code(c.err_field() as u64).unwrap_or(Field::Reset),
                    pos: c.err_pos(),
                    tx: c.err_tx(),
                },
            ));
            if self.cfg.single_shot {
                self.current = None;
                self.gap = true;
            }
        }
        if c.rx_valid() {
            let f = c.rx_frame();
            self.log.push((now, HostEvent::Rx(f)));
        }
        if let Some(t) = self.tracer.as_mut() {
            for l in t.clock(now / 1000, &self.core) {
                self.trace.push((now, l));
            }
        }
    }
}

impl Component for CanNode {
    fn name(&self) -> &str {
        &self.name
    }
    fn clock(&self) -> ClockSpec {
        self.clock
    }
    fn tick(&mut self, io: &mut Io<'_>) {
        self.cycles += 1;
        self.core.inp.rx = io.input(0);
        if self.reset_left > 0 {
            self.reset_left -= 1;
            self.core.inp.reset = true;
            self.apply_config();
        } else {
            self.core.inp.reset = false;
        }
        if self.gap {
            // tx_req was low for this clock: the next request may start.
            self.core.inp.tx_req = false;
            self.gap = false;
        } else {
            self.drive_request();
        }
        self.core.inp.recover = std::mem::take(&mut self.recover_pulse);
        match self.load.take() {
            Some((tec, rec)) => {
                self.core.inp.cnt_load = true;
                self.core.inp.tec_in = tec as u16;
                self.core.inp.rec_in = rec as u8;
            }
            None => self.core.inp.cnt_load = false,
        }
        self.core.cycle();
        self.collect(io.now());
        io.set_output(0, self.core.tx());
    }
    fn probe(&self, probe: &mut dyn Probe) {
        self.core.accept(&self.name, probe);
    }
    fn set_trace(&mut self, on: bool) {
        self.core.set_trace(on);
    }
}
