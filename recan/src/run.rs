//! One simulation run of a ReCANcentrate network with faults ([`run`]).

use std::path::PathBuf;

use serde::{Deserialize, Serialize};

use canstar_controller::fsm::Field;
use canstar_controller::frame::Frame;

use canstar_sim::{Handle, Sim};
use canstar_sim::net::{FaultMode, NetId};
use crate::app::{Receiver, Sender};
use crate::ctrl::Ctrl;
use crate::driver::{Driver, Notice, QuaReason};
use crate::events::{EventRunner, NodeEvent, PowerChange};
use crate::fault::{CtrlRef, Dir, FaultKind, FaultSpec, FaultStart, FaultTarget, StartField};
use crate::network::Network;
use crate::spec::{AppKind, NetworkSpec};

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
        RunSpec { network, seed, faults: Vec::new(), frames, quiet_frames: None, max_time_ps: None, vcd: None, trace: false, engine: Default::default(), events: Vec::new() }
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

/// An isolation seen during a run.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct IsolationEvent {
    pub what: Isolated,
    /// When it was first seen (ps; resolution: a quarter bit).
    pub t_ps: u64,
    /// Bit times since the first fault started (None if before it or without fault).
    pub latency_bits: Option<f64>,
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

/// Field codes of the controller for a start field.
fn ctrl_field(f: StartField) -> Field {
    match f {
        StartField::Sof => Field::Sof,
        StartField::Ident => Field::Ident,
        StartField::Dlc => Field::Dlc,
        StartField::Data => Field::Data,
        StartField::Crc => Field::Crc,
        StartField::AckSlot => Field::AckSlot,
        StartField::Eof => Field::Eof,
        StartField::Inter => Field::Inter,
    }
}

fn mode_of(k: FaultKind) -> FaultMode {
    match k {
        FaultKind::Sad => FaultMode::StuckDominant,
        FaultKind::Sar => FaultMode::StuckRecessive,
        FaultKind::Invert => FaultMode::Invert,
        FaultKind::BitFlip { .. } | FaultKind::Force { .. } | FaultKind::Burst { .. } => FaultMode::None,
    }
}

/// Two controllers of one node, mutably, from the simulation.
fn pair(sim: &mut Sim, h: [Handle<Ctrl>; 2]) -> [&mut Ctrl; 2] {
    // two distinct components: split the borrow through raw pointers
    let a: *mut Ctrl = sim.get_mut(h[0]);
    let b: *mut Ctrl = sim.get_mut(h[1]);
    assert!(!std::ptr::eq(a, b));
    // SAFETY: the handles refer to different components of `sim`, which stays borrowed mutably
    unsafe { [&mut *a, &mut *b] }
}

struct Active {
    /// (node, ctrl) made unhealthy by this fault (their links, their crash, their hub).
    unhealthy: Vec<(usize, usize)>,
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
    if let Some(p) = &spec.vcd {
        if let Err(e) = sim.start_vcd_file(p, None) {
            let m = format!("cannot write VCD {}: {e}", p.display());
            res.failures.push(m.clone());
            res.vcd_error = Some(m);
            return res;
        }
    }
    let ns = &spec.network;
    let nn = ns.nodes.len();
    let bit = res.bit_time_ps;
    let slice = (bit / 4).max(1);
    let mut drivers: Vec<Driver> =
        (0..nn).map(|k| Driver::new(k, &ns.driver, bit, ns.nodes[k].initial_tx, spec.trace)).collect();
    let mut senders: Vec<Option<Sender>> = ns
        .nodes
        .iter()
        .map(|n| matches!(n.app, AppKind::Counter | AppKind::Blinker).then(|| Sender::new(n.id)))
        .collect();
    let mut receivers: Vec<Receiver> = vec![Receiver::default(); nn];
    let app_delay = (ns.driver.app_delay_bits * bit as f64).round() as u64;
    let start_at = ns.driver.start_bits as u64 * bit;
    // next request time per sender
    let mut next_req: Vec<Option<u64>> = senders.iter().map(|s| s.as_ref().map(|_| start_at)).collect();
    // the faults, then the overload events as one-bit faults (not counted as faults)
    let nf = spec.faults.len();
    let faults: Vec<FaultSpec> = spec.faults.iter().copied().chain(spec.events.iter().filter_map(|e| e.as_fault(bit))).collect();
    let mut events = EventRunner::new(&spec.events);
    let mut fault_start: Vec<Option<u64>> = vec![None; faults.len()];
    let mut fault_resolved = vec![String::new(); faults.len()];
    let mut delivered_at_last_fault: u64 = 0;
    let mut last_disturb: u64 = 0;
    let mut quiet_stop = false;
    let mut errors_seen: u64 = 0;
    let mut seen_iso: Vec<Isolated> = Vec::new();
    let mut unhealthy: Vec<(usize, usize)> = Vec::new();
    let mut healthy_errors_base: Option<Vec<u64>> = None;
    res.delivered_per_node = vec![0; nn];
    res.max_tec_rec = vec![[(0, 0); 2]; nn];
    let max_after = faults
        .iter()
        .map(|f| match f.start {
            FaultStart::Field { after_frames, .. } => after_frames as u64 * 200 * bit,
            FaultStart::At { t_ps } => t_ps,
        })
        .max()
        .unwrap_or(0);
    let limit = spec.max_time_ps.unwrap_or(start_at + max_after + (spec.frames as u64 + 5) * 200 * bit);

    loop {
        let now = sim.now();
        // ---- faults waiting for their start
        let all_started = fault_start[..nf].iter().all(|s| s.is_some());
        if all_started && spec.frames > 0 && res.delivered >= delivered_at_last_fault + spec.frames as u64 {
            break;
        }
        if let (true, Some(q)) = (all_started, spec.quiet_frames) {
            let stuck = drivers.iter().any(|d| d.pending_since.is_some_and(|t| now > t + 150 * bit));
            if !stuck && res.delivered >= delivered_at_last_fault.max(last_disturb) + q as u64 {
                quiet_stop = true;
                break;
            }
        }
        if now >= limit {
            break;
        }
        let mut target = (now + slice).min(limit);
        let mut field_wait: Option<usize> = None;
        for (i, f) in faults.iter().enumerate() {
            if fault_start[i].is_some() {
                continue;
            }
            match f.start {
                FaultStart::At { t_ps } => target = target.min(t_ps.max(now)),
                FaultStart::Field { after_frames, .. } => {
                    if res.delivered >= after_frames as u64 && field_wait.is_none() {
                        field_wait = Some(i);
                    }
                }
            }
        }
        let mut trigger: Option<(usize, u64)> = None;
        if let Some(i) = field_wait {
            let FaultStart::Field { field, bit: fbit, of_node, delay_ns, .. } = faults[i].start else { unreachable!() };
            let want = ctrl_field(field);
            let cands: Vec<Handle<Ctrl>> = net
                .ctrls
                .iter()
                .enumerate()
                .filter(|(k, _)| of_node.is_none_or(|o| o == *k))
                .flat_map(|(_, p)| p.iter().copied())
                .collect();
            // POSITION is 1-based; the transmitter keeps its role through intermission
            let hit = sim.run_until_cond(target, |s| {
                cands.iter().any(|&h| {
                    let c = s.get(h);
                    c.transmitting() && !c.is_held() && c.field() == want && c.pos() == fbit + 1
                })
            });
            if hit {
                // the field value changes at the sample point of the previous bit;
                // the bit itself starts PH2 later
                let c = sim.get(cands[0]).spec().clone();
                let ph2 = c.period_ps() * c.timing.brp as u64 * c.timing.ph2() as u64;
                trigger = Some((i, sim.now() + ph2 + (delay_ns * 1000.0).round() as u64));
            } else {
                sim.run_until(target);
            }
        } else {
            sim.run_until(target);
        }
        let now = sim.now();
        // ---- start faults
        for (i, f) in faults.iter().enumerate() {
            if fault_start[i].is_some() {
                continue;
            }
            let t = match (f.start, trigger) {
                (FaultStart::At { t_ps }, _) if t_ps <= now => now,
                (FaultStart::Field { .. }, Some((j, t))) if j == i => t,
                _ => continue,
            };
            let info = inject(&mut sim, &net, &drivers, f, t, bit, limit, &mut fault_resolved[i]);
            fault_start[i] = Some(t);
            if i >= nf {
                events.applied.push(spec.events.iter().filter(|e| e.as_fault(bit).is_some()).nth(i - nf).map_or(String::new(), |e| e.describe()));
                continue;
            }
            unhealthy.extend(info.unhealthy.iter().copied());
            delivered_at_last_fault = res.delivered;
            if healthy_errors_base.is_none() {
                healthy_errors_base = Some(all_errors(&sim, &net));
            }
        }
        // ---- isolation status
        for h in 0..2 {
            let hub = &sim.get(net.hubs[h]).hub;
            for i in 0..hub.ports() {
                let w = Isolated::Port { hub: h, port: i };
                if hub.isolated(i) && !seen_iso.contains(&w) {
                    seen_iso.push(w);
                }
            }
            for j in 0..hub.sublinks() {
                let w = Isolated::Sublink { hub: h, sublink: j };
                if hub.sub_isolated(j) && !seen_iso.contains(&w) {
                    seen_iso.push(w);
                }
            }
        }
        while res.isolated.len() < seen_iso.len() {
            last_disturb = res.delivered;
            let what = seen_iso[res.isolated.len()];
            let first = fault_start[..nf].iter().flatten().min().copied();
            let latency_bits = first.filter(|&f| f <= now).map(|f| (now - f) as f64 / bit as f64);
            res.isolated.push(IsolationEvent { what, t_ps: now, latency_bits });
        }
        // ---- legal events
        for ch in events.step(now, bit, &mut sim, &net) {
            match ch {
                PowerChange::Off(k) => {
                    next_req[k] = None;
                    receivers[k].rejoin();
                }
                PowerChange::On(k) => {
                    drivers[k] = Driver::new(k, &ns.driver, bit, ns.nodes[k].initial_tx, spec.trace);
                    if senders[k].is_some() {
                        next_req[k] = Some(now + app_delay);
                    }
                }
            }
        }
        // ---- drivers and applications
        for k in 0..nn {
            if events.is_off(k) {
                continue;
            }
            let mut cs = pair(&mut sim, net.ctrls[k]);
            let notices = drivers[k].step(now, &mut cs);
            let mut sample = false;
            for n in notices {
                match n {
                    Notice::TxSuccess(_) => {
                        if let Some(s) = senders[k].as_mut() {
                            s.success();
                            next_req[k] = Some(now + app_delay);
                        }
                        res.max_retransmissions = res.max_retransmissions.max(drivers[k].retx_this_frame);
                        res.delivered += 1;
                        res.delivered_per_node[k] += 1;
                        sample = true;
                    }
                    Notice::Deliver(f) => {
                        receivers[k].deliver(&f);
                    }
                    Notice::Quarantined { ctrl, t, reason } => {
                        last_disturb = res.delivered;
                        res.quarantined.push((k, ctrl, t));
                        res.quarantine_reasons.push(
                            match reason {
                                QuaReason::Tec => "tec",
                                QuaReason::Rec => "rec",
                                QuaReason::Timer => "timer",
                            }
                            .to_string(),
                        );
                        sample = true;
                    }
                    Notice::Retransmit => {
                        last_disturb = res.delivered;
                        res.retransmissions += 1;
                        res.max_retransmissions = res.max_retransmissions.max(drivers[k].retx_this_frame);
                    }
                    Notice::Rerequest => res.rerequests += 1,
                    Notice::NoController => res.failures.push(format!("node {k} has no active controller left")),
                }
            }
            if let (Some(t), Some(s)) = (next_req[k], senders[k].as_ref()) {
                if now >= t && drivers[k].pending.is_none() {
                    let f: Frame = s.frame();
                    let mut cs = pair(&mut sim, net.ctrls[k]);
                    if drivers[k].tx_request(f, now, &mut cs) || drivers[k].tx.is_none() {
                        next_req[k] = None;
                    }
                }
            }
            if sample {
                for (kk, p) in net.ctrls.iter().enumerate() {
                    for (c, &h) in p.iter().enumerate() {
                        let x = sim.get(h);
                        res.counters.push(CounterSample { t_ps: now, node: kk, ctrl: c, tec: x.tec(), rec: x.rec() });
                    }
                }
            }
        }
        // ---- errors at active controllers
        let errs: u64 = net.ctrls.iter().flat_map(|p| p.iter()).map(|&h| sim.get(h).errors).sum();
        if errs != errors_seen {
            errors_seen = errs;
            last_disturb = res.delivered;
        }
        // ---- counters: maxima of every controller, worst of the healthy ones, blames
        for (k, p) in net.ctrls.iter().enumerate() {
            for (c, &h) in p.iter().enumerate() {
                let x = sim.get(h);
                let m = &mut res.max_tec_rec[k][c];
                *m = (m.0.max(x.tec()), m.1.max(x.rec()));
                if !unhealthy.contains(&(k, c)) && !x.is_held() {
                    res.worst_healthy_tec_rec = res.worst_healthy_tec_rec.max(x.tec()).max(x.rec());
                }
            }
        }
        for (i, &h) in net.hubs.iter().enumerate() {
            let hub = &sim.get(h).hub;
            res.max_bic.resize(2, vec![]);
            res.max_bic[i].resize(hub.debug_bic_len(), 0);
            for (j, m) in res.max_bic[i].iter_mut().enumerate() {
                *m = (*m).max(hub.debug_bic(j) as u32);
            }
        }
        progress(sim.now(), limit);
    }
    // ---- results
    res.end_ps = sim.now();
    for (k, p) in net.ctrls.iter().enumerate() {
        for (c, &h) in p.iter().enumerate() {
            let x = sim.get(h);
            res.counters.push(CounterSample { t_ps: res.end_ps, node: k, ctrl: c, tec: x.tec(), rec: x.rec() });
        }
    }
    res.sim_cycles = sim.total_cycles();
    fault_start.truncate(nf);
    fault_resolved.truncate(nf);
    res.fault_start_ps = fault_start.clone();
    res.fault_resolved = fault_resolved;
    res.events_applied = events.applied.clone();
    res.tx_ctrl = drivers.iter().map(|d| d.tx).collect();
    for (h, &hh) in net.hubs.iter().enumerate() {
        res.blames.extend(sim.get(hh).stats.blame_log.iter().map(|&(t, u, f, p, c)| (h, t, u, f, p, c)));
        res.glitches.extend(sim.get(hh).stats.glitch_log.iter().map(|&(t, u)| (h, t, u)));
    }
    res.blames.sort_by_key(|b| b.1);
    res.glitches.sort_by_key(|g| g.1);
    res.short_runs = net.hubs.iter().map(|&h| sim.get(h).stats.short_runs.clone()).collect();
    res.edge_phase = net.hubs.iter().map(|&h| sim.get(h).stats.edge_phase.clone()).collect();
    for (k, p) in net.ctrls.iter().enumerate() {
        for (c, &h) in p.iter().enumerate() {
            res.ctrl_errors.extend(sim.get(h).error_log.iter().map(|&(t, tx, f)| (t, k, c, tx, f)));
        }
    }
    res.ctrl_errors.sort_by_key(|e| e.0);
    res.final_bic = net.hubs.iter().map(|&h| { let hub = &sim.get(h).hub; (0..hub.debug_bic_len()).map(|i| hub.debug_bic(i) as u32).collect() }).collect();
    if let Some(base) = &healthy_errors_base {
        let now_err = all_errors(&sim, &net);
        let mut i = 0;
        for k in 0..nn {
            for c in 0..2 {
                if !unhealthy.contains(&(k, c)) {
                    res.healthy_errors_after_fault += now_err[i] - base[i];
                }
                i += 1;
            }
        }
    }
    for (k, r) in receivers.iter().enumerate() {
        res.duplicates += r.duplicates as u32;
        for &(id, a, b) in &r.misses {
            res.lost.push(format!("node {k} ({}) missed {id:#x} counter {a}..={b}", ns.nodes[k].name));
        }
    }
    if !res.lost.is_empty() {
        res.failures.push(format!("{} gap(s) in received counters: {}", res.lost.len(), res.lost.join("; ")));
    }
    let lim = ns.driver.warning_limit;
    if res.worst_healthy_tec_rec >= lim {
        res.failures.push(format!("a healthy controller reached TEC/REC {} (limit {lim})", res.worst_healthy_tec_rec));
    }
    for (i, s) in fault_start.iter().enumerate() {
        if s.is_none() {
            res.failures.push(format!("fault {i} never started"));
        }
    }
    let after = res.delivered.saturating_sub(delivered_at_last_fault);
    if !quiet_stop && spec.frames > 0 && fault_start.iter().all(|s| s.is_some()) && after < spec.frames as u64 {
        res.failures.push(format!("only {after} of {} frames delivered after the fault (time limit)", spec.frames));
    }
    if spec.trace {
        let mut lines: Vec<(u64, String)> = Vec::new();
        for d in &drivers {
            for l in d.log.iter().flatten() {
                lines.push((0, l.clone()));
            }
        }
        // lines start with the time: sort by it (stable across nodes)
        lines.sort_by(|a, b| {
            let ta: f64 = a.1.split_whitespace().next().and_then(|x| x.parse().ok()).unwrap_or(0.0);
            let tb: f64 = b.1.split_whitespace().next().and_then(|x| x.parse().ok()).unwrap_or(0.0);
            ta.partial_cmp(&tb).unwrap()
        });
        res.trace = lines.into_iter().map(|l| l.1).collect();
    }
    if spec.vcd.is_some() {
        if let Err(e) = sim.finish_vcd() {
            res.failures.push(format!("VCD: {e}"));
            res.vcd_error = Some(format!("VCD: {e}"));
        }
    }
    res.ok = res.failures.is_empty();
    finish(&mut sim, &net);
    res
}

fn all_errors(sim: &Sim, net: &Network) -> Vec<u64> {
    net.ctrls.iter().flat_map(|p| p.iter().map(|&h| sim.get(h).errors)).collect()
}

/// Start fault `f` at time `t >= now`; describe it in `desc`.
#[allow(clippy::too_many_arguments)]
fn inject(sim: &mut Sim, net: &Network, drivers: &[Driver], f: &FaultSpec, t: u64, bit: u64, limit: u64, desc: &mut String) -> Active {
    let resolve = |node: usize, r: CtrlRef| -> usize {
        let tx = drivers[node].tx.unwrap_or(0);
        match r {
            CtrlRef::A => 0,
            CtrlRef::B => 1,
            CtrlRef::Tx => tx,
            CtrlRef::NonTx => 1 - tx,
        }
    };
    let role = |node: usize, c: usize| if drivers[node].tx == Some(c) { "tx" } else { "non-tx" };
    let mut nets: Vec<NetId> = Vec::new();
    let mut unhealthy = Vec::new();
    match f.target {
        FaultTarget::Link { node, ctrl, dir } => {
            let c = resolve(node, ctrl);
            let hp = &net.links.hubs[c];
            nets.push(match dir {
                Dir::Up => hp.uplinks[node].output,
                Dir::Down => hp.downlinks[node].output,
            });
            unhealthy.push((node, c));
            *desc = format!("node {node} ctrl {} ({}) {:?}link {:?}", "AB".as_bytes()[c] as char, role(node, c), dir, f.kind);
        }
        FaultTarget::Sublink { interlink, from_hub } => {
            nets.push(net.links.hubs[from_hub].sub_out[interlink].output);
            *desc = format!("interlink {interlink} sublink from hub {from_hub} {:?}", f.kind);
        }
        FaultTarget::Interlink { interlink } => {
            nets.push(net.links.hubs[0].sub_out[interlink].output);
            nets.push(net.links.hubs[1].sub_out[interlink].output);
            *desc = format!("interlink {interlink} {:?}", f.kind);
        }
        FaultTarget::Hub { hub } => {
            let hp = &net.links.hubs[hub];
            nets.extend(hp.downlinks.iter().map(|l| l.output));
            nets.extend(hp.sub_out.iter().map(|l| l.output));
            unhealthy.extend((0..net.ctrls.len()).map(|k| (k, hub)));
            *desc = format!("hub {hub} output {:?}", f.kind);
        }
        FaultTarget::Crash { node, ctrl } => {
            let c = resolve(node, ctrl);
            *desc = format!("node {node} ctrl {} ({}) crash", "AB".as_bytes()[c] as char, role(node, c));
            // the crash is immediate (at the slice boundary)
            sim.get_mut(net.ctrls[node][c]).crash();
            return Active { unhealthy: vec![(node, c)] };
        }
    }
    let end = f.duration_ps.map(|d| t + d);
    for &id in &nets {
        if !crate::fault::schedule_pattern(sim, id, f.kind, t, end.unwrap_or(limit + bit), bit) {
            sim.schedule_fault(id, t, mode_of(f.kind));
            if let Some(e) = end {
                sim.schedule_fault(id, e, FaultMode::None);
            }
        }
    }
    Active { unhealthy }
}
