//! ISO 16845-1:2016 clause 7.2.9 — the IUT as receiver: form error at the
//! ACK delimiter.
//!
//! What the case checks (in our words): the LT sends a frame (the IUT
//! acknowledges it) whose ACK delimiter is dominant. The IUT must report a
//! form error at the ACK delimiter, drive an active error flag from the
//! first EOF bit on, deliver nothing and count REC +1.
//!
//! Elementary test: `iso_7_2_9_ack_delimiter_dominant`.

use super::super::LtBench;
use super::c7_2_7::form_error_at;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::Field;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_2_9".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = form_error_at(&mut lb, Field::AckDel, 1, 0, None);
    ctx.record("iso_7_2_9_ack_delimiter_dominant", r);
    ctx.results
}
