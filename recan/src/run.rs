//! One simulation run of a ReCANcentrate network with faults ([`run`]).
//!
//! The run advances in slices of a quarter bit (`state.rs`: advance, start due
//! faults, note isolations, step the nodes, follow the counters); faults are
//! started by `inject.rs`; `finish.rs` collects the logs and makes the generic
//! checks.

use std::path::PathBuf;

use serde::{Deserialize, Serialize};

use canstar_sim::Sim;

use crate::events::NodeEvent;
use crate::fault::FaultSpec;
use crate::network::Network;
use crate::spec::NetworkSpec;

mod finish;
mod inject;
mod state;
use state::RunState;

/// What to run.
#[derive(Clone, Debug, PartialEq)]
pub struct RunSpec {
    pub network: NetworkSpec,
    /// Seeds the clock phases left open in the network spec.
    pub seed: u64,
    pub faults: Vec<FaultSpec>,
    /// The run stops when this many frames were delivered (successful
    /// transmissions of any node) after the last fault started (after the
    /// start of the applications if there is no fault). 0: no frame target,
    /// run until `max_time_ps`.
    pub frames: u32,
    /// Stop earlier, once this many frames were delivered after the last
    /// disturbance (an error at an active controller, an isolation, a
    /// quarantine, a retransmission) with no frame pending for more than 150
    /// bit times (None: run all `frames`).
    pub quiet_frames: Option<u32>,
    /// Hard limit of simulated time in ps (None: 100 frame times per
    /// requested frame plus the time to the fault, i.e. only a stuck network hits it).
    pub max_time_ps: Option<u64>,
    /// Write a VCD of every signal.
    pub vcd: Option<PathBuf>,
    /// Only this window of simulated time (from, to, in ps) goes into the VCD (None: all
    /// of the run). A whole long run is gigabytes.
    pub vcd_window_ps: Option<(u64, u64)>,
    /// Record the driver's routine log in [`RunResult::trace`].
    pub trace: bool,
    /// Simulation engine of the hubs and controllers (compiled models by default).
    pub engine: canstar_models::Engine,
    /// Legal events of healthy nodes (not faults: they change neither the frame
    /// target nor which controllers count as healthy), see [`crate::events`].
    pub events: Vec<NodeEvent>,
}

impl RunSpec {
    /// The reference network without faults.
    pub fn new(network: NetworkSpec, seed: u64, frames: u32) -> Self {
        RunSpec { network, seed, faults: Vec::new(), frames, quiet_frames: None, max_time_ps: None, vcd: None, vcd_window_ps: None, trace: false, engine: Default::default(), events: Vec::new() }
    }
}

/// Something a hub isolated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Isolated {
    /// Node port `port` of hub `hub` (= controller A (hub 0) or B (hub 1) of node `port`).
    Port { hub: usize, port: usize },
    /// Incoming sublink `sublink` of hub `hub`.
    Sublink { hub: usize, sublink: usize },
}

impl std::fmt::Display for Isolated {
    /// `hub 0 port 2`, `hub 1 sublink 0`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Isolated::Port { hub, port } => write!(f, "hub {hub} port {port}"),
            Isolated::Sublink { hub, sublink } => write!(f, "hub {hub} sublink {sublink}"),
        }
    }
}

/// An isolation seen during a run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct IsolationEvent {
    pub what: Isolated,
    /// When it was first seen (ps; resolution: a quarter bit).
    pub t_ps: u64,
    /// Bit times since the first fault started (None if before it or without fault).
    pub latency_bits: Option<f64>,
    /// Which counters were at their limits ([`canstar_hub::cause::isolation_cause`]).
    #[serde(default)]
    pub cause: String,
}

/// TEC and REC of one controller at one instant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct CounterSample {
    pub t_ps: u64,
    pub node: usize,
    pub ctrl: usize,
    pub tec: u32,
    pub rec: u32,
}

/// Everything a run observed.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RunResult {
    /// `failures.is_empty()` (the generic checks, see below; scenario checks
    /// are added by [`crate::check`]).
    pub ok: bool,
    /// Generic checks that failed: a frame missed by a node, a healthy
    /// controller reaching the warning limit, a node left without controller,
    /// fewer frames than requested (stuck network), a fault that never started.
    pub failures: Vec<String>,
    /// Isolations in the order seen.
    pub isolated: Vec<IsolationEvent>,
    /// (node, controller, ps) of each quarantine.
    pub quarantined: Vec<(usize, usize, u64)>,
    /// Why each quarantine happened ("tec 96", "rec 96", "timer"), same order.
    pub quarantine_reasons: Vec<String>,
    /// Final tx controller per node (None: no active controller left).
    pub tx_ctrl: Vec<Option<usize>>,
    /// Largest number of retransmissions (omission discrepancies) of one frame.
    pub max_retransmissions: u32,
    /// Total retransmissions requested by omission discrepancies.
    pub retransmissions: u32,
    /// Frames requested again on a new tx controller after a quarantine.
    pub rerequests: u32,
    /// Frames copied to the non-tx controller after omission discrepancies (`DriverSpec::copy_tec`).
    pub copies: u32,
    /// Of those, copies given up unsent.
    pub copies_given_up: u32,
    /// Frames sent again on a new tx controller (`Notice::Resend`).
    pub resends: u32,
    /// Frames a receiving node missed: "node <r> missed <sender> <from>..<to>".
    pub lost: Vec<String>,
    /// Duplicates delivered to applications (allowed).
    pub duplicates: u32,
    /// Largest TEC or REC of any healthy controller (not on a faulty link,
    /// not crashed, not attached to a faulty hub).
    pub worst_healthy_tec_rec: u32,
    /// Error events of healthy controllers after the first fault started
    /// (> 0 means a global error was seen).
    pub healthy_errors_after_fault: u64,
    /// Sampled at every delivery, at every quarantine and at the end.
    pub counters: Vec<CounterSample>,
    /// When each fault started (ps), None if it never did.
    pub fault_start_ps: Vec<Option<u64>>,
    /// Each fault as resolved at its start ("node 1 ctrl B (tx) uplink SAD", ...).
    pub fault_resolved: Vec<String>,
    /// Nominal bit time of the hubs.
    pub bit_time_ps: u64,
    /// Frames delivered (successful transmissions reported by the senders' drivers).
    pub delivered: u64,
    /// Frames delivered per node (as sender).
    pub delivered_per_node: Vec<u64>,
    /// Simulated clock cycles (all components).
    pub sim_cycles: u64,
    /// Simulated time at the end (ps).
    pub end_ps: u64,
    /// Final blame counter (BIC, counter units) of every port, per hub
    /// (empty without the hub's debug outputs).
    pub final_bic: Vec<Vec<u32>>,
    /// Replica-rule charges (hub.md §5.7) of both hubs' sublinks, summed (the largest
    /// `rep_cnt` of each sublink during the run).
    #[serde(default)]
    pub replica_charges: u64,
    /// Largest blame counter of every port during the run, per hub (sampled
    /// every quarter bit; empty without the hub's debug outputs).
    #[serde(default)]
    pub max_bic: Vec<Vec<u32>>,
    /// Largest (TEC, REC) of every controller during the run, `[node][c]`
    /// (sampled every quarter bit, faulty controllers included).
    #[serde(default)]
    pub max_tec_rec: Vec<[(u32, u32); 2]>,
    /// Every blame of every hub's judge units: (hub, time ps, unit, field code,
    /// position, charged); unit = port i, or ports + j for incoming sublink j.
    pub blames: Vec<(usize, u64, usize, u8, u8, bool)>,
    /// Every glitch seen by a judge unit: (hub, time ps, unit).
    pub glitches: Vec<(usize, u64, usize)>,
    /// Every error event of every controller: (time ps, node, ctrl, transmitting,
    /// controller FIELD code).
    pub ctrl_errors: Vec<(u64, usize, usize, bool, u8)>,
    /// Per hub, per input (ports, then sublinks): runs of equal level shorter than
    /// 32 hub clocks, counted by length (see [`crate::rtl_hub::HubStats::short_runs`]).
    pub short_runs: Vec<Vec<[u64; 32]>>,
    /// Per hub, per input: edges counted by phase (see [`crate::rtl_hub::HubStats::edge_phase`]).
    #[serde(skip)]
    pub edge_phase: Vec<Vec<[u64; 64]>>,
    /// The legal events applied ([`RunSpec::events`]).
    pub events_applied: Vec<String>,
    /// Driver routine log (with `RunSpec::trace`).
    pub trace: Vec<String>,
    /// The VCD could not be written (also in `failures`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vcd_error: Option<String>,
}

/// Run `spec`. Never panics on a valid network; an invalid network gives a
/// result with `ok == false` and the validation error in `failures`.
pub fn run(spec: &RunSpec) -> RunResult {
    run_impl(spec, &mut |_, _| {}, &mut |_, _| {}, &mut |_, _| {})
}

/// [`run`], calling `progress(now_ps, limit_ps)` after every quarter bit
/// (`limit_ps`: the time limit of the run; it may stop earlier).
pub fn run_observed(spec: &RunSpec, progress: &mut dyn FnMut(u64, u64)) -> RunResult {
    run_impl(spec, progress, &mut |_, _| {}, &mut |_, _| {})
}

/// [`run`] with hooks: `setup` sees the simulation right after the network is built
/// (e.g. to start recording the components' inputs), `finish` at the end of the run
/// (to take what was recorded). Neither is called for an invalid network.
pub fn run_inspect(spec: &RunSpec, setup: &mut dyn FnMut(&mut Sim, &Network), finish: &mut dyn FnMut(&mut Sim, &Network)) -> RunResult {
    run_impl(spec, &mut |_, _| {}, setup, finish)
}

fn run_impl(
    spec: &RunSpec,
    progress: &mut dyn FnMut(u64, u64),
    setup: &mut dyn FnMut(&mut Sim, &Network),
    finish: &mut dyn FnMut(&mut Sim, &Network),
) -> RunResult {
    let mut res = RunResult { bit_time_ps: spec.network.bit_time_ps(), ..Default::default() };
    let mut sim = Sim::new(spec.seed);
    let net = match Network::build_with(&mut sim, &spec.network, spec.engine) {
        Ok(n) => n,
        Err(e) => {
            res.failures.push(format!("invalid network: {e}"));
            return res;
        }
    };
    setup(&mut sim, &net);
    // the VCD starts now, or at the start of its window (and stops at its end)
    let (vcd_from, vcd_to) = spec.vcd_window_ps.unwrap_or((0, u64::MAX));
    let mut vcd_state = if spec.vcd.is_some() { VcdWindow::Before } else { VcdWindow::Done };
    let start_vcd = |sim: &mut Sim, res: &mut RunResult| -> bool {
        let p = spec.vcd.as_ref().expect("a VCD path");
        if let Err(e) = sim.start_vcd_file(p, None) {
            let m = format!("cannot write VCD {}: {e}", p.display());
            res.failures.push(m.clone());
            res.vcd_error = Some(m);
            return false;
        }
        true
    };
    if vcd_state == VcdWindow::Before && vcd_from == 0 {
        if !start_vcd(&mut sim, &mut res) {
            return res;
        }
        vcd_state = VcdWindow::Open;
    }
    let mut st = RunState::new(spec, res);
    while !st.finished(sim.now()) {
        if vcd_state == VcdWindow::Before && sim.now() >= vcd_from {
            vcd_state = if start_vcd(&mut sim, &mut st.res) { VcdWindow::Open } else { VcdWindow::Done };
        }
        if vcd_state == VcdWindow::Open && sim.now() >= vcd_to {
            if let Err(e) = sim.finish_vcd() {
                // as at the end of a run (`RunState::finish`)
                st.res.failures.push(format!("VCD: {e}"));
                st.res.vcd_error = Some(format!("VCD: {e}"));
            }
            vcd_state = VcdWindow::Done;
        }
        let trigger = st.advance(&mut sim, &net);
        st.start_faults(&mut sim, &net, trigger);
        st.observe_isolations(&sim, &net);
        st.power_events(&mut sim, &net);
        st.step_nodes(&mut sim, &net);
        st.observe_counters(&sim, &net);
        progress(sim.now(), st.limit);
    }
    if vcd_state == VcdWindow::Before {
        // the run ended before the window: the file holds the last values
        start_vcd(&mut sim, &mut st.res);
    }
    let res = st.finish(&mut sim, &net);
    finish(&mut sim, &net);
    res
}

/// Where a run is with respect to its VCD window.
#[derive(Clone, Copy, PartialEq, Eq)]
enum VcdWindow {
    Before,
    Open,
    Done,
}
