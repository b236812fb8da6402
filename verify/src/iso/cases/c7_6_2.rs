//! ISO 16845-1:2016 clause 7.6.2 — REC +8 for a bit error in the IUT's
//! own overload flag.
//!
//! What the case checks (in our words): after a valid frame (REC 0) the LT
//! drives the first intermission bit dominant; the IUT sends an overload
//! flag, whose first, third or sixth bit the LT forces recessive. The IUT
//! must see a bit error at exactly that bit, with REC 0 + 8 = 8 after it,
//! and go on with an active error flag.
//!
//! Elementary tests: `iso_7_6_2_overload_flag_bit<N>`, N = 1, 3, 6.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_2".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [1, 3, 6] {
        let r = super::c7_6_1::flag_bit_error(&mut lb, true, n);
        ctx.record(&format!("iso_7_6_2_overload_flag_bit{n}"), r);
    }
    ctx.results
}
