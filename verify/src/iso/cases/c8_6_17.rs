//! ISO 16845-1:2016 clause 8.6.17 — no TEC increment for an ACK error of
//! an error-passive transmitter whose passive flag sees no dominant bit.
//!
//! What the case checks (in our words): with TEC preset to 128
//! (error-passive), the IUT transmits a frame the LT does not acknowledge.
//! The IUT must report the ACK error, send a passive error flag (recessive)
//! from the ACK delimiter on; as the bus stays recessive during that flag,
//! TEC must not change (can-protocol.md §13.3 exception 1). After its
//! suspend period it sends the frame again, acknowledged, and TEC goes to
//! 127.
//!
//! Elementary test: `iso_8_6_17_passive_ack_error_tec`.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_6_17".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = super::c8_2_6::ack_error(&mut lb, 128, true);
    ctx.record("iso_8_6_17_passive_ack_error_tec", r);
    ctx.results
}
