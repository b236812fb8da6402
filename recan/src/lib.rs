//! canstar-recan: the ReCANcentrate system simulation (recancentrate.md): two RTL hubs joined by
//! interlinks, nodes with two RTL controllers each, the nodes' media-management
//! driver and test applications as Rust models, fault injection, and the 21
//! published single-fault scenarios.
//!
//! - [`spec`]: [`NetworkSpec`] (TOML network file; `NetworkSpec::default()` is
//!   the reference system); [`network`]: the builder [`network::Network::build`];
//!   [`budget`]: the propagation budget ([`NetworkSpec::propagation_budget`]).
//! - [`ctrl`]: [`ctrl::Ctrl`], one controller (RTL `CanCore`) with its native host
//!   interface, as a kernel component.
//! - [`driver`]: the media-management driver of one node (tx, rx and qua
//!   routines, K wait, transmission timer, omission counter, quarantine at 96).
//! - [`app`]: 3BitCounter, Blinker and Receiver.
//! - [`fault`]: [`FaultSpec`]: link, sublink, interlink, hub faults and crashes.
//! - [`run()`]: one run ([`RunSpec`] → [`RunResult`]), stepping the kernel in
//!   slices of a quarter bit and running the drivers between slices
//!   (deterministic: the same spec and seed give the same result).
//! - [`rtl_hub`]: [`rtl_hub::RtlHub`], the generated hub RTL (frame monitor
//!   included) as a kernel component.
//! - [`events`]: legal events of healthy nodes (error-passive controllers,
//!   overload frames, late joiners, power cycles); [`soak`]: the fault-free soak
//!   (`canstar soak`).
//! - [`campaign`]: randomised fault campaigns over classes of faults
//!   (`canstar campaign`).
//! - [`scenarios`]: [`published_scenario`] (the 21 rows of recancentrate.md §5,
//!   randomised from a seed), [`Expected`] and [`check`].
//!
//! Modelling choices (all in [`DriverSpec`] / [`NetworkSpec`]):
//! - Network files give no PH2, so it is max(PH1, 2): the prototype's PROP 2 / PH1 3 /
//!   PH2 2 is expressed as PROP 3 / PH1 2 / PH2 2 (same 8 TQ, same sample point).
//! - The hubs use one input flip-flop (`sync_depth = 1`, as the prototype): with
//!   two, the round trip through both hubs no longer fits before the sample point.
//! - Host interrupt latency (`irq_latency_ns`, default 10 us): reports reach the
//!   driver that much later. With a host that reacts within a bit, a controller
//!   whose counter climbs by 8 per bit of a continuous error flag is quarantined
//!   at 96 before the hub's dominant-run judge (13 bits) can isolate its uplink,
//!   and scenarios 3 to 8 would not show the recorded isolation.
//! - Application delay (`app_delay_bits`, default 4 > the 3-bit intermission):
//!   two nodes sending at the maximal rate alternate instead of the higher
//!   priority starving the other.
//! - K = 4 bit times, transmission timeout 0xFFFF ticks at 29.48 MHz (2.2 ms),
//!   maxInconsists 3, warning limit 96. A quarantined controller is held in
//!   reset (uplink recessive) for the rest of the run.
//! - [`NetworkSpec::fast`] clocks the node controllers at 14.74 MHz with a
//!   2-clock quantum (same bit timing) to halve their simulation cost; the
//!   published scenarios use it.

pub mod app;
pub mod budget;
pub mod campaign;
pub mod ctrl;
pub mod driver;
pub mod events;
pub mod fault;
pub mod network;
pub mod rtl_hub;
pub mod run;
pub mod scenarios;
pub mod soak;
pub mod spec;

pub use fault::{CtrlRef, Dir, FaultKind, FaultSpec, FaultStart, FaultTarget, StartField};
pub use run::{run, run_inspect, run_observed, CounterSample, IsolationEvent, Isolated, RunResult, RunSpec};
pub use scenarios::{check, published_scenario, Expected, SCENARIO_NAMES};
pub use spec::{AppKind, CtrlSpec, DriverSpec, NetworkSpec, NodeSpec};
