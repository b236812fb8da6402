//! The end of a run: final counters, the hubs' and controllers' logs, and the
//! generic checks (lost frames, a healthy controller at the warning limit, a
//! fault that never started, a stuck network).

use canstar_sim::Sim;

use super::state::{all_errors, RunState};
use super::{CounterSample, RunResult};
use crate::network::Network;

impl RunState<'_> {
    /// The run's result: what was observed, the logs, and the generic checks.
    pub fn finish(mut self, sim: &mut Sim, net: &Network) -> RunResult {
        self.collect_logs(sim, net);
        self.judge(sim, net);
        if self.spec.trace {
            self.collect_trace();
        }
        if self.spec.vcd.is_some() {
            if let Err(e) = sim.finish_vcd() {
                self.res.failures.push(format!("VCD: {e}"));
                self.res.vcd_error = Some(format!("VCD: {e}"));
            }
        }
        self.res.ok = self.res.failures.is_empty();
        self.res
    }

    fn collect_logs(&mut self, sim: &Sim, net: &Network) {
        let res = &mut self.res;
        res.end_ps = sim.now();
        for (k, p) in net.ctrls.iter().enumerate() {
            for (c, &h) in p.iter().enumerate() {
                let x = sim.get(h);
                res.counters.push(CounterSample { t_ps: res.end_ps, node: k, ctrl: c, tec: x.tec(), rec: x.rec() });
            }
        }
        res.sim_cycles = sim.total_cycles();
        self.fault_start.truncate(self.nf);
        self.fault_resolved.truncate(self.nf);
        res.fault_start_ps = self.fault_start.clone();
        res.fault_resolved = std::mem::take(&mut self.fault_resolved);
        res.events_applied = self.events.applied.clone();
        res.tx_ctrl = self.drivers.iter().map(|d| d.tx).collect();
        for (h, &hh) in net.hubs.iter().enumerate() {
            res.blames.extend(sim.get(hh).stats.blame_log.iter().map(|&(t, u, f, p, c)| (h, t, u, f, p, c)));
            res.glitches.extend(sim.get(hh).stats.glitch_log.iter().map(|&(t, u)| (h, t, u)));
        }
        res.blames.sort_by_key(|b| b.1);
        res.replica_charges = net.hubs.iter().map(|&h| sim.get(h).stats.max_sub_rep.iter().sum::<u64>()).sum();
        res.glitches.sort_by_key(|g| g.1);
        res.short_runs = net.hubs.iter().map(|&h| sim.get(h).stats.short_runs.clone()).collect();
        res.edge_phase = net.hubs.iter().map(|&h| sim.get(h).stats.edge_phase.clone()).collect();
        for (k, p) in net.ctrls.iter().enumerate() {
            for (c, &h) in p.iter().enumerate() {
                res.ctrl_errors.extend(sim.get(h).error_log.iter().map(|&(t, tx, f)| (t, k, c, tx, f)));
            }
        }
        res.ctrl_errors.sort_by_key(|e| e.0);
        res.final_bic = net
            .hubs
            .iter()
            .map(|&h| {
                let hub = &sim.get(h).hub;
                (0..hub.debug_bic_len()).map(|i| hub.debug_bic(i) as u32).collect()
            })
            .collect();
    }

    /// Global errors after the first fault, lost frames, the warning limit, faults
    /// that never started, and too few frames after the fault.
    fn judge(&mut self, sim: &Sim, net: &Network) {
        let spec = self.spec;
        let ns = &spec.network;
        let res = &mut self.res;
        if let Some(base) = &self.healthy_errors_base {
            let now_err = all_errors(sim, net);
            let mut i = 0;
            for k in 0..ns.nodes.len() {
                for c in 0..2 {
                    if !self.unhealthy.contains(&(k, c)) {
                        res.healthy_errors_after_fault += now_err[i] - base[i];
                    }
                    i += 1;
                }
            }
        }
        for (k, r) in self.receivers.iter().enumerate() {
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
        for (i, s) in self.fault_start.iter().enumerate() {
            if s.is_none() {
                res.failures.push(format!("fault {i} never started"));
            }
        }
        let after = res.delivered.saturating_sub(self.delivered_at_last_fault);
        if !self.quiet_stop && spec.frames > 0 && self.fault_start.iter().all(|s| s.is_some()) && after < spec.frames as u64 {
            res.failures.push(format!("only {after} of {} frames delivered after the fault (time limit)", spec.frames));
        }
    }

    /// The drivers' routine logs, merged in time order.
    fn collect_trace(&mut self) {
        let mut lines: Vec<(u64, String)> = Vec::new();
        for d in &self.drivers {
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
        self.res.trace = lines.into_iter().map(|l| l.1).collect();
    }
}
