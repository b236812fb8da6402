//! ISO 16845-1:2016 clause 7.7.5 — resynchronisation of a receiving IUT
//! on an early edge (negative phase error, |e| ≤ SJW).
//!
//! What the case checks (in our words): as 7.7.3 (T10/6/2) with the
//! recessive bit shortened by |e| = 1..SJW TQ, so the dominant bit's edge
//! comes |e| TQ early, in the IUT's phase segment 2. The IUT must shorten
//! that segment by |e| (restart the bit at the edge): its sample points lie
//! 10 − |e| TQ apart, and it receives the frame without error. No
//! oscillator difference is needed.
//!
//! Elementary tests: `iso_7_7_5_e<E>`.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};

use super::c7_7_3::{iut, resync_step};

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_7_5".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![iut()]);
    let sjw = lb.timing.sjw;
    for e in 1..=sjw {
        let r = resync_step(&mut lb, -(e as i32), 10 - e as u64);
        ctx.record(&format!("iso_7_7_5_e{e}"), r);
    }
    ctx.results
}
