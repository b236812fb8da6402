//! Network properties checked in every fuzz run (can-protocol.md): bounded dominant runs,
//! recovery after the disturbances, consistent delivery.

use super::*;


/// Per-node property monitor fed with the golden steps (identical to the DUT's behaviour as long
/// as there is no divergence).
#[derive(Default)]
pub(super) struct Monitor {
    pub(super) dom_run: u32,
    /// Longest run seen and its bound.
    pub(super) max_run: (u32, u32),
    pub(super) restarts: u32,
    /// Times (ps) of bits at which the node was not error-active (or not yet integrated).
    pub(super) not_ea: Vec<(u64, u64)>,
    pub(super) cur_not_ea: Option<u64>,
    /// Bus-off intervals.
    pub(super) bus_off: Vec<(u64, u64)>,
    pub(super) cur_bus_off: Option<u64>,
    pub(super) worst: u32,
    pub(super) last_field: Option<Field>,
}

impl Monitor {
    pub(super) fn feed(&mut self, name: &str, t: u64, out: &canstar_golden::StepOut, violations: &mut Vec<String>) {
        if !out.drove {
            self.dom_run += 1;
            let in_flag = matches!(out.label.field, Field::ActiveErrorFlag | Field::OverloadFlag);
            if in_flag && out.events.contains(&Event::Error(canstar_golden::ErrorKind::Bit)) {
                self.restarts += 1;
            }
            let bound = 11 + 6 * self.restarts;
            if self.dom_run > self.max_run.0 {
                self.max_run = (self.dom_run, bound);
            }
            if self.dom_run > bound {
                violations.push(format!(
                    "dominant run: node {name} drove {} consecutive dominant bits (bound {bound}) at {} ns ({} {})",
                    self.dom_run,
                    t / 1000,
                    out.label.field_name(),
                    out.label.pos
                ));
                self.restarts += 100; // report once
            }
        } else {
            self.dom_run = 0;
            self.restarts = 0;
        }
        let ea = out.state == FaultState::ErrorActive
            && !matches!(out.label.field, Field::WaitForBusIdle | Field::Reset | Field::BusOff);
        match (ea, self.cur_not_ea) {
            (false, None) => self.cur_not_ea = Some(t),
            (true, Some(s)) => {
                self.not_ea.push((s, t));
                self.cur_not_ea = None;
            }
            _ => {}
        }
        match (out.state == FaultState::BusOff, self.cur_bus_off) {
            (true, None) => self.cur_bus_off = Some(t),
            (false, Some(s)) => {
                self.bus_off.push((s, t));
                self.cur_bus_off = None;
            }
            _ => {}
        }
        self.worst = self.worst.max(match out.state {
            FaultState::ErrorActive => 0,
            FaultState::ErrorPassive => 1,
            FaultState::BusOff => 2,
        });
        self.last_field = Some(out.label.field);
    }
    fn bus_off_at(&self, t: u64) -> bool {
        self.cur_bus_off.is_some_and(|s| s <= t) || self.bus_off.iter().any(|&(s, e)| s <= t && e >= t)
    }
    fn ea_throughout(&self, a: u64, b: u64) -> bool {
        if self.cur_not_ea.is_some_and(|s| s <= b) {
            return false;
        }
        !self.not_ea.iter().any(|&(s, e)| s <= b && e >= a)
    }
}

fn overlaps(ws: &[(u64, u64)], a: u64, b: u64) -> bool {
    ws.iter().any(|&(s, e)| s <= b && e >= a)
}

pub(super) fn check_properties(sim: &Sim, hs: &[Handle<LockstepNode>], p: &Plan, mons: &[Monitor], settle_from: u64, rep: &mut RunReport) {
    let bit = p.bit_ps;
    let names: Vec<String> = p.cfgs.iter().map(|(c, _)| c.name.clone()).collect();
    // recovery: no errors after the settling time
    for (i, h) in hs.iter().enumerate() {
        for (t, e) in sim.get(*h).node.log() {
            // an error-passive node may stay out of step with back-to-back traffic (see the module docs)
            if *t >= settle_from && mons[i].ea_throughout(t.saturating_sub(2 * bit), *t) {
                if let HostEvent::Error { kinds, field, pos, tx } = e {
                    // possibly nobody to acknowledge: another node is bus-off or error-passive
                    // (2 nodes, or the only receiver of two identical frames)
                    let ack_only = kinds.iter().all(|k| *k == crate::node::ErrorKind::Ack);
                    if ack_only && (0..hs.len()).any(|j| j != i && (mons[j].bus_off_at(*t) || !mons[j].ea_throughout(*t, *t))) {
                        continue;
                    }
                    rep.violations.push(format!(
                        "recovery: node {} reported an error {kinds:?} at {field:?} {pos} (tx {tx}) at {} ns, {} bits after the last disturbance",
                        names[i],
                        t / 1000,
                        (t - p.quiet_from) / bit
                    ));
                    break;
                }
            }
        }
    }
    // every requested frame sent
    for (i, h) in hs.iter().enumerate() {
        let mut want: Vec<Frame> = p
            .actions
            .iter()
            .filter_map(|(_, a)| if let Action::Request { node, frame } = a { (*node == i).then(|| frame.clone()) } else { None })
            .collect();
        let got = sim.get(*h).node.sent();
        want.sort_by_key(|f| format!("{f:?}"));
        let mut got_s = got.clone();
        got_s.sort_by_key(|f| format!("{f:?}"));
        if want != got_s {
            rep.violations.push(format!("delivery: node {} sent {} of {} requested frames", names[i], got.len(), want.len()));
        }
    }
    // delivery to error-active, error-free, undisturbed receivers
    let max_frame = 170 * bit;
    for (i, h) in hs.iter().enumerate() {
        for (t, e) in sim.get(*h).node.log() {
            let HostEvent::TxDone(f) = e else { continue };
            let (a, b) = (t.saturating_sub(max_frame), t + bit);
            for (j, hj) in hs.iter().enumerate() {
                if j == i {
                    continue;
                }
                let nj = sim.get(*hj);
                let log = nj.node.log();
                let in_win = |x: u64| x + bit >= *t && x <= t + bit;
                let same_sent = log.iter().any(|(x, e)| in_win(*x) && matches!(e, HostEvent::TxDone(g) if g == f));
                let erred = log.iter().any(|(x, e)| *x >= a && *x <= b && matches!(e, HostEvent::Error { .. }));
                if same_sent || erred || !mons[j].ea_throughout(a, b) || overlaps(&p.windows[j], a, b) {
                    continue;
                }
                let got = log.iter().any(|(x, e)| in_win(*x) && matches!(e, HostEvent::Rx(g) if g == f));
                if !got {
                    rep.violations.push(format!(
                        "delivery: frame {f:?} sent by {} at {} ns was not received by error-active, error-free node {}",
                        names[i],
                        t / 1000,
                        names[j]
                    ));
                }
            }
        }
    }
}

