//! ISO 16845-1:2016 clause 7.7.9.1 — a receiving IUT in Bus_Idle does not
//! take a dominant pulse of PROP + PH1 − 1 TQ for a SOF.
//!
//! What the case checks (in our words): on the idle bus the LT drives one
//! dominant pulse of PROP_SEG + PHASE_SEG1 − 1 TQ (ISO's segments: SP − 2
//! TQ in canstar's terms, SP counting the synchronisation segment), then
//! stays recessive for 9 bit times. The IUT hard-synchronises on the
//! pulse's edge, but its sample point, SP TQ after the edge, finds the bus
//! recessive again: it must stay in Bus_Idle, record no SOF and no error
//! (a SOF would end in a stuff error after five recessive bits), never
//! drive dominant and deliver nothing.
//!
//! Sample points as the IUT offers them: every timing of
//! [`super::c7_7_1::timings`].
//!
//! Elementary tests: `iso_7_7_9_1_<timing>`.
//!
//! [`stays_idle`] is shared with 7.7.9.2.

use super::super::{LtBench, Plan, StepRecord};
use super::c7_7_1::{iut_with, timing_name, timings};
use super::common::ERRORS;
use crate::conformance::{ensure, Ctx, StepResult};
use canstar_controller::fsm::*;

/// Play `p` on the idle bus in a new step and check that the IUT stays in
/// Bus_Idle: every bit it processes is a Bus_Idle bit without events, its
/// TX stays recessive on every clock, and no frame is delivered.
pub fn stays_idle(lb: &mut LtBench, p: &Plan) -> Result<StepRecord, String> {
    lb.begin_step("idle");
    let got0 = lb.b.node(0).received().len();
    lb.play_and_run(p);
    lb.run_bits(2);
    let r = lb.end_step();
    ensure!(!r.iut().is_empty(), "no IUT bit recorded");
    let ev = ERRORS | (1 << EV_SOF) | (1 << EV_OLF) | (1 << EV_AEF) | (1 << EV_PEF);
    ensure!(r.iut().iter().all(|b| b.field == Field::Idle && b.ev & ev == 0), "the IUT left Bus_Idle, read a SOF or flagged:{}", r.dump(0));
    ensure!(r.samples.iter().all(|s| s.iut_tx), "the IUT drove dominant:{}", r.dump(0));
    ensure!(lb.b.node(0).field() == Field::Idle, "IUT in {} at the end", lb.b.node(0).field().name());
    ensure!(lb.b.node(0).received().len() == got0, "a frame was delivered");
    ensure!(lb.b.rec(0) == 0 && lb.b.tec(0) == 0, "TEC {} REC {}", lb.b.tec(0), lb.b.rec(0));
    Ok(r)
}

fn step(lb: &mut LtBench) -> Result<(), String> {
    let t = lb.timing;
    let mut p = Plan::raw(t, &[true, false]);
    p.bits[1].tq = t.sp() - 2;
    p.push_recessive(9);
    stays_idle(lb, &p)?;
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_7_9_1".into(), vcd: None, results: vec![] };
    for t in timings() {
        let mut lb = LtBench::new(vec![iut_with(t)]);
        let r = step(&mut lb);
        ctx.record(&format!("iso_7_7_9_1_{}", timing_name(&t)), r);
    }
    ctx.results
}
