//! The state of a run between two slices (a quarter bit) and the steps of one
//! slice: advance the simulation (to the next slice or to a fault's trigger),
//! start due faults, note isolations, apply legal events, step the node
//! drivers and applications, and follow the counters.

use canstar_controller::frame::Frame;
use canstar_sim::{Handle, Sim};

use super::inject::{ctrl_field, inject};
use super::{CounterSample, IsolationEvent, Isolated, RunResult, RunSpec};
use crate::app::{Receiver, Sender};
use crate::ctrl::Ctrl;
use crate::driver::{Driver, Notice, QuaReason};
use crate::events::{EventRunner, PowerChange};
use crate::fault::{FaultSpec, FaultStart};
use crate::network::Network;
use crate::spec::AppKind;

/// Two controllers of one node, mutably, from the simulation.
pub(super) fn pair(sim: &mut Sim, h: [Handle<Ctrl>; 2]) -> [&mut Ctrl; 2] {
    // two distinct components: split the borrow through raw pointers
    let a: *mut Ctrl = sim.get_mut(h[0]);
    let b: *mut Ctrl = sim.get_mut(h[1]);
    assert!(!std::ptr::eq(a, b));
    // SAFETY: the handles refer to different components of `sim`, which stays borrowed mutably
    unsafe { [&mut *a, &mut *b] }
}

/// Error events of every controller, in (node, ctrl) order.
pub(super) fn all_errors(sim: &Sim, net: &Network) -> Vec<u64> {
    net.ctrls.iter().flat_map(|p| p.iter().map(|&h| sim.get(h).errors)).collect()
}

pub(super) struct RunState<'a> {
    pub spec: &'a RunSpec,
    pub res: RunResult,
    pub bit: u64,
    slice: u64,
    /// Time limit of the run (ps).
    pub limit: u64,
    app_delay: u64,
    pub drivers: Vec<Driver>,
    senders: Vec<Option<Sender>>,
    pub receivers: Vec<Receiver>,
    /// Next request time per sender.
    next_req: Vec<Option<u64>>,
    /// The faults of the spec (the first `nf`), then the overload events as one-bit faults.
    pub nf: usize,
    faults: Vec<FaultSpec>,
    pub events: EventRunner,
    pub fault_start: Vec<Option<u64>>,
    pub fault_resolved: Vec<String>,
    pub delivered_at_last_fault: u64,
    last_disturb: u64,
    pub quiet_stop: bool,
    errors_seen: u64,
    seen_iso: Vec<Isolated>,
    /// (node, ctrl) made unhealthy by a started fault.
    pub unhealthy: Vec<(usize, usize)>,
    /// Error events of every controller when the first fault started.
    pub healthy_errors_base: Option<Vec<u64>>,
}

impl<'a> RunState<'a> {
    pub fn new(spec: &'a RunSpec, res: RunResult) -> Self {
        let ns = &spec.network;
        let nn = ns.nodes.len();
        let bit = res.bit_time_ps;
        let drivers: Vec<Driver> = (0..nn).map(|k| Driver::new(k, &ns.driver, bit, ns.nodes[k].initial_tx, spec.trace)).collect();
        let senders: Vec<Option<Sender>> =
            ns.nodes.iter().map(|n| matches!(n.app, AppKind::Counter | AppKind::Blinker).then(|| Sender::new(n.id))).collect();
        let start_at = ns.driver.start_bits as u64 * bit;
        let next_req = senders.iter().map(|s| s.as_ref().map(|_| start_at)).collect();
        let nf = spec.faults.len();
        let faults: Vec<FaultSpec> = spec.faults.iter().copied().chain(spec.events.iter().filter_map(|e| e.as_fault(bit))).collect();
        let max_after = faults
            .iter()
            .map(|f| match f.start {
                FaultStart::Field { after_frames, .. } => after_frames as u64 * 200 * bit,
                FaultStart::At { t_ps } => t_ps,
            })
            .max()
            .unwrap_or(0);
        let limit = spec.max_time_ps.unwrap_or(start_at + max_after + (spec.frames as u64 + 5) * 200 * bit);
        let mut res = res;
        res.delivered_per_node = vec![0; nn];
        res.max_tec_rec = vec![[(0, 0); 2]; nn];
        RunState {
            spec,
            bit,
            slice: (bit / 4).max(1),
            limit,
            app_delay: (ns.driver.app_delay_bits * bit as f64).round() as u64,
            drivers,
            senders,
            receivers: vec![Receiver::default(); nn],
            next_req,
            nf,
            events: EventRunner::new(&spec.events),
            fault_start: vec![None; faults.len()],
            fault_resolved: vec![String::new(); faults.len()],
            faults,
            delivered_at_last_fault: 0,
            last_disturb: 0,
            quiet_stop: false,
            errors_seen: 0,
            seen_iso: Vec::new(),
            unhealthy: Vec::new(),
            healthy_errors_base: None,
            res,
        }
    }

    /// Whether the run is over at `now`: the frame target after the last fault, a
    /// quiet network (with `quiet_frames`), or the time limit.
    pub fn finished(&mut self, now: u64) -> bool {
        let spec = self.spec;
        let all_started = self.fault_start[..self.nf].iter().all(|s| s.is_some());
        if all_started && spec.frames > 0 && self.res.delivered >= self.delivered_at_last_fault + spec.frames as u64 {
            return true;
        }
        if let (true, Some(q)) = (all_started, spec.quiet_frames) {
            let stuck = self.drivers.iter().any(|d| d.pending_since.is_some_and(|t| now > t + 150 * self.bit));
            if !stuck && self.res.delivered >= self.delivered_at_last_fault.max(self.last_disturb) + q as u64 {
                self.quiet_stop = true;
                return true;
            }
        }
        now >= self.limit
    }

    /// Run the simulation to the end of the slice, to the next timed fault, or to
    /// the instant a field-triggered fault's trigger is seen; returns that fault
    /// and its start time.
    pub fn advance(&self, sim: &mut Sim, net: &Network) -> Option<(usize, u64)> {
        let now = sim.now();
        let mut target = (now + self.slice).min(self.limit);
        let mut field_wait: Option<usize> = None;
        for (i, f) in self.faults.iter().enumerate() {
            if self.fault_start[i].is_some() {
                continue;
            }
            match f.start {
                FaultStart::At { t_ps } => target = target.min(t_ps.max(now)),
                FaultStart::Field { after_frames, .. } => {
                    if self.res.delivered >= after_frames as u64 && field_wait.is_none() {
                        field_wait = Some(i);
                    }
                }
            }
        }
        let Some(i) = field_wait else {
            sim.run_until(target);
            return None;
        };
        let FaultStart::Field { field, bit: fbit, of_node, delay_ns, .. } = self.faults[i].start else { unreachable!() };
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
        if !hit {
            sim.run_until(target);
            return None;
        }
        // the field value changes at the sample point of the previous bit;
        // the bit itself starts PH2 later
        let c = sim.get(cands[0]).spec().clone();
        let ph2 = c.period_ps() * c.timing.brp as u64 * c.timing.ph2 as u64;
        Some((i, sim.now() + ph2 + (delay_ns * 1000.0).round() as u64))
    }

    /// Start the faults that are due at `now` (timed ones) or were triggered.
    pub fn start_faults(&mut self, sim: &mut Sim, net: &Network, trigger: Option<(usize, u64)>) {
        let now = sim.now();
        for i in 0..self.faults.len() {
            if self.fault_start[i].is_some() {
                continue;
            }
            let f = self.faults[i];
            let t = match (f.start, trigger) {
                (FaultStart::At { t_ps }, _) if t_ps <= now => now,
                (FaultStart::Field { .. }, Some((j, t))) if j == i => t,
                _ => continue,
            };
            let info = inject(sim, net, &self.drivers, &f, t, self.bit, self.limit, &mut self.fault_resolved[i]);
            self.fault_start[i] = Some(t);
            if i >= self.nf {
                let spec = self.spec;
                let applied = spec.events.iter().filter(|e| e.as_fault(self.bit).is_some()).nth(i - self.nf).map_or(String::new(), |e| e.describe());
                self.events.applied.push(applied);
                continue;
            }
            self.unhealthy.extend(info.unhealthy.iter().copied());
            self.delivered_at_last_fault = self.res.delivered;
            if self.healthy_errors_base.is_none() {
                self.healthy_errors_base = Some(all_errors(sim, net));
            }
        }
    }

    /// Note new isolations by either hub, with their latency from the first fault.
    pub fn observe_isolations(&mut self, sim: &Sim, net: &Network) {
        let now = sim.now();
        for h in 0..2 {
            let hub = &sim.get(net.hubs[h]).hub;
            for i in 0..hub.ports() {
                let w = Isolated::Port { hub: h, port: i };
                if hub.isolated(i) && !self.seen_iso.contains(&w) {
                    self.seen_iso.push(w);
                }
            }
            for j in 0..hub.sublinks() {
                let w = Isolated::Sublink { hub: h, sublink: j };
                if hub.sub_isolated(j) && !self.seen_iso.contains(&w) {
                    self.seen_iso.push(w);
                }
            }
        }
        while self.res.isolated.len() < self.seen_iso.len() {
            self.last_disturb = self.res.delivered;
            let what = self.seen_iso[self.res.isolated.len()];
            let first = self.fault_start[..self.nf].iter().flatten().min().copied();
            let latency_bits = first.filter(|&f| f <= now).map(|f| (now - f) as f64 / self.bit as f64);
            let cause = match what {
                Isolated::Port { hub, port } => sim.get(net.hubs[hub]).stats.isolated_by[port].clone(),
                Isolated::Sublink { hub, sublink } => sim.get(net.hubs[hub]).stats.sub_isolated_by[sublink].clone(),
            };
            self.res.isolated.push(IsolationEvent { what, t_ps: now, latency_bits, cause: cause.unwrap_or_default() });
        }
    }

    /// Apply the legal events due now (nodes switched off and on).
    pub fn power_events(&mut self, sim: &mut Sim, net: &Network) {
        let now = sim.now();
        let ns = &self.spec.network;
        for ch in self.events.step(now, self.bit, sim, net) {
            match ch {
                PowerChange::Off(k) => {
                    self.next_req[k] = None;
                    self.receivers[k].rejoin();
                }
                PowerChange::On(k) => {
                    self.drivers[k] = Driver::new(k, &ns.driver, self.bit, ns.nodes[k].initial_tx, self.spec.trace);
                    if self.senders[k].is_some() {
                        self.next_req[k] = Some(now + self.app_delay);
                    }
                }
            }
        }
    }

    /// Step every powered node's driver and application.
    pub fn step_nodes(&mut self, sim: &mut Sim, net: &Network) {
        for k in 0..self.drivers.len() {
            if !self.events.is_off(k) {
                self.step_node(sim, net, k);
            }
        }
    }

    fn step_node(&mut self, sim: &mut Sim, net: &Network, k: usize) {
        let now = sim.now();
        let res = &mut self.res;
        let mut cs = pair(sim, net.ctrls[k]);
        let notices = self.drivers[k].step(now, &mut cs);
        let mut sample = false;
        for n in notices {
            match n {
                Notice::TxSuccess(_) => {
                    if let Some(s) = self.senders[k].as_mut() {
                        s.success();
                        self.next_req[k] = Some(now + self.app_delay);
                    }
                    res.max_retransmissions = res.max_retransmissions.max(self.drivers[k].retx_this_frame);
                    res.delivered += 1;
                    res.delivered_per_node[k] += 1;
                    sample = true;
                }
                Notice::Deliver(f) => {
                    self.receivers[k].deliver(&f);
                }
                Notice::Quarantined { ctrl, t, reason } => {
                    self.last_disturb = res.delivered;
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
                    self.last_disturb = res.delivered;
                    res.retransmissions += 1;
                    res.max_retransmissions = res.max_retransmissions.max(self.drivers[k].retx_this_frame);
                }
                Notice::Rerequest => res.rerequests += 1,
                Notice::Copy => res.copies += 1,
                Notice::CopyGivenUp => res.copies_given_up += 1,
                Notice::Resend => res.resends += 1,
                Notice::NoController => res.failures.push(format!("node {k} has no active controller left")),
            }
        }
        if let (Some(t), Some(s)) = (self.next_req[k], self.senders[k].as_ref()) {
            if now >= t && self.drivers[k].pending.is_none() {
                let f: Frame = s.frame();
                let mut cs = pair(sim, net.ctrls[k]);
                if self.drivers[k].tx_request(f, now, &mut cs) || self.drivers[k].tx.is_none() {
                    self.next_req[k] = None;
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

    /// Errors at active controllers (a disturbance), the maxima of every
    /// controller's TEC and REC, the worst healthy one, and the hubs' blame counters.
    pub fn observe_counters(&mut self, sim: &Sim, net: &Network) {
        let res = &mut self.res;
        let errs: u64 = net.ctrls.iter().flat_map(|p| p.iter()).map(|&h| sim.get(h).errors).sum();
        if errs != self.errors_seen {
            self.errors_seen = errs;
            self.last_disturb = res.delivered;
        }
        for (k, p) in net.ctrls.iter().enumerate() {
            for (c, &h) in p.iter().enumerate() {
                let x = sim.get(h);
                let m = &mut res.max_tec_rec[k][c];
                *m = (m.0.max(x.tec()), m.1.max(x.rec()));
                if !self.unhealthy.contains(&(k, c)) && !x.is_held() {
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
    }
}
