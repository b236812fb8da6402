//! ISO 16845-1:2016 clause 7.6.14 — REC −1 for a valid frame.
//!
//! What the case checks (in our words): from REC 9 the LT sends a valid
//! frame; the IUT acknowledges and delivers it, and its REC must be 8.
//!
//! Elementary test: `iso_7_6_14_valid_frame`.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;

use canstar_controller::frame::{BuildOptions, Frame};

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_14".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        lb.begin_step("preset");
        lb.preset(0, 0, 9);
        receive_frame(&mut lb, &Frame::std(0x0F3, &[0x77]), BuildOptions::default())?;
        ensure!(lb.b.rec(0) == 8, "REC {}, expected 8", lb.b.rec(0));
        Ok(())
    })();
    ctx.record("iso_7_6_14_valid_frame", r);
    ctx.results
}
