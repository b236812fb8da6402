//! ISO 16845-1:2016 clause 8.6.12 — TEC −1 for a successful transmission
//! of an error-passive transmitter.
//!
//! What the case checks (in our words): with TEC preset to 128 (the IUT is
//! error-passive), the IUT transmits a frame that the LT acknowledges
//! (every bit the IUT drives checked). TEC must be 127 after the frame, REC
//! unchanged (0), and the IUT error-active again.
//!
//! Elementary test: `iso_8_6_12_passive_success_tec` (the classical-CAN
//! test; the CAN FD variant of the standard does not apply).

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::Frame;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_6_12".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let r = transmit_frame(&mut lb, &Frame::std(0x5D3, &[0x81, 0x7E]), 128, 0)?;
        ensure!(r.iut().first().is_some_and(|b| b.state == 1), "not error-passive while transmitting:{}", r.dump(0));
        ensure!(lb.b.tec(0) == 127 && lb.b.rec(0) == 0, "TEC {} REC {}, expected 127 and 0", lb.b.tec(0), lb.b.rec(0));
        ensure!(lb.b.state(0) == 0, "state {} at the end, expected error-active", lb.b.state(0));
        Ok(())
    })();
    ctx.record("iso_8_6_12_passive_success_tec", r);
    ctx.results
}
