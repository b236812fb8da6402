//! ISO 16845-1:2016 clause 8.6.14 — no further TEC change for a 13-bit
//! error flag.
//!
//! What the case checks (in our words): after a bit error in the data
//! field of the IUT's frame (TEC 9 + 8 = 17) and its active error flag, the
//! LT lengthens the flag by 7 dominant bits. TEC must stay 17 through them
//! (16 after the successful retransmission).
//!
//! Elementary test: `iso_8_6_14_13_bit_error_flag`.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_6_14".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let dom: Vec<usize> = (6..13).collect();
        let (r, _) = tx_flag_scenario(&mut lb, Start::ErrorInData, &dom, &[], Some((0, false)), 9)?;
        ensure!(tec_at(&r, Field::ActFlag, 13)? == 17, "TEC after the 7th dominant bit");
        ensure!(errors(&r).len() == 1, "errors {:?}", errors(&r));
        ensure!(lb.b.tec(0) == 16, "TEC {} at the end, expected 16", lb.b.tec(0));
        Ok(())
    })();
    ctx.record("iso_8_6_14_13_bit_error_flag", r);
    ctx.results
}
