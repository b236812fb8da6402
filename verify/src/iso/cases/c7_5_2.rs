//! ISO 16845-1:2016 clause 7.5.2 — an error-passive receiver accepts a
//! frame starting in the third intermission bit after its error frame.
//!
//! What the case checks (in our words): the IUT is error-passive (REC
//! 128); after a stuff error in the data field it sends a passive error
//! flag, which ends after six recessive bits; the LT leaves the bus
//! recessive for the flag, the 8-bit delimiter and two intermission bits,
//! and starts a valid frame in the third. The IUT must stay recessive up to
//! that frame and acknowledge and deliver it.
//!
//! Elementary test: `iso_7_5_2_frame_at_intermission_3`.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_5_2".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = super::c7_5_1::passive_then_frame(&mut lb, &[true; 6 + 8 + 2]);
    ctx.record("iso_7_5_2_frame_at_intermission_3", r);
    ctx.results
}
