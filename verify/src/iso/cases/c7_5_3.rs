//! ISO 16845-1:2016 clause 7.5.3 — an error-passive receiver detects no
//! error for up to 7 dominant bits after its passive error flag.
//!
//! What the case checks (in our words): the IUT is error-passive (REC
//! 128); after its passive error flag (six recessive bits after a stuff
//! error in the data field) the LT sends 1, 4 or 7 dominant bits, then 8 + 2
//! recessive bits and a valid frame in the third intermission bit. The IUT
//! must stay recessive, detect no further error, and acknowledge and
//! deliver the frame.
//!
//! Elementary tests: `iso_7_5_3_<K>_dominant`, K = 1, 4, 7.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_5_3".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for k in [1usize, 4, 7] {
        let mut v = vec![true; 6];
        v.extend(vec![false; k]);
        v.extend([true; 8 + 2]);
        let r = super::c7_5_1::passive_then_frame(&mut lb, &v);
        ctx.record(&format!("iso_7_5_3_{k}_dominant"), r);
    }
    ctx.results
}
