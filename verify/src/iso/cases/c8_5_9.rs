//! ISO 16845-1:2016 clause 8.5.9 — an error-passive transmitter that sees
//! a frame begin after its error frame, before its suspend is over, becomes
//! a receiver.
//!
//! What the case checks (in our words): the IUT is error-passive (TEC 128)
//! and transmits a base-format data frame; the LT overwrites its first
//! recessive data bit with a dominant one (bit error, TEC 136) and leaves
//! the bus recessive for the IUT's passive error flag, error delimiter and
//! intermission; the LT then starts a frame of lower priority than the
//! IUT's in the third intermission bit, the first or the seventh suspend
//! bit. The IUT must not take that SOF as its own (an error-active IUT
//! would go on with its identifier after a dominant third intermission
//! bit): it stays recessive up to the end of the LT's frame except for the
//! ACK, delivers the frame, and only then repeats its own, right after the
//! 3 intermission bits (the LT checks every bit of it). TEC is 135 at the
//! end.
//!
//! Elementary tests: `iso_8_5_9_sof_at_intermission3`,
//! `iso_8_5_9_sof_at_suspend1`, `iso_8_5_9_sof_at_suspend7`.

use super::super::LtBench;
use super::c8_5_2::frame_after;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_5_9".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for (name, before) in [("intermission3", 6 + 8 + 2), ("suspend1", 6 + 8 + 3), ("suspend7", 6 + 8 + 3 + 6)] {
        let r = frame_after(&mut lb, vec![true; before]);
        ctx.record(&format!("iso_8_5_9_sof_at_{name}"), r);
    }
    ctx.results
}
