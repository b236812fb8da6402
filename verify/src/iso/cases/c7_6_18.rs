//! ISO 16845-1:2016 clause 7.6.18 — no further REC increment for up to 7
//! dominant bits after the IUT's error flag.
//!
//! What the case checks (in our words): after a stuff error in the data
//! field (REC 1) and the IUT's active error flag, the LT drives 7 dominant
//! bits. Only the first of them counts (+8, REC 9); the other six must not
//! change REC.
//!
//! Elementary test: `iso_7_6_18_7_dominant_after_error_flag`.

use super::super::LtBench;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_18".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let r = super::c7_6_3::dominant_after_flag(&mut lb, false, 7, 0)?;
        super::c7_6_3::check_recs(&r, Field::ActFlag, &[(7, 9), (13, 9)])?;
        ensure!(lb.b.rec(0) == 9, "REC {} at the end, expected 9", lb.b.rec(0));
        Ok(())
    })();
    ctx.record("iso_7_6_18_7_dominant_after_error_flag", r);
    ctx.results
}
