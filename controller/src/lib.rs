//! canstar-controller: the CAN 2.0A/B protocol controller core.
//!
//! - [`fsm`]: the bit-stream processor, i.e. the complete frame state machine
//!   with destuffing, CRC, arbitration, error detection and fault confinement
//!   ([`fsm::CanFsm`], a composition of one sub-block per concern). Its FIELD
//!   encoding and event word are documented there.
//! - [`core`]: [`CanCore`], the top block: synchroniser, bit timing and the
//!   frame state machine, with the native host interface and debug bundle.
//! - [`frame`]: plain-Rust frames and the bit-level frame builder (stuffing,
//!   CRC-15, FIELD/POSITION of every bus bit, options for scripted
//!   transmitters).
//! - [`trace`]: per-bit trace lines (§18) from the debug bundle.
//! - [`view`]: [`CoreView`], the core's outputs and debug bundle as integers, the
//!   same for the rust-hdl block and the compiled model.
//!
//! The normative description is `can-protocol.md`.
//!
//! # Tests
//!
//! `tests/common` holds two harnesses: a bit-level bus of [`CanFsm`] blocks
//! (one bit per clock, per-node receive overrides, an optional scripted
//! transmitter) and a clock-level bus of [`CanCore`] blocks (wired-AND, RX
//! overrides and delays). The bit-level tests include the counter sequences
//! of the conformance programs txarb, stufferr, crc, emlcount, formerr,
//! biterror, idle, overload, extd_id and stuffbit (`tests/fsm_<program>.rs`).
//! `tests/lockstep_golden.rs` runs the frame state machine bit by bit in
//! lock-step with canstar-sim's golden model, and
//! `tests/lockstep_core_golden.rs` runs [`CanCore`] clock by clock against the
//! golden model behind the bit timing's clock-exact model (§19), both with
//! random traffic and disturbances. The Verilog flow (lint, Yosys,
//! co-simulation) runs in the ignored tests of `tests/fsm_verilog.rs` and
//! `tests/core_verilog.rs`.

pub mod core;
pub mod frame;
pub mod fsm;
pub mod trace;
pub mod view;

pub use crate::core::CanCore;
pub use frame::{BuildOptions, BusBit, Frame};
pub use fsm::{CanFsm, Field};
pub use view::CoreView;
pub mod sja1000;
pub mod slcan;
