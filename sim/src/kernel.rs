//! Components, their ports and the scheduler ([`Sim`]). Clocks are in
//! [`crate::clock`], the adapters from rust-hdl blocks and closures in
//! [`crate::component`].

use std::any::Any;
use std::cmp::Reverse;
use std::collections::{BinaryHeap, VecDeque};
use std::io::Write;
use std::marker::PhantomData;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rust_hdl::prelude::Probe;

use crate::clock::ClockSpec;

use crate::net::{FaultMode, NetId, Nets, Node};
use crate::vcd::{VcdState, VcdView};

/// Ports of a component during one tick: read inputs, write outputs.
///
/// `input(i)` is the level of the `i`-th input net just before the current
/// edge; `set_output(i, v)` changes the `i`-th output net at the current edge.
pub struct Io<'a> {
    pub(crate) now: u64,
    pub(crate) nets: &'a mut Nets,
    pub(crate) inputs: &'a [NetId],
    pub(crate) outputs: &'a [NetId],
}

impl<'a> Io<'a> {
    /// Time of the current edge in ps.
    #[inline]
    pub fn now(&self) -> u64 {
        self.now
    }
    #[inline]
    pub fn n_inputs(&self) -> usize {
        self.inputs.len()
    }
    #[inline]
    pub fn n_outputs(&self) -> usize {
        self.outputs.len()
    }
    /// Level of input `i` sampled just before the current edge.
    #[inline]
    pub fn input(&self, i: usize) -> bool {
        self.nets.before(self.inputs[i], self.now)
    }
    /// Drive output `i` to `v` from the current edge on.
    #[inline]
    pub fn set_output(&mut self, i: usize, v: bool) {
        self.nets.write(self.outputs[i], self.now, v);
    }
    /// A view on a subset of the ports (for wrapper components).
    pub fn sub<'b>(&'b mut self, inputs: std::ops::Range<usize>, outputs: std::ops::Range<usize>) -> Io<'b> {
        Io { now: self.now, nets: self.nets, inputs: &self.inputs[inputs], outputs: &self.outputs[outputs] }
    }
}

/// A clocked participant of a simulation (CAN node, hub, tester, ...).
///
/// On each of its rising clock edges the kernel calls [`Component::tick`];
/// the component reads its input nets and writes its output nets through
/// [`Io`]. Which nets those are is decided when it is added
/// ([`Sim::add`]).
pub trait Component: Any {
    /// Instance name (VCD scope name; unique names are recommended).
    fn name(&self) -> &str;
    /// The component's clock.
    fn clock(&self) -> ClockSpec;
    /// One rising edge at `io.now()`.
    fn tick(&mut self, io: &mut Io<'_>);
    /// VCD hook: present the component's signals to `probe` (rust-hdl
    /// blocks: `self.block.accept(self.name(), probe)`). Default: none.
    fn probe(&self, _probe: &mut dyn Probe) {}
    /// VCD hook: the kernel turns tracing on before the first probe walk; a
    /// component whose engine skips signals no output needs (compiled models)
    /// evaluates all of them from then on. Default: nothing to do.
    fn set_trace(&mut self, _on: bool) {}
}

/// Index of a component in its simulation.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct CompId(pub usize);

/// Typed handle to a component, returned by [`Sim::add`].
pub struct Handle<T> {
    pub id: CompId,
    _t: PhantomData<fn() -> T>,
}
impl<T> Clone for Handle<T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<T> Copy for Handle<T> {}
impl<T> std::fmt::Debug for Handle<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Handle({})", self.id.0)
    }
}

pub(crate) struct Slot {
    pub(crate) comp: Box<dyn Component>,
    pub(crate) inputs: Vec<NetId>,
    pub(crate) outputs: Vec<NetId>,
    clock: ClockSpec,
    next_n: u64,
    jitter: Option<ChaCha8Rng>,
    pub(crate) cycles: u64,
}

impl Slot {
    #[inline]
    fn edge(&mut self, n: u64) -> u64 {
        let t = self.clock.edge_time(n);
        match &mut self.jitter {
            Some(r) => t + r.gen_range(0..=self.clock.jitter_ps),
            None => t,
        }
    }
}

/// The simulation: nets, components, time.
pub struct Sim {
    pub(crate) nets: Nets,
    pub(crate) slots: Vec<Slot>,
    heap: BinaryHeap<Reverse<(u64, usize)>>,
    now: u64,
    started: bool,
    seed: u64,
    rng: ChaCha8Rng,
    horizon: Option<u64>,
    keep: u64,
    valid_from: u64,
    next_prune: u64,
    ticked: Vec<usize>,
    pub(crate) vcd: Option<VcdState>,
    /// A VCD write failed during the run: dumping stopped, [`Sim::finish_vcd`] reports it.
    vcd_err: Option<std::io::Error>,
}

impl Sim {
    /// A new empty simulation at time 0; `seed` seeds [`Sim::rng`].
    pub fn new(seed: u64) -> Self {
        Sim {
            nets: Nets::new(),
            slots: Vec::new(),
            heap: BinaryHeap::new(),
            now: 0,
            started: false,
            seed,
            rng: ChaCha8Rng::seed_from_u64(seed),
            horizon: None,
            keep: 0,
            valid_from: 0,
            next_prune: 0,
            ticked: Vec::new(),
            vcd: None,
            vcd_err: None,
        }
    }

    /// The simulation's random generator (phases, jitter, stimulus).
    pub fn rng(&mut self) -> &mut ChaCha8Rng {
        &mut self.rng
    }

    /// A clock with a random start phase in `[0, period)` drawn from [`Sim::rng`].
    pub fn random_phase_clock(&mut self, period_ps: u64, ppm: f64) -> ClockSpec {
        let phase = self.rng.gen_range(0..period_ps);
        ClockSpec::new(period_ps).with_ppm(ppm).with_phase(phase)
    }

    /// Current time in ps (time of the last processed edge, or the target of
    /// the last `run_until`).
    pub fn now(&self) -> u64 {
        self.now
    }

    // ---------------------------------------------------------------- nets

    /// A net driven by one component output (or by test code with
    /// [`Sim::drive`]); `init` is its level before the first write.
    pub fn driven(&mut self, name: &str, init: bool) -> NetId {
        self.horizon = None;
        self.nets.add(name, Node::Driven { base: init, hist: VecDeque::new(), driver: None })
    }
    /// A delay line: transitions of `src` to dominant appear `d_dom` ps later,
    /// transitions to recessive `d_rec` ps later (see [`crate::net`]).
    pub fn delay(&mut self, name: &str, src: NetId, d_dom: u64, d_rec: u64) -> NetId {
        self.horizon = None;
        self.nets.add(name, Node::Delay { src, d_dom, d_rec })
    }
    /// Wired-AND (dominant 0 wins) of several nets.
    pub fn wired_and(&mut self, name: &str, srcs: &[NetId]) -> NetId {
        self.horizon = None;
        self.nets.add(name, Node::And(srcs.to_vec()))
    }
    /// A fault transform of `src`, initially [`FaultMode::None`]. Change it
    /// with [`Sim::set_fault`], [`Sim::schedule_fault`], [`Sim::add_flip_window`].
    pub fn fault(&mut self, name: &str, src: NetId) -> NetId {
        self.horizon = None;
        self.nets.add(
            name,
            Node::Fault { src, base: FaultMode::None, sched: VecDeque::new(), windows: VecDeque::new() },
        )
    }
    /// A net by its name.
    pub fn net(&self, name: &str) -> Option<NetId> {
        self.nets.by_name.get(name).copied()
    }
    /// The name of a net.
    pub fn net_name(&self, id: NetId) -> &str {
        &self.nets.names[id.index()]
    }
    /// Level of a net now (transitions at the current time included).
    pub fn value(&self, id: NetId) -> bool {
        self.nets.at(id, self.now)
    }
    /// Level of a net at instant `t` (transitions at `t` included). `t` may
    /// lie in the future (the result assumes no further writes). History is
    /// pruned: by default only the last [`Sim::horizon`] ps (plus up to 1 us)
    /// are kept; panics if `t` lies before [`Sim::history_start`]. Use
    /// [`Sim::keep_history`] to look further back.
    pub fn value_at(&self, id: NetId, t: u64) -> bool {
        assert!(
            t >= self.valid_from,
            "value_at({t}) lies before the kept history (from {}): use Sim::keep_history",
            self.valid_from
        );
        self.nets.at(id, t)
    }
    /// Keep `ps` more picoseconds of history than needed by the net graph
    /// (so [`Sim::value_at`] can look back that far). `u64::MAX` disables
    /// pruning. Default 0.
    pub fn keep_history(&mut self, ps: u64) {
        self.keep = ps;
    }
    /// Earliest instant [`Sim::value_at`] can still answer.
    pub fn history_start(&self) -> u64 {
        self.valid_from
    }
    /// Drive a driven net without a component driver to `v` at the current time.
    pub fn drive(&mut self, id: NetId, v: bool) {
        assert!(self.nets.driver(id).is_none(), "net {:?} is driven by a component", self.net_name(id));
        self.nets.write(id, self.now, v);
    }
    /// Change a fault/interference net's mode now (takes effect for values at
    /// the current time and for all later edges; cancels later scheduled changes).
    pub fn set_fault(&mut self, id: NetId, mode: impl Into<FaultMode>) {
        self.nets.clear_schedule_after(id, self.now);
        self.nets.schedule(id, self.now, mode.into());
    }
    /// Schedule a mode change of a fault/interference net at time `t >= now`.
    pub fn schedule_fault(&mut self, id: NetId, t: u64, mode: impl Into<FaultMode>) {
        assert!(t >= self.now, "cannot schedule a fault in the past");
        self.nets.schedule(id, t, mode.into());
    }
    /// The mode of a fault/interference net at instant `t`.
    pub fn fault_mode_at(&self, id: NetId, t: u64) -> FaultMode {
        self.nets.mode_at(id, t)
    }
    /// Invert a fault/interference net's output during `[start, end)` (on top
    /// of its mode). Overlapping windows merge.
    pub fn add_flip_window(&mut self, id: NetId, start: u64, end: u64) {
        assert!(start >= self.now, "cannot add a flip window in the past");
        self.nets.add_window(id, start, end);
    }
    /// `count` flip windows of `len` ps each, starting at `start`, every `every` ps.
    pub fn add_flip_pattern(&mut self, id: NetId, start: u64, len: u64, every: u64, count: usize) {
        for k in 0..count as u64 {
            self.add_flip_window(id, start + k * every, start + k * every + len);
        }
    }
    /// Number of stored transitions and schedule entries over all nets
    /// (bounded by pruning).
    pub fn stored_events(&self) -> usize {
        self.nets.stored_events()
    }
    /// Largest total delay along any path of the net graph (history older
    /// than `now - horizon` is pruned).
    pub fn horizon(&mut self) -> u64 {
        if self.horizon.is_none() {
            self.horizon = Some(self.nets.horizon());
        }
        self.horizon.unwrap()
    }

    // ---------------------------------------------------------- components

    /// Add a component reading `inputs` and driving `outputs` (driven nets,
    /// one driver each). Its first edge is `clock().edge_time(0)` or, if the
    /// simulation already ran, the first edge after now.
    pub fn add<C: Component>(&mut self, comp: C, inputs: &[NetId], outputs: &[NetId]) -> Handle<C> {
        let id = self.add_boxed(Box::new(comp), inputs, outputs);
        Handle { id, _t: PhantomData }
    }

    /// [`Sim::add`] for a boxed component.
    pub fn add_boxed(&mut self, comp: Box<dyn Component>, inputs: &[NetId], outputs: &[NetId]) -> CompId {
        assert!(self.vcd.is_none(), "add components before starting the VCD");
        let idx = self.slots.len();
        for &o in outputs {
            self.nets.set_driver(o, idx);
        }
        for &i in inputs {
            assert!(i.index() < self.nets.nodes.len(), "unknown input net");
        }
        let clock = comp.clock();
        let next_n = if self.started { clock.first_edge_after(self.now) } else { 0 };
        let jitter = (clock.jitter_ps > 0)
            .then(|| ChaCha8Rng::seed_from_u64(self.seed ^ (idx as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15)));
        let mut slot = Slot { comp, inputs: inputs.to_vec(), outputs: outputs.to_vec(), clock, next_n, jitter, cycles: 0 };
        let t0 = slot.edge(next_n).max(self.now);
        self.heap.push(Reverse((t0, idx)));
        self.slots.push(slot);
        CompId(idx)
    }

    pub fn n_components(&self) -> usize {
        self.slots.len()
    }
    /// The component behind a typed handle.
    pub fn get<T: Component>(&self, h: Handle<T>) -> &T {
        self.component_as::<T>(h.id).expect("handle type mismatch")
    }
    pub fn get_mut<T: Component>(&mut self, h: Handle<T>) -> &mut T {
        self.component_as_mut::<T>(h.id).expect("handle type mismatch")
    }
    pub fn component(&self, id: CompId) -> &dyn Component {
        &*self.slots[id.0].comp
    }
    /// Downcast a component.
    pub fn component_as<T: Component>(&self, id: CompId) -> Option<&T> {
        let c: &dyn Any = &*self.slots[id.0].comp;
        c.downcast_ref::<T>()
    }
    pub fn component_as_mut<T: Component>(&mut self, id: CompId) -> Option<&mut T> {
        let c: &mut dyn Any = &mut *self.slots[id.0].comp;
        c.downcast_mut::<T>()
    }
    /// The component with the given name (first one if several).
    pub fn find(&self, name: &str) -> Option<CompId> {
        self.slots.iter().position(|s| s.comp.name() == name).map(CompId)
    }
    /// The input and output nets a component was bound to.
    pub fn ports(&self, id: CompId) -> (&[NetId], &[NetId]) {
        (&self.slots[id.0].inputs, &self.slots[id.0].outputs)
    }
    /// Clock cycles (ticks) a component has done.
    pub fn cycles(&self, id: CompId) -> u64 {
        self.slots[id.0].cycles
    }
    /// Total ticks of all components.
    pub fn total_cycles(&self) -> u64 {
        self.slots.iter().map(|s| s.cycles).sum()
    }

    // ------------------------------------------------------------- running

    /// Time of the next clock edge of any component.
    pub fn next_edge_time(&self) -> Option<u64> {
        self.heap.peek().map(|r| r.0 .0)
    }

    /// Advance to the next clock edge time and tick every component with an
    /// edge at that time (in order of addition; order does not matter since
    /// inputs are sampled before the edge). Returns the new time.
    pub fn step(&mut self) -> u64 {
        let Some(&Reverse((t, _))) = self.heap.peek() else {
            return self.now;
        };
        self.started = true;
        self.now = t;
        self.ticked.clear();
        // tick the components of the heap's top in place: the new edge time replaces
        // the top and sinks once (instead of a pop and a push); (time, index) order as
        // before, and order does not matter anyway (inputs are sampled before the edge)
        while let Some(mut top) = self.heap.peek_mut() {
            let Reverse((tt, idx)) = *top;
            if tt != t {
                break;
            }
            let slot = &mut self.slots[idx];
            let mut io = Io { now: t, nets: &mut self.nets, inputs: &slot.inputs, outputs: &slot.outputs };
            slot.comp.tick(&mut io);
            slot.cycles += 1;
            slot.next_n += 1;
            *top = Reverse((slot.edge(slot.next_n), idx));
            drop(top);
            self.ticked.push(idx);
        }
        if self.vcd.is_some() {
            self.vcd_dump(t, true);
        }
        self.maybe_prune();
        t
    }

    fn maybe_prune(&mut self) {
        if self.now < self.next_prune {
            return;
        }
        let h = self.horizon().saturating_add(2);
        let cutoff = self.now.saturating_sub(h).saturating_sub(self.keep);
        if cutoff > 0 {
            self.nets.prune(cutoff);
            self.valid_from = cutoff + h;
        }
        // prune again once the horizon (at least 1 us) has passed
        self.next_prune = self.now + h.max(1_000_000);
    }

    /// Process every edge at a time `<= t`, then set the time to `t`.
    pub fn run_until(&mut self, t: u64) {
        while self.next_edge_time().is_some_and(|e| e <= t) {
            self.step();
        }
        if t > self.now {
            self.started = true;
            self.now = t;
            if self.vcd.is_some() {
                self.vcd_dump(t, false);
            }
        }
    }

    /// Run for `dt` ps.
    pub fn run_for(&mut self, dt: u64) {
        self.run_until(self.now + dt);
    }

    /// Step until `cond(self)` holds (checked first, then after every step)
    /// or the next edge lies beyond `deadline_ps` (time then stays at the last
    /// processed edge). Returns whether the condition held.
    pub fn run_until_cond(&mut self, deadline_ps: u64, mut cond: impl FnMut(&Sim) -> bool) -> bool {
        loop {
            if cond(self) {
                return true;
            }
            match self.next_edge_time() {
                Some(e) if e <= deadline_ps => {
                    self.step();
                }
                _ => return false,
            }
        }
    }

    // ----------------------------------------------------------------- VCD

    /// Start writing a VCD of all signals (`filter == None`) or of those whose
    /// hierarchical name matches one of the patterns (see [`crate::vcd`]).
    /// Add all components and nets first.
    pub fn start_vcd(&mut self, out: Box<dyn Write>, filter: Option<&[&str]>) -> std::io::Result<()> {
        for s in self.slots.iter_mut() {
            s.comp.set_trace(true);
        }
        let st = VcdState::start(self, out, filter)?;
        self.vcd = Some(st);
        Ok(())
    }

    /// [`Sim::start_vcd`] into a file.
    pub fn start_vcd_file(&mut self, path: impl AsRef<std::path::Path>, filter: Option<&[&str]>) -> std::io::Result<()> {
        let f = std::fs::File::create(path)?;
        self.start_vcd(Box::new(std::io::BufWriter::new(f)), filter)
    }

    /// Write pending wire changes up to now, flush and close the VCD.
    pub fn finish_vcd(&mut self) -> std::io::Result<()> {
        if self.vcd.is_some() {
            self.vcd_dump(self.now, false);
        }
        if let Some(e) = self.vcd_err.take() {
            return Err(e);
        }
        match self.vcd.take() {
            Some(st) => st.finish(),
            None => Ok(()),
        }
    }

    /// Write the changes at `t`; a write error (a full disk) stops the VCD
    /// and is kept for [`Sim::finish_vcd`] instead of ending the run.
    fn vcd_dump(&mut self, t: u64, with_ticked: bool) {
        let Some(mut st) = self.vcd.take() else { return };
        let ticked: &[usize] = if with_ticked { &self.ticked } else { &[] };
        match st.dump(self, t, ticked) {
            Ok(()) => self.vcd = Some(st),
            Err(e) => self.vcd_err = Some(e),
        }
    }
}

impl VcdView for Sim {
    fn now(&self) -> u64 {
        self.now
    }
    fn component_count(&self) -> usize {
        self.slots.len()
    }
    fn probe_component(&self, i: usize, probe: &mut dyn Probe) {
        self.slots[i].comp.probe(probe)
    }
    fn net_names(&self) -> Vec<(&str, NetId)> {
        self.nets.by_name.iter().map(|(n, &id)| (n.as_str(), id)).collect()
    }
    fn net_at(&self, id: NetId, t: u64) -> bool {
        self.nets.at(id, t)
    }
    fn next_event(&self, id: NetId, after: i64) -> Option<u64> {
        self.nets.next_event(id, after)
    }
}
