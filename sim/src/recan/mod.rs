//! ReCANcentrate system simulation (recancentrate.md): two RTL hubs joined by
//! interlinks, nodes with two RTL controllers each, the nodes' media-management
//! driver and test applications as Rust models, fault injection, and the 21
//! published single-fault scenarios.
//!
//! - [`spec`]: [`NetworkSpec`] (TOML network file; `NetworkSpec::default()` is
//!   the reference system) and the builder [`spec::Network::build`].
//! - [`ctrl`]: [`ctrl::Ctrl`], one controller (RTL `CanCore`) with its native host
//!   interface, as a kernel component.
//! - [`driver`]: the media-management driver of one node (tx, rx and qua
//!   routines, K wait, transmission timer, omission counter, quarantine at 96).
//! - [`app`]: 3BitCounter, Blinker and Receiver.
//! - [`fault`]: [`FaultSpec`]: link, sublink, interlink, hub faults and crashes.
//! - [`run()`]: one run ([`RunSpec`] → [`RunResult`]), stepping the kernel in
//!   slices of a quarter bit and running the drivers between slices
//!   (deterministic: the same spec and seed give the same result).
//! - [`scenarios`]: [`published_scenario`] (the 21 rows of recancentrate.md §5,
//!   randomised from a seed), [`Expected`] and [`check`].

pub mod app;
pub mod ctrl;
pub mod driver;
pub mod fault;
pub mod run;
pub mod scenarios;
pub mod spec;

pub use fault::{CtrlRef, Dir, FaultKind, FaultSpec, FaultStart, FaultTarget, StartField};
pub use run::{run, CounterSample, IsolationEvent, Isolated, RunResult, RunSpec};
pub use scenarios::{check, published_scenario, Expected, SCENARIO_NAMES};
pub use spec::{AppKind, CtrlSpec, DriverSpec, NetworkSpec, NodeSpec};
