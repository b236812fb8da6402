//! The hub without its frame monitor, [`HubCore`] (the complete hub with its monitor is
//! [`crate::top::Hub`]; configuration: [`crate::config::HubConfig`]).
//!
//! [`HubCore`] wires the coupler, the error-flag generator, one port judge unit per
//! uplink, one sublink judge unit per incoming sublink, the frame-state decoder and the
//! fault-injection controller. The frame monitor (bit timing + receive path of the CAN
//! controller in listen-only mode) is *outside* `HubCore`: `HubCore` exports the coupled
//! bit `bt` and takes the monitor's frame state on its `mon_*` inputs, so that frame
//! tracking has exactly one implementation in the code base (the controller's).
//!
//! # Ports (1 = recessive on every CAN line)
//! | port | dir | meaning |
//! |---|---|---|
//! | `rst_n` | in | reset, active low; synchronised by 2 flip-flops ([`RESET_SYNC_DEPTH`]), then a synchronous reset of everything (H3) |
//! | `inject_fault` | in | fault-injection button (H8), unused without hooks |
//! | `rx$i` (N) | in | uplinks |
//! | `reh_rx$j` (M) | in | incoming sublinks |
//! | `mon_sample` | in | strobe: the monitor samples BT now |
//! | `mon_bit_start` | in | strobe: a new bit starts (the error flag starts here) |
//! | `mon_field` (4) | in | field of the bit being sampled, [`crate::frame_state::Field`] code |
//! | `mon_pos` (4) | in | position of that bit in its field (0-based, saturating) |
//! | `mon_crc_ok` | in | the received CRC was correct (valid in the ACK slot) |
//! | `mon_frame_ok` | in | with `mon_sample` at the last EOF bit: the frame completed without error |
//! | `mon_error` | in | with `mon_sample`: stuff, CRC or form error detected at this bit |
//! | `mon_stuff` | in | with `mon_sample`: the sampled bit is a stuff bit |
//! | `tx$i` (N) | out | downlinks, `BT` through one output register |
//! | `hub_tx$j` (M) | out | outgoing sublinks, `ANDC` through one output register |
//! | `bt` | out | the coupled bit, combinational, for the frame monitor |
//! | `reset_out` | out | the synchronised internal reset (active high), for the frame monitor |
//! | `isolated$i`, `silent$i` (N) | out | port isolated (judge `dis`), port reported silent (NACK) |
//! | `sub_isolated$j` (M) | out | sublink isolated |
//! | `frame_state` (4) | out | `mon_field` (H9) |
//! | `efg_active` | out | the hub's error flag is being driven |
//! | `inject_active` | out | an injected fault is active |
//! | `bic$i` (8), `dbc$i` (5), `nack$i` (3) | out | port counters, only with `debug` |
//! | `sub_bic$j` (8), `sub_dbc$j` (5), `sub_rep$j` (3) | out | sublink counters, only with `debug` |
//!
//! Coupling latency (H2): [`HubConfig::coupling_latency`] = sync depth + 1 clock edges
//! from `rx` to `tx` (and from `reh_rx` to `tx`, from `rx` to `hub_tx`): with the default
//! depth 1, 2 clocks (at most 135.7 ns at 14.74 MHz) to the own downlinks and 4 clocks to
//! the other hub's downlinks (measured on the pins in the kernel, plus cable delays).
//!
//! Verilog note: every signal that crosses a module boundary inside a combinational
//! path is assigned exactly once per evaluation (if/else, never "default, then
//! override"). Otherwise the zero-delay glitches of two `always @(*)` blocks that feed
//! each other retrigger one another forever in an event-driven simulator.
//!
//! The hub's error phase for the judges is the monitor's error/overload phase OR the
//! error-flag generator's `busy`; the error flag is triggered at a sample with
//! `mon_error`, with a blame from any judge unit, or with a transmitter bit error seen
//! by a judge unit (H6; see [`crate::judge`]).

use crate::config::{FaultPoint, HubConfig};
use crate::coupler::{self, Coupler};
use crate::efg::ErrorFlagGen;
use crate::frame_state::{Field, FrameDecode};
use crate::inject::Injector;
use crate::judge::JudgeUnit;
use crate::peer::PeerEstimate;
use crate::run_start::RunStart;
use crate::sigs;
use rust_hdl::prelude::*;

/// The hub without its frame monitor (see the module docs for the ports).
#[derive(LogicBlock)]
pub struct HubCore {
    pub clock: Signal<In, Clock>,
    pub rst_n: Signal<In, Bit>,
    pub inject_fault: Signal<In, Bit>,
    pub rx: Vec<Signal<In, Bit>>,
    pub reh_rx: Vec<Signal<In, Bit>>,
    pub mon_sample: Signal<In, Bit>,
    pub mon_bit_start: Signal<In, Bit>,
    pub mon_field: Signal<In, Bits<4>>,
    pub mon_pos: Signal<In, Bits<4>>,
    pub mon_crc_ok: Signal<In, Bit>,
    pub mon_frame_ok: Signal<In, Bit>,
    pub mon_error: Signal<In, Bit>,
    pub mon_stuff: Signal<In, Bit>,
    pub tx: Vec<Signal<Out, Bit>>,
    pub hub_tx: Vec<Signal<Out, Bit>>,
    pub bt: Signal<Out, Bit>,
    /// The synchronised internal reset (active high), for the frame monitor.
    pub reset_out: Signal<Out, Bit>,
    pub isolated: Vec<Signal<Out, Bit>>,
    pub silent: Vec<Signal<Out, Bit>>,
    pub sub_isolated: Vec<Signal<Out, Bit>>,
    pub frame_state: Signal<Out, Bits<4>>,
    pub efg_active: Signal<Out, Bit>,
    pub inject_active: Signal<Out, Bit>,
    pub bic: Vec<Signal<Out, Bits<8>>>,
    pub dbc: Vec<Signal<Out, Bits<5>>>,
    pub nack: Vec<Signal<Out, Bits<3>>>,
    pub sub_bic: Vec<Signal<Out, Bits<8>>>,
    pub sub_dbc: Vec<Signal<Out, Bits<5>>>,
    pub sub_rep: Vec<Signal<Out, Bits<3>>>,
    coupler: Coupler,
    efgen: ErrorFlagGen,
    err_start_r: DFF<Bit>,
    ff_r: DFF<Bit>,
    /// How BT's dominant run began (the dominant stuff bit of §5.10, the early SOF from
    /// the peer's side of §5.26): the first-flagger rule is off in such a run.
    run_start: RunStart,
    gl_one: Signal<Local, Bit>,
    gl_two: Signal<Local, Bit>,
    /// some port glitched in this frame; sublinks with a glitch of their own (not common)
    /// in this frame: at least one, at least two (§5.15)
    gl_port: Signal<Local, Bit>,
    /// Enabled ports dominant: at least one, at least two; an enabled sublink dominant
    /// (the §5.17 follower test's `others_dom`).
    pd_one: Signal<Local, Bit>,
    pd_two: Signal<Local, Bit>,
    sd_one: Signal<Local, Bit>,
    glo_one: Signal<Local, Bit>,
    glo_two: Signal<Local, Bit>,
    sub_bl_r: DFF<Bit>,
    any_sub_blame: Signal<Local, Bit>,
    sub_all_an: Signal<Local, Bit>,
    sub_one: Signal<Local, Bit>,
    sub_two: Signal<Local, Bit>,
    decode: FrameDecode,
    injector: Injector,
    pj: Vec<JudgeUnit>,
    sj: Vec<JudgeUnit>,
    up_code: Vec<Constant<Bits<2>>>,
    down_code: Vec<Constant<Bits<2>>>,
    hub_code: Vec<Constant<Bits<2>>>,
    reset: Signal<Local, Bit>,
    rst_s1: DFF<Bit>,
    rst_s2: DFF<Bit>,
    err_phase: Signal<Local, Bit>,
    bs_r: DFF<Bits<5>>,
    delim_r: DFF<Bit>,
    delim_z: Signal<Local, Bit>,
    stuff_dom: Signal<Local, Bit>,
    any_an: Signal<Local, Bit>,
    any_blame: Signal<Local, Bit>,
    any_tx_error: Signal<Local, Bit>,
    trigger: Signal<Local, Bit>,
    rep_rec: Signal<Local, Bit>,
    rep_dom: Signal<Local, Bit>,
    rep_rec_w: Signal<Local, Bit>,
    rep_gl: Signal<Local, Bit>,
    /// §5.20 peer guard: the estimate of the peer's sublink counters; `pinc`, `pch_*` and
    /// `guard` below come from the units' registered `step`, i.e. the last clock's charges:
    /// `pch_port` a port was charged, `pch_shared` the charge was not a port's alone (two
    /// ports, or a port and a sublink, §5.24).
    peer: PeerEstimate,
    pinc: Signal<Local, Bits<2>>,
    guard: Signal<Local, Bit>,
    pch_port: Signal<Local, Bit>,
    pch_shared: Signal<Local, Bit>,
    _n: usize,
    _m: usize,
    _dn: usize,
    _dm: usize,
    _cfg: HubConfig,
}

impl HubCore {
    /// Build a hub. Panics if the configuration is invalid ([`HubConfig::validate`]).
    pub fn new(cfg: &HubConfig) -> Self {
        if let Err(e) = cfg.validate() {
            panic!("invalid hub configuration: {e}");
        }
        let (n, m) = (cfg.ports, cfg.sublinks);
        let (dn, dm) = if cfg.debug { (n, m) } else { (0, 0) };
        let code = |pt: FaultPoint| -> Constant<Bits<2>> {
            let c = match cfg.fault_injection {
                Some(f) if f.point == pt => f.kind.code(),
                _ => coupler::FAULT_NONE,
            };
            Constant::new(c.into())
        };
        let start = cfg.fault_injection.map(|f| f.start_field as u64).unwrap_or(Field::Eof.code());
        Self {
            clock: Default::default(),
            rst_n: Default::default(),
            inject_fault: Default::default(),
            rx: sigs(n),
            reh_rx: sigs(m),
            mon_sample: Default::default(),
            mon_bit_start: Default::default(),
            mon_field: Default::default(),
            mon_pos: Default::default(),
            mon_crc_ok: Default::default(),
            mon_frame_ok: Default::default(),
            mon_error: Default::default(),
            mon_stuff: Default::default(),
            tx: sigs(n),
            hub_tx: sigs(m),
            bt: Default::default(),
            reset_out: Default::default(),
            isolated: sigs(n),
            silent: sigs(n),
            sub_isolated: sigs(m),
            frame_state: Default::default(),
            efg_active: Default::default(),
            inject_active: Default::default(),
            bic: sigs(dn),
            dbc: sigs(dn),
            nack: sigs(dn),
            sub_bic: sigs(dm),
            sub_dbc: sigs(dm),
            sub_rep: sigs(dm),
            coupler: Coupler::new(n, m, cfg.sync_depth),
            efgen: Default::default(),
            err_start_r: Default::default(),
            ff_r: Default::default(),
            run_start: RunStart::new(cfg.early_sof_clocks),
            gl_one: Default::default(),
            gl_two: Default::default(),
            gl_port: Default::default(),
            pd_one: Default::default(),
            pd_two: Default::default(),
            sd_one: Default::default(),
            glo_one: Default::default(),
            glo_two: Default::default(),
            sub_bl_r: Default::default(),
            any_sub_blame: Default::default(),
            sub_all_an: Default::default(),
            sub_one: Default::default(),
            sub_two: Default::default(),
            decode: Default::default(),
            injector: Injector::new(start),
            pj: (0..n).map(|_| JudgeUnit::port(cfg.port_params())).collect(),
            sj: (0..m).map(|_| JudgeUnit::sublink(cfg.sublink_params())).collect(),
            up_code: (0..n).map(|i| code(FaultPoint::Uplink(i))).collect(),
            down_code: (0..n).map(|i| code(FaultPoint::Downlink(i))).collect(),
            hub_code: (0..m).map(|j| code(FaultPoint::Sublink(j))).collect(),
            reset: Default::default(),
            rst_s1: Default::default(),
            rst_s2: Default::default(),
            err_phase: Default::default(),
            bs_r: Default::default(),
            delim_r: Default::default(),
            delim_z: Default::default(),
            stuff_dom: Default::default(),
            any_an: Default::default(),
            any_blame: Default::default(),
            any_tx_error: Default::default(),
            trigger: Default::default(),
            rep_rec: Default::default(),
            rep_dom: Default::default(),
            rep_rec_w: Default::default(),
            rep_gl: Default::default(),
            peer: PeerEstimate::new(m > 0 && cfg.peer_guard > 0, 8 * cfg.peer_guard, cfg.sub_bic_decay),
            pinc: Default::default(),
            guard: Default::default(),
            pch_port: Default::default(),
            pch_shared: Default::default(),
            _n: n,
            _m: m,
            _dn: dn,
            _dm: dm,
            _cfg: cfg.clone(),
        }
    }
    /// The configuration this hub was built from.
    pub fn config(&self) -> &HubConfig {
        &self._cfg
    }
    /// Simulation probe: some judge unit blames its port or sublink in this clock
    /// (combinational, meaningful after the inputs have settled).
    pub fn blame_any(&self) -> bool {
        self.any_blame.val()
    }
    /// Simulation probe: the port judge unit of port `i`.
    pub fn port_judge(&self, i: usize) -> &JudgeUnit {
        &self.pj[i]
    }
    /// Simulation probe: the sublink judge unit of sublink `j`.
    pub fn sublink_judge(&self, j: usize) -> &JudgeUnit {
        &self.sj[j]
    }
}

impl Logic for HubCore {
    #[hdl_gen]
    fn update(&mut self) {
        // reset synchroniser (2 flip-flops): `rst_n` may come from an asynchronous
        // button; the internal reset (active high) follows it after 2 clocks
        self.rst_s1.clock.next = self.clock.val();
        self.rst_s2.clock.next = self.clock.val();
        self.rst_s1.d.next = !self.rst_n.val();
        self.rst_s2.d.next = self.rst_s1.q.val();
        self.reset.next = self.rst_s2.q.val();
        self.reset_out.next = self.rst_s2.q.val();
        // frame state
        self.decode.clock.next = self.clock.val();
        self.decode.field.next = self.mon_field.val();
        self.decode.pos.next = self.mon_pos.val();
        self.frame_state.next = self.mon_field.val();
        self.err_phase.next = self.decode.err_phase.val() | self.efgen.busy.val();
        // clocks since the estimated bit start (window rule)
        self.bs_r.clock.next = self.clock.val();
        self.bs_r.d.next = self.bs_r.q.val();
        if self.mon_bit_start.val() {
            self.bs_r.d.next = 0.into();
        } else if self.bs_r.q.val() != 31 {
            self.bs_r.d.next = self.bs_r.q.val() + 1;
        }
        // error / overload delimiter after BT went recessive: bits 2..7 must be recessive
        // (the last delimiter bit may be dominant: an overload condition)
        self.delim_r.clock.next = self.clock.val();
        self.delim_r.d.next = self.delim_r.q.val();
        if self.mon_sample.val() {
            self.delim_r.d.next = self.err_phase.val() & self.coupler.bt.val();
        }
        self.delim_z.next = self.err_phase.val()
            & self.delim_r.q.val()
            & !(((self.mon_field.val() == 14) | (self.mon_field.val() == 15)) & (self.mon_pos.val() == 7));
        if self.reset.val() {
            self.delim_r.d.next = false;
        }
        // a stuff bit after five recessive bits: its level must be dominant (judge.rs,
        // stuff-bit rule: a dominant level there is blamed but not charged); whether BT's
        // dominant run began at one, or at an early SOF from the peer's side (§5.26: a
        // sublink and no port dominant), for the first-flagger rule
        self.run_start.clock.next = self.clock.val();
        self.run_start.reset.next = self.reset.val();
        self.run_start.sample.next = self.mon_sample.val();
        self.run_start.bit_start.next = self.mon_bit_start.val();
        self.run_start.stuff.next = self.mon_stuff.val();
        self.run_start.sof.next = self.decode.sof.val();
        self.run_start.bt.next = self.coupler.bt.val();
        self.stuff_dom.next = self.run_start.stuff_dom.val();
        // some unit glitched recently: the other units' blames are not charged
        self.any_an.next = false;
        // units that glitched in this frame: at least one, at least two (first-flagger rule)
        self.gl_one.next = false;
        self.gl_two.next = false;
        for i in 0..self._n {
            self.any_an.next = self.any_an.val() | self.pj[i].anomaly.val();
            if self.pj[i].glf.val() {
                self.gl_two.next = self.gl_two.val() | self.gl_one.val();
                self.gl_one.next = true;
            }
        }
        self.gl_port.next = self.gl_one.val();
        // every enabled replica sublink (at least two) glitched recently: a glitch of
        // the peer's contribution, not counted against the sublinks (hub.md §5.8)
        self.sub_all_an.next = true;
        self.sub_one.next = false;
        self.sub_two.next = false;
        self.glo_one.next = false;
        self.glo_two.next = false;
        for j in 0..self._m {
            if self.sj[j].glf_own.val() {
                self.glo_two.next = self.glo_two.val() | self.glo_one.val();
                self.glo_one.next = true;
            }
            self.any_an.next = self.any_an.val() | self.sj[j].anomaly.val();
            if self.sj[j].glf.val() {
                self.gl_two.next = self.gl_two.val() | self.gl_one.val();
                self.gl_one.next = true;
            }
            if !self.sj[j].dis.val() {
                self.sub_all_an.next = self.sub_all_an.val() & self.sj[j].anomaly.val();
                self.sub_two.next = self.sub_two.val() | self.sub_one.val();
                self.sub_one.next = true;
            }
        }
        // fault injection controller
        self.injector.clock.next = self.clock.val();
        self.injector.reset.next = self.reset.val();
        self.injector.button.next = self.inject_fault.val();
        self.injector.sample.next = self.mon_sample.val();
        self.injector.field.next = self.mon_field.val();
        self.injector.eof_last.next = self.decode.eof_last.val();
        self.inject_active.next = self.injector.active.val();
        // coupler
        self.coupler.clock.next = self.clock.val();
        self.coupler.reset.next = self.reset.val();
        self.coupler.efg.next = self.efgen.efg.val();
        self.bt.next = self.coupler.bt.val();
        // replica summary for the sublink judges
        self.rep_rec.next = false;
        self.rep_dom.next = false;
        self.rep_rec_w.next = false;
        self.rep_gl.next = false;
        self.sd_one.next = false;
        for j in 0..self._m {
            self.coupler.reh_rx[j].next = self.reh_rx[j].val();
            self.hub_tx[j].next = self.coupler.hub_tx[j].val();
            self.coupler.hdis[j].next = self.sj[j].dis.val();
            self.sub_isolated[j].next = self.sj[j].dis.val();
            if self.injector.active.val() {
                self.coupler.hub_fault[j].next = self.hub_code[j].val();
            } else {
                self.coupler.hub_fault[j].next = 0.into();
            }
            if !self.sj[j].dis.val() {
                self.rep_rec.next = self.rep_rec.val() | self.coupler.s[j].val();
                self.rep_dom.next = self.rep_dom.val() | !self.coupler.s[j].val();
                self.rep_rec_w.next = self.rep_rec_w.val() | !self.sj[j].window_dom.val();
                self.rep_gl.next = self.rep_gl.val() | (self.sj[j].gc.val() != 0);
                self.sd_one.next = self.sd_one.val() | !self.coupler.s[j].val();
            }
        }
        // §5.17 the dominant inputs that can lead a unit (enabled ones)
        self.pd_one.next = false;
        self.pd_two.next = false;
        for i in 0..self._n {
            if !self.coupler.u[i].val() & !self.pj[i].dis.val() {
                self.pd_two.next = self.pd_two.val() | self.pd_one.val();
                self.pd_one.next = true;
            }
        }
        // (§5.26) a sublink and no port dominant
        self.run_start.sub_lead.next = self.sd_one.val() & !self.pd_one.val();
        // §5.20 peer guard: the peer charges its sublinks for the episodes that this hub
        // charges to its ports, and takes one off every `sub_bic_decay` good frames; this
        // hub follows that count with the largest charge of a port in each clock; the guard
        // acts only on a port charged alone (two ports charged at once: no culprit; §5.24:
        // nor a port charged with a sublink: the episode came at least partly from the
        // peer's side, where the peer charges its own ports). All one clock late: the units'
        // `step` is registered, and so is the good frame.
        self.pinc.next = 0.into();
        self.pch_port.next = false;
        self.pch_shared.next = false;
        for i in 0..self._n {
            if self.pj[i].step.val() > self.pinc.val() {
                self.pinc.next = self.pj[i].step.val();
            }
            if self.pj[i].step.val() != 0 {
                self.pch_shared.next = self.pch_shared.val() | self.pch_port.val();
                self.pch_port.next = true;
            }
        }
        for j in 0..self._m {
            if self.sj[j].step.val() != 0 {
                self.pch_shared.next = true;
            }
        }
        self.peer.clock.next = self.clock.val();
        self.peer.reset.next = self.reset.val();
        self.peer.inc.next = self.pinc.val();
        self.peer.frame_ok.next = self.mon_sample.val() & self.mon_frame_ok.val();
        self.guard.next = self.peer.high.val() & !self.pch_shared.val();
        // port judges
        self.any_blame.next = false;
        self.any_sub_blame.next = false;
        self.any_tx_error.next = false;
        for i in 0..self._n {
            self.coupler.rx[i].next = self.rx[i].val();
            self.tx[i].next = self.coupler.tx[i].val();
            self.coupler.dis[i].next = self.pj[i].dis.val();
            self.isolated[i].next = self.pj[i].dis.val();
            self.silent[i].next = self.pj[i].silent.val();
            if self.injector.active.val() {
                self.coupler.up_fault[i].next = self.up_code[i].val();
                self.coupler.down_fault[i].next = self.down_code[i].val();
            } else {
                self.coupler.up_fault[i].next = 0.into();
                self.coupler.down_fault[i].next = 0.into();
            }
            self.pj[i].clock.next = self.clock.val();
            self.pj[i].reset.next = self.reset.val();
            self.pj[i].sample.next = self.mon_sample.val();
            self.pj[i].c.next = self.coupler.u[i].val();
            self.pj[i].bt.next = self.coupler.bt.val();
            self.pj[i].sof.next = self.decode.sof.val();
            self.pj[i].tx_region.next = self.decode.tx_region.val();
            self.pj[i].arb.next = self.decode.arb.val();
            self.pj[i].crc_delim.next = self.decode.crc_delim.val();
            self.pj[i].ack_slot.next = self.decode.ack_slot.val();
            self.pj[i].ack_delim.next = self.decode.ack_delim.val();
            self.pj[i].eof_1_6.next = self.decode.eof_1_6.val();
            self.pj[i].eof_last.next = self.decode.eof_last.val();
            self.pj[i].im_2.next = self.decode.im_2.val();
            self.pj[i].im_12.next = self.decode.im_12.val();
            self.pj[i].err_phase.next = self.err_phase.val();
            self.pj[i].crc_ok.next = self.mon_crc_ok.val();
            self.pj[i].frame_ok.next = self.mon_frame_ok.val();
            self.pj[i].err_start.next = false;
            self.pj[i].rep_rec.next = false;
            self.pj[i].rep_dom.next = false;
            self.pj[i].rep_mask.next = false;
            self.pj[i].rep_other.next = false;
            self.pj[i].rep_rec_w.next = false;
            self.pj[i].rep_glitched.next = false;
            self.pj[i].rep_blamed.next = false;
            self.pj[i].common.next = false;
            self.pj[i].ff.next = self.ff_r.q.val();
            self.pj[i].others_dom.next = self.pd_two.val() | (self.pd_one.val() & (self.coupler.u[i].val() | self.pj[i].dis.val())) | self.sd_one.val();
            self.pj[i].sub_dom.next = self.sd_one.val();
            self.pj[i].gl_others.next = self.gl_two.val() | (self.gl_one.val() & !self.pj[i].glf.val());
            self.pj[i].guard.next = self.guard.val();
            self.pj[i].bit_start.next = self.mon_bit_start.val();
            self.pj[i].bs_cnt.next = self.bs_r.q.val();
            self.pj[i].delim.next = self.delim_z.val();
            self.pj[i].stuff_dom.next = self.stuff_dom.val();
            self.pj[i].suppress.next = self.any_an.val() & !self.pj[i].anomaly.val();
            self.any_blame.next = self.any_blame.val() | self.pj[i].blame.val();
            self.any_tx_error.next = self.any_tx_error.val() | self.pj[i].tx_error.val();
        }
        for j in 0..self._m {
            self.sj[j].clock.next = self.clock.val();
            self.sj[j].reset.next = self.reset.val();
            self.sj[j].sample.next = self.mon_sample.val();
            self.sj[j].c.next = self.coupler.s[j].val();
            self.sj[j].bt.next = self.coupler.bt.val();
            self.sj[j].sof.next = self.decode.sof.val();
            self.sj[j].tx_region.next = self.decode.tx_region.val();
            self.sj[j].arb.next = self.decode.arb.val();
            self.sj[j].crc_delim.next = self.decode.crc_delim.val();
            self.sj[j].ack_slot.next = self.decode.ack_slot.val();
            self.sj[j].ack_delim.next = self.decode.ack_delim.val();
            self.sj[j].eof_1_6.next = self.decode.eof_1_6.val();
            self.sj[j].eof_last.next = self.decode.eof_last.val();
            self.sj[j].im_2.next = self.decode.im_2.val();
            self.sj[j].im_12.next = self.decode.im_12.val();
            self.sj[j].err_phase.next = self.err_phase.val();
            self.sj[j].crc_ok.next = self.mon_crc_ok.val();
            self.sj[j].frame_ok.next = self.mon_frame_ok.val();
            self.sj[j].rep_rec.next = self.rep_rec.val();
            self.sj[j].rep_dom.next = self.rep_dom.val();
            // (§5.18: a port or the hub's own flag decides BT, the replicas do not)
            self.sj[j].rep_mask.next = self.pd_one.val() | !self.efgen.efg.val();
            self.sj[j].rep_other.next = self.sub_two.val();
            self.sj[j].rep_rec_w.next = self.rep_rec_w.val();
            self.sj[j].rep_glitched.next = self.rep_gl.val();
            self.sj[j].bit_start.next = self.mon_bit_start.val();
            self.sj[j].bs_cnt.next = self.bs_r.q.val();
            self.sj[j].delim.next = self.delim_z.val();
            self.sj[j].stuff_dom.next = self.stuff_dom.val();
            self.sj[j].suppress.next = self.any_an.val() & !self.sj[j].anomaly.val();
            self.any_blame.next = self.any_blame.val() | self.sj[j].blame.val();
            self.any_sub_blame.next = self.any_sub_blame.val() | self.sj[j].blame.val();
            self.any_tx_error.next = self.any_tx_error.val() | self.sj[j].tx_error.val();
        }
        // error flag (H6)
        self.trigger.next = self.mon_sample.val() & (self.mon_error.val() | self.any_blame.val() | self.any_tx_error.val());
        // start of an error episode, registered (one clock after the sample point) so
        // that the replica evaluation does not depend combinationally on the blames
        self.err_start_r.clock.next = self.clock.val();
        self.err_start_r.d.next = self.trigger.val() & !self.efgen.busy.val();
        // (a sample that started or renewed an error episode: the next bit carries the
        // reactions to that error and is no delimiter bit that must be recessive)
        if self.trigger.val() {
            self.delim_r.d.next = false;
        }
        // first-flagger rule (judge.rs §5.12): the monitor alone started the episode, in
        // the transmission region, and BT's dominant run did not begin at a dominant stuff
        // bit or at an early SOF (§5.26) (each unit excuses itself if another input glitched)
        self.ff_r.clock.next = self.clock.val();
        self.ff_r.d.next = self.trigger.val()
            & !self.efgen.busy.val()
            & self.mon_error.val()
            & !self.any_blame.val()
            & !self.any_tx_error.val()
            & !self.run_start.excused.val()
            & !self.stuff_dom.val()
            & self.decode.tx_region.val();
        if self.reset.val() {
            self.ff_r.d.next = false;
        }
        // some sublink was blamed at the sample that started the episode (replica rule)
        self.sub_bl_r.clock.next = self.clock.val();
        self.sub_bl_r.d.next = self.any_sub_blame.val();
        for j in 0..self._m {
            self.sj[j].err_start.next = self.err_start_r.q.val();
            self.sj[j].ff.next = self.ff_r.q.val();
            // (a common glitch, the peer's contribution on every replica, does not excuse
            // the replicas from each other, §5.15)
            self.sj[j].others_dom.next = self.pd_one.val();
            self.sj[j].sub_dom.next = false;
            self.sj[j].gl_others.next = self.gl_port.val() | self.glo_two.val() | (self.glo_one.val() & !self.sj[j].glf_own.val());
            self.sj[j].rep_blamed.next = self.sub_bl_r.q.val();
            self.sj[j].common.next = self.sub_all_an.val() & self.sub_two.val();
            self.sj[j].guard.next = false;
        }
        self.efgen.clock.next = self.clock.val();
        self.efgen.reset.next = self.reset.val();
        self.efgen.trigger.next = self.trigger.val();
        self.efgen.bit_start.next = self.mon_bit_start.val();
        self.efg_active.next = self.efgen.active.val();
        // debug counters
        for i in 0..self._dn {
            self.bic[i].next = self.pj[i].bic.val();
            self.dbc[i].next = self.pj[i].dbc.val();
            self.nack[i].next = self.pj[i].nack.val();
        }
        for j in 0..self._dm {
            self.sub_bic[j].next = self.sj[j].bic.val();
            self.sub_dbc[j].next = self.sj[j].dbc.val();
            self.sub_rep[j].next = self.sj[j].rep_cnt.val();
        }
    }
}

canstar_hdl::impl_clocked!(HubCore);

/// Flip-flops of the reset synchroniser: the internal reset follows `rst_n` after this
/// many clocks, and the outputs are recessive one clock later.
pub const RESET_SYNC_DEPTH: usize = 2;
