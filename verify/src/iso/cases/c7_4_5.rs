//! ISO 16845-1:2016 clause 7.4.5 — form error in the IUT's overload
//! delimiter.
//!
//! What the case checks (in our words): after a valid frame and the IUT's
//! overload flag, the LT drives the 2nd, 4th or 7th overload delimiter bit
//! dominant. The IUT must report a form error at that bit and send an
//! active error flag from the next bit.
//!
//! Elementary tests: `iso_7_4_5_overload_delimiter_bit<N>`, N = 2, 4, 7.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_4_5".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [2usize, 4, 7] {
        let r = (|| {
            let (r, _) = flag_scenario(&mut lb, Start::OverloadAfterFrame, &[delim(n)], &[], Some(delim(n) + 1), 0)?;
            let b = event_at(&r, EV_FORM_ERR, Field::OvlDel, n as u32)?;
            ensure!(b.has(EV_AEF), "no active error flag after {b}");
            Ok(())
        })();
        ctx.record(&format!("iso_7_4_5_overload_delimiter_bit{n}"), r);
    }
    ctx.results
}
