//! ISO 16845-1:2016 clause 8.6.8 — TEC +8 for an ACK error of an
//! error-active transmitter.
//!
//! What the case checks (in our words): the step of 8.2.6 from TEC 5: the
//! ACK error must raise TEC to exactly 13 at the ACK slot, and the
//! successful retransmission bring it to 12.
//!
//! Elementary test: `iso_8_6_8_ack_error_tec`.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_6_8".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = super::c8_2_6::ack_error(&mut lb, 5, false);
    ctx.record("iso_8_6_8_ack_error_tec", r);
    ctx.results
}
