//! ISO 16845-1:2016 clause 7.6.4 — REC +8 for each eighth dominant bit
//! after the IUT's overload flag.
//!
//! What the case checks (in our words): after a valid frame (REC 0 stays
//! 0) the LT drives the first intermission bit dominant; after the IUT's
//! overload flag it keeps the bus dominant for 16 more bits. The first of
//! them must not change REC (unlike after an error flag); the 8th and the
//! 16th must add 8 each: 0, 8, 16.
//!
//! Elementary test: `iso_7_6_4_16_dominant_after_overload_flag`.

use super::super::LtBench;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_4".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let r = super::c7_6_3::dominant_after_flag(&mut lb, true, 16, 0)?;
        super::c7_6_3::check_recs(&r, Field::OvlFlag, &[(6, 0), (7, 0), (13, 0), (14, 8), (21, 8), (22, 16)])?;
        ensure!(lb.b.rec(0) == 16, "REC {} at the end", lb.b.rec(0));
        Ok(())
    })();
    ctx.record("iso_7_6_4_16_dominant_after_overload_flag", r);
    ctx.results
}
