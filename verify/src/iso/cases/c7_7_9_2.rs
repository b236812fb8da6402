//! ISO 16845-1:2016 clause 7.7.9.2 — a receiving IUT that hard-synchronised
//! on an edge in Bus_Idle uses no further edge before its sample point.
//!
//! What the case checks (in our words): on the idle bus the LT forces a
//! group of three dominant glitches (with a = (PROP + PH1 − 2) / 2 TQ, ISO's
//! segments, i.e. (SP − 3) / 2 TQ in canstar's terms, and the minimum time
//! quantum = one clock):
//! a dominant for a, recessive for 2 TQ, dominant for a − 1 clock,
//! recessive for 1 TQ + 2 clocks, dominant for 2a. The IUT hard-synchronises
//! on the first edge; its sample point, SP TQ later, falls in the recessive
//! gap before the third glitch, so it must stay in Bus_Idle (no SOF, no
//! error, TX recessive). Had it synchronised again on the second or third
//! edge (resynchronisation by SJW ≥ 2, or a second hard synchronisation),
//! its sample point would fall in the third glitch and it would start a
//! frame, then flag a stuff error. With SJW = 1 a resynchronisation on the
//! second edge still samples in the gap (only the other two faults show).
//!
//! Timings: those of [`super::c7_7_1::timings`] with SP ≥ 4; where a is
//! not a whole number of clocks (or under 2 clocks), the timing's prescaler
//! is doubled until it is ([`with_glitch_brp`]), which the test name
//! shows. The group's timing does not depend on the phase of the IUT's TQ
//! ticks (the gap holds the sample point for any phase).
//!
//! Elementary tests: `iso_7_7_9_2_<timing>`.

use super::super::{At, LtBench, Plan, Span};
use super::c7_7_1::{iut_with, timing_name, timings};
use super::c7_7_9_1::stays_idle;
use crate::conformance::{Ctx, StepResult};
use canstar_hdl::timing::BtlConfig;

/// `t` with its prescaler doubled until a = (SP − 3) × BRP / 2 clocks is a
/// whole number of at least 2; `None` when SP < 4 (no glitch fits).
pub fn with_glitch_brp(t: BtlConfig) -> Option<BtlConfig> {
    if t.sp() < 4 {
        return None;
    }
    let mut b = t.brp;
    while ((t.sp() - 3) * b) % 2 != 0 || (t.sp() - 3) * b / 2 < 2 {
        b *= 2;
    }
    Some(t.with_brp(b))
}

fn step(lb: &mut LtBench) -> Result<(), String> {
    let t = lb.timing;
    let b = t.brp;
    let a = (t.sp() - 3) * b / 2;
    let mut p = Plan::raw(t, &[true; 12]);
    let at = |c: u32| At { bit: 1, tq: 0, clocks: c };
    p.glitch(at(0), Span::Clocks(a), false);
    p.glitch(at(a + 2 * b), Span::Clocks(a - 1), false);
    p.glitch(at(2 * a + 3 * b + 1), Span::Clocks(2 * a), false);
    stays_idle(lb, &p)?;
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_7_9_2".into(), vcd: None, results: vec![] };
    for t in timings().into_iter().filter_map(with_glitch_brp) {
        let mut lb = LtBench::new(vec![iut_with(t)]);
        let r = step(&mut lb);
        ctx.record(&format!("iso_7_7_9_2_{}", timing_name(&t)), r);
    }
    ctx.results
}
