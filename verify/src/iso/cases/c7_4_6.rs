//! ISO 16845-1:2016 clause 7.4.6 — overload frame for a dominant bit in
//! the first two intermission bits after an error frame.
//!
//! What the case checks (in our words): after a stuff error in the data
//! field, the IUT's active error flag and error delimiter, the LT drives
//! intermission bit 1 or 2 dominant; the IUT must send an overload flag
//! from the next bit, with no new error.
//!
//! Elementary tests: `iso_7_4_6_intermission<M>_dominant`, M = 1, 2.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_4_6".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for m in [1usize, 2] {
        let r = (|| {
            let (r, _) = flag_scenario(&mut lb, Start::ErrorInData, &[inter(m)], &[], Some(inter(m) + 1), 0)?;
            event_at(&r, EV_OLF, Field::Inter, m as u32)?;
            ensure!(errors(&r).len() == 1, "errors {:?}", errors(&r));
            Ok(())
        })();
        ctx.record(&format!("iso_7_4_6_intermission{m}_dominant"), r);
    }
    ctx.results
}
