//! ISO 16845-1:2016 clause 8.6.3 — TEC +8 for each eighth dominant bit
//! after the transmitting IUT's active error flag.
//!
//! What the case checks (in our words): after a bit error in the data
//! field of the IUT's frame (TEC 8) and its active error flag, the LT keeps
//! the bus dominant for 16 more bits. TEC must not change for the first 7,
//! rise by 8 at the 8th (16) and by 8 at the 16th (24); the retransmission
//! then brings it to 23.
//!
//! Elementary test: `iso_8_6_3_16_dominant_after_error_flag`.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_6_3".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let dom: Vec<usize> = (6..22).collect();
        let (r, _) = tx_flag_scenario(&mut lb, Start::ErrorInData, &dom, &[], Some((0, false)), 0)?;
        for (pos, tec) in [(7u32, 8u32), (13, 8), (14, 16), (21, 16), (22, 24)] {
            let got = tec_at(&r, Field::ActFlag, pos)?;
            ensure!(got == tec, "TEC {got} after dominant bit {} after the flag, expected {tec}", pos - 6);
        }
        ensure!(lb.b.tec(0) == 23, "TEC {} at the end, expected 23", lb.b.tec(0));
        Ok(())
    })();
    ctx.record("iso_8_6_3_16_dominant_after_error_flag", r);
    ctx.results
}
