//! ISO 16845-1:2016 clause 7.7.4 — resynchronisation of a receiving IUT
//! on a late edge with a positive phase error e > SJW.
//!
//! What the case checks (in our words): as 7.7.3 (T10/6/2) with the
//! recessive bit lengthened by e = SJW + 1 .. NTQ − PH2 − 1 TQ (3..5): the
//! IUT may lengthen phase segment 1 by SJW only, so its sample points lie
//! 10 + SJW = 12 TQ apart, and the frame is still received without error.
//! No oscillator difference is needed.
//!
//! Elementary tests: `iso_7_7_4_e<E>`.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};

use super::c7_7_3::{iut, resync_step};

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_7_4".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![iut()]);
    let sjw = lb.timing.sjw;
    for e in sjw + 1..=10 - lb.timing.ph2 - 1 {
        let r = resync_step(&mut lb, e as i32, 10 + sjw as u64);
        ctx.record(&format!("iso_7_7_4_e{e}"), r);
    }
    ctx.results
}
