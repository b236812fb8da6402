//! ISO 16845-1:2016 clause 7.2.10 — the IUT as receiver: form error in
//! End_Of_Frame.
//!
//! What the case checks (in our words): the LT sends a valid frame (the
//! IUT acknowledges it) and drives one of the first five End_Of_Frame
//! bits dominant. The IUT must report a form error at that bit, drive an
//! active error flag from the next bit on, deliver nothing and count REC
//! +1. (EOF bit 6 is clause 7.2.11, bit 7 clause 7.1.12.)
//!
//! Elementary tests: `iso_7_2_10_eof<N>_dominant`, N = 1..5.

use super::super::LtBench;
use super::c7_2_7::form_error_at;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::Field;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_2_10".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in 1..=5 {
        let r = form_error_at(&mut lb, Field::Eof, n, 0, None);
        ctx.record(&format!("iso_7_2_10_eof{n}_dominant"), r);
    }
    ctx.results
}
