//! Ready-made components: any clocked rust-hdl block ([`HdlComponent`]) and a
//! closure ([`FnComponent`]).

use canstar_hdl::drive::{self, Clocked};
use rust_hdl::prelude::Probe;

use crate::clock::ClockSpec;
use crate::kernel::{Component, Io};

/// Maps the input nets' levels (in binding order) to the block's inputs.
pub type InputMap<B> = Box<dyn FnMut(&mut B, &[bool])>;
/// Maps the block's outputs to the output nets' levels (in binding order).
pub type OutputMap<B> = Box<dyn FnMut(&B, &mut [bool])>;

/// Adapter turning any clocked rust-hdl block into a [`Component`].
///
/// Each edge: input net levels are read and handed to `set_inputs`, then
/// `drive::cycle` settles the block, applies the rising edge (and the falling
/// edge), then `get_outputs` maps the block's outputs to the output nets.
///
/// ```
/// use canstar_sim::{bench::EdgeCounter, bus::{Bus, NodeDelays}, ClockSpec, HdlComponent, Sim};
/// let mut sim = Sim::new(1);
/// let bus = Bus::uniform(&mut sim, "bus", 1, NodeDelays::symmetric(0, 0));
/// // one input (RX), no outputs; a controller would map `o[0] = b.tx.val()`
/// let node = HdlComponent::new("node0", ClockSpec::mhz(40.0), EdgeCounter::default(), 1, 0,
///     |b, i| b.rx.next = i[0], |_b, _o| {});
/// let h = sim.add(node, &[bus.nodes[0].rx], &[]);
/// sim.drive(bus.nodes[0].tx, false);
/// sim.run_until(1_000_000);
/// // the synchroniser powers up at 0 (one edge to recessive), then sees the dominant edge
/// assert_eq!(sim.get(h).block.edges.val().index(), 2);
/// ```
pub struct HdlComponent<B: Clocked> {
    name: String,
    clock: ClockSpec,
    /// The wrapped block (read its signals with `.val()` between steps).
    pub block: B,
    set_inputs: InputMap<B>,
    get_outputs: OutputMap<B>,
    ins: Vec<bool>,
    outs: Vec<bool>,
}

impl<B: Clocked + 'static> HdlComponent<B> {
    /// Wrap `block` (it is connected and settled here with `drive::init`).
    pub fn new(
        name: &str,
        clock: ClockSpec,
        mut block: B,
        n_inputs: usize,
        n_outputs: usize,
        set_inputs: impl FnMut(&mut B, &[bool]) + 'static,
        get_outputs: impl FnMut(&B, &mut [bool]) + 'static,
    ) -> Self {
        drive::init(&mut block);
        HdlComponent {
            name: name.to_string(),
            clock,
            block,
            set_inputs: Box::new(set_inputs),
            get_outputs: Box::new(get_outputs),
            ins: vec![true; n_inputs],
            outs: vec![true; n_outputs],
        }
    }
}

impl<B: Clocked + 'static> Component for HdlComponent<B> {
    fn name(&self) -> &str {
        &self.name
    }
    fn clock(&self) -> ClockSpec {
        self.clock
    }
    fn tick(&mut self, io: &mut Io<'_>) {
        for (i, v) in self.ins.iter_mut().enumerate() {
            *v = io.input(i);
        }
        (self.set_inputs)(&mut self.block, &self.ins);
        drive::cycle(&mut self.block);
        (self.get_outputs)(&self.block, &mut self.outs);
        for (i, &v) in self.outs.iter().enumerate() {
            io.set_output(i, v);
        }
    }
    fn probe(&self, probe: &mut dyn Probe) {
        self.block.accept(&self.name, probe);
    }
}

/// A plain-Rust component from a closure called on every edge (stimulus
/// generators, testers, stand-ins). State lives in the closure's captures.
pub struct FnComponent<F: FnMut(&mut Io<'_>) + 'static> {
    name: String,
    clock: ClockSpec,
    f: F,
}

impl<F: FnMut(&mut Io<'_>) + 'static> FnComponent<F> {
    pub fn new(name: &str, clock: ClockSpec, f: F) -> Self {
        FnComponent { name: name.to_string(), clock, f }
    }
}

impl<F: FnMut(&mut Io<'_>) + 'static> Component for FnComponent<F> {
    fn name(&self) -> &str {
        &self.name
    }
    fn clock(&self) -> ClockSpec {
        self.clock
    }
    fn tick(&mut self, io: &mut Io<'_>) {
        (self.f)(io)
    }
}

