//! The simulation bench of a conformance program: N controllers on a wired-AND
//! bus of the kernel, start-up, bit records, WAIT_FOR-style forcing, and the
//! run log that collects lock-step divergences and simulation effort.

use canstar_controller::view::CoreView;
use super::*;

thread_local! {
    /// Lock-step mode of the benches built on this thread.
    pub(crate) static LOCKSTEP: Cell<bool> = const { Cell::new(false) };
    /// What the benches of the current program run left behind.
    pub(crate) static RUN_LOG: RefCell<RunLog> = RefCell::new(RunLog::default());
    /// Divergences found since the last recorded step (one line each).
    pub(crate) static NEW_DIVS: RefCell<Vec<String>> = const { RefCell::new(Vec::new()) };
}

/// Build every node of the benches created on this thread from now on as a
/// [`LockstepNode`] (`true`) or a plain [`CanNode`] (`false`, the default).
pub fn set_lockstep(on: bool) {
    LOCKSTEP.with(|c| c.set(on));
}

/// Is lock-step mode on for benches built on this thread?
pub fn lockstep_mode() -> bool {
    LOCKSTEP.with(|c| c.get())
}

thread_local! {
    static ENGINE: Cell<Engine> = const { Cell::new(Engine::Compiled) };
}

/// Simulation engine of the RTL nodes of benches built on this thread from now on
/// (overrides the engine of their configurations; compiled by default).
pub fn set_engine(e: Engine) {
    ENGINE.with(|c| c.set(e));
}

/// The engine benches built on this thread use.
pub fn engine_mode() -> Engine {
    ENGINE.with(|c| c.get())
}

/// What the benches of one program run did, collected when each bench is
/// dropped: lock-step divergences and simulation effort.
#[derive(Clone, Debug, Default)]
pub struct RunLog {
    /// The first divergence of every lock-stepped node that had one.
    pub divergences: Vec<Divergence>,
    /// Benches built.
    pub benches: usize,
    /// Clock cycles (ticks) of every kernel component, summed.
    pub cycles: u64,
    /// Clock cycles of the CAN nodes only.
    pub node_cycles: u64,
    /// Simulated time, summed over the benches (ps).
    pub sim_ps: u64,
    /// Simulated nominal bit times of N1, summed over the benches.
    pub bit_times: u64,
    /// Sample points compared by the lock-step checkers.
    pub checked_bits: u64,
    /// Frames found identical by the lock-step checkers.
    pub checked_frames: u64,
    /// Diagnostic differences (can-protocol.md §19.7: labels, event words) the checkers
    /// noted, prefixed with the node name (at most 8 per node).
    pub warnings: Vec<String>,
    /// VCD files that could not be written (path and error).
    pub vcd_errors: Vec<String>,
}

fn note_vcd_error(p: &str, e: &std::io::Error) {
    RUN_LOG.with(|l| l.borrow_mut().vcd_errors.push(format!("{p}: {e}")));
}

pub(crate) fn take_run_log() -> RunLog {
    RUN_LOG.with(|l| std::mem::take(&mut *l.borrow_mut()))
}

/// A node of the bench: the RTL alone, or the RTL in lock step with its
/// golden model.
#[derive(Clone, Copy, Debug)]
pub enum NodeHandle {
    Rtl(Handle<CanNode>),
    Lockstep(Handle<LockstepNode>),
}

impl NodeHandle {
    /// The RTL node behind this handle.
    pub fn get(self, sim: &Sim) -> &CanNode {
        match self {
            NodeHandle::Rtl(h) => sim.get(h),
            NodeHandle::Lockstep(h) => &sim.get(h).node,
        }
    }
}

/// The simulation bench of one program (see the module documentation).
pub struct Bench {
    pub sim: Sim,
    pub bus: Bus,
    pub nodes: Vec<NodeHandle>,
    pub script: Option<Handle<Scripted>>,
    recs: Vec<Vec<BitRec>>,
    pending: Vec<Option<BitRec>>,
    /// Divergence of node i already reported to the current step.
    div_seen: Vec<bool>,
    seen_cycles: Vec<u64>,
    /// Nominal bit time of N1 in ps.
    pub bit_ps: u64,
    vcd: Option<String>,
}

impl Bench {
    /// N nodes with the given configurations (100 ns clocks, in phase), an
    /// optional scripted transmitter, started up as conformance-tests.md §0 says.
    pub fn new(cfgs: Vec<NodeConfig>, scripted: bool, vcd: Option<&Path>) -> Bench {
        let mut b = Self::new_unintegrated(cfgs, scripted, vcd);
        let n = b.n();
        let ok = b.run_until(40, |b| (0..n).all(|i| b.node(i).field() == Field::Idle));
        assert!(ok.is_ok(), "start-up: nodes did not integrate");
        b
    }

    /// As [`Bench::new`], but returns right after the dominant start-up
    /// pulse, while the nodes wait for bus idle.
    pub fn new_unintegrated(cfgs: Vec<NodeConfig>, scripted: bool, vcd: Option<&Path>) -> Bench {
        let clocks = vec![ClockSpec::new(CLOCK_PS); cfgs.len()];
        Self::with_clocks(cfgs, clocks, scripted, vcd)
    }

    /// Nodes on their own clocks (unintegrated, as [`Bench::new_unintegrated`]);
    /// the scripted transmitter uses N1's clock and bit length.
    pub fn with_clocks(cfgs: Vec<NodeConfig>, clocks: Vec<ClockSpec>, scripted: bool, vcd: Option<&Path>) -> Bench {
        Self::with_slots(cfgs, clocks, scripted, &[], vcd)
    }

    /// [`Bench::with_clocks`] with further bus slots named `extra`, after the
    /// nodes and the scripted transmitter: bus node `n + scripted + k` is
    /// slot `k`. Their TX nets stay undriven (recessive) until a component
    /// is bound to them with [`Sim::add`] (the ISO lower tester,
    /// `crate::iso`); with a VCD file, that component cannot be added.
    pub fn with_slots(cfgs: Vec<NodeConfig>, clocks: Vec<ClockSpec>, scripted: bool, extra: &[&str], vcd: Option<&Path>) -> Bench {
        let mut sim = Sim::new(1);
        let n = cfgs.len();
        let cfgs_brp0 = cfgs[0].timing.brp;
        let mut names: Vec<String> = (1..=n).map(|i| format!("n{i}")).collect();
        if scripted {
            names.push("script".into());
        }
        names.extend(extra.iter().map(|s| s.to_string()));
        let spec: Vec<(&str, NodeDelays)> = names.iter().map(|s| (s.as_str(), NodeDelays::default())).collect();
        let bus = Bus::build(&mut sim, "bus", &spec);
        let clock = clocks[0];
        let ntq = cfgs[0].timing.ntq();
        let bit_ps = clock.period_ps * cfgs[0].timing.brp as u64 * ntq as u64;
        let mut nodes = vec![];
        let lockstep = lockstep_mode();
        for (i, mut c) in cfgs.into_iter().enumerate() {
            c.name = names[i].clone();
            c.engine = engine_mode();
            let (rx, tx) = (bus.nodes[i].rx, bus.nodes[i].tx);
            nodes.push(if lockstep {
                NodeHandle::Lockstep(sim.add(LockstepNode::new(c, clocks[i]), &[rx], &[tx]))
            } else {
                NodeHandle::Rtl(sim.add(CanNode::new(c, clocks[i]), &[rx], &[tx]))
            });
        }
        let script = if scripted {
            Some(sim.add(Scripted::new("script", clock, ntq * cfgs_brp0), &[bus.nodes[n].rx], &[bus.nodes[n].tx]))
        } else {
            None
        };
        let mut b = Bench { sim, bus, nodes, script, recs: vec![vec![]; n], pending: vec![None; n], div_seen: vec![false; n], seen_cycles: vec![0; n], bit_ps, vcd: None };
        if let Some(p) = vcd {
            b.start_vcd(p);
        }
        // Reset, then one dominant bit on every node's RX, then integration.
        let t = b.sim.now() + (RESET_CYCLES as u64 + 2) * clocks.iter().map(|c| c.period_ps).max().unwrap_or(CLOCK_PS);
        b.run_until_time(t);
        for i in 0..n {
            b.bus.set_interference(&mut b.sim, i, FaultMode::StuckDominant);
        }
        let t = b.sim.now() + b.bit_ps;
        b.run_until_time(t);
        for i in 0..n {
            b.bus.set_interference(&mut b.sim, i, FaultMode::None);
        }
        b
    }

    pub fn n(&self) -> usize {
        self.nodes.len()
    }
    pub fn node(&self, i: usize) -> &CanNode {
        self.nodes[i].get(&self.sim)
    }
    pub fn node_mut(&mut self, i: usize) -> &mut CanNode {
        match self.nodes[i] {
            NodeHandle::Rtl(h) => self.sim.get_mut(h),
            NodeHandle::Lockstep(h) => &mut self.sim.get_mut(h).node,
        }
    }
    /// Node `i`'s lock-step checker (`None` unless the bench runs in lock step).
    pub fn lockstep(&self, i: usize) -> Option<&LockstepNode> {
        match self.nodes[i] {
            NodeHandle::Rtl(_) => None,
            NodeHandle::Lockstep(h) => Some(self.sim.get(h)),
        }
    }
    /// The divergences found so far (one at most per node).
    pub fn divergences(&self) -> Vec<Divergence> {
        (0..self.n()).filter_map(|i| self.lockstep(i).and_then(|l| l.divergence().cloned())).collect()
    }
    pub fn tec(&self, i: usize) -> u32 {
        self.node(i).tec()
    }
    pub fn rec(&self, i: usize) -> u32 {
        self.node(i).rec()
    }
    pub fn state(&self, i: usize) -> u32 {
        self.node(i).state()
    }
    /// Completed bus-off recovery runs of node `i`.
    pub fn runs(&self, i: usize) -> u32 {
        self.node(i).core.dbg_runs() as u32
    }
    /// (field, pos) of the bit node `i` has in progress.
    pub fn at(&self, i: usize) -> (Field, u32) {
        (self.node(i).field(), self.node(i).pos())
    }
    /// Set the interference of node `i` now (and leave it).
    pub fn set(&mut self, i: usize, mode: FaultMode) {
        self.bus.set_interference(&mut self.sim, i, mode);
    }
    /// All bits node `i` processed so far.
    pub fn recs(&self, i: usize) -> &[BitRec] {
        &self.recs[i]
    }
    /// Number of records of node `i` (a mark for [`Bench::since`]).
    pub fn mark(&self, i: usize) -> usize {
        self.recs[i].len()
    }
    /// Records of node `i` from mark `m` on.
    pub fn since(&self, i: usize, m: usize) -> &[BitRec] {
        &self.recs[i][m.min(self.recs[i].len())..]
    }
    /// Records of node `i` from mark `m` on that carry event `ev`.
    pub fn events(&self, i: usize, m: usize, ev: usize) -> Vec<BitRec> {
        self.since(i, m).iter().filter(|r| r.has(ev)).copied().collect()
    }
    /// Count of records with event `ev` since `m`.
    pub fn count(&self, i: usize, m: usize, ev: usize) -> usize {
        self.events(i, m, ev).len()
    }
    /// The records since `m`, one per line (for failure messages).
    pub fn dump(&self, i: usize, m: usize) -> String {
        self.since(i, m).iter().map(|r| format!("\n    {r}")).collect()
    }
    /// The records since `m` that carry any event other than SOF/bit (short form).
    pub fn dump_events(&self, i: usize, m: usize) -> String {
        self.since(i, m)
            .iter()
            .filter(|r| r.ev & !((1 << EV_BIT) | (1 << EV_RUN)) != 0)
            .map(|r| format!("\n    {r}"))
            .collect()
    }

    /// Advance the simulation by one clock edge and record processed bits.
    pub fn step(&mut self) {
        self.sim.step();
        for i in 0..self.nodes.len() {
            if let NodeHandle::Lockstep(h) = self.nodes[i] {
                if !self.div_seen[i] {
                    if let Some(d) = self.sim.get(h).divergence() {
                        self.div_seen[i] = true;
                        let m = format!("lock-step divergence at {} ns, node {}: {} DUT={} golden={} ({})", d.t_ps / 1000, d.node, d.signal, d.dut, d.golden, d.golden_label);
                        NEW_DIVS.with(|v| v.borrow_mut().push(m));
                    }
                }
            }
            let nd = self.nodes[i].get(&self.sim);
            let cy = nd.cycles();
            if cy == self.seen_cycles[i] {
                continue;
            }
            self.seen_cycles[i] = cy;
            let c = &nd.core;
            let ev = c.dbg_events() as u32;
            if (ev >> EV_BIT) & 1 == 1 {
                if let Some(mut r) = self.pending[i].take() {
                    r.ev = ev;
                    r.t = self.sim.now();
                    r.tec = nd.tec();
                    r.rec = nd.rec();
                    r.state = nd.state();
                    self.recs[i].push(r);
                }
            }
            if c.dbg_sample() {
                self.pending[i] = Some(BitRec {
                    t: 0,
                    field: Field::from_code(c.dbg_field() as u64).unwrap_or(Field::Reset),
                    pos: c.dbg_pos() as u32,
                    stuff: c.dbg_stuff(),
                    tx_role: c.dbg_role(),
                    level: c.dbg_busmon(),
                    drove: c.tx(),
                    ev: 0,
                    tec: 0,
                    rec: 0,
                    state: 0,
                });
            }
        }
    }

    /// Run until time `t` (ps).
    pub fn run_until_time(&mut self, t: u64) {
        while self.sim.next_edge_time().is_some_and(|e| e <= t) {
            self.step();
        }
    }

    /// Run for `n` nominal bit times.
    pub fn run_bits(&mut self, n: u64) {
        let t = self.sim.now() + n * self.bit_ps;
        self.run_until_time(t);
    }

    /// Run until `pred` holds (checked after every edge), at most `max_bits`
    /// bit times.
    pub fn run_until(&mut self, max_bits: u64, mut pred: impl FnMut(&Bench) -> bool) -> Result<(), String> {
        let end = self.sim.now() + max_bits * self.bit_ps;
        loop {
            if pred(self) {
                return Ok(());
            }
            if self.sim.now() >= end {
                return Err(format!("condition not reached within {max_bits} bits"));
            }
            self.step();
        }
    }

    /// Run until every node is in Bus_Idle (and the script is done).
    pub fn run_idle(&mut self, max_bits: u64) -> Result<(), String> {
        let n = self.n();
        let sc = self.script;
        self.run_until(max_bits, |b| (0..n).all(|i| b.node(i).field() == Field::Idle) && sc.is_none_or(|h| !b.sim.get(h).busy()))
            .map_err(|e| format!("bus idle: {e}"))
    }

    /// Run until node `i` has processed the bit before (field, pos, stuff):
    /// its debug bundle then shows the target as the bit in progress. If
    /// called no later than the forcing instant of the last processed bit
    /// (e.g. right after a forcing window), that bit counts.
    pub fn wait_for(&mut self, i: usize, field: Field, pos: u32, stuff: bool, max_bits: u64) -> Result<(), String> {
        let m0 = self.mark(i);
        let mut m = m0;
        // Right at the clock that carries a bit's events, the target may
        // already be the bit in progress.
        let rest = self.ph2_rest_ps(i);
        let nd = self.node(i);
        let period = nd.bit_time_ps() / (nd.config().timing.ntq() as u64 * nd.config().timing.brp as u64);
        if self.recs[i].last().is_some_and(|r| self.sim.now() <= r.t + rest + period) {
            m = usize::MAX;
        }
        let end = self.sim.now() + max_bits * self.bit_ps;
        loop {
            if self.mark(i) != m {
                m = self.mark(i);
                let nd = self.node(i);
                if nd.field() == field && nd.pos() == pos && nd.core.dbg_stuff() == stuff {
                    return Ok(());
                }
            }
            if self.sim.now() >= end {
                return Err(format!(
                    "N{} never reached {}{}{} within {max_bits} bits; bits seen:{}",
                    i + 1,
                    field.name(),
                    pos,
                    if stuff { " (stuff)" } else { "" },
                    self.dump(i, m0.max(self.mark(i).saturating_sub(40)))
                ));
            }
            self.step();
        }
    }

    /// Time from the clock that carries a bit's events to the end of its PH2
    /// as the node perceives it: the node reads the bus `L_rx` clocks late
    /// (RX synchroniser and bit timing input stage, can-protocol.md §1.5), so an override
    /// set `L_rx − 1` clocks before its TX edge of the next bit is first
    /// read in that bit's SYNC_SEG, as in the manual's WAIT_FOR (see the
    /// module documentation). Never earlier than now.
    pub fn ph2_rest_ps(&self, i: usize) -> u64 {
        let nd = self.node(i);
        let c = nd.config();
        let period = nd.bit_time_ps() / (c.timing.ntq() as u64 * c.timing.brp as u64);
        let l_rx = canstar_controller::core::CanCore::l_rx(c.sync_depth) as u64;
        (c.timing.ph2 as u64 * c.timing.brp as u64).saturating_sub(l_rx) * period
    }

    /// Set the interference of `nodes` for `k` nominal bit times from now,
    /// then back to none.
    pub fn force_now(&mut self, nodes: &[usize], mode: FaultMode, k: u64) {
        for &i in nodes {
            self.bus.set_interference(&mut self.sim, i, mode);
        }
        let t = self.sim.now() + k * self.bit_ps;
        self.run_until_time(t);
        for &i in nodes {
            self.bus.set_interference(&mut self.sim, i, FaultMode::None);
        }
    }

    /// WAIT_FOR (field, pos, stuff) at `nodes[0]`, then force `nodes` for `k`
    /// bits, and run until `nodes[0]` has processed the k forced bits. Returns the mark of `nodes[0]` at the first forced bit (its
    /// record is `since(nodes[0], mark)[0]`).
    pub fn force_at(&mut self, nodes: &[usize], field: Field, pos: u32, stuff: bool, mode: FaultMode, k: u64) -> Result<usize, String> {
        let i = nodes[0];
        self.wait_for(i, field, pos, stuff, 3000)?;
        let t = self.recs[i].last().map_or(0, |r| r.t) + self.ph2_rest_ps(i);
        self.run_until_time(t);
        let m = self.mark(i);
        self.force_now(nodes, mode, k);
        // The last forced bit is sampled after the window closes (RX latency).
        self.run_until(2, |b| b.mark(i) >= m + k as usize)?;
        Ok(m)
    }

    /// The record of node `i` at mark `m` (the first bit processed after it).
    pub fn rec_at(&self, i: usize, m: usize) -> Result<BitRec, String> {
        self.recs[i].get(m).copied().ok_or_else(|| "no bit recorded".to_string())
    }

    /// Start writing the VCD file `p` now (for a bench whose extra components
    /// are added after construction); it is finished with the bench, and an
    /// error goes to the run log as for a VCD given at construction.
    pub fn start_vcd(&mut self, p: &Path) {
        self.finish();
        match self.sim.start_vcd_file(p, None) {
            Ok(()) => self.vcd = Some(p.display().to_string()),
            Err(e) => note_vcd_error(&p.display().to_string(), &e),
        }
    }

    /// A VCD file is being written.
    pub fn writes_vcd(&self) -> bool {
        self.vcd.is_some()
    }

    /// Finish the VCD file (if one is being written).
    pub fn finish(&mut self) {
        if let Some(p) = self.vcd.take() {
            if let Err(e) = self.sim.finish_vcd() {
                note_vcd_error(&p, &e);
            }
        }
    }
}

impl Drop for Bench {
    fn drop(&mut self) {
        self.finish();
        let divs = self.divergences();
        let mut node_cycles = 0;
        let (mut bits, mut frames) = (0, 0);
        let mut warnings = vec![];
        for i in 0..self.n() {
            node_cycles += self.node(i).cycles();
            if let Some(l) = self.lockstep(i) {
                bits += l.stats().bits;
                frames += l.stats().frames;
                warnings.extend(l.warnings().iter().map(|w| format!("N{}: {w}", i + 1)));
            }
        }
        let (cycles, now, bit_ps) = (self.sim.total_cycles(), self.sim.now(), self.bit_ps);
        RUN_LOG.with(|l| {
            let mut l = l.borrow_mut();
            l.divergences.extend(divs);
            l.benches += 1;
            l.cycles += cycles;
            l.node_cycles += node_cycles;
            l.sim_ps += now;
            l.bit_times += now / bit_ps.max(1);
            l.checked_bits += bits;
            l.checked_frames += frames;
            l.warnings.extend(warnings);
        });
    }
}

/// Which counter of N1 a step checks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ctr {
    Tec,
    Rec,
}

impl Bench {
    pub fn ctr(&self, i: usize, c: Ctr) -> u32 {
        match c {
            Ctr::Tec => self.tec(i),
            Ctr::Rec => self.rec(i),
        }
    }

    /// Run until node `i` has finished its flags (and the dominant bits after
    /// them): it is at Error/Overload_Delimiter 2 or later, Intermission,
    /// Suspend_Transmission or Bus_Idle.
    pub fn settle(&mut self, i: usize) -> Result<(), String> {
        self.run_until(80, |b| {
            let (f, p) = b.at(i);
            matches!(f, Field::Inter | Field::Idle | Field::Suspend) || (matches!(f, Field::ErrDel | Field::OvlDel) && p >= 2)
        })
        .map_err(|e| format!("N{} did not reach a delimiter: {e}", i + 1))
    }

    /// WAIT_FOR the target at `nodes[0]`, force `nodes` for `k` bits and
    /// check that the first forced bit of `nodes[0]` carries every event of
    /// `want`. Returns the mark of the first forced bit.
    pub fn forced_bit(&mut self, nodes: &[usize], field: Field, pos: u32, mode: FaultMode, k: u64, want: &[usize]) -> Result<usize, String> {
        let i = nodes[0];
        let m = self.force_at(nodes, field, pos, false, mode, k)?;
        let r = self.rec_at(i, m)?;
        ensure!(r.field == field && r.pos == pos, "forced bit recorded as {r}");
        let names = ["SOF", "ARB_LOST", "BIT_ERR", "STUFF_ERR", "CRC_ERR", "FORM_ERR", "ACK_ERR", "AEF", "PEF", "OLF", "OVL", "DAF"];
        for &e in want {
            ensure!(r.has(e), "forced bit {r}: expected {}", names.get(e).unwrap_or(&"?"));
        }
        Ok(m)
    }

    /// One forcing step: WAIT_FOR the target at `nodes[0]`, force `nodes`
    /// for `k` bits, check that the first forced bit of `nodes[0]` carries
    /// every event of `want`, settle, and check the change of `nodes[0]`'s
    /// counter. Returns the mark of the first forced bit.
    #[allow(clippy::too_many_arguments)]
    pub fn forced_step(&mut self, nodes: &[usize], field: Field, pos: u32, mode: FaultMode, k: u64, want: &[usize], ctr: Ctr, delta: i64) -> Result<usize, String> {
        let i = nodes[0];
        let c0 = self.ctr(i, ctr) as i64;
        let m = self.forced_bit(nodes, field, pos, mode, k, want)?;
        self.settle(i)?;
        let c1 = self.ctr(i, ctr) as i64;
        ensure!(c1 - c0 == delta, "{ctr:?} {c0}→{c1}, expected Δ {delta:+}:{}", self.dump_events(i, m));
        Ok(m)
    }
}
