//! ISO 16845-1:2016 clause 7.4.3 — overload frame for a dominant eighth
//! bit of an error or overload delimiter.
//!
//! What the case checks (in our words): the LT drives the last bit of the
//! IUT's error delimiter (after a stuff error in the data field) or of its
//! overload delimiter (after an overload flag caused by a dominant first
//! intermission bit) dominant. The IUT must treat it as an overload
//! condition: an overload flag from the next bit, no new error.
//!
//! Elementary tests: `iso_7_4_3_error_delimiter_bit8`,
//! `iso_7_4_3_overload_delimiter_bit8`.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_4_3".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for (start, name, field, nerr) in [(Start::ErrorInData, "error", Field::ErrDel, 1), (Start::OverloadAfterFrame, "overload", Field::OvlDel, 0)] {
        let r = (|| {
            let (r, _) = flag_scenario(&mut lb, start, &[delim(8)], &[], Some(delim(8) + 1), 0)?;
            event_at(&r, EV_OLF, field, 8)?;
            ensure!(errors(&r).len() == nerr, "errors {:?}", errors(&r));
            Ok(())
        })();
        ctx.record(&format!("iso_7_4_3_{name}_delimiter_bit8"), r);
    }
    ctx.results
}
