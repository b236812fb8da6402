//! ISO 16845-1:2016 clause 7.6.6 — REC +1 for a form error at the CRC
//! delimiter.
//!
//! What the case checks (in our words): the step of 7.2.7 (dominant CRC
//! delimiter) from REC 5: REC must be exactly 6 after it.
//!
//! Elementary test: `iso_7_6_6_crc_delimiter_form_error`.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_6".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = super::c7_2_7::form_error_at(&mut lb, Field::CrcDel, 1, 5, None);
    ctx.record("iso_7_6_6_crc_delimiter_form_error", r);
    ctx.results
}
