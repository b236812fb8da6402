//! Compiled models of canstar's RTL designs.
//!
//! Every file under `generated/` is straight-line Rust written by `canstar-rtlc` from the
//! rust-hdl design (see [`registry`] for the list of designs and shapes). The models are
//! committed, so building and testing this crate needs neither a C toolchain nor an EDA
//! tool; `tests/current.rs` fails when a committed model is stale
//! (`CANSTAR_BLESS=1 cargo test -p canstar-models --test current` rewrites them).
//!
//! A model clocks like `canstar_hdl::drive::cycle` on the rust-hdl design and gives the
//! same values: set inputs (public fields, or [`Model::set_inputs`]), call `cycle()`,
//! read outputs (public fields, or [`Model::outputs`]). Internal fields are public for
//! reading; change state only through [`Model::set_atom`] or [`Model::load`].
//!
//! ```
//! use canstar_controller::core::CanCore;
//! use canstar_models::generated::can_core;
//! use canstar_models::Model;
//!
//! // the constants (synchroniser depth 1 here), state and inputs of a rust-hdl instance
//! let hdl = CanCore::with_sync_depth(1);
//! let mut m = can_core::CanCore::from_instance(&hdl).unwrap();
//! m.reset = true;
//! m.rx = true;
//! m.cycle();
//! m.reset = false;
//! for _ in 0..100 {
//!     m.cycle();
//! }
//! assert!(m.tx); // recessive: nothing to send
//!
//! // the same through the generic interface, found by the instance's shape
//! let mut any = canstar_models::model_for(&hdl).unwrap();
//! let rx = any.input_index("rx").unwrap();
//! any.set_input(rx, 1);
//! any.cycle();
//! assert_eq!(any.output(any.output_index("tx").unwrap()), 1);
//! ```
//!
//! [`lockstep`] runs a model next to its rust-hdl design and compares them;
//! `models/verilator/run.sh` benchmarks rust-hdl, the models and Verilator on the
//! same recorded stimulus.

pub mod generated;
pub mod lockstep;
pub mod registry;
pub mod semantics;

pub use canstar_rtlc::rt::Model;

/// A compiled model for a rust-hdl instance: the committed model whose shape
/// fingerprint matches, loaded with the instance's constants, state and inputs.
/// A clear error names the fingerprint when no committed model has that shape
/// (compile one with `canstar_rtlc::generate`).
pub fn model_for(b: &dyn canstar_rtlc::rt::Block) -> Result<Box<dyn Model>, canstar_rtlc::Error> {
    let fp = canstar_rtlc::fingerprint(b)?;
    for mut m in generated::all() {
        if m.info().fingerprint == fp {
            m.load(b)?;
            return Ok(m);
        }
    }
    Err(canstar_rtlc::Error::ShapeMismatch { model: "any committed model".into(), expected: 0, found: fp })
}
