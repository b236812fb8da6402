//! Randomised differential testing: 2 to 5 RTL nodes on one bus, each in
//! lock step with its own golden model ([`crate::lockstep`]), random traffic
//! and random receive-path disturbances, plus network properties (can-protocol.md).
//!
//! One *run* ([`run_seed`]) is a pure function of its seed (and
//! [`RunOptions`]): the seed draws the node count, bit timing, clock offsets
//! and phases, bus delays, the traffic and the disturbances. [`fuzz`] chains
//! runs with seeds derived from a master seed until the requested number of
//! frames has been run.
//!
//! # A run
//!
//! - Nodes: 2..=5 [`LockstepNode`]s on a [`Bus`]. All share the nominal bit
//!   time; the timing is one of T10/6/4, T10/6/2, T10/8/1, T25/17/1 (all at
//!   100 ns per TQ), each node with either a 100 ns clock and BRP 1 or a
//!   50 ns clock and BRP 2. Clock offsets are drawn within ±40 % of the CAN
//!   oscillator tolerance of the timing, `df = min(SJW / (20·NTQ),
//!   min(PH1, PH2) / (2·(13·NTQ − PH2)))`, random phases; symmetric TX and RX
//!   delays up to 20 ns per PROP TQ.
//! - Traffic: batches of 1..=n frames requested at the same instant on
//!   distinct nodes (forcing arbitration), separated by random gaps. Frames:
//!   standard or extended ids (small id spaces, so equal base ids and
//!   data/remote pairs occur), data or remote, DLC 0..15, random data. A
//!   given (IDE, id, RTR) is only ever sent with one content, whichever node
//!   sends it, so two nodes may send the same frame at once (legal) but never
//!   the same id with different content (illegal CAN).
//! - Disturbances (in about 3 runs out of 4), during the first part of the
//!   run only: on random nodes' receive paths, single inverted bits, bursts of
//!   inverted bits, stuck-dominant and stuck-recessive windows (1..=40 bits,
//!   occasionally long enough to drive a node error-passive or bus-off), at
//!   random instants, i.e. at random fields and positions, on transmitters and
//!   receivers alike.
//! - Then the run goes quiet and continues until every queue is empty and the
//!   bus has been idle, bounded by a deadline.
//!
//! # Checked on every run
//!
//! - Lock step: no [`Divergence`] on any node.
//! - Dominant runs: a node never drives more than 11 consecutive dominant
//!   bits, plus 6 for every restart of an active error or overload flag by a
//!   bit error inside it. The 11 are the longest legal sequence without such
//!   a restart (5 equal frame bits, a bit error detected at the fifth, then a
//!   6-bit flag, §5, §10); superposition makes the *bus* show up to 12 `D`
//!   bits after the error, but each node's own contribution stays within the
//!   bound. A node that reads `R` while it drives its own active flag (only
//!   possible with a broken receive path) restarts the flag, +8 each time,
//!   until it turns error-passive (C14), so the run is bounded by the error
//!   counters, not by 11.
//! - Recovery: after the last disturbance has ended and a settling time of
//!   250 bits, no error-active node reports an error; every queued frame is eventually
//!   sent (bus-off nodes recover on their own, C18); at the end every node is
//!   in Bus_Idle and the bus has been recessive for at least 20 bits.
//!   An ACK error while another node is bus-off or error-passive is exempt
//!   (with 2 nodes, or with two nodes sending the same frame, nobody else may
//!   be able to acknowledge: the other node is bus-off, seed
//!   0xaa30ee537d2d2a07, or an error-passive node is stuck in passive flags
//!   as described below, seed 0x6ef6dd6358bb956f; a bus-off node's 128 runs
//!   of 11 recessive bits can take thousands of bits when the others keep the
//!   bus busy).
//!   Error-passive nodes are exempt from "no error after settling": a node
//!   whose passive error flag overlaps another node's frame cannot find its 6
//!   equal bits until that frame's End_Of_Frame, then needs 1 + 7 more
//!   recessive bits for its delimiter, 14 in all, while back-to-back traffic
//!   offers only 11 (ACK delimiter, EOF, intermission) before the next SOF:
//!   it gets a form error in its delimiter and starts again, as long as the
//!   traffic stays back to back (found by seed 0x494e3bc8db6e2bc2; legal CAN
//!   behaviour, harmless because its flags are recessive, and it ends as
//!   soon as the bus pauses, which the "all frames sent, all nodes idle" check
//!   then confirms).
//! - Delivery: every frame a node reports as sent was received (in the same
//!   bit, within one bit time) by every other node that was error-active
//!   throughout the frame, reported no error during it, had no disturbance on
//!   its receive path during it and did not itself send an identical frame in
//!   that bit.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use canstar_controller::frame::Frame;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

mod plan;
mod properties;
use plan::{plan, Action, Plan};
use properties::{check_properties, Monitor};

use canstar_sim::bus::{Bus, NodeDelays};
use canstar_golden::{Event, FaultState, Field};
use canstar_sim::{ClockSpec, Handle, Sim};
use crate::lockstep::{Divergence, LockstepNode};
use canstar_sim::net::FaultMode;
use crate::node::{HostEvent, NodeConfig};

/// Options of one run.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Frames requested in the run.
    pub frames: usize,
    /// Allow receive-path disturbances.
    pub disturb: bool,
    /// On a divergence, rerun the seed and write the window around it as a VCD into this directory.
    pub vcd_dir: Option<PathBuf>,
    /// Simulation engine of the RTL nodes (compiled models by default).
    pub engine: crate::node::Engine,
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions { frames: 16, disturb: true, vcd_dir: None, engine: Default::default() }
    }
}

/// Result of one run.
#[derive(Clone, Debug, Default)]
pub struct RunReport {
    pub seed: u64,
    pub nodes: usize,
    /// Frames requested.
    pub frames: usize,
    /// Frames reported sent (identical frames sent at once count once per sender).
    pub sent: usize,
    /// Frames delivered by receivers, all nodes.
    pub received: usize,
    /// Errors reported by the nodes.
    pub errors: usize,
    /// Disturbance windows applied.
    pub disturbances: usize,
    /// Highest error state reached by any node (0 EA, 1 EP, 2 bus-off).
    pub worst_state: u32,
    pub divergence: Option<Divergence>,
    /// Property violations (each names the property, node and time).
    pub violations: Vec<String>,
    /// VCD written for the divergence.
    pub vcd: Option<PathBuf>,
    /// Simulated time in ps and total clock cycles.
    pub sim_ps: u64,
    pub cycles: u64,
    /// Bits compared by the lock-step checkers, all nodes.
    pub bits: u64,
    /// Longest run of consecutive dominant bits driven by one node, and that run's bound.
    pub max_dom_run: (u32, u32),
}

impl RunReport {
    pub fn ok(&self) -> bool {
        self.divergence.is_none() && self.violations.is_empty()
    }
}


/// Build the simulation of a plan.
fn build(seed: u64, p: &Plan, golden_nets: bool) -> (Sim, Bus, Vec<Handle<LockstepNode>>) {
    let mut sim = Sim::new(seed);
    let names: Vec<String> = p.cfgs.iter().map(|(c, _)| c.name.clone()).collect();
    let spec: Vec<(&str, NodeDelays)> = names.iter().zip(&p.delays).map(|(n, d)| (n.as_str(), *d)).collect();
    let bus = Bus::build(&mut sim, "bus", &spec);
    let mut hs = Vec::new();
    for (i, (cfg, clock)) in p.cfgs.iter().enumerate() {
        let mut node = LockstepNode::new(cfg.clone(), *clock);
        node.set_seed(seed);
        node.record_steps();
        let outs = if golden_nets {
            let g = sim.driven(&format!("golden.{}.tx", cfg.name), true);
            let s = sim.driven(&format!("golden.{}.sample", cfg.name), false);
            vec![bus.nodes[i].tx, g, s]
        } else {
            vec![bus.nodes[i].tx]
        };
        hs.push(sim.add(node, &[bus.nodes[i].rx], &outs));
    }
    (sim, bus, hs)
}

fn apply(sim: &mut Sim, bus: &Bus, hs: &[Handle<LockstepNode>], t: u64, a: &Action) {
    match a {
        Action::Request { node, frame } => sim.get_mut(hs[*node]).node.request(frame.clone()),
        Action::Disturb { node, mode, len } => {
            bus.schedule_interference(sim, *node, t, *mode);
            bus.schedule_interference(sim, *node, t + len, FaultMode::None);
        }
        Action::Flip { node, len, every, count } => sim.add_flip_pattern(bus.nodes[*node].rx, t, *len, *every, *count),
    }
}

/// Run one seed. See the module documentation.
pub fn run_seed(seed: u64, opts: &RunOptions) -> RunReport {
    let p = plan(seed, opts);
    let n = p.cfgs.len();
    let (mut sim, bus, hs) = build(seed, &p, false);
    let mut rep = RunReport { seed, nodes: n, frames: opts.frames, ..Default::default() };
    let mut mons: Vec<Monitor> = (0..n).map(|_| Monitor::default()).collect();
    let names: Vec<String> = p.cfgs.iter().map(|(c, _)| c.name.clone()).collect();
    let bit = p.bit_ps;
    let chunk = 100 * bit;
    let mut drained = vec![0usize; n];
    let mut ai = 0;
    let settle_from = p.quiet_from + 250 * bit;
    let mut deadline = p.actions.last().map(|a| a.0).unwrap_or(0).max(p.quiet_from) + (opts.frames as u64 * 400 + 4000) * bit;
    let mut last_busy = 0u64; // last time a queue was non-empty or the bus dominant
    let mut idle_since: Option<u64> = None;
    loop {
        let next_action = p.actions.get(ai).map(|a| a.0).unwrap_or(u64::MAX);
        sim.run_until(next_action.min(sim.now() + chunk));
        while let Some((t, a)) = p.actions.get(ai) {
            if *t > sim.now() {
                break;
            }
            let now = sim.now();
            apply(&mut sim, &bus, &hs, now, a);
            ai += 1;
        }
        // drain golden steps into the monitors
        for i in 0..n {
            let node = sim.get(hs[i]);
            let steps = node.steps();
            for (t, out) in &steps[drained[i]..] {
                mons[i].feed(&names[i], *t, out, &mut rep.violations);
            }
            drained[i] = steps.len();
        }
        if let Some(d) = hs.iter().find_map(|h| sim.get(*h).divergence().cloned()) {
            rep.divergence = Some(d);
            break;
        }
        let pending = hs.iter().any(|h| sim.get(*h).node.pending()) || ai < p.actions.len();
        let bus_r = sim.value(bus.level);
        if pending || !bus_r {
            last_busy = sim.now();
            idle_since = None;
        } else if idle_since.is_none() {
            idle_since = Some(last_busy);
        }
        let all_idle = hs.iter().all(|h| sim.get(*h).golden().label().field == Field::BusIdle);
        if !pending && all_idle && sim.now() >= settle_from && idle_since.is_some_and(|s| sim.now() - s >= 20 * bit) {
            break;
        }
        if sim.now() >= deadline {
            let stuck: Vec<String> = hs
                .iter()
                .filter(|h| sim.get(**h).node.pending() || sim.get(**h).golden().label().field != Field::BusIdle)
                .map(|h| {
                    let n = sim.get(*h);
                    format!("{} (pending {}, {})", n.node.config().name, n.node.pending(), n.golden().label().field_name())
                })
                .collect();
            rep.violations.push(format!(
                "recovery: network not idle with all frames sent by {} ns after the last disturbance: {}",
                (deadline - p.quiet_from) / 1000,
                stuck.join(", ")
            ));
            break;
        }
        // long bus-off recoveries push the deadline only while someone is in bus-off
        if hs.iter().any(|h| sim.get(*h).golden().state() == FaultState::BusOff) {
            deadline = deadline.max(sim.now() + 2000 * bit);
        }
    }
    rep.sim_ps = sim.now();
    rep.cycles = sim.total_cycles();
    rep.disturbances = p.windows.iter().map(|w| w.len()).sum();
    rep.worst_state = mons.iter().map(|m| m.worst).max().unwrap_or(0);
    rep.max_dom_run = mons.iter().map(|m| m.max_run).max().unwrap_or((0, 0));
    for h in &hs {
        let n = sim.get(*h);
        rep.sent += n.node.sent().len();
        rep.received += n.node.received().len();
        rep.errors += n.node.errors();
        rep.bits += n.stats().bits;
    }
    if rep.divergence.is_none() {
        check_properties(&sim, &hs, &p, &mons, settle_from, &mut rep);
    }
    if let (Some(d), Some(dir)) = (&rep.divergence, &opts.vcd_dir) {
        let path = dir.join(format!("fuzz-divergence-seed{seed}.vcd"));
        match write_window_vcd(seed, opts, &path, d.t_ps) {
            Ok(()) => rep.vcd = Some(path),
            Err(e) => rep.violations.push(format!("could not write the divergence VCD: {e}")),
        }
    }
    rep
}

/// Rerun `seed` and return the golden per-bit trace lines (§18) of all nodes between `from_ps`
/// and `to_ps`, with the host events of the nodes (as `HOST` lines), sorted by time.
pub fn trace_window(seed: u64, opts: &RunOptions, from_ps: u64, to_ps: u64) -> Vec<String> {
    let p = plan(seed, opts);
    let (mut sim, bus, hs) = build(seed, &p, false);
    let mut ai = 0;
    while sim.now() < to_ps {
        let next = p.actions.get(ai).map(|a| a.0).unwrap_or(u64::MAX);
        sim.run_until(next.min(to_ps));
        while let Some((t, a)) = p.actions.get(ai) {
            if *t > sim.now() {
                break;
            }
            let now = sim.now();
            apply(&mut sim, &bus, &hs, now, a);
            ai += 1;
        }
    }
    let mut lines: Vec<(u64, String)> = Vec::new();
    for h in &hs {
        let n = sim.get(*h);
        let name = format!("G{}", n.node.config().name);
        for (t, out) in n.steps() {
            if *t >= from_ps && *t <= to_ps {
                lines.push((*t, canstar_golden::trace::trace_line(t / 1000, &name, out)));
            }
        }
        for (t, e) in n.node.log() {
            if *t >= from_ps && *t <= to_ps {
                lines.push((*t, format!("{:>6}   HOST {} {e:?}", t / 1000, n.node.config().name)));
            }
        }
    }
    for (i, ws) in p.windows.iter().enumerate() {
        for (a, b) in ws {
            if *b >= from_ps && *a <= to_ps {
                lines.push((*a, format!("{:>6}   DISTURB n{} until {} ns", a / 1000, i + 1, b / 1000)));
            }
        }
    }
    lines.sort_by_key(|l| l.0);
    lines.into_iter().map(|l| l.1).collect()
}

/// Rerun `seed` and write a VCD from 60 bits before `t_ps` to 10 bits after it. The golden TX and
/// sample strobe of every node are added as nets `golden.<node>.tx` / `golden.<node>.sample`.
pub fn write_window_vcd(seed: u64, opts: &RunOptions, path: &Path, t_ps: u64) -> std::io::Result<()> {
    let p = plan(seed, opts);
    let (mut sim, bus, hs) = build(seed, &p, true);
    let from = t_ps.saturating_sub(60 * p.bit_ps);
    let to = t_ps + 10 * p.bit_ps;
    let mut started = false;
    let mut ai = 0;
    loop {
        let next = p.actions.get(ai).map(|a| a.0).unwrap_or(u64::MAX);
        let stop = if started { next.min(to) } else { next.min(from) };
        sim.run_until(stop);
        if !started && sim.now() >= from {
            sim.start_vcd_file(path, None)?;
            started = true;
        }
        if started && sim.now() >= to {
            break;
        }
        while let Some((t, a)) = p.actions.get(ai) {
            if *t > sim.now() {
                break;
            }
            let now = sim.now();
            apply(&mut sim, &bus, &hs, now, a);
            ai += 1;
        }
    }
    sim.finish_vcd()
}

/// Totals over several runs.
#[derive(Clone, Debug, Default)]
pub struct FuzzSummary {
    pub runs: u64,
    pub frames: u64,
    pub sent: u64,
    pub errors: u64,
    pub bits: u64,
    pub cycles: u64,
    pub sim_ps: u64,
    /// Runs that reached error-passive / bus-off somewhere.
    pub passive_runs: u64,
    pub busoff_runs: u64,
    /// Longest dominant run driven by one node over all runs (with its bound).
    pub max_dom_run: (u32, u32),
    /// Failing runs (divergence or property violation).
    pub failures: Vec<RunReport>,
}

/// Seed of run `k` of a fuzz session with master seed `seed`.
pub fn run_seed_of(seed: u64, k: u64) -> u64 {
    let mut x = seed ^ k.wrapping_mul(0x9e37_79b9_7f4a_7c15);
    x ^= x >> 31;
    x = x.wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x ^ (x >> 29)
}

/// Run `frames` frames in runs of `opts.frames` (the last one shorter), run `k` with seed
/// [`run_seed_of`]`(seed, k)`, on `jobs` threads; `progress(summary, last_report)` is called
/// after every run in the calling thread. Stops starting new runs after `max_failures`
/// failing runs. The set of runs and their results do not depend on `jobs`.
pub fn fuzz(
    frames: u64,
    seed: u64,
    opts: &RunOptions,
    jobs: usize,
    max_failures: usize,
    mut progress: impl FnMut(&FuzzSummary, &RunReport),
) -> FuzzSummary {
    use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
    let per = opts.frames.max(1) as u64;
    let runs = frames.div_ceil(per);
    let next = AtomicU64::new(0);
    let stop = AtomicBool::new(false);
    let mut s = FuzzSummary::default();
    let (tx, rx) = std::sync::mpsc::channel::<RunReport>();
    std::thread::scope(|sc| {
        for _ in 0..jobs.max(1) {
            let tx = tx.clone();
            let (next, stop) = (&next, &stop);
            sc.spawn(move || loop {
                if stop.load(Ordering::Relaxed) {
                    break;
                }
                let k = next.fetch_add(1, Ordering::Relaxed);
                if k >= runs {
                    break;
                }
                let mut o = opts.clone();
                o.frames = per.min(frames - k * per) as usize;
                let r = run_seed(run_seed_of(seed, k), &o);
                if tx.send(r).is_err() {
                    break;
                }
            });
        }
        drop(tx);
        for r in rx {
            s.runs += 1;
            s.frames += r.frames as u64;
            s.sent += r.sent as u64;
            s.errors += r.errors as u64;
            s.bits += r.bits;
            s.cycles += r.cycles;
            s.sim_ps += r.sim_ps;
            s.passive_runs += (r.worst_state >= 1) as u64;
            s.busoff_runs += (r.worst_state >= 2) as u64;
            s.max_dom_run = s.max_dom_run.max(r.max_dom_run);
            if !r.ok() {
                s.failures.push(r.clone());
                if s.failures.len() >= max_failures {
                    stop.store(true, Ordering::Relaxed);
                }
            }
            progress(&s, &r);
        }
    });
    s
}
