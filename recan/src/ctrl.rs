//! [`Ctrl`]: one CAN controller of a ReCANcentrate node as a kernel component:
//! the RTL [`CanCore`] plus the native host interface the media-management
//! driver uses (request a frame, withdraw it, deactivate = hold in reset,
//! crash = stop), and an event queue the driver drains between steps.
//!
//! Bind it with one input (its downlink) and one output (its uplink).

use canstar_sim::{ClockSpec, Component, Io};
use crate::spec::CtrlSpec;
use canstar_controller::frame::Frame;
use canstar_controller::fsm::Field;
use canstar_controller::view::CoreView;
use canstar_models::core_sim::CoreSim;
use canstar_models::Engine;
use rust_hdl::prelude::Probe;

/// Clocks the controller is held in reset after power-up.
pub const RESET_CYCLES: u32 = 4;

/// What a controller reported to its host.
#[derive(Clone, Debug, PartialEq)]
pub enum CtrlEvent {
    /// The requested frame was sent.
    TxDone(Frame),
    /// A frame was received.
    Rx(Frame),
    /// An error was detected (while transmitting or not) in `field` (what the SJA1000's
    /// error code capture register reports).
    Error { tx: bool, field: Field },
}

/// A controller with its host interface. See the module documentation.
pub struct Ctrl {
    name: String,
    clock: ClockSpec,
    /// The controller RTL on its engine (outputs through [`CoreView`]).
    pub core: CoreSim,
    spec: CtrlSpec,
    reset_left: u32,
    request: Option<Frame>,
    /// The last frame requested (reported with a `tx_done` that follows a withdraw).
    last: Option<Frame>,
    gap: bool,
    held: bool,
    crashed: bool,
    events: Vec<(u64, CtrlEvent)>,
    cycles: u64,
    /// Error events seen so far (also while inactive: none are produced then).
    pub errors: u64,
    /// Every error event: (time ps, transmitting, FIELD code at the error).
    pub error_log: Vec<(u64, bool, u8)>,
    /// TEC/REC to load at the next clock ([`Ctrl::load_counters`]).
    load: Option<(u32, u32)>,
}

impl Ctrl {
    /// A controller on the compiled model.
    pub fn new(name: &str, spec: &CtrlSpec, clock: ClockSpec) -> Self {
        Self::with_engine(name, spec, clock, Engine::default())
    }

    /// A controller on `engine`.
    pub fn with_engine(name: &str, spec: &CtrlSpec, clock: ClockSpec, engine: Engine) -> Self {
        let core = CoreSim::new(engine, spec.sync_depth);
        let mut c = Ctrl {
            name: name.to_string(),
            clock,
            core,
            spec: spec.clone(),
            reset_left: RESET_CYCLES,
            request: None,
            last: None,
            gap: false,
            held: false,
            crashed: false,
            events: Vec::new(),
            cycles: 0,
            errors: 0,
            error_log: Vec::new(),
            load: None,
        };
        c.apply_config();
        c
    }

    fn apply_config(&mut self) {
        let s = &self.spec;
        let f = |v: u32| v.saturating_sub(1) as u8;
        let i = &mut self.core.inp;
        i.brp = f(s.timing.brp);
        i.prop = f(s.timing.prop);
        i.ph1 = f(s.timing.ph1);
        i.ph2 = f(s.timing.ph2);
        i.sjw = f(s.timing.sjw);
        i.triple = false;
        i.listen_only = false;
        i.self_test = false;
        i.single_shot = false;
        i.host_recovery = false;
    }

    /// Request `f` (replaces a pending request; the controller retries until it is sent).
    pub fn request(&mut self, f: Frame) {
        self.last = Some(f.clone());
        self.request = Some(f);
    }
    /// Withdraw the pending request (an attempt in progress finishes).
    pub fn withdraw(&mut self) {
        self.request = None;
    }
    /// The frame requested and not yet reported sent.
    pub fn pending(&self) -> Option<&Frame> {
        self.request.as_ref()
    }
    /// Deactivate: reset the controller and hold it in reset (uplink recessive).
    pub fn deactivate(&mut self) {
        self.held = true;
        self.request = None;
    }
    /// Crash: the controller stops; its uplink is recessive; it reports nothing.
    pub fn crash(&mut self) {
        self.crashed = true;
        self.request = None;
    }
    /// Power on again after [`Ctrl::crash`] (a node switched off and on): the
    /// controller is reset (counters cleared) and integrates into the bus like a node
    /// at power-up; nothing is requested.
    pub fn power_on(&mut self) {
        self.crashed = false;
        self.held = false;
        self.request = None;
        self.last = None;
        self.gap = false;
        self.reset_left = RESET_CYCLES;
    }
    /// Load TEC and REC at the next clock (a host setting the error counters, e.g. to
    /// make the controller error-passive with TEC >= 128).
    pub fn load_counters(&mut self, tec: u32, rec: u32) {
        self.load = Some((tec, rec));
    }
    pub fn is_held(&self) -> bool {
        self.held
    }
    pub fn is_crashed(&self) -> bool {
        self.crashed
    }
    /// Take the events reported since the last call.
    pub fn take_events(&mut self) -> Vec<(u64, CtrlEvent)> {
        std::mem::take(&mut self.events)
    }
    /// Report `e` at `t` as if the controller had (driver unit tests).
    #[cfg(test)]
    pub(crate) fn report(&mut self, t: u64, e: CtrlEvent) {
        self.events.push((t, e));
    }
    pub fn has_events(&self) -> bool {
        !self.events.is_empty()
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
    /// Is the controller the transmitter of the frame in progress?
    pub fn transmitting(&self) -> bool {
        self.core.dbg_role()
    }
    pub fn cycles(&self) -> u64 {
        self.cycles
    }
    pub fn spec(&self) -> &CtrlSpec {
        &self.spec
    }

    fn collect(&mut self, now: u64) {
        let c = &self.core;
        if c.tx_done() {
            if let Some(f) = self.request.take().or_else(|| self.last.clone()) {
                self.events.push((now, CtrlEvent::TxDone(f)));
            }
            self.gap = true;
        }
        if c.error() {
            self.errors += 1;
            self.error_log.push((now, c.err_tx(), c.field() as u8));
            self.events.push((now, CtrlEvent::Error { tx: c.err_tx(), field: Field::from_code(c.err_field() as u64).unwrap_or(Field::Reset) }));
        }
        if c.rx_valid() {
            let f = c.rx_frame();
            self.events.push((now, CtrlEvent::Rx(f)));
        }
    }
}

impl Component for Ctrl {
    fn name(&self) -> &str {
        &self.name
    }
    fn clock(&self) -> ClockSpec {
        self.clock
    }
    fn tick(&mut self, io: &mut Io<'_>) {
        if self.held || self.crashed {
            // off: no logic runs, the uplink is recessive
            io.set_output(0, true);
            return;
        }
        self.cycles += 1;
        let core = &mut self.core.inp;
        core.rx = io.input(0);
        if self.reset_left > 0 {
            self.reset_left -= 1;
            core.reset = true;
        } else {
            core.reset = false;
        }
        core.tx_abort = false;
        if let Some((t, r)) = self.load.take() {
            core.cnt_load = true;
            core.tec_in = t as u16;
            core.rec_in = r as u8;
        } else {
            core.cnt_load = false;
        }
        if self.gap {
            // tx_req low for one clock after a success
            core.tx_req = false;
            self.gap = false;
        } else if let Some(f) = &self.request {
            core.tx_req = true;
            core.tx_ide = f.ide;
            core.tx_rtr = f.rtr;
            core.tx_id = f.id;
            core.tx_dlc = f.dlc;
            core.tx_data = f.data_word();
        } else {
            core.tx_req = false;
        }
        if self.reset_left > 0 {
            self.apply_config();
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
