//! canstar-sim: the cycle-simulation kernel.
//!
//! A [`Sim`] holds nets and clocked [`Component`]s. Each component has its
//! own [`ClockSpec`] (period in ps, oscillator offset in ppm, start phase),
//! so nodes drift against each other; edge times are exact integers. On each
//! rising edge a component samples its input nets just before the edge and
//! writes its output nets at the edge ([`Io`]). rust-hdl blocks become
//! components through [`HdlComponent`] (driven with `canstar_hdl::drive`,
//! never rust-hdl's `Simulation`).
//!
//! Nets ([`net`]) are driven nets with a transition history, or derived nets
//! computed lazily by time: delay lines with separate delays towards
//! dominant and recessive, wired-AND, and fault transforms. Level `false` is
//! dominant. History older than the largest total delay is pruned, so long
//! runs use bounded memory.
//!
//! Time is in integer picoseconds. A transition written at `t` is visible
//! at every instant `>= t` ([`Sim::value_at`]); a component ticking at `t`
//! samples its inputs just before `t`, so components with simultaneous edges
//! never see each other's new outputs at that same instant, and the result
//! never depends on processing order.
//!
//! Builders: [`bus::Bus`] (wired-AND bus with per-node delays and
//! receive-path interference), [`star::HubPorts`] / [`star::TwoHubs`] (star and
//! two-hub networks of [`star::Link`]s with link faults).
//!
//! VCD output ([`vcd`]): [`Sim::start_vcd_file`] / [`Sim::finish_vcd`].
//! Benchmark of the kernel itself: [`bench::bench`].
//!
//! This crate knows no CAN controller and no hub: the controller as a node,
//! lock-step, fuzzing and the conformance suite are `canstar-verify`; the hub
//! RTL as a component and the ReCANcentrate system are `canstar-recan`.
//!
//! ```
//! use canstar_sim::{Sim, ClockSpec, bus::{Bus, NodeDelays}, star::AndHub};
//! let mut sim = Sim::new(1);
//! let bus = Bus::uniform(&mut sim, "bus", 2, NodeDelays::symmetric(100, 50));
//! sim.drive(bus.nodes[0].tx, false); // test code drives node 0's TX dominant
//! sim.run_until(1_000);
//! assert!(!sim.value(bus.nodes[1].rx));
//! ```

pub mod bench;
pub mod bus;
mod clock;
mod component;
mod kernel;
pub mod net;
pub mod star;
pub mod vcd;

pub use clock::ClockSpec;
pub use component::{FnComponent, HdlComponent, InputMap, OutputMap};
pub use kernel::{CompId, Component, Handle, Io, Sim};
pub use net::{FaultMode, NetId};
