//! The lower tester as a kernel component: a bus participant that is not a
//! CAN node. It drives the TX levels of a [`super::Plan`] clock by clock
//! (no synchronisation, no protocol) and records, on every clock while a step
//! is recorded, what the bus and the IUT did ([`ClockSample`]).
//!
//! # Design
//!
//! The component runs on the IUT's clock (same period and phase), so a TQ of
//! the IUT is `brp` of its clocks and a plan's clock counts are exact. The
//! bench arms it with the plan's TX runs and the time of the plan's first
//! clock ([`LowerTester::play`]); the tick at that time drives the first
//! level. The disturbances of a plan are not driven here: the bench
//! schedules them on the receive nets of the bus (`super::bench`), which a
//! component cannot reach through its ports.
//!
//! Ports: output 0 is the LT's TX (one input of the wired AND); inputs are
//! 0 the LT's own receive net (the bus as every node sees it, after
//! bus-wide disturbances), 1 the wired-AND level, 2 the IUT's receive net
//! (after its own disturbances), 3 the IUT's TX.

use canstar_sim::{ClockSpec, Component, Io};
use std::collections::VecDeque;

/// The levels during the clock period that ends at `t` (inputs as the
/// kernel samples them just before an edge; true = recessive).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ClockSample {
    /// Time of the edge (ps).
    pub t: u64,
    /// The bus as every node sees it (after bus-wide disturbances).
    pub bus: bool,
    /// The wired AND of all TX levels (no disturbance).
    pub wired: bool,
    /// What the IUT receives (after bus-wide and its own disturbances).
    pub iut_rx: bool,
    /// The IUT's TX.
    pub iut_tx: bool,
    /// The LT's TX.
    pub lt_tx: bool,
}

/// The lower tester component (see the module documentation).
pub struct LowerTester {
    name: String,
    clock: ClockSpec,
    start_at: Option<u64>,
    runs: VecDeque<(u64, bool)>,
    level: bool,
    recording: bool,
    log: Vec<ClockSample>,
}

impl LowerTester {
    pub fn new(name: &str, clock: ClockSpec) -> Self {
        LowerTester { name: name.to_string(), clock, start_at: None, runs: VecDeque::new(), level: true, recording: false, log: vec![] }
    }

    /// Drive `runs` (clocks, level) from the tick at time `t0` on (which must
    /// be one of this component's edges), replacing what was still to drive.
    /// Recessive afterwards.
    pub fn play(&mut self, t0: u64, runs: Vec<(u64, bool)>) {
        self.runs = runs.into_iter().filter(|r| r.0 > 0).collect();
        self.start_at = (!self.runs.is_empty()).then_some(t0);
    }

    /// Stop driving (recessive from the next clock).
    pub fn stop(&mut self) {
        self.runs.clear();
        self.start_at = None;
    }

    /// Is a plan still being driven (or waiting for its start)?
    pub fn busy(&self) -> bool {
        self.start_at.is_some()
    }

    /// Start a new record (drops the old one).
    pub fn record(&mut self, on: bool) {
        self.recording = on;
        self.log.clear();
    }

    /// The record since [`LowerTester::record`].
    pub fn samples(&self) -> &[ClockSample] {
        &self.log
    }

    /// Take the record (recording goes on with an empty one).
    pub fn take_samples(&mut self) -> Vec<ClockSample> {
        std::mem::take(&mut self.log)
    }
}

impl Component for LowerTester {
    fn name(&self) -> &str {
        &self.name
    }
    fn clock(&self) -> ClockSpec {
        self.clock
    }
    fn tick(&mut self, io: &mut Io<'_>) {
        let now = io.now();
        let mut level = true;
        if self.start_at.is_some_and(|t0| now >= t0) {
            if let Some(front) = self.runs.front_mut() {
                level = front.1;
                front.0 -= 1;
                if front.0 == 0 {
                    self.runs.pop_front();
                }
            }
            if self.runs.is_empty() {
                self.start_at = None;
            }
        }
        if self.recording {
            self.log.push(ClockSample { t: now, bus: io.input(0), wired: io.input(1), iut_rx: io.input(2), iut_tx: io.input(3), lt_tx: self.level });
        }
        self.level = level;
        io.set_output(0, level);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_sim::bus::{Bus, NodeDelays};
    use canstar_sim::Sim;

    #[test]
    fn drives_the_runs_from_the_start_edge_and_records_what_it_saw() {
        let mut sim = Sim::new(1);
        let bus = Bus::uniform(&mut sim, "bus", 2, NodeDelays::default());
        let clock = ClockSpec::new(100_000);
        let ins = [bus.nodes[0].rx, bus.level, bus.nodes[1].rx, bus.nodes[1].tx];
        let h = sim.add(LowerTester::new("lt", clock), &ins, &[bus.nodes[0].tx]);
        sim.run_until(300_000);
        sim.get_mut(h).record(true);
        sim.get_mut(h).play(500_000, vec![(2, false), (1, true), (1, false)]);
        sim.run_until(1_000_000);
        let s = sim.get(h).samples();
        // edges at 0.4, 0.5, ..., 1.0 us; the edge at t shows the level before t
        let tx: Vec<(u64, bool)> = s.iter().map(|c| (c.t / 100_000, c.lt_tx)).collect();
        assert_eq!(tx, vec![(4, true), (5, true), (6, false), (7, false), (8, true), (9, false), (10, true)]);
        let busl: Vec<bool> = s.iter().map(|c| c.bus).collect();
        assert_eq!(busl, s.iter().map(|c| c.lt_tx).collect::<Vec<_>>(), "alone on the bus, the bus is the LT's TX");
        assert!(!sim.get(h).busy());
    }
}
