//! ISO 16845-1:2016 clause 7.6.10 — REC +1 for a CRC error.
//!
//! What the case checks (in our words): the step of 7.2.5 (one CRC bit
//! inverted, the stuffing unchanged) from REC 5: the IUT leaves the ACK
//! slot recessive, flags from the first EOF bit and ends with REC 6.
//!
//! Elementary test: `iso_7_6_10_crc_error`.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;

use canstar_controller::frame::Frame;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_10".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = super::c7_2_5::crc_error(&mut lb, &Frame::std(0x35C, &[0x96, 0x0E]), false, 5).map(|_| ());
    ctx.record("iso_7_6_10_crc_error", r);
    ctx.results
}
