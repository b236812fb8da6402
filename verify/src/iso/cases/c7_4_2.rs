//! ISO 16845-1:2016 clause 7.4.2 — overload frame for a dominant last
//! End_Of_Frame bit.
//!
//! What the case checks (in our words): the LT drives the seventh EOF bit
//! of a valid frame dominant; the IUT must send an overload flag from the
//! next bit (and, as in 7.1.12, deliver the frame without error).
//!
//! Elementary test: `iso_7_4_2_eof7_dominant`.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_4_2".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = super::c7_1_12::eof7_overload(&mut lb);
    ctx.record("iso_7_4_2_eof7_dominant", r);
    ctx.results
}
