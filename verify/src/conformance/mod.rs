//! The Bosch conformance programs of `conformance-tests.md` on the
//! multi-node cycle simulation.
//!
//! Every program is library code: [`run_program`] runs one program on a
//! fresh [`Bench`] (N [`CanNode`]s, the RTL controller with its bit timing,
//! on a wired-AND [`Bus`] of the kernel) and returns one [`StepResult`] per
//! step of the plan, named `<program>_<part>_<step>` as the plan names them.
//! The cargo tests in `sim/tests/conformance_*.rs` and the
//! `canstar conformance` subcommand ([`run_cli`]) both use it.
//!
//! # The bench
//!
//! - Node `i` of the plan (N1 = index 0) is a [`CanNode`], clock 100 ns,
//!   BRP 1, timing T10/6/4 unless the program says otherwise. An optional
//!   scripted transmitter ([`Scripted`], the plan's "test-only transmitter")
//!   is one more bus participant that drives a precomputed stuffed bit
//!   sequence from the controller's frame builder
//!   ([`canstar_controller::frame::bus_bits`] with [`BuildOptions`]).
//! - Start-up (§0): the nodes hold their controllers in reset, then every
//!   node's RX reads one dominant bit (interference stuck-dominant), then the
//!   nodes integrate; the bench waits until every node is in Bus_Idle.
//! - Records: every bit a node processes becomes a [`BitRec`] (field,
//!   position, stuff flag, role and levels of the bit as sampled, the
//!   `EV_*` event word and the counters after it), read from the RTL debug
//!   bundle: on the clock with `dbg_sample` the bundle describes the bit
//!   being sampled; on the next clock `dbg_events` carries its events.
//! - Forcing ([`Bench::force_at`]): like the manual's WAIT_FOR, the bench
//!   runs until the forced node has processed the bit *before* the target
//!   (its `field()`/`pos()`/`dbg_stuff` then show the target bit), waits for
//!   the end of that bit's PH2 and sets the receive-path interference of the
//!   forced node(s) for k nominal bit times, then sets it back to none.
//!
//! # Programs and deviations
//!
//! Implemented: all 13 programs, every step of the plan: baudrate,
//! biterror, btl (cases a–f, three timings), crc, dlc, emlcount (rx_1..20,
//! tx_1..37), extd_id, formerr, idle, overload, stuffbit, stufferr, txarb.
//! Not yet: nothing of the plan's step list. Where a
//! step's frame condition cannot be met by a legal frame the program says
//! so at the step (txarb_12, stufferr_5) and uses the
//! nearest legal frame. biterror resets N1 between its receiver and
//! transmitter parts. Frames with a recessive r0/r1 or a dominant SRR come
//! from the scripted transmitter, a bus participant besides N2.
//!
//! # Lock-step mode
//!
//! With [`RunOptions::lockstep`] (or [`set_lockstep`] before building a
//! bench) every node of the bench is a [`LockstepNode`]: the RTL plus its
//! own golden model (P§19), fed with the node's receive stream *after* its
//! interference, so both see the same disturbed bits. The programs run
//! unchanged (they see the RTL through [`Bench::node`]). A divergence fails
//! the step during which it was found (the plan's pass criterion: no
//! lock-step mismatch during the program); the divergences of all benches
//! of a run, with the checkers' §19.7 warnings, are collected in the
//! [`RunLog`] of [`run_program_with`] and printed by
//! `canstar conformance --lockstep`.
//! Nodes 2..N are checked too, and the scripted transmitter has no model.
//!
//! # Timing of a stimulus
//!
//! The node reads the bus `L_rx` clocks late (`CanCore::l_rx`: synchroniser
//! and bit-timing input stage). Its TX edge of the target bit comes on the
//! tick that ends the previous bit, and that tick still reads the level of
//! `L_rx` clocks before, in the previous bit's last TQ. The override is
//! therefore set `L_rx − 1` clocks before the node's TX edge of the target
//! bit, so that the node first reads it in the target bit's SYNC_SEG, as
//! the manual's WAIT_FOR does (never earlier than the clock that carries the
//! previous bit's events: with T10/8/1 the override starts 1 clock late).
//! The btl cases b–f check this alignment to the TQ: they place edges at
//! `WAIT_FOR instant + j TQ` and assert the resulting sample points.
//! (Until the btl cases existed the override was set one clock earlier,
//! in the previous bit's last TQ; no step's outcome depended on it.)
#![allow(clippy::redundant_closure_call)]

use canstar_sim::bus::{Bus, NodeDelays};
use canstar_sim::{ClockSpec, Component, Handle, Io, Sim};
use crate::lockstep::{Divergence, LockstepNode};
use canstar_sim::net::FaultMode;
use crate::node::{CanNode, NodeConfig, RESET_CYCLES};
use std::cell::{Cell, RefCell};
use canstar_controller::frame::{bus_bits, BuildOptions, BusBit, Frame};
use canstar_controller::fsm::*;
use std::path::{Path, PathBuf};

pub mod baudrate;
pub mod biterror;
pub mod btl;
pub mod crc;
pub mod dlc;
pub mod emlcount;
pub mod extd_id;
pub mod formerr;
pub mod idle;
pub mod overload;
pub mod stuffbit;
pub mod stufferr;
pub mod txarb;

/// Clock period of the default configuration (100 ns).
pub const CLOCK_PS: u64 = 100_000;

/// Outcome of one step of a program.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StepResult {
    /// `<program>_<part>_<step>`, e.g. `biterror_tx_12`.
    pub name: String,
    pub pass: bool,
    /// Empty on success; what differed otherwise.
    pub msg: String,
}

/// One program of the suite.
pub struct Program {
    pub name: &'static str,
    /// Runs the program; `vcd` names a VCD file to write.
    pub run: fn(&mut Ctx),
}

/// All programs, in plan order.
pub fn programs() -> Vec<Program> {
    vec![
        Program { name: "baudrate", run: baudrate::run },
        Program { name: "biterror", run: biterror::run },
        Program { name: "btl", run: btl::run },
        Program { name: "crc", run: crc::run },
        Program { name: "dlc", run: dlc::run },
        Program { name: "emlcount", run: emlcount::run },
        Program { name: "extd_id", run: extd_id::run },
        Program { name: "formerr", run: formerr::run },
        Program { name: "idle", run: idle::run },
        Program { name: "overload", run: overload::run },
        Program { name: "stuffbit", run: stuffbit::run },
        Program { name: "stufferr", run: stufferr::run },
        Program { name: "txarb", run: txarb::run },
    ]
}

/// Step collector of one program run.
pub struct Ctx {
    pub program: String,
    pub vcd: Option<PathBuf>,
    pub results: Vec<StepResult>,
}

impl Ctx {
    /// Record the outcome of step `name`. In lock-step mode a divergence
    /// found while the step ran fails it (P§19.9).
    pub fn record(&mut self, name: &str, r: Result<(), String>) {
        let divs = NEW_DIVS.with(|d| std::mem::take(&mut *d.borrow_mut()));
        let (mut pass, mut msg) = match r {
            Ok(()) => (true, String::new()),
            Err(m) => (false, m),
        };
        if !divs.is_empty() {
            pass = false;
            if !msg.is_empty() {
                msg.push_str("; ");
            }
            msg.push_str(&divs.join("; "));
        }
        self.results.push(StepResult { name: name.to_string(), pass, msg });
    }

    /// A bench for this program (writes a VCD if asked for).
    pub fn bench(&self, cfgs: Vec<NodeConfig>, scripted: bool) -> Bench {
        let vcd = self.vcd.as_ref().map(|d| d.join(format!("{}.vcd", self.program)));
        Bench::new(cfgs, scripted, vcd.as_deref())
    }
}

/// Options of a program run.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// Write the VCD files of the program into this directory.
    pub vcd_dir: Option<PathBuf>,
    /// Run every node of every bench in lock step with its own golden model.
    pub lockstep: bool,
}

/// Everything one program run produced.
#[derive(Clone, Debug)]
pub struct ProgramRun {
    pub results: Vec<StepResult>,
    /// Divergences and simulation effort of the program's benches.
    pub log: RunLog,
    /// Wall-clock time of the run.
    pub wall: std::time::Duration,
}

/// Run program `name`; `None` if there is no such program.
pub fn run_program(name: &str, vcd_dir: Option<&Path>) -> Option<Vec<StepResult>> {
    run_program_with(name, &RunOptions { vcd_dir: vcd_dir.map(|d| d.to_path_buf()), lockstep: false }).map(|r| r.results)
}

/// Run program `name` with `opts`; `None` if there is no such program.
/// With `opts.lockstep` every node of the program's benches is a
/// [`LockstepNode`]; the divergences are in the returned [`RunLog`], and the
/// step during which one was found fails with it (see [`Ctx::record`]).
pub fn run_program_with(name: &str, opts: &RunOptions) -> Option<ProgramRun> {
    let p = programs().into_iter().find(|p| p.name == name)?;
    let mut ctx = Ctx { program: name.to_string(), vcd: opts.vcd_dir.clone(), results: vec![] };
    let run = p.run;
    let was = lockstep_mode();
    set_lockstep(opts.lockstep);
    let _ = take_run_log();
    NEW_DIVS.with(|d| d.borrow_mut().clear());
    let t0 = std::time::Instant::now();
    let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| run(&mut ctx)));
    let wall = t0.elapsed();
    set_lockstep(was);
    if let Err(e) = r {
        let m = e.downcast_ref::<String>().cloned().or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string())).unwrap_or_default();
        ctx.results.push(StepResult { name: format!("{name}_panic"), pass: false, msg: m });
    }
    Some(ProgramRun { results: ctx.results, log: take_run_log(), wall })
}

/// The `canstar conformance` command: runs `program` (or all), prints one
/// line per program and a final `N passed, M failed` line counting steps,
/// and returns (passed, failed). Failed steps are listed with their message.
pub fn run_cli(program: Option<&str>, vcd_dir: Option<&Path>, out: &mut dyn std::io::Write) -> std::io::Result<(usize, usize)> {
    run_cli_with(program, vcd_dir, false, out).map(|(p, f, _)| (p, f))
}

/// [`run_cli`] with lock-step mode: with `lockstep` every divergence is
/// printed after its program's line and the final line reads
/// `N passed, M failed, K divergences`. Before the final line a summary gives
/// the simulation effort (clock cycles, simulated bit times, wall time and
/// the rates). Returns (passed, failed, divergences).
pub fn run_cli_with(program: Option<&str>, vcd_dir: Option<&Path>, lockstep: bool, out: &mut dyn std::io::Write) -> std::io::Result<(usize, usize, usize)> {
    let names: Vec<&'static str> = programs().iter().map(|p| p.name).collect();
    let chosen: Vec<&str> = match program {
        Some(p) => {
            if !names.contains(&p) {
                writeln!(out, "unknown program {p}; programs: {}", names.join(", "))?;
                writeln!(out, "0 passed, 1 failed")?;
                return Ok((0, 1, 0));
            }
            vec![p]
        }
        None => names.clone(),
    };
    if let Some(d) = vcd_dir {
        std::fs::create_dir_all(d)?;
    }
    let opts = RunOptions { vcd_dir: vcd_dir.map(|d| d.to_path_buf()), lockstep };
    let (mut tp, mut tf, mut td) = (0, 0, 0);
    let mut total = RunLog::default();
    let mut wall = std::time::Duration::ZERO;
    for p in chosen {
        let run = run_program_with(p, &opts).expect("program exists");
        let res = &run.results;
        let pass = res.iter().filter(|r| r.pass).count();
        let fail = res.len() - pass;
        tp += pass;
        tf += fail;
        let nd = run.log.divergences.len();
        td += nd;
        let ls = if lockstep {
            format!(", {nd} divergences, {} bits and {} frames checked, {} warnings", run.log.checked_bits, run.log.checked_frames, run.log.warnings.len())
        } else {
            String::new()
        };
        writeln!(out, "{p:<9} {:>3} steps, {pass:>3} passed, {fail:>3} failed{ls} ({:.1} s)", res.len(), run.wall.as_secs_f64())?;
        for r in res.iter().filter(|r| !r.pass) {
            writeln!(out, "  FAIL {}: {}", r.name, r.msg)?;
        }
        for d in &run.log.divergences {
            for l in format!("{d}").lines() {
                writeln!(out, "  {l}")?;
            }
        }
        for w in &run.log.warnings {
            writeln!(out, "  warning {w}")?;
        }
        wall += run.wall;
        total.cycles += run.log.cycles;
        total.node_cycles += run.log.node_cycles;
        total.sim_ps += run.log.sim_ps;
        total.bit_times += run.log.bit_times;
        total.checked_bits += run.log.checked_bits;
    }
    let w = wall.as_secs_f64().max(1e-9);
    writeln!(
        out,
        "simulated {:.3} ms ({} bit times), {} node clock cycles ({} component ticks) in {:.2} s wall: {:.0} node cycles/s, {:.0} bit times/s",
        total.sim_ps as f64 / 1e9,
        total.bit_times,
        total.node_cycles,
        total.cycles,
        w,
        total.node_cycles as f64 / w,
        total.bit_times as f64 / w
    )?;
    if lockstep {
        writeln!(out, "{tp} passed, {tf} failed, {td} divergences")?;
    } else {
        writeln!(out, "{tp} passed, {tf} failed")?;
    }
    Ok((tp, tf, td))
}

/// Assert inside a step: returns `Err(message)` from the enclosing function.
macro_rules! ensure {
    ($c:expr, $($m:tt)+) => {
        if !$c {
            return Err(format!($($m)+));
        }
    };
}
pub(crate) use ensure;

/// One bit as processed by a node.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BitRec {
    /// Time of the clock that carried the events (ps).
    pub t: u64,
    pub field: Field,
    pub pos: u32,
    pub stuff: bool,
    /// Transmitter role.
    pub tx_role: bool,
    /// Sampled level (true = recessive).
    pub level: bool,
    /// Level the node drove.
    pub drove: bool,
    /// `EV_*` event word.
    pub ev: u32,
    pub tec: u32,
    pub rec: u32,
    pub state: u32,
}

impl BitRec {
    pub fn has(&self, ev: usize) -> bool {
        (self.ev >> ev) & 1 == 1
    }
    /// Event names as in the §18 trace.
    pub fn events(&self) -> String {
        let names = [
            (EV_SOF, "SOF"),
            (EV_ARB_LOST, "ARB_LOST"),
            (EV_BIT_ERR, "BIT_ERR"),
            (EV_STUFF_ERR, "STUFF_ERR"),
            (EV_CRC_ERR, "CRC_ERR"),
            (EV_FORM_ERR, "FORM_ERR"),
            (EV_ACK_ERR, "ACK_ERR"),
            (EV_AEF, "AEF"),
            (EV_PEF, "PEF"),
            (EV_OLF, "OLF"),
            (EV_OVL, "OVL"),
            (EV_DAF, "DAF"),
            (EV_TX_OK, "TX_OK"),
            (EV_RX_OK, "RX_OK"),
            (EV_EXC1, "EXC1"),
            (EV_EXC2, "EXC2"),
            (EV_RUN, "RUN"),
            (EV_RECOVERED, "RECOVERED"),
            (EV_INTEGRATED, "INTEGRATED"),
        ];
        let v: Vec<&str> = names.iter().filter(|(b, _)| self.has(*b)).map(|(_, n)| *n).collect();
        v.join(",")
    }
}

impl std::fmt::Display for BitRec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{:>9} ns {}{} {}{} smp {} drv {} tec {} rec {} st {} [{}]",
            self.t / 1000,
            if self.field.has_role() { if self.tx_role { "Tx_" } else { "Rx_" } } else { "" },
            self.field.name(),
            self.pos,
            if self.stuff { "S" } else { "" },
            self.level as u8,
            self.drove as u8,
            self.tec,
            self.rec,
            self.state,
            self.events()
        )
    }
}

/// The plan's test-only transmitter: drives a precomputed bit sequence, one
/// level per `ntq` clocks, no synchronisation. It reads the bus (input 0)
/// only to start in step with another node's SOF ([`Scripted::send_with`]).
pub struct Scripted {
    name: String,
    clock: ClockSpec,
    ntq: u32,
    bits: Vec<bool>,
    idx: usize,
    cnt: u32,
    active: bool,
    wait_sof: bool,
    level: bool,
}

impl Scripted {
    pub fn new(name: &str, clock: ClockSpec, ntq: u32) -> Self {
        Scripted { name: name.to_string(), clock, ntq, bits: vec![], idx: 0, cnt: 0, active: false, wait_sof: false, level: true }
    }
    /// Start sending `bits` at the next clock.
    pub fn send(&mut self, bits: Vec<bool>) {
        self.bits = bits;
        self.idx = 0;
        self.cnt = 0;
        self.active = true;
        self.wait_sof = false;
    }
    /// Start sending `bits` when the bus goes dominant (another node's SOF).
    pub fn send_with(&mut self, bits: Vec<bool>) {
        self.send(bits);
        self.active = false;
        self.wait_sof = true;
    }
    /// Still sending (or waiting to)?
    pub fn busy(&self) -> bool {
        self.active || self.wait_sof
    }
}

impl Component for Scripted {
    fn name(&self) -> &str {
        &self.name
    }
    fn clock(&self) -> ClockSpec {
        self.clock
    }
    fn tick(&mut self, io: &mut Io<'_>) {
        if self.wait_sof && !io.input(0) {
            self.wait_sof = false;
            self.active = true;
            // The bus went dominant one clock ago: this SOF is one clock short.
            self.cnt = 1;
        }
        if self.active {
            self.level = self.bits[self.idx];
            self.cnt += 1;
            if self.cnt >= self.ntq {
                self.cnt = 0;
                self.idx += 1;
                if self.idx >= self.bits.len() {
                    self.active = false;
                }
            }
        } else {
            self.level = true;
        }
        io.set_output(0, self.level);
    }
}

/// Levels of frame `f` as a scripted transmitter sends it (ACK slot
/// recessive, up to the last EOF bit), with test-only options.
pub fn script_bits(f: &Frame, o: BuildOptions) -> Vec<bool> {
    bus_bits(f, o, false).iter().map(|b| b.level).collect()
}

/// The bus bit of frame `f` at (field, pos, stuff), if it exists.
pub fn frame_bit(f: &Frame, o: BuildOptions, field: Field, pos: u32, stuff: bool) -> Option<BusBit> {
    bus_bits(f, o, false).into_iter().find(|b| b.field == field && b.pos as u32 == pos && b.stuff == stuff)
}

/// Level of frame `f`'s bit at (field, pos, stuff) (true = recessive).
pub fn level_of(f: &Frame, field: Field, pos: u32, stuff: bool) -> Option<bool> {
    frame_bit(f, BuildOptions::default(), field, pos, stuff).map(|b| b.level)
}

/// The first frame of a deterministic family (extended or not, remote or
/// not) whose bus bits satisfy `pred`.
pub fn choose(ide: bool, rtr: bool, pred: impl Fn(&Frame) -> bool) -> Frame {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    let pats = [0x00u8, 0xFF, 0x0F, 0xF0, 0x1F, 0xF8, 0x83, 0x7C, 0x3E, 0xC1, 0x07, 0xE0];
    for _ in 0..400_000 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        let id = if ide { (x >> 20) as u32 & 0x1FFF_FFFF } else { (x >> 20) as u32 & 0x7FF };
        let dlc = if (x >> 60) == 0 { 9 + ((x >> 56) % 7) as u8 } else { ((x >> 52) % 9) as u8 };
        let data: Vec<u8> = (0..dlc as usize)
            .map(|i| if (x >> (i + 8)) & 1 == 0 { pats[((x >> (2 * i)) % 12) as usize] } else { (x >> (5 * i + 3)) as u8 })
            .collect();
        let f = if rtr { Frame::remote(ide, id, dlc) } else { Frame::data(ide, id, dlc, &data) };
        if pred(&f) {
            return f;
        }
    }
    panic!("no frame meets the step's condition");
}

thread_local! {
    /// Lock-step mode of the benches built on this thread.
    static LOCKSTEP: Cell<bool> = const { Cell::new(false) };
    /// What the benches of the current program run left behind.
    static RUN_LOG: RefCell<RunLog> = RefCell::new(RunLog::default());
    /// Divergences found since the last recorded step (one line each).
    static NEW_DIVS: RefCell<Vec<String>> = const { RefCell::new(Vec::new()) };
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
    /// Diagnostic differences (§19.7: labels, event words) the checkers
    /// noted, prefixed with the node name (at most 8 per node).
    pub warnings: Vec<String>,
}

fn take_run_log() -> RunLog {
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
    vcd: bool,
}

impl Bench {
    /// N nodes with the given configurations (100 ns clocks, in phase), an
    /// optional scripted transmitter, started up as §0 says.
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
        let mut sim = Sim::new(1);
        let n = cfgs.len();
        let cfgs_brp0 = cfgs[0].timing.brp;
        let mut names: Vec<String> = (1..=n).map(|i| format!("n{i}")).collect();
        if scripted {
            names.push("script".into());
        }
        let spec: Vec<(&str, NodeDelays)> = names.iter().map(|s| (s.as_str(), NodeDelays::default())).collect();
        let bus = Bus::build(&mut sim, "bus", &spec);
        let clock = clocks[0];
        let ntq = cfgs[0].timing.ntq();
        let bit_ps = clock.period_ps * cfgs[0].timing.brp as u64 * ntq as u64;
        let mut nodes = vec![];
        let lockstep = lockstep_mode();
        for (i, mut c) in cfgs.into_iter().enumerate() {
            c.name = names[i].clone();
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
        let mut vcd_on = false;
        if let Some(p) = vcd {
            if sim.start_vcd_file(p, None).is_ok() {
                vcd_on = true;
            }
        }
        let mut b = Bench { sim, bus, nodes, script, recs: vec![vec![]; n], pending: vec![None; n], div_seen: vec![false; n], seen_cycles: vec![0; n], bit_ps, vcd: vcd_on };
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
        self.node(i).core.dbg_runs.val().index() as u32
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
            let ev = c.dbg_events.val().index() as u32;
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
            if c.dbg_sample.val() {
                self.pending[i] = Some(BitRec {
                    t: 0,
                    field: Field::from_code(c.dbg_field.val().index() as u64).unwrap_or(Field::Reset),
                    pos: c.dbg_pos.val().index() as u32,
                    stuff: c.dbg_stuff.val(),
                    tx_role: c.dbg_role.val(),
                    level: c.dbg_busmon.val(),
                    drove: c.tx.val(),
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
                if nd.field() == field && nd.pos() == pos && nd.core.dbg_stuff.val() == stuff {
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
    /// (RX synchroniser and bit timing input stage, §1.5), so an override
    /// set `L_rx − 1` clocks before its TX edge of the next bit is first
    /// read in that bit's SYNC_SEG, as in the manual's WAIT_FOR (see the
    /// module documentation). Never earlier than now.
    pub fn ph2_rest_ps(&self, i: usize) -> u64 {
        let nd = self.node(i);
        let c = nd.config();
        let period = nd.bit_time_ps() / (c.timing.ntq() as u64 * c.timing.brp as u64);
        let l_rx = canstar_controller::core::CanCore::l_rx(c.sync_depth) as u64;
        (c.timing.ph2() as u64 * c.timing.brp as u64).saturating_sub(l_rx) * period
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

    /// Finish the VCD file (if one is being written).
    pub fn finish(&mut self) {
        if self.vcd {
            let _ = self.sim.finish_vcd();
            self.vcd = false;
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

/// Standard configuration of node `name` (T10/6/4, BRP 1).
pub fn cfg() -> NodeConfig {
    NodeConfig::named("n")
}

/// Timing T10/8/1 (PROP 5, PH1 2, PH2 2, SJW 1), BRP 1.
pub fn cfg_t10_8_1() -> NodeConfig {
    NodeConfig::named("n").timing(1, 5, 2, 1)
}

/// Check that the frames delivered at node `i` since count `from` are `want`.
pub fn check_delivered(b: &Bench, i: usize, from: usize, want: &[Frame]) -> Result<(), String> {
    let got = b.node(i).received();
    let got = &got[from.min(got.len())..];
    ensure!(got == want, "N{} delivered {:?}, expected {:?}", i + 1, got, want);
    Ok(())
}

/// Panic unless step `name` ran and passed (used by the cargo tests).
pub fn assert_step(results: &[StepResult], name: &str) {
    match results.iter().find(|r| r.name == name) {
        None => panic!("step {name} did not run; results: {:?}", results.iter().map(|r| (&r.name, r.pass)).collect::<Vec<_>>()),
        Some(r) => assert!(r.pass, "{name} failed: {}", r.msg),
    }
}

/// Generates one `#[test]` per step of a program (the program runs once per
/// test binary), plus a test that the list covers every step that ran.
///
/// ```ignore
/// canstar_sim::conformance_tests!("txarb"; txarb_1, #[ignore = "RTL bug: ..."] txarb_2);
/// ```
#[macro_export]
macro_rules! conformance_tests {
    ($prog:literal; $( $(#[$m:meta])* $name:ident ),* $(,)?) => {
        fn program_results() -> &'static [$crate::conformance::StepResult] {
            static R: std::sync::OnceLock<Vec<$crate::conformance::StepResult>> = std::sync::OnceLock::new();
            R.get_or_init(|| $crate::conformance::run_program($prog, None).expect("no such program"))
        }
        $( $(#[$m])* #[test] fn $name() { $crate::conformance::assert_step(program_results(), stringify!($name)); } )*
        #[test]
        fn every_step_has_a_test() {
            let listed: Vec<&str> = vec![$( stringify!($name) ),*];
            let ran: Vec<&str> = program_results().iter().map(|r| r.name.as_str()).collect();
            assert_eq!(ran, listed, "steps run vs tests listed");
        }
    };
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
