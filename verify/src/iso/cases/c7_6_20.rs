//! ISO 16845-1:2016 clause 7.6.20 — no REC change for a dominant last bit
//! of the IUT's overload delimiter.
//!
//! What the case checks (in our words): after a valid frame (REC 0) and an
//! overload flag caused by a dominant first intermission bit, the LT
//! drives the 8th bit of the overload delimiter dominant: a new overload
//! flag from the next bit, no error, REC 0.
//!
//! Elementary test: `iso_7_6_20_overload_delimiter_bit8`.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_20".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = super::c7_6_19::delimiter8(&mut lb, true);
    ctx.record("iso_7_6_20_overload_delimiter_bit8", r);
    ctx.results
}
