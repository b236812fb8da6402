//! ISO 16845-1:2016 clause 8.6.20 — TEC unchanged by a frame the IUT
//! receives.
//!
//! What the case checks (in our words): with TEC preset to 9 and REC 0,
//! the LT sends a valid frame; the IUT acknowledges and delivers it and
//! TEC must still be 9.
//!
//! Elementary test: `iso_8_6_20_reception_tec`.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_6_20".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        lb.begin_step("preset");
        lb.preset(0, 9, 0);
        receive_frame(&mut lb, &Frame::std(0x6F1, &[0x10, 0x20]), BuildOptions::default())?;
        ensure!(lb.b.tec(0) == 9 && lb.b.rec(0) == 0, "TEC {} REC {}, expected 9 and 0", lb.b.tec(0), lb.b.rec(0));
        Ok(())
    })();
    ctx.record("iso_8_6_20_reception_tec", r);
    ctx.results
}
