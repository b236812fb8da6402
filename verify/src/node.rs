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
use canstar_controller::core::CanCore;
use canstar_controller::frame::Frame;
use canstar_controller::fsm::{Field, ERRK_ACK, ERRK_BIT, ERRK_CRC, ERRK_FORM, ERRK_STUFF};
use canstar_controller::trace::BitTracer;
use canstar_hdl::drive;
use canstar_hdl::timing::BtlConfig;
use rust_hdl::prelude::*;
use std::collections::VecDeque;

/// Clocks the controller is held in reset after power-up or [`CanNode::hard_reset`].
pub const RESET_CYCLES: u32 = 4;

/// Static configuration of a node (real values, not register encodings).
#[derive(Debug, Clone, PartialEq)]
pub struct NodeConfig {
    pub name: String,
    /// Bit timing (real values; PH2 = max(PH1, 2)).
    pub timing: BtlConfig,
    pub listen_only: bool,
    pub self_test: bool,
    pub single_shot: bool,
    pub host_recovery: bool,
    /// RX synchroniser depth (1 or 2).
    pub sync_depth: usize,
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
        }
    }
    /// The same node with bit timing `brp` clocks per TQ, PROP, PH1, SJW in TQ
    /// (triple sampling unchanged).
    pub fn timing(mut self, brp: u32, prop: u32, ph1: u32, sjw: u32) -> Self {
        self.timing = BtlConfig { triple: self.timing.triple, ..BtlConfig::new(brp, prop, ph1, sjw) };
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

/// A CAN node: [`CanCore`] plus host model. See the module documentation.
pub struct CanNode {
    name: String,
    clock: ClockSpec,
    /// The controller RTL (read its signals with `.val()` between steps).
    pub core: CanCore,
    cfg: NodeConfig,
    reset_left: u32,
    queue: VecDeque<Frame>,
    current: Option<Frame>,
    /// tx_req must be low for a clock between two requests.
    gap: bool,
    recover_pulse: bool,
    log: Vec<(u64, HostEvent)>,
    tracer: Option<BitTracer>,
    trace: Vec<(u64, String)>,
    cycles: u64,
}

impl CanNode {
    pub fn new(cfg: NodeConfig, clock: ClockSpec) -> Self {
        let mut core = CanCore::with_sync_depth(cfg.sync_depth);
        drive::init(&mut core);
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
        let f = |v: u32| v.saturating_sub(1) as u64;
        self.core.brp.next = f(c.timing.brp).into();
        self.core.prop.next = f(c.timing.prop).into();
        self.core.ph1.next = f(c.timing.ph1).into();
        self.core.sjw.next = f(c.timing.sjw).into();
        self.core.triple.next = c.timing.triple;
        self.core.listen_only.next = c.listen_only;
        self.core.self_test.next = c.self_test;
        self.core.single_shot.next = c.single_shot;
        self.core.host_recovery.next = c.host_recovery;
        self.core.cnt_load.next = false;
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
                self.core.tx_req.next = true;
                self.core.tx_ide.next = f.ide;
                self.core.tx_rtr.next = f.rtr;
                self.core.tx_id.next = (f.id as u64).into();
                self.core.tx_dlc.next = (f.dlc as u64).into();
                self.core.tx_data.next = f.data_word().into();
            }
            _ => self.core.tx_req.next = false,
        }
    }

    fn collect(&mut self, now: u64) {
        let c = &self.core;
        if c.tx_done.val() {
            if let Some(f) = self.current.take() {
                self.log.push((now, HostEvent::TxDone(f)));
            }
            self.gap = true;
        }
        if c.arb_lost.val() {
            self.log.push((now, HostEvent::ArbLost(c.arb_lost_pos.val().index() as u32)));
        }
        if c.error.val() {
            let k = c.err_kind.val().index() as usize;
            let kinds = [(ERRK_BIT, ErrorKind::Bit), (ERRK_STUFF, ErrorKind::Stuff), (ERRK_CRC, ErrorKind::Crc), (ERRK_FORM, ErrorKind::Form), (ERRK_ACK, ErrorKind::Ack)]
                .iter()
                .filter(|(b, _)| (k >> b) & 1 == 1)
                .map(|(_, e)| *e)
                .collect();
            self.log.push((
                now,
                HostEvent::Error {
                    kinds,
                    field: Field::from_code(c.err_field.val().index() as u64).unwrap_or(Field::Reset),
                    pos: c.err_pos.val().index() as u32,
                    tx: c.err_tx.val(),
                },
            ));
            if self.cfg.single_shot {
                self.current = None;
                self.gap = true;
            }
        }
        if c.rx_valid.val() {
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
        self.core.rx.next = io.input(0);
        if self.reset_left > 0 {
            self.reset_left -= 1;
            self.core.reset.next = true;
            self.apply_config();
        } else {
            self.core.reset.next = false;
        }
        if self.gap {
            // tx_req was low for this clock: the next request may start.
            self.core.tx_req.next = false;
            self.gap = false;
        } else {
            self.drive_request();
        }
        self.core.recover.next = std::mem::take(&mut self.recover_pulse);
        drive::cycle(&mut self.core);
        self.collect(io.now());
        io.set_output(0, self.core.tx.val());
    }
    fn probe(&self, probe: &mut dyn Probe) {
        self.core.accept(&self.name, probe);
    }
}
