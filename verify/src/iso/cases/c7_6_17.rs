//! ISO 16845-1:2016 clause 7.6.17 — no REC change for an overload flag
//! lengthened to 13 bits.
//!
//! What the case checks (in our words): from REC 9 the LT sends a valid
//! frame (REC 8) and drives the first intermission bit dominant; after the
//! IUT's 6-bit overload flag the LT drives 7 more dominant bits. Fewer than
//! eight dominant bits after an overload flag cost nothing: REC must be 8.
//!
//! Elementary test: `iso_7_6_17_7_dominant_after_overload_flag`.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_17".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let r = super::c7_6_3::dominant_after_flag(&mut lb, true, 7, 9)?;
        ensure!(errors(&r).is_empty(), "errors {:?}", errors(&r));
        ensure!(lb.b.rec(0) == 8, "REC {}, expected 8:{}", lb.b.rec(0), r.dump(0));
        Ok(())
    })();
    ctx.record("iso_7_6_17_7_dominant_after_overload_flag", r);
    ctx.results
}
