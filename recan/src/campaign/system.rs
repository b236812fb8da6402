//! From a (class, run seed) pair to a [`crate::RunSpec`] and its pass criteria, and
//! from a [`crate::RunResult`] to a campaign [`RunOutcome`] and a [`PlotData`].
//!
//! Published classes use [`crate::published_scenario`] and [`crate::check`] (the
//! recorded outcome). Every other class is judged by [`Generic`] criteria.
//!
//! Randomised per run (from the run seed): oscillator offsets of every hub and
//! controller (±[`PPM`]), clock phases (by the run's kernel seed), the applications'
//! start (traffic phase), which controller of each node starts as tx controller, and
//! the injection instant (a random bit of a random field of a random frame, or a
//! random absolute time, which also randomises the phase within a bit).

use super::classes::{Class, ClassKind, Double, EofBit, EofSubset, Fault, Node, Role, FLIP_RATE_PERMILLE};
use super::plot::{Marker, MarkerKind, PlotData, Series};
use super::{RunOutcome, RunPlan, Settings};
use crate::{
    CtrlRef, Dir, FaultKind, FaultSpec, FaultStart, FaultTarget, Isolated, NetworkSpec, RunResult, RunSpec,
    StartField,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::PathBuf;

/// Oscillator offset range of the non-published classes, ± ppm (the CAN tolerance of
/// the reference bit timing, SJW 1 of 8 TQ, is about ±4900 ppm).
pub const PPM: f64 = 300.0;
/// Frames delivered after the last fault started before a run ends at the latest.
pub const FRAMES_AFTER_FAULT: u32 = 60;
/// A run ends earlier once this many frames were delivered after the last disturbance
/// (error, isolation, quarantine, retransmission) as in the published scenarios.
pub const QUIET_FRAMES: u32 = 5;

/// Generic pass criteria (recancentrate.md §5–6).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Generic {
    /// (node, ctrl) whose own links are faulty, crashed, or on a faulty hub.
    pub unhealthy: Vec<(usize, usize)>,
    /// Nodes left without a fault-free controller path: their frames may be lost (and
    /// if the Receiver is one of them, losses are not checked at all).
    pub excused: Vec<usize>,
    /// Isolations that must happen (a hub can see the fault).
    pub must_isolate: Vec<Isolated>,
    /// Isolations that are allowed (anything else is a failure, e.g. the hubs isolating
    /// each other for a single fault, or a healthy port isolated).
    pub may_isolate: Vec<Isolated>,
}

/// Pass criteria of one run.
#[derive(Clone, Debug, PartialEq)]
pub enum Expectation {
    Published(crate::Expected),
    Generic(Generic),
}

/// A ready-to-run scenario.
#[derive(Clone, Debug)]
pub struct Built {
    pub spec: RunSpec,
    pub expect: Expectation,
    /// The faults in `spec` must start at the same instant: resolve the first one's
    /// start by a short pre-run (deterministic) and start them all then.
    pub simultaneous: bool,
}

fn node_idx(n: Node) -> usize {
    n.index()
}

fn rand_ppm(rng: &mut ChaCha8Rng) -> f64 {
    (rng.gen_range(-PPM..PPM) * 10.0).round() / 10.0
}

fn randomise(net: &mut NetworkSpec, rng: &mut ChaCha8Rng) {
    for h in &mut net.hubs {
        h.ppm = rand_ppm(rng);
    }
    for nd in &mut net.nodes {
        nd.initial_tx = rng.gen_range(0..2);
        for c in 0..2 {
            nd.ctrl_mut(c).ppm = rand_ppm(rng);
        }
    }
    net.driver.start_bits = rng.gen_range(15..60);
}

/// A random injection instant: a random bit of a random field of a frame (of a random
/// sender) after 2..8 frames, or a random time 100..600 bit times after start.
fn rand_start(rng: &mut ChaCha8Rng, net: &NetworkSpec) -> FaultStart {
    if rng.gen_bool(0.5) {
        use StartField::*;
        let (field, len) = [(Sof, 1), (Ident, 11), (Dlc, 4), (Data, 8), (Crc, 15), (AckSlot, 1), (Eof, 7), (Inter, 3)][rng.gen_range(0..8)];
        let of_node = [None, Some(0), Some(1)][rng.gen_range(0..3)];
        FaultStart::Field { field, bit: rng.gen_range(0..len), of_node, after_frames: rng.gen_range(2..8), delay_ns: 0.0 }
    } else {
        let bit = net.bit_time_ps();
        let t = (net.driver.start_bits as u64 + rng.gen_range(100..600)) * bit + rng.gen_range(0..bit);
        FaultStart::At { t_ps: t }
    }
}

fn flip_kind(rng: &mut ChaCha8Rng, net: &NetworkSpec, per_mille: u32) -> FaultKind {
    let bit_ns = net.bit_time_ps() as f64 / 1000.0;
    let every = 1000.0 / per_mille as f64 * rng.gen_range(0.8..1.2);
    FaultKind::BitFlip {
        every_bits: every,
        width_ns: (bit_ns * rng.gen_range(0.3..1.2)).round(),
        offset_ns: (rng.gen_range(0.0..every) * bit_ns).round(),
    }
}

fn kind_of(f: Fault, rng: &mut ChaCha8Rng, net: &NetworkSpec) -> FaultKind {
    match f {
        Fault::Sad => FaultKind::Sad,
        Fault::Sar => FaultKind::Sar,
        Fault::Flip => flip_kind(rng, net, FLIP_RATE_PERMILLE),
    }
}

/// Concrete controller (0 = A, 1 = B) of `role` on `node` at the start of the run.
fn ctrl_of(net: &NetworkSpec, node: usize, role: Role) -> usize {
    let tx = net.nodes[node].initial_tx;
    match role {
        Role::Tx => tx,
        Role::NonTx => 1 - tx,
    }
}

fn cref(c: usize) -> CtrlRef {
    if c == 0 {
        CtrlRef::A
    } else {
        CtrlRef::B
    }
}


/// Add the criteria of one node-link fault.
fn link_expect(g: &mut Generic, node: usize, c: usize, dir: Dir, kind: Fault) {
    g.unhealthy.push((node, c));
    let port = Isolated::Port { hub: c, port: node };
    // the faulty path may always be cut; a hub must cut it when it sees it stuck dominant
    g.may_isolate.push(port);
    if (dir, kind) == (Dir::Up, Fault::Sad) {
        g.must_isolate.push(port);
    }
}

fn sublink_expect(g: &mut Generic, interlink: usize, from_hub: usize, kind: Fault) {
    let s = Isolated::Sublink { hub: 1 - from_hub, sublink: interlink };
    g.may_isolate.push(s);
    if kind == Fault::Sad {
        g.must_isolate.push(s);
    }
}

/// Add the criteria of a fault of hub `h`'s whole output.
fn hub_expect(g: &mut Generic, h: usize, nodes: usize, f: Fault) {
    for k in 0..nodes {
        g.unhealthy.push((k, h));
        g.may_isolate.push(Isolated::Port { hub: h, port: k });
    }
    for i in 0..2 {
        g.may_isolate.push(Isolated::Sublink { hub: h, sublink: i });
        sublink_expect(g, i, h, f);
    }
    // the nodes keep their other controller: nobody is excused
}

fn finish(mut g: Generic, nodes: usize) -> Generic {
    g.unhealthy.sort();
    g.unhealthy.dedup();
    g.must_isolate.sort();
    g.must_isolate.dedup();
    g.may_isolate.sort();
    g.may_isolate.dedup();
    g.excused = (0..nodes).filter(|&k| g.unhealthy.contains(&(k, 0)) && g.unhealthy.contains(&(k, 1))).collect();
    g
}

/// The scenario of `class` for run seed `seed`.
pub fn build(class: &Class, seed: u64, settings: &Settings) -> Built {
    if let ClassKind::Published(n) = class.kind {
        let (mut spec, e) = crate::published_scenario(n as usize, seed);
        spec.engine = settings.engine;
        if let Some(h) = &settings.hub {
            spec.network.hub = h.clone();
        }
        return Built { spec, expect: Expectation::Published(e), simultaneous: false };
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0xca3a_1a7e);
    // the reference system with 14.74 MHz controller clocks (same time quantum and bit
    // timing, half the cycles), as the published scenarios
    let mut net = NetworkSpec::fast();
    if let Some(h) = &settings.hub {
        net.hub = h.clone();
    }
    randomise(&mut net, &mut rng);
    let nn = net.nodes.len();
    let bit = net.bit_time_ps();
    let mut g = Generic::default();
    let mut faults = vec![];
    let mut simultaneous = false;
    match class.kind {
        ClassKind::Published(_) => unreachable!(),
        ClassKind::BitFlip { node, role, dir, rate } => {
            let k = node_idx(node);
            let c = ctrl_of(&net, k, role);
            let start = rand_start(&mut rng, &net);
            faults.push(FaultSpec::new(FaultTarget::Link { node: k, ctrl: cref(c), dir: dir }, flip_kind(&mut rng, &net, rate), start));
            link_expect(&mut g, k, c, dir, Fault::Flip);
        }
        ClassKind::Sublink(f) => {
            let (i, h) = (rng.gen_range(0..2), rng.gen_range(0..2));
            let kind = kind_of(f, &mut rng, &net);
            faults.push(FaultSpec::new(FaultTarget::Sublink { interlink: i, from_hub: h }, kind, rand_start(&mut rng, &net)));
            sublink_expect(&mut g, i, h, f);
        }
        ClassKind::Interlink(f) => {
            let i = rng.gen_range(0..2);
            let kind = kind_of(f, &mut rng, &net);
            faults.push(FaultSpec::new(FaultTarget::Interlink { interlink: i }, kind, rand_start(&mut rng, &net)));
            sublink_expect(&mut g, i, 0, f);
            sublink_expect(&mut g, i, 1, f);
        }
        ClassKind::Hub(f) => {
            let h = rng.gen_range(0..2);
            let kind = kind_of(f, &mut rng, &net);
            faults.push(FaultSpec::new(FaultTarget::Hub { hub: h }, kind, rand_start(&mut rng, &net)));
            hub_expect(&mut g, h, nn, f);
        }
        ClassKind::Sweep { point, shape, every } => {
            let start = rand_start(&mut rng, &net);
            let kind = super::sweep::kind(shape, every, &mut rng, &net);
            let target = super::sweep::target(point, &mut rng);
            match target {
                FaultTarget::Link { node, ctrl, dir } => link_expect(&mut g, node, (ctrl == CtrlRef::B) as usize, dir, Fault::Flip),
                FaultTarget::Sublink { interlink, from_hub } => sublink_expect(&mut g, interlink, from_hub, Fault::Flip),
                FaultTarget::Interlink { interlink } => {
                    sublink_expect(&mut g, interlink, 0, Fault::Flip);
                    sublink_expect(&mut g, interlink, 1, Fault::Flip);
                }
                FaultTarget::Hub { hub } => hub_expect(&mut g, hub, nn, Fault::Flip),
                FaultTarget::Crash { .. } => unreachable!("sweep targets are links and hubs"),
            }
            faults.push(FaultSpec::new(target, kind, start));
        }
        ClassKind::Crash { node, role } => {
            let k = node_idx(node);
            let c = ctrl_of(&net, k, role);
            let t = (net.driver.start_bits as u64 + rng.gen_range(100..600)) * bit + rng.gen_range(0..bit);
            faults.push(FaultSpec::new(FaultTarget::Crash { node: k, ctrl: cref(c) }, FaultKind::Sar, FaultStart::At { t_ps: t }));
            g.unhealthy.push((k, c));
            g.may_isolate.push(Isolated::Port { hub: c, port: k });
        }
        ClassKind::Double(d) => {
            let delay = settings.double_delay_bits as u64 * bit;
            let t0 = (net.driver.start_bits as u64 + rng.gen_range(100..600)) * bit + rng.gen_range(0..bit);
            let link = |g: &mut Generic, faults: &mut Vec<FaultSpec>, rng: &mut ChaCha8Rng, k: usize, c: usize, dir: Dir, f: Fault, t: u64| {
                let kind = kind_of(f, rng, &net);
                faults.push(FaultSpec::new(FaultTarget::Link { node: k, ctrl: cref(c), dir: dir }, kind, FaultStart::At { t_ps: t }));
                link_expect(g, k, c, dir, f);
            };
            let b = Node::Blinker.index();
            let r = Node::Receiver.index();
            match d {
                Double::TwoNodes => {
                    let (cb, cr) = (ctrl_of(&net, b, Role::Tx), ctrl_of(&net, r, Role::NonTx));
                    link(&mut g, &mut faults, &mut rng, b, cb, Dir::Up, Fault::Sad, t0);
                    link(&mut g, &mut faults, &mut rng, r, cr, Dir::Down, Fault::Sar, t0 + delay);
                }
                Double::BlinkerBoth => {
                    let c = ctrl_of(&net, b, Role::Tx);
                    link(&mut g, &mut faults, &mut rng, b, c, Dir::Up, Fault::Sad, t0);
                    link(&mut g, &mut faults, &mut rng, b, 1 - c, Dir::Up, Fault::Sad, t0 + delay);
                }
                Double::BlinkerDeaf => {
                    let c = ctrl_of(&net, b, Role::Tx);
                    link(&mut g, &mut faults, &mut rng, b, c, Dir::Down, Fault::Sar, t0);
                    link(&mut g, &mut faults, &mut rng, b, 1 - c, Dir::Down, Fault::Sar, t0 + delay);
                }
                Double::Interlinks => {
                    let i = rng.gen_range(0..2);
                    for (j, t) in [(i, t0), (1 - i, t0 + delay)] {
                        faults.push(FaultSpec::new(FaultTarget::Interlink { interlink: j }, FaultKind::Sad, FaultStart::At { t_ps: t }));
                        sublink_expect(&mut g, j, 0, Fault::Sad);
                        sublink_expect(&mut g, j, 1, Fault::Sad);
                    }
                }
                Double::Random => {
                    let mut points = vec![];
                    while points.len() < 2 {
                        let p = (
                            [b, r][rng.gen_range(0..2)],
                            rng.gen_range(0..2usize),
                            [Dir::Up, Dir::Down][rng.gen_range(0..2)],
                            Fault::ALL[rng.gen_range(0..3)],
                        );
                        if !points.iter().any(|q: &(usize, usize, Dir, Fault)| q.0 == p.0 && q.1 == p.1 && q.2 == p.2) {
                            points.push(p);
                        }
                    }
                    for (j, (k, c, dir, f)) in points.into_iter().enumerate() {
                        link(&mut g, &mut faults, &mut rng, k, c, dir, f, t0 + j as u64 * delay);
                    }
                }
            }
        }
        ClassKind::Eof { bit: eb, subset } => {
            let b = Node::Blinker.index();
            let r = Node::Receiver.index();
            let ebit = match eb {
                EofBit::Last => 6,
                EofBit::Penultimate => 5,
            };
            let start = FaultStart::Field { field: StartField::Eof, bit: ebit, of_node: Some(b), after_frames: rng.gen_range(2..8), delay_ns: 0.0 };
            let btx = ctrl_of(&net, b, Role::Tx);
            let rtx = ctrl_of(&net, r, Role::Tx);
            let targets: Vec<(usize, usize)> = match subset {
                EofSubset::ReceiverOne => vec![(r, rtx)],
                EofSubset::ReceiverBoth | EofSubset::ReceiverBothThenCrash => vec![(r, 0), (r, 1)],
                EofSubset::TransmitterTx | EofSubset::TransmitterTxThenCrash => vec![(b, btx)],
                EofSubset::TransmitterNonTx => vec![(b, 1 - btx)],
                EofSubset::AllButTransmitter => (0..nn).flat_map(|k| [(k, 0), (k, 1)]).filter(|&p| p != (b, btx)).collect(),
            };
            for &(k, c) in &targets {
                let mut f = FaultSpec::new(FaultTarget::Link { node: k, ctrl: cref(c), dir: Dir::Down }, FaultKind::Sad, start);
                f.duration_ps = Some(bit);
                faults.push(f);
                g.unhealthy.push((k, c));
            }
            if matches!(subset, EofSubset::TransmitterTxThenCrash | EofSubset::ReceiverBothThenCrash) {
                // the transmitter's tx controller stops 2 bit times after the disturbance,
                // inside its error flag, before it can retransmit
                faults.push(FaultSpec::new(FaultTarget::Crash { node: b, ctrl: cref(btx) }, FaultKind::Sar, start));
                g.unhealthy.push((b, btx));
            }
            simultaneous = faults.len() > 1;
        }
    }
    let g = finish(g, nn);
    let mut spec = RunSpec::new(net, seed, FRAMES_AFTER_FAULT);
    spec.quiet_frames = Some(QUIET_FRAMES);
    spec.faults = faults;
    spec.engine = settings.engine;
    Built { spec, expect: Expectation::Generic(g), simultaneous }
}

/// Resolve field-triggered starts of a `simultaneous` spec to one absolute time (the
/// first fault's start, found by a pre-run that stops when it starts; crashes 2 bit
/// times later). Err if the trigger never came.
fn resolve_simultaneous(spec: &mut RunSpec) -> Result<(), String> {
    let mut pre = spec.clone();
    pre.faults.truncate(1);
    pre.frames = 0;
    pre.quiet_frames = None;
    pre.vcd = None;
    pre.trace = false;
    let r = crate::run(&pre);
    let t = r.fault_start_ps.first().copied().flatten().ok_or_else(|| "the EOF trigger never came (pre-run)".to_string())?;
    let bit = spec.network.bit_time_ps();
    for f in &mut spec.faults {
        let crash = matches!(f.target, FaultTarget::Crash { .. });
        f.start = FaultStart::At { t_ps: if crash { t + 2 * bit } else { t } };
    }
    Ok(())
}

/// (receiving node, sender id) of a `RunResult::lost` line ("node 2 (receiver) missed 0xb0 counter 3..=3").
fn parse_lost(s: &str) -> Option<(usize, u32)> {
    let rest = s.strip_prefix("node ")?;
    let k: usize = rest.split_whitespace().next()?.parse().ok()?;
    let m = rest.split(" missed ").nth(1)?;
    let id = m.split_whitespace().next()?;
    let id = u32::from_str_radix(id.trim_start_matches("0x"), 16).ok()?;
    Some((k, id))
}

/// Everything about one run.
pub struct Detailed {
    pub outcome: RunOutcome,
    pub result: RunResult,
    pub plot: PlotData,
}

fn unhealthy_of(spec: &RunSpec, expect: &Expectation) -> Vec<(usize, usize)> {
    match expect {
        Expectation::Generic(g) => g.unhealthy.clone(),
        Expectation::Published(_) => spec
            .faults
            .iter()
            .filter_map(|f| f.faulty_ctrl())
            .map(|(k, r)| {
                let tx = spec.network.nodes[k].initial_tx;
                let c = match r {
                    CtrlRef::A => 0,
                    CtrlRef::B => 1,
                    CtrlRef::Tx => tx,
                    CtrlRef::NonTx => 1 - tx,
                };
                (k, c)
            })
            .collect(),
    }
}

fn judge_generic(spec: &RunSpec, g: &Generic, r: &RunResult, lost: &mut Vec<String>, notes: &mut Vec<String>) -> Vec<String> {
    let net = &spec.network;
    let recv = net.nodes.iter().position(|n| n.app == crate::AppKind::Receiver);
    let mut f = vec![];
    // generic run failures, except the ones re-judged here
    for m in &r.failures {
        if m.contains("gap(s) in received counters") || m.starts_with("a healthy controller reached") {
            continue;
        }
        if let Some(rest) = m.strip_prefix("node ") {
            if m.ends_with("has no active controller left") {
                if let Some(k) = rest.split_whitespace().next().and_then(|x| x.parse::<usize>().ok()) {
                    if g.excused.contains(&k) {
                        notes.push(m.clone());
                        continue;
                    }
                }
            }
        }
        f.push(m.clone());
    }
    // losses at the Receiver of non-excused senders
    for l in &r.lost {
        match parse_lost(l) {
            Some((k, id)) => {
                let sender = net.nodes.iter().position(|n| n.id == id && n.app != crate::AppKind::Receiver);
                let excused = g.excused.contains(&k) || sender.is_some_and(|s| g.excused.contains(&s));
                if Some(k) == recv && !excused {
                    lost.push(l.clone());
                } else {
                    notes.push(l.clone());
                }
            }
            None => lost.push(l.clone()),
        }
    }
    if !lost.is_empty() {
        f.push(format!("Receiver missed frames: {}", lost.join("; ")));
    }
    // healthy controllers
    let lim = net.driver.warning_limit;
    let (tec, rec) = worst_sampled(r, &g.unhealthy);
    let worst = healthy_worst(r, &g.unhealthy);
    if worst >= lim || tec.max(rec) >= lim {
        f.push(format!("a healthy controller reached TEC/REC {} (limit {lim})", worst.max(tec).max(rec)));
    }
    for &(k, c, _) in &r.quarantined {
        if !g.unhealthy.contains(&(k, c)) {
            f.push(format!("healthy controller {} of node {k} quarantined", "AB".as_bytes()[c] as char));
        }
    }
    // isolations
    let mut seen: Vec<Isolated> = r.isolated.iter().map(|i| i.what).collect();
    seen.sort();
    seen.dedup();
    for m in &g.must_isolate {
        if !seen.contains(m) {
            f.push(format!("{m} not isolated"));
        }
    }
    for s in &seen {
        if !g.may_isolate.contains(s) {
            let what = match s {
                Isolated::Sublink { .. } => "hubs isolated each other: ",
                Isolated::Port { .. } => "healthy path isolated: ",
            };
            f.push(format!("{what}{s}"));
        }
    }
    f
}

/// Highest TEC or REC of a healthy controller: the run's continuous value when its
/// notion of healthy (faulty links and crashes) matches ours, else the sampled one.
fn healthy_worst(r: &RunResult, unhealthy: &[(usize, usize)]) -> u32 {
    let (t, c) = worst_sampled(r, unhealthy);
    let extra = unhealthy.len() > r.fault_resolved.iter().filter(|d| d.contains(" ctrl ")).count();
    if extra {
        // hub faults: the run counts the faulty hub's controllers as healthy
        t.max(c)
    } else {
        r.worst_healthy_tec_rec
    }
}

fn worst_sampled(r: &RunResult, unhealthy: &[(usize, usize)]) -> (u32, u32) {
    let mut w = (0, 0);
    for s in &r.counters {
        if !unhealthy.contains(&(s.node, s.ctrl)) {
            w.0 = w.0.max(s.tec);
            w.1 = w.1.max(s.rec);
        }
    }
    w
}

/// Shortest run of equal level on the inputs of both hubs: the ports of healthy
/// controllers (`Some(unhealthy)`: port k of hub h is controller (k, h)) or the sublinks.
fn min_pulse(r: &RunResult, np: usize, ports_except: Option<&[(usize, usize)]>) -> Option<u32> {
    let mut best: Option<u32> = None;
    for (h, hub) in r.short_runs.iter().enumerate() {
        for (k, runs) in hub.iter().enumerate() {
            let keep = match ports_except {
                Some(u) => k < np && !u.contains(&(k, h)),
                None => k >= np,
            };
            if let (true, Some(len)) = (keep, runs.iter().position(|&c| c > 0)) {
                best = Some(best.map_or(len as u32, |b| b.min(len as u32)));
            }
        }
    }
    best
}

/// Run one plan (the runner of [`super::execute`]).
pub fn run_plan(p: &RunPlan, settings: &Settings) -> RunOutcome {
    run_detailed(&p.class, p.rep, p.seed, settings, None, false).outcome
}

/// Run `class` with seed `seed` (repetition `rep`, for the record), optionally writing
/// a VCD; returns the outcome, the raw result and the plot data.
pub fn run_detailed(class: &Class, rep: u32, seed: u64, settings: &Settings, vcd: Option<PathBuf>, trace: bool) -> Detailed {
    let mut b = build(class, seed, settings);
    b.spec.vcd = vcd;
    b.spec.trace = trace;
    run_built(class, rep, seed, b)
}

/// Run a built campaign run (`build`, possibly changed: another node driver, say) and
/// judge it as the campaign does.
pub fn run_built(class: &Class, rep: u32, seed: u64, mut b: Built) -> Detailed {
    let mut pre_fail = None;
    if b.simultaneous {
        if let Err(e) = resolve_simultaneous(&mut b.spec) {
            pre_fail = Some(e);
        }
    }
    let r = crate::run(&b.spec);
    let unhealthy = unhealthy_of(&b.spec, &b.expect);
    let mut lost = vec![];
    let mut notes = vec![];
    let mut failures = match &b.expect {
        Expectation::Published(e) => {
            lost = r.lost.clone();
            if !e.note.is_empty() {
                notes.push(e.note.clone());
            }
            crate::check(&r, e)
        }
        Expectation::Generic(g) => judge_generic(&b.spec, g, &r, &mut lost, &mut notes),
    };
    if let Some(e) = pre_fail {
        failures.insert(0, e);
    }
    if r.copies > 0 {
        notes.push(format!(
            "{} frame(s) copied to the other star by a node driver (copy_tec), {} given up unsent",
            r.copies, r.copies_given_up
        ));
    }
    if r.resends > 0 {
        notes.push(format!(
            "{} unconfirmed frame(s) sent again on a new tx controller by a node driver",
            r.resends
        ));
    }
    let bit = r.bit_time_ps.max(1);
    let (tec, rec) = worst_sampled(&r, &unhealthy);
    let outcome = RunOutcome {
        class: class.name.clone(),
        rep,
        seed,
        pass: failures.is_empty(),
        failures,
        lost,
        worst_healthy: healthy_worst(&r, &unhealthy),
        worst_healthy_tec: tec,
        worst_healthy_rec: rec,
        isolation_latency_bits: r.isolated.iter().filter_map(|i| i.latency_bits).next().map(|l| l.round() as u32),
        isolations: r.isolated.iter().map(|i| format!("{}@{} ({})", i.what, i.t_ps / bit, i.cause)).collect(),
        quarantined: r
            .quarantined
            .iter()
            .zip(r.quarantine_reasons.iter().map(|s| s.as_str()).chain(std::iter::repeat("")))
            .map(|(&(k, c, t), why)| format!("node {k} {}@{} ({why})", "AB".as_bytes()[c] as char, t / bit))
            .collect(),
        max_retransmissions: r.max_retransmissions,
        duplicates: r.duplicates,
        delivered: r.delivered as u32,
        sim_cycles: r.sim_cycles,
        faults: r
            .fault_resolved
            .iter()
            .zip(&r.fault_start_ps)
            .map(|(d, t)| match t {
                Some(t) => format!("{d} @{}", t / bit),
                None => format!("{d} (never started)"),
            })
            .collect(),
        notes,
        min_pulse_healthy_port: min_pulse(&r, b.spec.network.hub.ports, Some(&unhealthy)),
        min_pulse_sublink: min_pulse(&r, b.spec.network.hub.ports, None),
    };
    let plot = plot_data(class, seed, &b.spec, &r);
    Detailed { outcome, result: r, plot }
}

/// TEC/REC series of every controller with fault, isolation and quarantine markers.
pub fn plot_data(class: &Class, seed: u64, spec: &RunSpec, r: &RunResult) -> PlotData {
    let bit = r.bit_time_ps.max(1);
    let mut series = vec![];
    for (k, n) in spec.network.nodes.iter().enumerate() {
        for c in 0..2 {
            let points: Vec<(u64, u32, u32)> =
                r.counters.iter().filter(|s| s.node == k && s.ctrl == c).map(|s| (s.t_ps, s.tec, s.rec)).collect();
            series.push(Series { label: format!("{} {}", n.name, if c == 0 { "A (hub 0)" } else { "B (hub 1)" }), points });
        }
    }
    let mut markers = vec![];
    for (d, t) in r.fault_resolved.iter().zip(&r.fault_start_ps) {
        if let Some(t) = t {
            markers.push(Marker { t_ps: *t, kind: MarkerKind::Fault, label: format!("fault: {d}") });
        }
    }
    for i in &r.isolated {
        markers.push(Marker { t_ps: i.t_ps, kind: MarkerKind::Isolation, label: format!("isolated {}", i.what) });
    }
    for &(k, c, t) in &r.quarantined {
        let name = spec.network.nodes.get(k).map(|n| n.name.clone()).unwrap_or_else(|| format!("node {k}"));
        markers.push(Marker { t_ps: t, kind: MarkerKind::Quarantine, label: format!("quarantined {name} {}", "AB".as_bytes()[c] as char) });
    }
    PlotData {
        title: format!("{} seed {seed}: TEC/REC per controller ({} bit times)", class.name, r.end_ps / bit),
        end_ps: r.end_ps,
        series,
        markers,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lost_lines_parse() {
        assert_eq!(parse_lost("node 2 (receiver) missed 0xb0 counter 3..=4"), Some((2, 0xb0)));
        assert_eq!(parse_lost("garbage"), None);
    }
}
