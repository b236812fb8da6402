//! ISO 16845-1:2016 clause 7.6.15 — REC back into 119..127 after a valid
//! frame received while error-passive.
//!
//! What the case checks (in our words): with REC preset to an
//! error-passive value (128, and the maximum 135), the LT sends a valid
//! frame; the IUT (passive receivers acknowledge too) acknowledges and
//! delivers it, and its REC must then lie in 119..127 (canstar: 127, C11)
//! with the IUT error-active again.
//!
//! Elementary tests: `iso_7_6_15_from_rec<R>`.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;

use canstar_controller::frame::{BuildOptions, Frame};

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_15".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for rec in [128, 135] {
        let r = (|| {
            lb.begin_step("preset");
            lb.preset(0, 0, rec);
            ensure!(lb.b.state(0) == 1, "not error-passive at REC {}", lb.b.rec(0));
            receive_frame(&mut lb, &Frame::std(0x4D2, &[0x01, 0x80]), BuildOptions::default())?;
            ensure!((119..=127).contains(&lb.b.rec(0)) && lb.b.state(0) == 0, "REC {} state {}", lb.b.rec(0), lb.b.state(0));
            Ok(())
        })();
        ctx.record(&format!("iso_7_6_15_from_rec{rec}"), r);
    }
    ctx.results
}
