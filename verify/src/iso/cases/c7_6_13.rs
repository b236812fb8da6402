//! ISO 16845-1:2016 clause 7.6.13 — REC +1 for a form error in the
//! IUT's overload delimiter.
//!
//! What the case checks (in our words): after a valid frame (REC 0) and an
//! overload flag caused by a dominant first intermission bit, the LT drives
//! the 2nd or the 7th bit of the overload delimiter dominant. The IUT must
//! report a form error at that bit, with REC 1 after it, and send an
//! active error flag from the next bit.
//!
//! Elementary tests: `iso_7_6_13_overload_delimiter_bit<N>`, N = 2, 7.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_13".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [2, 7] {
        let r = super::c7_6_12::delimiter_form_error(&mut lb, true, n);
        ctx.record(&format!("iso_7_6_13_overload_delimiter_bit{n}"), r);
    }
    ctx.results
}
