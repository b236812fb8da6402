//! ISO 16845-1:2016 clause 8.5.14 — recovery time of an error-passive
//! transmitter after an error.
//!
//! What the case checks (in our words): the IUT is error-passive (TEC 128)
//! and transmits a base-format data frame; the LT corrupts a recessive data
//! bit (bit error, TEC 136). The IUT's passive error flag (6 recessive bits)
//! ends undisturbed; on the bit after it the LT sends 6 dominant bits,
//! which the IUT must tolerate (no new error, TEC unchanged) while it waits
//! for a recessive bit. Then come error delimiter (8), intermission (3) and
//! suspend transmission (8): the repeated frame's SOF must start exactly 31
//! bit times after the corrupted bit. The LT acknowledges and checks the
//! repeated frame; TEC is 135 at the end.
//!
//! Elementary test: `iso_8_5_14_passive_recovery_31_bits` (the step of
//! 8.5.1 with the LT's dominant bits after the flag).

use super::super::LtBench;
use super::c8_5_1::step;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::Frame;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_5_14".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = step(&mut lb, &Frame::std(0x2B4, &[0x96, 0x3C]), 7, 31);
    ctx.record("iso_8_5_14_passive_recovery_31_bits", r);
    ctx.results
}
