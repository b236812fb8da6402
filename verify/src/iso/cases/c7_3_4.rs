//! ISO 16845-1:2016 clause 7.3.4 — form error in the IUT's error
//! delimiter.
//!
//! What the case checks (in our words): after a stuff error in the data
//! field and the IUT's active error flag, the LT drives the 2nd, 4th or 7th
//! error delimiter bit dominant. The IUT must report a form error at that
//! bit and start a new active error flag with the next bit.
//!
//! Elementary tests: `iso_7_3_4_error_delimiter_bit<N>`, N = 2, 4, 7.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_3_4".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [2usize, 4, 7] {
        let r = (|| {
            let (r, _) = flag_scenario(&mut lb, Start::ErrorInData, &[delim(n)], &[], Some(delim(n) + 1), 0)?;
            let b = event_at(&r, EV_FORM_ERR, Field::ErrDel, n as u32)?;
            ensure!(b.has(EV_AEF), "no new active error flag after {b}");
            Ok(())
        })();
        ctx.record(&format!("iso_7_3_4_error_delimiter_bit{n}"), r);
    }
    ctx.results
}
