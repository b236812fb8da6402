//! ISO 16845-1:2016 clause 8.5.3 — an error-passive transmitter detects no
//! error for up to 7 dominant bits after its passive error flag.
//!
//! What the case checks (in our words): the IUT is error-passive (TEC 128)
//! and transmits a base-format data frame; the LT overwrites its first
//! recessive data bit with a dominant one (bit error, TEC 136). After the
//! IUT's passive error flag (six recessive bits) the LT sends 1, 4 or 7
//! dominant bits, which the IUT must tolerate (no new error, TEC unchanged)
//! while it waits for a recessive bit; the LT then leaves the bus recessive
//! for 8 + 3 bits (error delimiter and intermission) and sends a valid
//! frame, which starts in the IUT's first suspend bit. The IUT must stay
//! recessive from its flag on except for its ACK of the LT's frame, deliver
//! that frame, and send its own frame again 1 + 7 + 3 bit times after that
//! ACK bit (ACK delimiter, End_Of_Frame, intermission; no suspend, it was a
//! receiver); the LT checks every bit of it. TEC is 135 at the end.
//!
//! Elementary tests: `iso_8_5_3_<K>_dominant`, K = 1, 4, 7.

use super::super::LtBench;
use super::c8_5_2::frame_after;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_5_3".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for k in [1usize, 4, 7] {
        let mut v = vec![true; 6];
        v.extend(vec![false; k]);
        v.extend([true; 8 + 3]);
        let r = frame_after(&mut lb, v);
        ctx.record(&format!("iso_8_5_3_{k}_dominant"), r);
    }
    ctx.results
}
