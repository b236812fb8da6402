//! Lock-step checking of the RTL controller against the golden model
//! (can-protocol.md §19).
//!
//! [`LockstepNode`] is a kernel [`Component`] that wraps a [`CanNode`] (the
//! RTL [`canstar_controller::CanCore`] with its host model) and runs, on the
//! same clock and the same receive stream, an independent golden node made
//! of two parts:
//!
//! - a clock-exact golden bit timing: the RX synchroniser (a shift register of
//!   `sync_depth` stages, recessive under reset) followed by
//!   [`canstar_hdl::btl::BtlCycleModel`], the prescaler and the normative
//!   §2.3 counter model ([`canstar_hdl::btl::BtlModel`]). Its `drive` and
//!   `hs_en` inputs come from the golden bit-stream model below, presented
//!   with the RTL's bit-stream latency (the decision taken at a sample point
//!   is used by the bit timing from the second clock after the sample
//!   strobe, the same instant as [`canstar_controller::fsm::CanFsm`] presents
//!   it; the IPT of §2.5 is at least 2 clocks, so the decision is always in
//!   place by the earliest transmit point);
//! - the golden bit-stream model [`GoldenNode`], stepped at every sample
//!   point of the golden bit timing with the golden sampled level.
//!
//! The golden model follows the DUT's `reset` input: on a clock with reset
//! asserted it is reset too, and its cleared counters and state are the
//! compared values from that clock on (the DUT clears its own on the same
//! clock); on the release it enters Wait_For_Bus_Idle, and its `hs_en`
//! (set there, §3.3) is presented to the golden bit timing at once, as the
//! DUT's bit-stream logic presents its own.
//!
//! So the golden side never looks at the RTL except for the host request
//! (§19.2 start alignment: the golden request follows the DUT's
//! `dbg_tx_rqst`; its frame is the one on the DUT's `tx_*` request inputs)
//! and for the §19.6 REC adoption. Only the DUT's TX drives the bus.
//!
//! # What is compared, and when
//!
//! Nothing is compared until the DUT has sampled its first dominant bit after
//! reset (§19.3, "arming"). From then on, after every clock edge of the node:
//!
//! | item | golden value | when | tolerance |
//! |---|---|---|---|
//! | `dbg_sample` (sample instant) | registered sample strobe of the golden bit timing | every clock | exact |
//! | `dbg_busmon` (sampled level) | golden `busmon` | every clock | exact |
//! | TX pin | golden `tx` pin | every clock | exact |
//! | driven bit | [`StepOut::drove`] vs TX at the sample strobe | every sample point | exact |
//! | TEC | golden TEC | every clock | exact |
//! | REC | golden REC | every clock | exact while golden REC ≤ 127, else "both > 127" |
//! | state (EA/EP/bus-off) | golden state | every clock | exact |
//! | received frame | [`StepOut::delivered`] | on the clock the DUT shows the bit's results (`rx_valid`) | identical frame in the same bit, both ways |
//!
//! Golden counters and state become visible one clock after the golden step
//! (the clock on which the DUT shows the results of the bit, its `EV_BIT`
//! event word), so every clock compares like with like.
//!
//! The clock-exact comparison is stricter than the ±TQ/2 window of §19.5:
//! with BRP = 1 the two are identical, with BRP > 1 the golden prescaler is
//! aligned with the DUT's (both start at the release of reset, C4), so an
//! edge that passes the window also passes the exact comparison unless the
//! DUT places it on another TQ, which §2.3 forbids.
//!
//! §19.6: when a successful reception drops the golden REC from above 127
//! and the DUT's REC is in 119..=127, the golden model adopts the DUT's
//! value. Diagnostics (§19.7, reported next to the first real mismatch but
//! never a failure themselves): FIELD/POSITION/stuff/role labels, and the
//! event words.
//!
//! The first mismatch stops checking and is kept as a [`Divergence`] (time,
//! node, signal, both values, golden and DUT labels and counters, the last
//! 20 trace lines of both sides, diagnostics). [`LockstepNode::divergence`]
//! returns it; runs stop on it (see [`crate::fuzz`], which also rewrites the
//! window around it as a VCD by rerunning the seed).

use std::collections::VecDeque;
use std::fmt;

use canstar_controller::fsm::{self as cfsm};
use canstar_controller::trace::BitTracer;
use canstar_hdl::btl::{BtlCycleModel, BtlInputs};
use canstar_controller::view::CoreView;
use rust_hdl::prelude::*;

use canstar_golden::{self as golden, trace::trace_line, BitLabel, Event, FaultState, GoldenNode, StepOut};
use canstar_sim::{ClockSpec, Component, Io};
use crate::node::{CanNode, NodeConfig};

/// Number of trace lines of each side kept for a report (§19.8).
pub const TRACE_KEEP: usize = 20;

/// The first mismatch between the DUT and its golden model.
#[derive(Clone, Debug, PartialEq)]
pub struct Divergence {
    /// Node name.
    pub node: String,
    /// Time of the clock edge after which the mismatch was seen, in ps.
    pub t_ps: u64,
    /// What differs (`sample`, `busmon`, `tx`, `drove`, `tec`, `rec`, `state`, `rx_frame`).
    pub signal: String,
    pub dut: String,
    pub golden: String,
    /// Label of the golden bit in progress (or just processed), e.g. `Rx_Data_Field 12`.
    pub golden_label: String,
    /// The DUT's debug FIELD/POSITION/stuff/role.
    pub dut_label: String,
    /// Golden (tec, rec, state) and DUT (tec, rec, state).
    pub golden_counters: (u16, u8, String),
    pub dut_counters: (u32, u32, String),
    /// Diagnostic differences seen so far (labels, event words), most recent last.
    pub warnings: Vec<String>,
    /// Last trace lines of the golden model (`G<name>`) and of the DUT (`D<name>`).
    pub golden_trace: Vec<String>,
    pub dut_trace: Vec<String>,
    /// Seed of the run, if the harness set one ([`LockstepNode::set_seed`]).
    pub seed: Option<u64>,
}

impl fmt::Display for Divergence {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "lock-step divergence at {} ns, node {}{}: {} DUT={} golden={}",
            self.t_ps / 1000,
            self.node,
            self.seed.map(|s| format!(" (seed {s})")).unwrap_or_default(),
            self.signal,
            self.dut,
            self.golden
        )?;
        writeln!(f, "  golden bit: {}   DUT bit: {}", self.golden_label, self.dut_label)?;
        writeln!(
            f,
            "  golden tec/rec/state {}/{}/{}   DUT {}/{}/{}",
            self.golden_counters.0,
            self.golden_counters.1,
            self.golden_counters.2,
            self.dut_counters.0,
            self.dut_counters.1,
            self.dut_counters.2
        )?;
        for w in &self.warnings {
            writeln!(f, "  warning: {w}")?;
        }
        writeln!(f, "  last golden trace lines:")?;
        for l in &self.golden_trace {
            writeln!(f, "    {l}")?;
        }
        writeln!(f, "  last DUT trace lines:")?;
        for l in &self.dut_trace {
            writeln!(f, "    {l}")?;
        }
        Ok(())
    }
}

/// Counts of what a node has compared.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LockstepStats {
    /// Clocks compared (after arming).
    pub clocks: u64,
    /// Sample points compared (after arming).
    pub bits: u64,
    /// Frames delivered by both sides and found identical.
    pub frames: u64,
    /// §19.6 adoptions.
    pub rec_adoptions: u64,
}

/// Golden results of one step, shown on the clock after it.
struct Shown {
    out: StepOut,
    rec_before: u8,
}

fn state_token(s: FaultState) -> &'static str {
    s.token()
}

fn dut_state_token(s: u32) -> &'static str {
    match s {
        0 => "EA",
        1 => "EP",
        _ => "BO",
    }
}

fn to_golden_frame(f: &canstar_controller::frame::Frame) -> golden::Frame {
    golden::Frame { ide: f.ide, id: f.id, rtr: f.rtr, dlc: f.dlc, data: f.data.clone() }
}

fn label_text(l: &BitLabel) -> String {
    format!("{} {}{}", l.field_name(), l.pos, if l.stuff { " (stuff)" } else { "" })
}

/// The RTL node and its golden model in lock step (see the module documentation).
///
/// Bind it like a [`CanNode`] with one input (RX) and one output (TX); an
/// optional second and third output receive the golden TX and the golden
/// sample strobe (for waveforms).
pub struct LockstepNode {
    /// The device under test (RTL + host model).
    pub node: CanNode,
    golden: GoldenNode,
    btl: BtlCycleModel,
    /// Timing fields (value - 1 encoding) for the golden bit timing.
    btl_cfg: BtlInputs,
    /// Synchroniser model, stage 0 first.
    sync: Vec<bool>,
    /// `drive`/`hs_en` as the bit timing sees them on the current clock.
    g_drive: bool,
    g_hs_en: bool,
    /// New `drive`/`hs_en`, used from the next clock.
    pipe: Option<(bool, bool)>,
    /// Golden step to show on the next clock.
    shown: Option<Shown>,
    /// Golden counters and state as shown (one clock after the step).
    vis: (u16, u8, FaultState),
    /// Label of the last golden step.
    last_label: Option<BitLabel>,
    in_reset: bool,
    armed: bool,
    prev_rqst: bool,
    divergence: Option<Divergence>,
    warnings: Vec<String>,
    g_trace: VecDeque<String>,
    d_trace: VecDeque<String>,
    tracer: BitTracer,
    seed: Option<u64>,
    stats: LockstepStats,
    /// Every golden step (time ps, result), when recording is on.
    record: Option<Vec<(u64, StepOut)>>,
    /// Test hook: corrupt the golden TEC by this amount at the first golden step after arming.
    pub inject_tec_fault: Option<u16>,
}

impl LockstepNode {
    /// Wrap a new [`CanNode`] with configuration `cfg` on `clock`.
    pub fn new(cfg: NodeConfig, clock: ClockSpec) -> Self {
        let gcfg = golden::Config {
            listen_only: cfg.listen_only,
            self_test: cfg.self_test,
            single_shot: cfg.single_shot,
            host_recovery: cfg.host_recovery,
            rec_bosch_1999: cfg.rec_rule == canstar_controller::core::RecRule::Bosch1999,
        };
        let depth = cfg.sync_depth;
        // the golden RX path: `depth` synchroniser stages + the bit timing's own register
        assert_eq!(depth + canstar_hdl::btl::L_RX, canstar_controller::core::CanCore::l_rx(depth), "L_rx model");
        let name = cfg.name.clone();
        let f = |v: u32| v.saturating_sub(1);
        let btl_cfg = BtlInputs {
            reset: false,
            brp: f(cfg.timing.brp),
            prop: f(cfg.timing.prop),
            ph1: f(cfg.timing.ph1),
            ph2: f(cfg.timing.ph2),
            sjw: f(cfg.timing.sjw),
            triple: cfg.timing.triple,
            rx: true,
            drive: true,
            hs_en: false,
        };
        let mut golden = GoldenNode::new(gcfg);
        golden.hold_reset(true);
        LockstepNode {
            node: CanNode::new(cfg, clock),
            g_drive: golden.drive(),
            g_hs_en: golden.hs_en(),
            golden,
            btl: BtlCycleModel::new(),
            btl_cfg,
            sync: vec![true; depth],
            pipe: None,
            shown: None,
            vis: (0, 0, FaultState::ErrorActive),
            last_label: None,
            in_reset: true,
            armed: false,
            prev_rqst: false,
            divergence: None,
            warnings: Vec::new(),
            g_trace: VecDeque::new(),
            d_trace: VecDeque::new(),
            tracer: BitTracer::new(&format!("D{name}")),
            seed: None,
            stats: LockstepStats::default(),
            record: None,
            inject_tec_fault: None,
        }
    }

    /// Test hook: give the golden synchroniser `extra` more stages than the DUT's (a wrong
    /// `L_rx`), which must show up as a sample-instant or sampled-level divergence.
    pub fn skew_golden_rx(&mut self, extra: usize) {
        self.sync.extend(std::iter::repeat_n(true, extra));
    }
    /// Seed reported with a divergence.
    pub fn set_seed(&mut self, seed: u64) {
        self.seed = Some(seed);
    }
    /// Keep every golden step (for property checks and tests).
    pub fn record_steps(&mut self) {
        self.record = Some(Vec::new());
    }
    /// Golden steps recorded so far (empty unless [`Self::record_steps`]).
    pub fn steps(&self) -> &[(u64, StepOut)] {
        self.record.as_deref().unwrap_or(&[])
    }
    /// The first divergence, if any.
    pub fn divergence(&self) -> Option<&Divergence> {
        self.divergence.as_ref()
    }
    /// Has the checker armed (§19.3)?
    pub fn armed(&self) -> bool {
        self.armed
    }
    /// Diagnostic differences (labels, event words) seen so far (at most 8).
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }
    pub fn stats(&self) -> LockstepStats {
        self.stats
    }
    /// The golden bit-stream model.
    pub fn golden(&self) -> &GoldenNode {
        &self.golden
    }

    fn push_trace(q: &mut VecDeque<String>, l: String) {
        if q.len() == TRACE_KEEP {
            q.pop_front();
        }
        q.push_back(l);
    }

    fn dut_label(&self) -> String {
        let c = &self.node.core;
        let fld = cfsm::Field::from_code(c.dbg_field() as u64);
        let f = fld.map(|f| f.name()).unwrap_or("?");
        format!(
            "{}{} {}{}",
            if c.dbg_role() && fld.is_some_and(|f| f.has_role()) { "Tx_" } else { "" },
            f,
            c.dbg_pos(),
            if c.dbg_stuff() { " (stuff)" } else { "" }
        )
    }

    fn fail(&mut self, now: u64, signal: &str, dut: String, golden: String) {
        if self.divergence.is_some() {
            return;
        }
        let n = &self.node;
        let gl = if self.golden_in_bit() {
            self.golden.label()
        } else {
            self.last_label.unwrap_or_else(|| self.golden.label())
        };
        self.divergence = Some(Divergence {
            node: self.node.config().name.clone(),
            t_ps: now,
            signal: signal.to_string(),
            dut,
            golden,
            golden_label: label_text(&gl),
            dut_label: self.dut_label(),
            golden_counters: (self.vis.0, self.vis.1, state_token(self.vis.2).to_string()),
            dut_counters: (n.tec(), n.rec(), dut_state_token(n.state()).to_string()),
            warnings: self.warnings.clone(),
            golden_trace: self.g_trace.iter().cloned().collect(),
            dut_trace: self.d_trace.iter().cloned().collect(),
            seed: self.seed,
        });
    }

    fn golden_in_bit(&self) -> bool {
        self.shown.is_none()
    }

    fn warn(&mut self, w: String) {
        if self.warnings.len() < 8 {
            self.warnings.push(w);
        }
    }

    /// The frame on the DUT's request inputs.
    fn requested_frame(&self) -> golden::Frame {
        let c = &self.node.core;
        let i = &c.inp;
        let f = canstar_controller::frame::Frame::from_native(i.tx_ide, i.tx_rtr, i.tx_id, i.tx_dlc, i.tx_data);
        to_golden_frame(&f)
    }

    /// Events of the DUT's event word as §18 tokens (for diagnostics).
    fn dut_event_mask(&self) -> u64 {
        (self.node.core.dbg_events() as u64) & !(1u64 << cfsm::EV_INTEGRATED)
    }

    fn golden_event_mask(out: &StepOut) -> u64 {
        let mut m = 1u64 << cfsm::EV_BIT;
        for e in &out.events {
            let b = match e {
                Event::Sof => cfsm::EV_SOF,
                Event::ArbLost(_) => cfsm::EV_ARB_LOST,
                Event::Error(k) => match k {
                    golden::ErrorKind::Bit => cfsm::EV_BIT_ERR,
                    golden::ErrorKind::Stuff => cfsm::EV_STUFF_ERR,
                    golden::ErrorKind::Crc => cfsm::EV_CRC_ERR,
                    golden::ErrorKind::Form => cfsm::EV_FORM_ERR,
                    golden::ErrorKind::Ack => cfsm::EV_ACK_ERR,
                },
                Event::Aef => cfsm::EV_AEF,
                Event::Pef => cfsm::EV_PEF,
                Event::Olf => cfsm::EV_OLF,
                Event::Ovl => cfsm::EV_OVL,
                Event::Daf(_) => cfsm::EV_DAF,
                Event::TxOk => cfsm::EV_TX_OK,
                Event::RxOk(_) => cfsm::EV_RX_OK,
                Event::Exc1 => cfsm::EV_EXC1,
                Event::Exc2 => cfsm::EV_EXC2,
                Event::Run(_) => cfsm::EV_RUN,
                Event::Recovered => cfsm::EV_RECOVERED,
                _ => continue,
            };
            m |= 1 << b;
        }
        m
    }

    /// Everything after the DUT's clock edge at `now` with `rx_raw` the RX level it read.
    fn check(&mut self, now: u64, rx_raw: bool) {
        let reset = self.node.core.inp.reset;
        let t_ns = now / 1000;

        // ---- golden bit timing: this clock's inputs, then the edge.
        let depth = self.sync.len();
        let inputs = BtlInputs {
            reset,
            rx: self.sync[depth - 1],
            drive: self.g_drive,
            hs_en: self.g_hs_en,
            ..self.btl_cfg
        };
        self.btl.step(&inputs);
        if reset {
            self.sync.iter_mut().for_each(|s| *s = true);
        } else {
            for k in (1..depth).rev() {
                self.sync[k] = self.sync[k - 1];
            }
            self.sync[0] = rx_raw;
        }
        // Golden bit-stream model: reset follows the DUT's reset input.
        let mut released = false;
        if reset {
            if !self.in_reset {
                self.golden.hold_reset(true);
            }
            self.in_reset = true;
            self.pipe = None;
            self.shown = None;
            // A hardware reset clears the DUT's counters and state on this
            // clock: so does it the golden model's, visible at once.
            self.vis = (self.golden.tec(), self.golden.rec(), self.golden.state());
        } else if self.in_reset {
            self.in_reset = false;
            self.golden.hold_reset(false);
            released = true;
        }
        if let Some((d, h)) = self.pipe.take() {
            self.g_drive = d;
            self.g_hs_en = h;
        }
        // On the release of reset the golden model enters Wait_For_Bus_Idle,
        // where hard synchronisation is enabled (§3.3): present it at once,
        // as the DUT does, not only from the first golden sample point.
        if self.in_reset || released {
            self.g_drive = self.golden.drive();
            self.g_hs_en = self.golden.hs_en();
        }
        let p_sample = !reset && self.btl.last_events().is_some_and(|e| e.sample);
        let (p_busmon, p_tx) = self.btl.model().map(|m| (m.busmon, m.tx)).unwrap_or((true, true));

        // ---- DUT trace (for reports).
        for l in self.tracer.clock(t_ns, &self.node.core) {
            Self::push_trace(&mut self.d_trace, l);
        }

        // ---- request alignment (§19.2).
        let rqst = self.node.core.dbg_tx_rqst();
        if rqst && !self.prev_rqst {
            let fr = self.requested_frame();
            self.golden.request(fr);
        } else if !rqst && self.prev_rqst && self.golden.pending() {
            self.golden.withdraw();
        }
        self.prev_rqst = rqst;

        // ---- results of the previous golden step become visible.
        let c_rx_valid = self.node.core.rx_valid();
        let dut_frame = c_rx_valid.then(|| {
            let c = &self.node.core;
            to_golden_frame(&c.rx_frame())
        });
        let mut delivered_golden: Option<golden::Frame> = None;
        let mut had_shown = false;
        if let Some(sh) = self.shown.take() {
            had_shown = true;
            let out = &sh.out;
            let mut rec = out.rec;
            // §19.6
            if sh.rec_before > 127 && out.rec <= 127 && out.delivered().is_some() {
                let d = self.node.rec();
                if (119..=127).contains(&d) && d as u8 != out.rec {
                    self.golden.adopt_rec(d as u8);
                    rec = d as u8;
                    self.stats.rec_adoptions += 1;
                }
            }
            self.vis = (out.tec, rec, out.state);
            delivered_golden = out.delivered().cloned();
            if self.armed {
                let dm = self.dut_event_mask();
                let gm = Self::golden_event_mask(out);
                if dm != gm {
                    self.warn(format!("{t_ns} ns: event word DUT {dm:#x} golden {gm:#x}"));
                }
            }
        }

        // ---- arming (§19.3): the DUT's first sampled dominant bit.
        if !self.armed && !reset && self.node.core.dbg_sample() && !self.node.core.dbg_busmon() {
            self.armed = true;
        }

        // ---- comparisons (§19.4).
        if self.armed && self.divergence.is_none() {
            self.stats.clocks += 1;
            let (d_sample, d_busmon, d_tx) = {
                let c = &self.node.core;
                (c.dbg_sample(), c.dbg_busmon(), c.tx())
            };
            if d_sample != p_sample {
                self.fail(now, "sample", d_sample.to_string(), p_sample.to_string());
            } else if d_busmon != p_busmon {
                self.fail(now, "busmon", (d_busmon as u8).to_string(), (p_busmon as u8).to_string());
            } else if d_tx != p_tx {
                self.fail(now, "tx", (d_tx as u8).to_string(), (p_tx as u8).to_string());
            }
            let (tec, rec, st) = (self.node.tec(), self.node.rec(), self.node.state());
            let g = self.vis;
            if tec != g.0 as u32 {
                self.fail(now, "tec", tec.to_string(), g.0.to_string());
            }
            let rec_ok = if g.1 <= 127 { rec == g.1 as u32 } else { rec > 127 };
            if !rec_ok {
                self.fail(now, "rec", rec.to_string(), g.1.to_string());
            }
            if dut_state_token(st) != state_token(g.2) {
                self.fail(now, "state", dut_state_token(st).into(), state_token(g.2).into());
            }
            if had_shown || c_rx_valid {
                if dut_frame != delivered_golden {
                    self.fail(now, "rx_frame", format!("{dut_frame:?}"), format!("{delivered_golden:?}"));
                } else if dut_frame.is_some() {
                    self.stats.frames += 1;
                }
            }
        }

        // ---- golden sample point: step the bit-stream model.
        if p_sample {
            let label_dut = self.dut_label();
            let rec_before = self.golden.rec();
            let mut out = self.golden.step(p_busmon);
            if self.armed {
                if let Some(k) = self.inject_tec_fault.take() {
                    out.tec += k;
                }
            }
            if self.armed && self.divergence.is_none() {
                self.stats.bits += 1;
                let d_tx = self.node.core.tx();
                if d_tx != out.drove {
                    self.fail(now, "drove", (d_tx as u8).to_string(), (out.drove as u8).to_string());
                }
                let gl = label_text(&out.label);
                // (the DUT's 8-bit debug POSITION saturates at 255, e.g. in a long Bus_Idle)
                let gl_cmp = format!("{}{} {}{}",
                    if out.label.role == golden::Role::Tx { "Tx_" } else { "" },
                    out.label.field.name(), out.label.pos.min(255), if out.label.stuff { " (stuff)" } else { "" });
                if gl_cmp != label_dut {
                    self.warn(format!("{t_ns} ns: label DUT {label_dut} golden {gl}"));
                }
            }
            Self::push_trace(&mut self.g_trace, trace_line(t_ns, &format!("G{}", self.node.config().name), &out));
            self.pipe = Some((out.next_drive, self.golden.hs_en()));
            self.last_label = Some(out.label);
            if let Some(r) = self.record.as_mut() {
                r.push((now, out.clone()));
            }
            self.shown = Some(Shown { out, rec_before });
        }
    }
}

impl Component for LockstepNode {
    fn name(&self) -> &str {
        self.node.name()
    }
    fn clock(&self) -> ClockSpec {
        self.node.clock()
    }
    fn tick(&mut self, io: &mut Io<'_>) {
        let rx_raw = io.input(0);
        self.node.tick(io);
        self.check(io.now(), rx_raw);
        if io.n_outputs() > 2 {
            let (_, tx) = self.btl.model().map(|m| (m.busmon, m.tx)).unwrap_or((true, true));
            io.set_output(1, tx);
            io.set_output(2, self.btl.last_events().is_some_and(|e| e.sample));
        }
    }
    fn probe(&self, probe: &mut dyn Probe) {
        self.node.probe(probe);
    }
    fn set_trace(&mut self, on: bool) {
        self.node.set_trace(on);
    }
}
