//! ISO 16845-1:2016 clause 7.7.6 — resynchronisation of a receiving IUT
//! on an early edge with |e| > SJW.
//!
//! What the case checks (in our words): as 7.7.5 (T10/6/2) with the
//! recessive bit shortened by |e| = SJW + 1 .. PH2 TQ (3, 4): the IUT may
//! shorten phase segment 2 by SJW only, so its sample points lie
//! 10 − SJW = 8 TQ apart, and the frame is received without error. No
//! oscillator difference is needed.
//!
//! Elementary tests: `iso_7_7_6_e<E>`.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};

use super::c7_7_3::{iut, resync_step};

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_7_6".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![iut()]);
    let sjw = lb.timing.sjw;
    for e in sjw + 1..=lb.timing.ph2 {
        let r = resync_step(&mut lb, -(e as i32), 10 - sjw as u64);
        ctx.record(&format!("iso_7_7_6_e{e}"), r);
    }
    ctx.results
}
