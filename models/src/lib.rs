//! Compiled models of canstar's RTL designs.
//!
//! Every file under `generated/` is straight-line Rust written by `canstar-rtlc` from the
//! rust-hdl design (see [`registry`] for the list of designs and shapes). The models are
//! committed, so building and testing this crate needs neither a C toolchain nor an EDA
//! tool; `tests/current.rs` fails when a committed model is stale.

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
