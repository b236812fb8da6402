//! ISO 16845-1:2016 clause 8.3.4 — form error in the transmitting IUT's
//! error delimiter.
//!
//! What the case checks (in our words): after a bit error in the data
//! field of the IUT's frame (TEC 8) and its active error flag, the LT drives
//! the 2nd, 4th or 7th error delimiter bit dominant. The IUT must report a
//! form error at that bit (TEC 16, clause 8.6.9's +8), start a new active
//! error flag with the next bit, and later send the frame again (TEC 15).
//!
//! Elementary tests: `iso_8_3_4_error_delimiter_bit<N>`, N = 2, 4, 7.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_3_4".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [2usize, 4, 7] {
        let r = (|| {
            let (r, _) = tx_flag_scenario(&mut lb, Start::ErrorInData, &[delim(n)], &[], Some((delim(n) + 1, false)), 0)?;
            let b = event_at(&r, EV_FORM_ERR, Field::ErrDel, n as u32)?;
            ensure!(b.has(EV_AEF) && b.tec == 16, "at {b}: a new active flag and TEC 16 expected");
            ensure!(lb.b.tec(0) == 15, "TEC {} at the end, expected 15", lb.b.tec(0));
            Ok(())
        })();
        ctx.record(&format!("iso_8_3_4_error_delimiter_bit{n}"), r);
    }
    ctx.results
}
