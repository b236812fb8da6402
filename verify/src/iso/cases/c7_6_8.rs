//! ISO 16845-1:2016 clause 7.6.8 — REC after a form error in
//! End_Of_Frame of a frame that was error-free up to the ACK slot.
//!
//! What the case checks (in our words): from REC 9 the LT sends a frame,
//! the IUT acknowledges it, and the LT drives EOF bit 2, 3 or 5 dominant.
//! The IUT must flag the form error from the next bit and deliver nothing;
//! per ISO REC drops by 1 at the ACK slot and rises by 1 at the form
//! error: REC 9 at the end.
//!
//! **Disagreement (README "Disagreements", D2).** ISO 11898-1 counts a
//! reception as successful once the ACK slot has passed without error, so
//! an ISO receiver decrements REC there and the later form error adds 1:
//! ISO 16845-1 expects REC unchanged (9). canstar follows the Bosch
//! reference model and can-protocol.md §13.2/§13.4 (C21): the decrement
//! comes only with a recessive End_Of_Frame bit 7, so REC ends at 10. The
//! check keeps the ISO value; the elementary tests are known failures.
//!
//! Elementary tests: `iso_7_6_8_eof<N>_form_error`, N = 2, 3, 5.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_8".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [2, 3, 5] {
        let r = super::c7_2_7::form_error_at(&mut lb, Field::Eof, n, 9, Some(9));
        ctx.record(&format!("iso_7_6_8_eof{n}_form_error"), r);
    }
    ctx.results
}
