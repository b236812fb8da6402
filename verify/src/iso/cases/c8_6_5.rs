//! ISO 16845-1:2016 clause 8.6.5 — TEC +8 for each eighth dominant bit
//! after the transmitting IUT's overload flag.
//!
//! What the case checks (in our words): after its successful frame (TEC 0)
//! the IUT answers a dominant first intermission bit with an overload
//! flag; the LT then keeps the bus dominant for 16 more bits. TEC must rise
//! by 8 at the 8th and at the 16th of them only: 8, then 16.
//!
//! Elementary test: `iso_8_6_5_16_dominant_after_overload_flag`.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_6_5".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let dom: Vec<usize> = (6..22).collect();
        let (r, _) = tx_flag_scenario(&mut lb, Start::OverloadAfterFrame, &dom, &[], Some((0, false)), 0)?;
        for (pos, tec) in [(7u32, 0u32), (13, 0), (14, 8), (21, 8), (22, 16)] {
            let got = tec_at(&r, Field::OvlFlag, pos)?;
            ensure!(got == tec, "TEC {got} after dominant bit {} after the flag, expected {tec}", pos - 6);
        }
        ensure!(lb.b.tec(0) == 16, "TEC {} at the end, expected 16", lb.b.tec(0));
        Ok(())
    })();
    ctx.record("iso_8_6_5_16_dominant_after_overload_flag", r);
    ctx.results
}
