//! ISO 16845-1:2016 clause 7.4.7 — overload frame for a dominant bit in
//! the first two intermission bits after an overload frame.
//!
//! What the case checks (in our words): after a valid frame, a dominant
//! first intermission bit and the IUT's overload flag and delimiter, the LT
//! drives the next intermission's bit 1 or 2 dominant; the IUT must send
//! another overload flag from the next bit, with no error.
//!
//! Elementary tests: `iso_7_4_7_intermission<M>_dominant`, M = 1, 2.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_4_7".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for m in [1usize, 2] {
        let r = (|| {
            let (r, _) = flag_scenario(&mut lb, Start::OverloadAfterFrame, &[inter(m)], &[], Some(inter(m) + 1), 0)?;
            let o = r.iut_events(EV_OLF);
            ensure!(o.len() == 2 && (o[1].field, o[1].pos) == (Field::Inter, m as u32), "overload flags {o:?}");
            ensure!(errors(&r).is_empty(), "errors {:?}", errors(&r));
            Ok(())
        })();
        ctx.record(&format!("iso_7_4_7_intermission{m}_dominant"), r);
    }
    ctx.results
}
