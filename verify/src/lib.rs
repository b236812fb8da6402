//! canstar-verify: verification of the CAN controller RTL on the simulation kernel.
//!
//! - [`node`]: [`node::CanNode`], the controller (`CanCore`) with a scripted host
//!   as a kernel component, and its per-bit trace (can-protocol.md §18).
//! - [`lockstep`]: [`lockstep::LockstepNode`] runs an RTL node in lock step with
//!   the independent golden model (golden bit timing + `canstar_golden::GoldenNode`,
//!   can-protocol.md §19).
//! - [`fuzz`]: randomised multi-node lock-step sessions with receive-path
//!   disturbances and network properties (`canstar fuzz`).
//! - [`scenario`]: bus scenario files (`canstar sim SCENARIO.toml`).
//! - [`conformance`]: the 13 Bosch conformance programs (conformance-tests.md),
//!   run on the kernel (`canstar conformance`).

pub mod conformance;
pub mod fuzz;
pub mod iso;
pub mod lockstep;
pub mod node;
pub mod scenario;
