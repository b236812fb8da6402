//! ISO 16845-1:2016 clause 8.6.13 — no TEC change for a 13-bit overload
//! flag after the IUT's frame.
//!
//! What the case checks (in our words): after its successful frame (TEC 9
//! before, 8 after) the IUT answers a dominant first intermission bit with
//! an overload flag, which the LT lengthens by 7 dominant bits. TEC must
//! stay 8, with no error.
//!
//! Elementary test: `iso_8_6_13_13_bit_overload_flag`.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_6_13".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let dom: Vec<usize> = (6..13).collect();
        let (r, _) = tx_flag_scenario(&mut lb, Start::OverloadAfterFrame, &dom, &[], Some((0, false)), 9)?;
        ensure!(errors(&r).is_empty(), "errors {:?}", errors(&r));
        ensure!(lb.b.tec(0) == 8, "TEC {} at the end, expected 8", lb.b.tec(0));
        Ok(())
    })();
    ctx.record("iso_8_6_13_13_bit_overload_flag", r);
    ctx.results
}
