//! The propagation budget of a network: the longest loop a bit travels before the
//! controller that sent it samples the answer (docs/recancentrate.md §1.1).
//!
//! A transmitter T sees a receiver R's reaction (an ACK bit, a dominant arbitration bit,
//! an error flag) only after the loop T → its hub → (the peer hub, when R hangs on it) →
//! R, and R's bit back the same way. R starts its bit when T's edge reaches it, so R's bit
//! reaches T `loop` after T's own edge; T samples at its sample point. When the loop is
//! longer than the sample point, fault-free traffic has bit and ACK errors and the hubs
//! blame healthy inputs. Per pair of controllers:
//!
//! - same hub: `T.up + lat + R.down` and back `R.up + lat + T.down`;
//! - across the hubs: `T.up + lat + sub + lat + R.down` and back the same way, where `sub`
//!   is the fastest sublink in that direction (the wired AND of the replicas passes the
//!   first dominant edge) and `lat` the hub's coupling latency (sync depth + 1 clocks).
//!
//! The synchronisers, the controllers' own reaction and the oscillators' drift are left
//! out, so the margin is a nominal figure. Against the simulated reference network with
//! every oscillator at the tolerance limit it is what separates clean from failing soaks:
//! no chunk failed from 51 ns of margin up, some did from 31 ns down, and most below 0
//! (docs/recancentrate.md §1.1; test `tests/soak_cli.rs`, `budget_predicts_the_first_errors`).
//! [`Budget::warning`] therefore warns below one time quantum of margin, and says
//! "expect errors" below 0.

use crate::spec::NetworkSpec;

/// One controller of a network: node index and controller (0 = A on hub 0, 1 = B on hub 1).
pub type CtrlAt = (usize, usize);

/// The tightest pair of a network (see the module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct Budget {
    /// The transmitter whose margin is smallest.
    pub tx: CtrlAt,
    /// The receiver whose answer comes last to it.
    pub rx: CtrlAt,
    /// The loop T → R → T, ps.
    pub loop_ps: u64,
    /// T's sample point from the start of its bit, ps.
    pub sample_point_ps: u64,
    /// T's time quantum, ps.
    pub tq_ps: u64,
}

impl Budget {
    /// Sample point minus loop, ps (negative: over budget).
    pub fn margin_ps(&self) -> i64 {
        self.sample_point_ps as i64 - self.loop_ps as i64
    }

    /// One line for a command's output, controllers by name (`counter.a`).
    pub fn describe(&self, net: &NetworkSpec) -> String {
        let name = |(k, c): CtrlAt| format!("{}.{}", net.nodes[k].name, ["a", "b"][c]);
        format!(
            "propagation budget: longest loop {:.1} ns ({} -> {} -> {}), sample point {:.1} ns, margin {:.1} ns",
            self.loop_ps as f64 / 1000.0,
            name(self.tx),
            name(self.rx),
            name(self.tx),
            self.sample_point_ps as f64 / 1000.0,
            self.margin_ps() as f64 / 1000.0
        )
    }

    /// The warning for a network over budget or within one time quantum of it (None
    /// otherwise). The second level is measured, not derived: with every oscillator at
    /// the tolerance limit, fault-free soaks had controller errors in some chunks from
    /// about 30 ns of margin down (docs/recancentrate.md §1.1).
    pub fn warning(&self) -> Option<String> {
        let m = self.margin_ps() as f64 / 1000.0;
        if m < 0.0 {
            Some(format!(
                "the loop through the hubs is {:.1} ns longer than the sample point: expect bit and ACK errors \
                 and blames of healthy inputs in fault-free traffic (shorten the links or the interlinks, or \
                 move the sample point later)",
                -m
            ))
        } else if self.margin_ps() < self.tq_ps as i64 {
            Some(format!(
                "the loop through the hubs leaves only {m:.1} ns before the sample point, less than one time \
                 quantum ({:.1} ns): oscillators near the tolerance limit can cause bit and ACK errors \
                 (docs/recancentrate.md §1.1)",
                self.tq_ps as f64 / 1000.0
            ))
        } else {
            None
        }
    }
}

impl NetworkSpec {
    /// The pair of controllers with the smallest propagation margin (the spec must
    /// validate: every node has two controllers and there are sublinks in both
    /// directions or none).
    pub fn propagation_budget(&self) -> Budget {
        let lat = self.hub.coupling_latency() as u64 * self.hub_period_ps();
        let sub = |from: usize| {
            self.interlinks.iter().map(|l| if from == 0 { l.h0_to_h1_ps } else { l.h1_to_h0_ps }).min().unwrap_or(0)
        };
        let ctrls: Vec<CtrlAt> = (0..self.nodes.len()).flat_map(|k| [(k, 0), (k, 1)]).collect();
        let mut worst: Option<Budget> = None;
        for &t in &ctrls {
            let ts = self.nodes[t.0].ctrl(t.1);
            let tq = ts.period_ps() * ts.timing.brp as u64;
            let sp = tq * ts.timing.sp() as u64;
            for &r in ctrls.iter().filter(|&&r| r != t) {
                let rs = self.nodes[r.0].ctrl(r.1);
                let hubs = if t.1 == r.1 { 2 * lat } else { 4 * lat + sub(t.1) + sub(r.1) };
                let b = Budget { tx: t, rx: r, loop_ps: ts.up_ps + rs.down_ps + rs.up_ps + ts.down_ps + hubs, sample_point_ps: sp, tq_ps: tq };
                if worst.as_ref().map_or(true, |w| b.margin_ps() < w.margin_ps()) {
                    worst = Some(b);
                }
            }
        }
        worst.expect("a validated network has at least two controllers")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with_links(up_ps: u64, down_ps: u64, interlink_ps: u64) -> NetworkSpec {
        let mut n = NetworkSpec::default();
        for node in &mut n.nodes {
            for c in 0..2 {
                node.ctrl_mut(c).up_ps = up_ps;
                node.ctrl_mut(c).down_ps = down_ps;
            }
        }
        for l in &mut n.interlinks {
            l.h0_to_h1_ps = interlink_ps;
            l.h1_to_h0_ps = interlink_ps;
        }
        n
    }

    #[test]
    fn reference_network_loop_is_counted_through_both_hubs() {
        let n = NetworkSpec::default();
        n.validate().unwrap();
        let b = n.propagation_budget();
        // 2 x (10 + 135.7 + 10 + 135.7 + 10) ns; sample point 6 TQ of 4 clocks at 29.48 MHz
        let lat = 2 * n.hub_period_ps();
        assert_eq!(b.loop_ps, 2 * (30_000 + 2 * lat));
        assert_eq!(b.sample_point_ps, 6 * 4 * n.nodes[0].a.period_ps());
        assert_ne!(b.tx.1, b.rx.1, "the longest loop crosses the hubs: {b:?}");
        assert!(b.margin_ps() > 200_000, "{}", b.describe(&n));
        assert!(b.warning().is_none());
        assert!(b.describe(&n).contains("margin 211."), "{}", b.describe(&n));
    }

    #[test]
    fn the_fastest_replica_counts_and_each_link_adds_twice() {
        let base = with_links(10_000, 10_000, 10_000).propagation_budget();
        // one slow interlink: the other still carries the dominant edge
        let mut n = with_links(10_000, 10_000, 10_000);
        n.interlinks[1].h0_to_h1_ps = 150_000;
        n.interlinks[1].h1_to_h0_ps = 150_000;
        assert_eq!(n.propagation_budget().loop_ps, base.loop_ps);
        // both slow: +140 ns each way
        assert_eq!(with_links(10_000, 10_000, 150_000).propagation_budget().loop_ps, base.loop_ps + 280_000);
        // node links count on both ends of the loop
        assert_eq!(with_links(60_000, 10_000, 10_000).propagation_budget().loop_ps, base.loop_ps + 100_000);
    }

    #[test]
    fn one_long_link_makes_its_controller_the_tight_one() {
        let mut n = NetworkSpec::default();
        n.nodes[2].b.up_ps = 300_000;
        let b = n.propagation_budget();
        assert!(b.tx == (2, 1) || b.rx == (2, 1), "{b:?}");
        assert!(b.warning().is_some(), "{}", b.describe(&n));
    }

    #[test]
    fn a_margin_below_one_quantum_is_tight() {
        // interlinks at 100 ns: margin 31 ns, inside the budget but within one TQ (135.7 ns)
        let n = with_links(10_000, 10_000, 100_000);
        let b = n.propagation_budget();
        assert!(b.margin_ps() > 0 && b.margin_ps() < b.tq_ps as i64, "{}", b.describe(&n));
        assert!(b.warning().unwrap().contains("only 31."), "{:?}", b.warning());
        // 40 ns: margin 151 ns, more than one TQ
        assert!(with_links(10_000, 10_000, 40_000).propagation_budget().warning().is_none());
    }

    #[test]
    fn a_second_hub_synchroniser_stage_is_over_budget() {
        // lib.rs: with two input flip-flops the round trip no longer fits
        let mut n = NetworkSpec::default();
        n.hub.sync_depth = 2;
        let b = n.propagation_budget();
        assert!(b.margin_ps() < 0, "{}", b.describe(&n));
        assert!(b.warning().unwrap().contains("longer than the sample point"));
    }
}
