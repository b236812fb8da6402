//! The generated hub RTL as a kernel component ([`RtlHub`]), with judge statistics
//! and input recording for replay (co-simulation, benchmarks).

use canstar_hub::cause::{isolation_cause, JudgeCounts};
use canstar_hub::judge::JudgeParams;
use canstar_models::hub_sim::HubSim;
use canstar_models::Engine;
use canstar_sim::{ClockSpec, Component, Io};

/// The generated hub RTL ([`canstar_hub::top::Hub`], frame monitor included) as a
/// kernel component. Bind it exactly like [`AndHub`]:
/// `sim.add(hub, &ports.hub_inputs(), &ports.hub_outputs())` (inputs: uplinks then
/// incoming sublinks; outputs: downlinks then outgoing sublinks).
///
/// `rst_n` is held low for the first [`RtlHub::RESET_CYCLES`] clocks, then high.
/// The `inject_fault` button is a field ([`RtlHub::inject_button`]): set it from
/// the test or schedule presses with [`RtlHub::press_inject_at`].
pub struct RtlHub {
    name: String,
    clock: ClockSpec,
    /// The RTL on its engine (read status outputs such as `isolated(i)` between steps).
    pub hub: HubSim,
    n: usize,
    m: usize,
    cycles: u64,
    /// Level of the `inject_fault` input.
    pub inject_button: bool,
    /// Scheduled presses: (start ps, end ps) during which the button is held.
    presses: Vec<(u64, u64)>,
    /// What the judges did so far (updated every clock).
    pub stats: HubStats,
    record: Option<Vec<u64>>,
    samples: Option<Vec<(u64, bool, u8)>>,
    /// Judge parameters of the port units and of the sublink units.
    params: [JudgeParams; 2],
}

/// Judge activity of an [`RtlHub`], accumulated clock by clock (needs
/// `debug: true` in the configuration for the counter maxima).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct HubStats {
    /// Clocks in which some judge unit blamed its port or sublink (`HubCore::blame_any`).
    pub blames: u64,
    /// Largest `bic` seen per port / per sublink.
    pub max_bic: Vec<u64>,
    pub max_sub_bic: Vec<u64>,
    /// Largest `dbc` seen per port / per sublink.
    pub max_dbc: Vec<u64>,
    pub max_sub_dbc: Vec<u64>,
    /// Largest replica-rule count (`rep_cnt`, hub.md §5.7) seen per sublink: charges of
    /// the replica rule (it never decays).
    pub max_sub_rep: Vec<u64>,
    /// Time (ps) of the first clock with the port / sublink isolated.
    pub isolated_at: Vec<Option<u64>>,
    pub sub_isolated_at: Vec<Option<u64>>,
    /// Why each port / sublink was isolated ([`canstar_hub::cause::isolation_cause`] of
    /// its counters in the clock before), set with `isolated_at` / `sub_isolated_at`.
    pub isolated_by: Vec<Option<String>>,
    pub sub_isolated_by: Vec<Option<String>>,
    /// Per unit (ports, then sublinks): its counters in the last clock.
    last_counts: Vec<JudgeCounts>,
    /// Time (ps) of the first clock with the port reported silent.
    pub silent_at: Vec<Option<u64>>,
    /// Clocks with the hub's error flag driven.
    pub efg_clocks: u64,
    /// Frames the frame monitor saw completed without error.
    pub frames_ok: u64,
    /// Errors (stuff, CRC, form) the frame monitor detected.
    pub monitor_errors: u64,
    /// Bits the frame monitor sampled in an overload frame.
    pub overload_bits: u64,
    /// Every blame: (time ps, unit: port i or sublink N + j, field code, position,
    /// charged: not suppressed by another unit's glitch).
    pub blame_log: Vec<(u64, usize, u8, u8, bool)>,
    /// Every glitch: (time ps, unit).
    pub glitch_log: Vec<(u64, usize)>,
    /// Per input (ports, then sublinks): completed runs of equal input level shorter
    /// than 32 clocks, counted by length (`short_runs[input][len]`), measured on the
    /// inputs as the hub samples them (after reset).
    pub short_runs: Vec<[u64; 32]>,
    /// Per input: (level, clocks) of the run in progress.
    run_now: Vec<(bool, u64)>,
    /// Per input: edges counted by their phase, in clocks since the frame monitor's last
    /// sample strobe: `edge_phase[input][min(phase, 31)]` for recessive-to-dominant
    /// edges, `[32 + min(phase, 31)]` for dominant-to-recessive ones.
    pub edge_phase: Vec<[u64; 64]>,
    since_sample: u64,
}

/// One clock of an [`RtlHub`]'s input stimulus, packed: bit 0 `rst_n`, bit 1
/// `inject_fault`, bits 2.. `rx[i]`, then `reh_rx[j]` (see [`RtlHub::start_recording`]).
pub type HubInputWord = u64;

impl RtlHub {
    /// Clocks with `rst_n` low after power-up.
    pub const RESET_CYCLES: u64 = 4;

    /// A hub with the configuration's clock (`clock_hz`, no offset).
    pub fn new(name: &str, cfg: &canstar_hub::config::HubConfig) -> Self {
        let period = (1e12 / cfg.clock_hz as f64).round() as u64;
        Self::with_clock(name, cfg, ClockSpec::new(period))
    }

    /// A hub with an explicit clock (ppm offset, phase), on the compiled model.
    pub fn with_clock(name: &str, cfg: &canstar_hub::config::HubConfig, clock: ClockSpec) -> Self {
        Self::with_engine(name, cfg, clock, Engine::default())
    }

    /// A hub with an explicit clock on `engine` (rust-hdl with a warning when no
    /// committed model has the configuration's shape).
    pub fn with_engine(name: &str, cfg: &canstar_hub::config::HubConfig, clock: ClockSpec, engine: Engine) -> Self {
        let hub = HubSim::new(engine, cfg);
        RtlHub {
            name: name.to_string(),
            clock,
            hub,
            n: cfg.ports,
            m: cfg.sublinks,
            cycles: 0,
            inject_button: false,
            presses: Vec::new(),
            stats: HubStats {
                max_bic: vec![0; cfg.ports],
                max_sub_bic: vec![0; cfg.sublinks],
                max_dbc: vec![0; cfg.ports],
                max_sub_dbc: vec![0; cfg.sublinks],
                max_sub_rep: vec![0; cfg.sublinks],
                isolated_at: vec![None; cfg.ports],
                sub_isolated_at: vec![None; cfg.sublinks],
                isolated_by: vec![None; cfg.ports],
                sub_isolated_by: vec![None; cfg.sublinks],
                last_counts: vec![JudgeCounts::default(); cfg.ports + cfg.sublinks],
                silent_at: vec![None; cfg.ports],
                short_runs: vec![[0; 32]; cfg.ports + cfg.sublinks],
                run_now: vec![(true, 0); cfg.ports + cfg.sublinks],
                edge_phase: vec![[0; 64]; cfg.ports + cfg.sublinks],
                ..Default::default()
            },
            record: None,
            samples: None,
            params: [cfg.port_params(), cfg.sublink_params()],
        }
    }

    /// Record the hub's inputs from now on, one [`HubInputWord`] per clock (for
    /// replaying the run on the generated Verilog, e.g. with `canstar_hdl::flow::cosim`).
    /// Ports + sublinks + 2 must not exceed 64.
    pub fn start_recording(&mut self) {
        assert!(self.n + self.m + 2 <= 64, "too many inputs to record");
        self.record = Some(Vec::new());
    }

    /// The recorded input words (empty if recording was never started).
    pub fn take_recording(&mut self) -> Vec<HubInputWord> {
        self.record.take().unwrap_or_default()
    }

    /// Record, at every sample point of the hub's frame monitor, the time, the level the
    /// hub drives on its downlink 0 and the monitor's field code (see [`RtlHub::samples`]).
    pub fn record_samples(&mut self) {
        self.samples = Some(Vec::new());
    }

    /// (time ps, downlink 0 level, field code of `canstar_hub::frame_state::Field`) at
    /// each sample point of the frame monitor.
    pub fn samples(&self) -> &[(u64, bool, u8)] {
        self.samples.as_deref().unwrap_or(&[])
    }

    /// Apply one recorded input word to a hub RTL (the replay side of
    /// [`RtlHub::start_recording`]).
    pub fn apply_input_word(hub: &mut canstar_hub::top::Hub, w: HubInputWord) {
        let n = hub.rx.len();
        hub.rst_n.next = w & 1 != 0;
        hub.inject_fault.next = w & 2 != 0;
        for (i, r) in hub.rx.iter_mut().enumerate() {
            r.next = (w >> (2 + i)) & 1 != 0;
        }
        for (j, r) in hub.reh_rx.iter_mut().enumerate() {
            r.next = (w >> (2 + n + j)) & 1 != 0;
        }
    }

    /// Port `i` isolated at time `t` or before?
    pub fn isolated_at(&self, i: usize) -> Option<u64> {
        self.stats.isolated_at[i]
    }

    /// Hold the `inject_fault` button during `[t, t + width)` (ps).
    pub fn press_inject_at(&mut self, t: u64, width: u64) {
        self.presses.push((t, t + width));
    }

    /// Which node ports are isolated.
    pub fn isolated(&self) -> Vec<bool> {
        (0..self.n).map(|i| self.hub.isolated(i)).collect()
    }

    /// Which node ports are reported silent.
    pub fn silent(&self) -> Vec<bool> {
        (0..self.n).map(|i| self.hub.silent(i)).collect()
    }

    /// Which incoming sublinks are isolated.
    pub fn sub_isolated(&self) -> Vec<bool> {
        (0..self.m).map(|j| self.hub.sub_isolated(j)).collect()
    }

    /// The 4-bit frame state output.
    pub fn frame_state(&self) -> u8 {
        self.hub.frame_state()
    }

    /// Clock cycles simulated.
    pub fn cycles(&self) -> u64 {
        self.cycles
    }
}

impl Component for RtlHub {
    fn name(&self) -> &str {
        &self.name
    }
    fn clock(&self) -> ClockSpec {
        self.clock
    }
    fn tick(&mut self, io: &mut Io<'_>) {
        let now = io.now();
        let pressed = self.inject_button || self.presses.iter().any(|&(a, b)| now >= a && now < b);
        let rst_n = self.cycles >= Self::RESET_CYCLES;
        let n = self.n;
        self.hub.set_inputs(rst_n, pressed, |i| io.input(i), |j| io.input(n + j));
        if let Some(r) = self.record.as_mut() {
            let mut w: HubInputWord = rst_n as u64 | (pressed as u64) << 1;
            for i in 0..self.n {
                w |= (io.input(i) as u64) << (2 + i);
            }
            for j in 0..self.m {
                w |= (io.input(self.n + j) as u64) << (2 + self.n + j);
            }
            r.push(w);
        }
        if rst_n {
            let st = &mut self.stats;
            for k in 0..self.n + self.m {
                let v = io.input(k);
                let r = &mut st.run_now[k];
                if v == r.0 {
                    r.1 += 1;
                } else {
                    if r.1 < 32 {
                        st.short_runs[k][r.1 as usize] += 1;
                    }
                    st.edge_phase[k][st.since_sample.min(31) as usize + if v { 32 } else { 0 }] += 1;
                    *r = (v, 1);
                }
            }
        }
        let hub = &mut self.hub;
        hub.cycle();
        for i in 0..self.n {
            io.set_output(i, hub.tx(i));
        }
        for j in 0..self.m {
            io.set_output(self.n + j, hub.hub_tx(j));
        }
        self.cycles += 1;
        // judge activity
        let st = &mut self.stats;
        if hub.blame_any() {
            st.blames += 1;
            let (f, p) = (hub.mon_field(), hub.mon_pos());
            for i in 0..self.n {
                if hub.port_blame(i) {
                    st.blame_log.push((now, i, f, p, hub.port_charged(i)));
                }
            }
            for k in 0..self.m {
                if hub.sub_blame(k) {
                    st.blame_log.push((now, self.n + k, f, p, hub.sub_charged(k)));
                }
            }
        }
        for i in 0..self.n {
            if hub.port_glitch(i) {
                st.glitch_log.push((now, i));
            }
        }
        for k in 0..self.m {
            if hub.sub_glitch(k) {
                st.glitch_log.push((now, self.n + k));
            }
        }
        if hub.efg_active() {
            st.efg_clocks += 1;
        }
        st.since_sample += 1;
        if hub.mon_sample() {
            st.since_sample = 0;
            if hub.mon_frame_ok() {
                st.frames_ok += 1;
            }
            if hub.mon_error() {
                st.monitor_errors += 1;
            }
            if hub.mon_field() as u64 == canstar_hub::frame_state::Field::Overload.code() {
                st.overload_bits += 1;
            }
            if let Some(s) = self.samples.as_mut() {
                if self.n > 0 {
                    s.push((now, hub.tx(0), hub.mon_field()));
                }
            }
        }
        for i in 0..self.n {
            st.max_bic[i] = st.max_bic[i].max(hub.port_bic(i));
            st.max_dbc[i] = st.max_dbc[i].max(hub.port_dbc(i));
            if st.isolated_at[i].is_none() {
                if hub.isolated(i) {
                    st.isolated_at[i] = Some(now);
                    st.isolated_by[i] = Some(isolation_cause(&self.params[0], false, &st.last_counts[i]));
                } else {
                    let c = &mut st.last_counts[i];
                    (c.bic, c.life, c.dbc, c.gc) = (hub.port_bic(i), hub.port_life(i), hub.port_dbc(i), hub.port_gc(i));
                    c.guard = hub.port_guard(i) && hub.port_step(i) != 0;
                }
            }
            if st.silent_at[i].is_none() && hub.silent(i) {
                st.silent_at[i] = Some(now);
            }
        }
        for k in 0..self.m {
            st.max_sub_bic[k] = st.max_sub_bic[k].max(hub.sub_bic(k));
            st.max_sub_dbc[k] = st.max_sub_dbc[k].max(hub.sub_dbc(k));
            let rep = hub.sub_rep_cnt(k);
            st.max_sub_rep[k] = st.max_sub_rep[k].max(rep);
            if st.sub_isolated_at[k].is_none() {
                if hub.sub_isolated(k) {
                    st.sub_isolated_at[k] = Some(now);
                    st.sub_isolated_by[k] = Some(isolation_cause(&self.params[1], true, &st.last_counts[self.n + k]));
                } else {
                    let c = &mut st.last_counts[self.n + k];
                    (c.bic, c.life, c.dbc, c.gc) = (hub.sub_bic(k), hub.sub_life(k), hub.sub_dbc(k), hub.sub_gc(k));
                    (c.pgc, c.rep_cnt) = (hub.sub_pgc(k), rep);
                }
            }
        }
    }
    fn set_trace(&mut self, on: bool) {
        self.hub.set_trace(on);
    }
    fn probe(&self, probe: &mut dyn rust_hdl::prelude::Probe) {
        self.hub.accept(&self.name, probe);
    }
}
