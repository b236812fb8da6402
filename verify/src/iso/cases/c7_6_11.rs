//! ISO 16845-1:2016 clause 7.6.11 — REC +8 for a dominant bit right
//! after the IUT's active error flag.
//!
//! What the case checks (in our words): after a stuff error in the data
//! field (REC 1) and the IUT's active error flag, the LT drives one more
//! dominant bit. REC must rise by 8 at that bit (9) and stay there.
//!
//! Elementary test: `iso_7_6_11_dominant_after_error_flag`.

use super::super::LtBench;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_11".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let r = super::c7_6_3::dominant_after_flag(&mut lb, false, 1, 0)?;
        super::c7_6_3::check_recs(&r, Field::ActFlag, &[(6, 1), (7, 9)])?;
        ensure!(lb.b.rec(0) == 9, "REC {} at the end", lb.b.rec(0));
        Ok(())
    })();
    ctx.record("iso_7_6_11_dominant_after_error_flag", r);
    ctx.results
}
