//! ISO 16845-1:2016 clause 7.7.8 — one synchronisation per bit: two
//! recessive-to-dominant edges between two sample points of a receiving
//! IUT, the first one before the synchronisation segment.
//!
//! What the case checks (in our words): as 7.7.7, with the recessive bit
//! before the dominant stuff bit (identifier bit 5) shortened by 1 TQ: the
//! stuff bit's first edge comes 1 TQ early, in the IUT's phase segment 2
//! (phase error −1), and the IUT resynchronises on it (its bit restarts at
//! the edge). The 1-TQ recessive glitch from the third TQ of the stuff bit
//! gives a second edge before the sample point, which the IUT must ignore
//! (no sample point in between): it samples the stuff bit exactly SP TQ
//! after the first edge, detects the stuff error at the sixth recessive
//! bit after it and starts its active error flag exactly 7 bit times after
//! the first edge.
//!
//! Timings: those of [`super::c7_7_1::timings`] with SP ≥ 4 TQ (see 7.7.7).
//!
//! Elementary tests: `iso_7_7_8_<timing>`.

use super::super::LtBench;
use super::c7_7_1::{iut_with, timing_name, timings};
use super::c7_7_7::{applicable, double_edge_step};
use crate::conformance::{Ctx, StepResult};

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_7_8".into(), vcd: None, results: vec![] };
    for t in timings().into_iter().filter(applicable) {
        let mut lb = LtBench::new(vec![iut_with(t)]);
        let r = double_edge_step(&mut lb, true);
        ctx.record(&format!("iso_7_7_8_{}", timing_name(&t)), r);
    }
    ctx.results
}
