//! [`LtBench`]: the lower tester on the conformance bench. The IUT is node 0
//! of a [`Bench`] (further nodes optional); the LT is one more bus
//! participant on a slot of the same wired-AND bus.
//!
//! # Design
//!
//! The shared [`Bench`] stays as it is (start-up, bit records read from the
//! debug bundle, Bosch WAIT_FOR); [`Bench::with_slots`] only reserves the
//! LT's bus slot. Everything a step does goes through [`LtBench::tick`],
//! one clock edge of the bench plus the per-clock observation a bit record
//! cannot give (entry into Reset).
//!
//! A *step* ([`LtBench::begin_step`] .. [`LtBench::end_step`]) is the unit
//! of recording and of occurrence counting: it marks every node's bit
//! records, starts the LT's clock record (and a VCD file if one was asked
//! for with [`LtBench::vcd_next_step`]), and resets the occurrence counts
//! of the triggers ([`super::trigger`]). Inside a step:
//!
//! - [`LtBench::preset`] loads TEC/REC of a node through its counter-load
//!   port; [`LtBench::reset_iut`] is the step reset (hard reset of the IUT,
//!   LT silent, disturbances cleared);
//! - [`LtBench::wait`] runs until a trigger fires and stops just before its
//!   instant, so that [`LtBench::play`] starts a plan exactly there (at the
//!   next clock edge when called without a trigger);
//! - [`LtBench::play`] arms the LT with the plan's TX levels and schedules
//!   the plan's disturbances on the receive nets of the bus: a bus-wide one
//!   on every node's net (the LT's included), a node one on that node's.
//!   Per net the timeline is composed window by window ([`compose`]): a
//!   node disturbance applies to what the bus disturbance left (a forced
//!   level wins, an inversion inverts it).
//!
//! All bench nodes and the LT share the IUT's clock (100 ns, in phase), as
//! in the Bosch bench, so the plan's clock counts are exact times.

use super::plan::{Action, Plan, Target, Window};
use super::record::{Played, StepRecord};
use super::tester::LowerTester;
use super::trigger::{begins_occurrence, Occurrences, Trigger, Where};
use crate::conformance::{Bench, CLOCK_PS};
use crate::node::NodeConfig;
use canstar_controller::fsm::Field;
use canstar_controller::view::CoreView;
use canstar_hdl::timing::BtlConfig;
use canstar_sim::net::FaultMode;
use canstar_sim::{ClockSpec, Handle};
use std::path::{Path, PathBuf};

thread_local! {
    /// `canstar conformance --suite iso --vcd DIR`: while a case runs, every
    /// [`LtBench`] it creates writes a VCD of its whole life (start-up and
    /// every step) into the directory: `<case>.vcd`, then `<case>_2.vcd` ...
    /// for a case with several benches (one per controller configuration).
    static CASE_VCD: std::cell::RefCell<Option<(PathBuf, String, usize)>> = const { std::cell::RefCell::new(None) };
}

/// Run `f` (a case named `case`) with its benches writing VCD files into
/// `dir` (see [`CASE_VCD`]); without a directory just run it. Errors of the
/// VCD files go to the conformance run log, as for the Bosch programs.
pub fn with_case_vcd<R>(dir: Option<&Path>, case: &str, f: impl FnOnce() -> R) -> R {
    let Some(d) = dir else { return f() };
    CASE_VCD.with(|c| *c.borrow_mut() = Some((d.to_path_buf(), case.to_string(), 0)));
    struct Clear;
    impl Drop for Clear {
        fn drop(&mut self) {
            CASE_VCD.with(|c| *c.borrow_mut() = None);
        }
    }
    let _clear = Clear;
    f()
}

/// The VCD file of the next bench of the running case, if one is asked for.
fn next_case_vcd() -> Option<PathBuf> {
    CASE_VCD.with(|c| {
        let mut c = c.borrow_mut();
        let (dir, case, n) = c.as_mut()?;
        *n += 1;
        Some(if *n == 1 { dir.join(format!("{case}.vcd")) } else { dir.join(format!("{case}_{n}.vcd")) })
    })
}

struct StepState {
    name: String,
    t0: u64,
    marks: Vec<usize>,
    occ: Occurrences,
    /// Next IUT record to count.
    cursor: usize,
    in_reset: bool,
    /// Set when a Reset trigger fired on this clock (occurrence number).
    reset_entries: Vec<u64>,
    plays: Vec<Played>,
    vcd: bool,
}

/// The LT bench (see the module documentation).
pub struct LtBench {
    pub b: Bench,
    pub lt: Handle<LowerTester>,
    /// Bus node index of the LT.
    pub lt_slot: usize,
    /// The IUT's bit timing.
    pub timing: BtlConfig,
    step: StepState,
    vcd_next: Option<PathBuf>,
    /// VCD errors (path: error) of finished steps.
    pub vcd_errors: Vec<String>,
}

/// The fault mode of a receive net under a bus-wide action `bus` and a
/// node action `node` (the node's receive path after the bus).
pub fn compose(bus: Option<Action>, node: Option<Action>) -> FaultMode {
    let stuck = |l: bool| if l { FaultMode::StuckRecessive } else { FaultMode::StuckDominant };
    match (bus, node) {
        (_, Some(Action::Force(l))) => stuck(l),
        (Some(Action::Force(l)), Some(Action::Invert)) => stuck(!l),
        (Some(Action::Invert), Some(Action::Invert)) => FaultMode::None,
        (None, Some(Action::Invert)) | (Some(Action::Invert), None) => FaultMode::Invert,
        (Some(Action::Force(l)), None) => stuck(l),
        (None, None) => FaultMode::None,
    }
}

/// The mode changes (clock from the plan start, mode) of one receive net
/// given the windows that concern it (`node` says which are its own).
pub fn net_timeline(windows: &[(Window, bool)]) -> Vec<(u64, FaultMode)> {
    let mut cuts: Vec<u64> = windows.iter().flat_map(|(w, _)| [w.start, w.end]).collect();
    cuts.sort_unstable();
    cuts.dedup();
    let mut out = vec![];
    let mut cur = FaultMode::None;
    for &c in &cuts {
        let covering = |own: bool| windows.iter().filter(|(w, o)| *o == own && w.start <= c && c < w.end).map(|(w, _)| w.action).next_back();
        let m = compose(covering(false), covering(true));
        if m != cur {
            out.push((c, m));
            cur = m;
        }
    }
    out
}

impl LtBench {
    /// The IUT (configuration `cfgs[0]`) and further nodes on one bus with
    /// the LT, started up and integrated (every node in Bus_Idle).
    pub fn new(cfgs: Vec<NodeConfig>) -> LtBench {
        let timing = cfgs[0].timing;
        let n = cfgs.len();
        let clocks = vec![ClockSpec::new(CLOCK_PS); n];
        let mut b = Bench::with_slots(cfgs, clocks, false, &["lt"], None);
        let lt_slot = n;
        let bus = b.bus.clone();
        let ins = [bus.nodes[lt_slot].rx, bus.level, bus.nodes[0].rx, bus.nodes[0].tx];
        let lt = b.sim.add(LowerTester::new("lt", ClockSpec::new(CLOCK_PS)), &ins, &[bus.nodes[lt_slot].tx]);
        if let Some(p) = next_case_vcd() {
            b.start_vcd(&p);
        }
        let ok = b.run_until(40, |b| (0..n).all(|i| b.node(i).field() == Field::Idle));
        assert!(ok.is_ok(), "start-up: nodes did not integrate");
        let step = StepState { name: String::new(), t0: 0, marks: vec![0; n], occ: Occurrences::default(), cursor: 0, in_reset: false, reset_entries: vec![], plays: vec![], vcd: false };
        let mut lb = LtBench { b, lt, lt_slot, timing, step, vcd_next: None, vcd_errors: vec![] };
        lb.begin_step("start");
        lb
    }

    /// One clock edge of the bench (all nodes and the LT), plus the
    /// per-clock observations of the step.
    pub fn tick(&mut self) {
        self.b.step();
        let r = self.b.node(0).field() == Field::Reset;
        if r && !self.step.in_reset {
            self.step.occ.bump(Field::Reset);
            self.step.reset_entries.push(self.b.sim.now());
        }
        self.step.in_reset = r;
    }

    /// Run every edge up to and including time `t`.
    pub fn run_until_time(&mut self, t: u64) {
        while self.b.sim.next_edge_time().is_some_and(|e| e <= t) {
            self.tick();
        }
    }

    /// Run `n` nominal bit times.
    pub fn run_bits(&mut self, n: u64) {
        let t = self.b.sim.now() + n * self.b.bit_ps;
        self.run_until_time(t);
    }

    /// Run until `pred` holds, at most `max_bits` bit times.
    pub fn run_until(&mut self, max_bits: u64, mut pred: impl FnMut(&LtBench) -> bool) -> Result<(), String> {
        let end = self.b.sim.now() + max_bits * self.b.bit_ps;
        while !pred(self) {
            if self.b.sim.now() >= end {
                return Err(format!("condition not reached within {max_bits} bits"));
            }
            self.tick();
        }
        Ok(())
    }

    /// Run until every node is in Bus_Idle and the LT is done.
    pub fn run_idle(&mut self, max_bits: u64) -> Result<(), String> {
        let n = self.b.n();
        let lt = self.lt;
        self.run_until(max_bits, |s| !s.b.sim.get(lt).busy() && (0..n).all(|i| s.b.node(i).field() == Field::Idle)).map_err(|e| format!("bus idle: {e}"))
    }

    /// Clock period, TQ and nominal bit of the IUT (ps).
    pub fn clock_ps(&self) -> u64 {
        CLOCK_PS
    }
    pub fn tq_ps(&self) -> u64 {
        CLOCK_PS * self.timing.brp as u64
    }

    /// Write a VCD file of the next step (from its begin to its end).
    pub fn vcd_next_step(&mut self, path: &Path) {
        self.vcd_next = Some(path.to_path_buf());
    }

    /// Start a step named `name` (ends the current one, dropping its record).
    pub fn begin_step(&mut self, name: &str) {
        if self.step.vcd {
            self.finish_vcd();
        }
        let n = self.b.n();
        self.step = StepState {
            name: name.to_string(),
            t0: self.b.sim.now(),
            marks: (0..n).map(|i| self.b.mark(i)).collect(),
            occ: Occurrences::default(),
            cursor: self.b.mark(0),
            in_reset: self.b.node(0).field() == Field::Reset,
            reset_entries: vec![],
            plays: vec![],
            vcd: false,
        };
        self.b.sim.get_mut(self.lt).record(true);
        if let Some(p) = self.vcd_next.take() {
            // a VCD of the whole case ([`with_case_vcd`]) leaves no room for a step's
            if self.b.writes_vcd() {
                self.vcd_errors.push(format!("{}: the bench already writes the VCD of the whole case", p.display()));
                return;
            }
            match self.b.sim.start_vcd_file(&p, None) {
                Ok(()) => self.step.vcd = true,
                Err(e) => self.vcd_errors.push(format!("{}: {e}", p.display())),
            }
        }
    }

    fn finish_vcd(&mut self) {
        if let Err(e) = self.b.sim.finish_vcd() {
            self.vcd_errors.push(format!("{}: {e}", self.step.name));
        }
        self.step.vcd = false;
    }

    /// End the step and return its record.
    pub fn end_step(&mut self) -> StepRecord {
        if self.step.vcd {
            self.finish_vcd();
        }
        let samples = self.b.sim.get_mut(self.lt).take_samples();
        let bits = (0..self.b.n()).map(|i| self.b.since(i, self.step.marks[i]).to_vec()).collect();
        StepRecord {
            name: self.step.name.clone(),
            t0: self.step.t0,
            t_end: self.b.sim.now(),
            clock_ps: CLOCK_PS,
            tq_ps: self.tq_ps(),
            samples,
            bits,
            plays: std::mem::take(&mut self.step.plays),
        }
    }

    /// Load TEC and REC of node `i` through its counter-load port; they are
    /// visible when this returns.
    pub fn preset(&mut self, i: usize, tec: u32, rec: u32) {
        self.b.node_mut(i).load_counters(tec, rec);
        let c0 = self.b.node(i).cycles();
        while self.b.node(i).cycles() == c0 {
            self.tick();
        }
    }

    /// The step reset: the LT stops driving, every disturbance is cleared,
    /// the IUT is reset (counters 0, integration follows).
    pub fn reset_iut(&mut self) {
        self.b.sim.get_mut(self.lt).stop();
        for j in 0..self.b.bus.nodes.len() {
            let rx = self.b.bus.nodes[j].rx;
            self.b.sim.set_fault(rx, FaultMode::None);
        }
        self.b.node_mut(0).withdraw();
        self.b.node_mut(0).hard_reset();
    }

    /// Run until `trig` fires (at most `max_bits` bit times) and stop just
    /// before its instant: the next clock edge is the trigger time, which is
    /// returned (ps). See [`super::trigger`] for the counting rules.
    pub fn wait(&mut self, trig: Trigger, max_bits: u64) -> Result<u64, String> {
        let end = self.b.sim.now() + max_bits * self.b.bit_ps;
        let rest = self.b.ph2_rest_ps(0);
        let tq = self.tq_ps();
        let f = trig.field();
        let mut seen_mark = usize::MAX;
        let mut seen_reset = self.step.reset_entries.len();
        loop {
            // count the bits processed since the last look
            let recs = self.b.recs(0);
            while self.step.cursor < recs.len() {
                let k = self.step.cursor;
                // bit k starts after the previous bit's sample point (or,
                // after a reset, about one bit before its own)
                if k >= 1 && (recs[k - 1].t + rest).max(recs[k].t.saturating_sub(self.b.bit_ps)) >= self.step.t0 {
                    let (p, c) = (recs[k - 1], recs[k]);
                    self.step.occ.note((p.field, p.pos), (c.field, c.pos, c.stuff));
                }
                self.step.cursor += 1;
            }
            let fire = if trig.at == Where::Reset {
                let e = &self.step.reset_entries;
                let hit = (seen_reset..e.len()).find(|&k| k as u32 + 1 == trig.nth);
                seen_reset = e.len();
                hit.map(|k| e[k] + trig.tq as u64 * tq)
            } else if self.b.mark(0) != seen_mark {
                seen_mark = self.b.mark(0);
                self.candidate(trig, f, rest).map(|start| start + trig.tq as u64 * tq)
            } else {
                None
            };
            if let Some(t) = fire {
                // The instant may be the clock just processed (no PH2 rest
                // beyond the RX latency, a Reset entry): the plan then starts
                // one clock late, as the Bosch bench's override does. A
                // trigger instant further back is an error.
                let next = self.b.sim.next_edge_time().unwrap_or(t);
                if t + CLOCK_PS < next {
                    return Err(format!("trigger {trig:?}: its instant {} ns has passed (now {} ns); wait for it while the plan before it plays", t / 1000, self.b.sim.now() / 1000));
                }
                let t = t.max(next);
                self.run_until_time(t - 1);
                return Ok(t);
            }
            if self.b.sim.now() >= end {
                return Err(format!(
                    "trigger {trig:?} not reached within {max_bits} bits ({} occurrences of {} in the step); IUT bits:{}",
                    self.step.occ.of(f),
                    f.name(),
                    self.b.dump(0, self.step.marks[0].max(self.b.mark(0).saturating_sub(30)))
                ));
            }
            self.tick();
        }
    }

    /// If the IUT's bit in progress is where `trig` points, its start (ps).
    fn candidate(&self, trig: Trigger, f: Field, rest: u64) -> Option<u64> {
        let nd = self.b.node(0);
        let (field, pos, stuff, runs) = (nd.field(), nd.pos(), nd.core.dbg_stuff(), nd.core.dbg_runs());
        let last = *self.b.recs(0).last()?;
        let start = last.t + rest;
        if start < self.step.t0 || !trig.matches(field, pos, stuff, runs) {
            return None;
        }
        let n = self.step.occ.of(f) + (field == f && begins_occurrence((last.field, last.pos), (field, pos, stuff))) as u32;
        (n == trig.nth).then_some(start)
    }

    /// Play `plan` from the next clock edge (the trigger instant right after
    /// [`LtBench::wait`]). Returns the index of the play in the step record.
    pub fn play(&mut self, plan: &Plan) -> usize {
        assert_eq!(plan.timing, self.timing, "a plan is made for the IUT's timing");
        let t0 = self.b.sim.next_edge_time().expect("a running bench");
        self.b.sim.get_mut(self.lt).play(t0, plan.tx_runs());
        let windows = plan.windows();
        for j in 0..self.b.bus.nodes.len() {
            let mine: Vec<(Window, bool)> = windows
                .iter()
                .filter_map(|w| match w.target {
                    Target::Bus => Some((*w, false)),
                    Target::Node(i) if i == j => {
                        assert!(i < self.b.n(), "a node disturbance targets a CAN node of the bench");
                        Some((*w, true))
                    }
                    Target::Node(_) => None,
                })
                .collect();
            let rx = self.b.bus.nodes[j].rx;
            for (c, m) in net_timeline(&mine) {
                self.b.sim.schedule_fault(rx, t0 + c * CLOCK_PS, m);
            }
        }
        self.step.plays.push(Played { t0, plan: plan.clone() });
        self.step.plays.len() - 1
    }

    /// Run until the last played plan (bits and disturbances) is over.
    pub fn run_plan(&mut self) {
        if let Some(p) = self.step.plays.last() {
            let end_w = p.plan.windows().iter().map(|w| w.end).max().unwrap_or(0);
            let end = p.t0 + p.plan.total_clocks().max(end_w) * CLOCK_PS;
            self.run_until_time(end);
        }
    }

    /// Play `plan` now and run it to its end.
    pub fn play_and_run(&mut self, plan: &Plan) -> usize {
        let k = self.play(plan);
        self.run_plan();
        k
    }
}

impl Drop for LtBench {
    fn drop(&mut self) {
        if self.step.vcd {
            self.finish_vcd();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn w(start: u64, end: u64, action: Action) -> Window {
        Window { start, end, action, target: Target::Bus }
    }

    #[test]
    fn composition_of_bus_and_node_disturbances() {
        use Action::*;
        assert_eq!(compose(Some(Force(true)), None), FaultMode::StuckRecessive);
        assert_eq!(compose(Some(Force(true)), Some(Invert)), FaultMode::StuckDominant);
        assert_eq!(compose(Some(Force(false)), Some(Force(true))), FaultMode::StuckRecessive);
        assert_eq!(compose(Some(Invert), Some(Invert)), FaultMode::None);
        // a node inversion over part of a bus force, then the force alone, then nothing
        let t = net_timeline(&[(w(10, 30, Force(false)), false), (w(20, 40, Invert), true)]);
        assert_eq!(t, vec![(10, FaultMode::StuckDominant), (20, FaultMode::StuckRecessive), (30, FaultMode::Invert), (40, FaultMode::None)]);
        // the later of two overlapping bus windows wins; adjacent equal modes merge
        let t = net_timeline(&[(w(0, 10, Force(false)), false), (w(5, 8, Force(true)), false), (w(10, 12, Force(false)), false)]);
        assert_eq!(t, vec![(0, FaultMode::StuckDominant), (5, FaultMode::StuckRecessive), (8, FaultMode::StuckDominant), (12, FaultMode::None)]);
    }
}
