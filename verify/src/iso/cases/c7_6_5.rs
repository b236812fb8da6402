//! ISO 16845-1:2016 clause 7.6.5 — REC +1 for a bit error in the IUT's
//! ACK bit.
//!
//! What the case checks (in our words): the step of 7.2.1 (the IUT's
//! dominant ACK bit read back recessive) from REC 5: the bit error at the
//! ACK slot must raise REC to exactly 6 (no success decrement, no +8).
//!
//! Elementary test: `iso_7_6_5_ack_bit_error`.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_5".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = super::c7_2_1::ack_bit_error(&mut lb, 5);
    ctx.record("iso_7_6_5_ack_bit_error", r);
    ctx.results
}
