//! Shared RTL blocks of canstar and the tooling every block goes through.
//!
//! - [`sync`]: input synchroniser (1 or 2 flip-flops) and edge detector.
//! - [`crc15`]: the CAN CRC-15 (polynomial 0x4599).
//! - [`stuff`]: bit stuffer and destuffer.
//! - [`timing`]: [`timing::BtlConfig`], the one bit-timing configuration type.
//! - [`btl`]: bit timing logic (prescaler, segments, hard and re-synchronisation).
//! - [`drive`]: the direct clock loop used instead of rust-hdl's `Simulation`.
//! - [`flow`]: Verilog emission, Verilator lint, Yosys synthesis and co-simulation.

pub mod btl;
pub mod btl_model;
pub mod crc15;
pub mod drive;
pub mod flow;
pub mod stuff;
pub mod sync;
pub mod timing;

pub use rust_hdl;
