//! Compiled models of canstar's RTL designs.
//!
//! Every file under `generated/` is straight-line Rust written by `canstar-rtlc` from the
//! rust-hdl design (see [`registry`] for the list of designs and shapes). The models are
//! committed, so building and testing this crate needs neither a C toolchain nor an EDA
//! tool; `tests/current.rs` fails when a committed model is stale.

pub mod generated;
pub mod lockstep;
pub mod registry;

pub use canstar_rtlc::rt::Model;
