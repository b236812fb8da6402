//! ISO 16845-1:2016 clause 8.6.11 — TEC −1 for a successful transmission.
//!
//! What the case checks (in our words): with TEC preset to 9, the IUT
//! transmits a frame that the LT acknowledges (every bit checked); TEC
//! must be 8 afterwards and REC unchanged (0).
//!
//! Elementary test: `iso_8_6_11_success_tec`.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::Frame;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_6_11".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        transmit_frame(&mut lb, &Frame::std(0x13C, &[0x42]), 9, 0)?;
        ensure!(lb.b.tec(0) == 8 && lb.b.rec(0) == 0, "TEC {} REC {}, expected 8 and 0", lb.b.tec(0), lb.b.rec(0));
        Ok(())
    })();
    ctx.record("iso_8_6_11_success_tec", r);
    ctx.results
}
