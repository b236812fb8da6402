//! ISO 16845-1:2016 clause 8.7.5 — resynchronisation of a transmitting IUT
//! on an early edge with |e| > SJW.
//!
//! What the case checks (in our words): as 8.7.4, on a timing whose PH2
//! leaves room for |e| > SJW within PH2 − IPT: 10 TQ per bit, sample point
//! after 5 TQ, PH2 5, SJW 1, IPT 2. The LT drives the bus dominant |e| TQ
//! (2, 3) before the IUT's own recessive-to-dominant edge in the
//! arbitration field. The IUT may shorten PH2 by SJW only: its sample
//! points of the two bits lie 10 − SJW TQ apart, every edge it sends
//! afterwards (up to the ACK slot) lies |e| − SJW TQ plus an integer number
//! of bit times after the LT's edge (the LT's answer follows that grid),
//! and the frame completes without error. On T10/6/2 (8.7.4's timing)
//! PH2 − IPT equals SJW, which leaves no value to test.
//!
//! Elementary tests: `iso_8_7_5_e<E>`, |e| = SJW + 1 .. PH2 − IPT.

use super::super::LtBench;
use super::c8_7_4::arbitration_step;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_7_5".into(), vcd: None, results: vec![] };
    let mut cfg = NodeConfig::named("iut").timing(1, 1, 3, 1);
    cfg.timing = cfg.timing.with_ph2(5);
    let mut lb = LtBench::new(vec![cfg]);
    let t = lb.timing;
    for e in t.sjw + 1..=t.ph2 - t.ipt() {
        let r = arbitration_step(&mut lb, e);
        ctx.record(&format!("iso_8_7_5_e{e}"), r);
    }
    ctx.results
}
