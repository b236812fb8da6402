//! canstar-controller: the CAN 2.0A/B protocol controller core.
//!
//! - [`fsm`]: the bit-stream processor, i.e. the complete frame state machine
//!   with destuffing, CRC, arbitration, error detection and fault confinement
//!   ([`fsm::CanFsm`]). Its FIELD encoding and event word are documented there.
//! - [`core`]: [`CanCore`], the top block: synchroniser, bit timing and the
//!   frame state machine, with the native host interface and debug bundle.
//! - [`frame`]: plain-Rust frames and the bit-level frame builder.
//! - [`trace`]: per-bit trace lines (§18) from the debug bundle.
//!
//! The normative description is `can-protocol.md`.

pub mod frame;
pub mod fsm;

pub use frame::{BuildOptions, BusBit, Frame};
pub use fsm::{CanFsm, Field};
pub mod core;
pub use crate::core::CanCore;
pub mod trace;
pub mod sja1000;
