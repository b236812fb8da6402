//! ISO 16845-1:2016 clause 7.7.7 — one synchronisation per bit: two
//! recessive-to-dominant edges between the synchronisation segment and the
//! sample point of a receiving IUT.
//!
//! What the case checks (in our words): the LT sends the frame of 7.7.1
//! (identifier 0x7FF); in its first dominant stuff bit (after identifier
//! bit 5) the bus is forced recessive for one TQ from the third TQ on (a
//! 1-TQ glitch), so the bit has a second recessive-to-dominant edge, 3 TQ
//! after the first, before the sample point. The IUT synchronises on the
//! first edge (phase error 0) and must ignore the second (a late edge would
//! lengthen phase segment 1 by min(3, SJW)): it samples the stuff bit
//! exactly SP TQ after its first edge. The stuff bit is followed by six
//! recessive bits (the LT sends the next stuff bit, due dominant,
//! recessive), so the IUT detects a stuff error at the sixth and starts
//! its active error flag exactly 7 bit times after the stuff bit's first
//! edge (checked on the IUT's sample points).
//!
//! Timings: those of [`super::c7_7_1::timings`] whose sample point comes
//! after the glitch and the second edge (SP ≥ 4 TQ: the edge in TQ 3 must
//! precede the sample point, which reads TQ SP − 1).
//!
//! Elementary tests: `iso_7_7_7_<timing>`.
//!
//! [`double_edge_step`] is shared with 7.7.8 (the same with the first edge
//! 1 TQ early).

use super::super::{At, LtBench, Plan, Span};
use super::c7_7_1::*;
use crate::conformance::{ensure, Ctx, StepResult};
use canstar_controller::frame::BuildOptions;
use canstar_controller::fsm::*;
use canstar_hdl::timing::BtlConfig;

/// The timings the case applies to (SP ≥ 4).
pub fn applicable(t: &BtlConfig) -> bool {
    t.sp() >= 4
}

/// The step of 7.7.7 (`early` false) and 7.7.8 (`early`: the recessive bit
/// before the stuff bit shortened by 1 TQ, so its first edge is 1 TQ early).
pub fn double_edge_step(lb: &mut LtBench, early: bool) -> Result<(), String> {
    let mut p = Plan::frame(lb.timing, &stuff_frame(), BuildOptions::default());
    let s1 = p.find(Field::Ident, 5, true).ok_or("no stuff bit after Identifier 5")?;
    let s2 = p.find(Field::Ident, 10, true).ok_or("no stuff bit after Identifier 10")?;
    ensure!(!p.bits[s1].level && p.bits[s1 - 1].level && (s1 + 1..s2).all(|i| p.bits[i].level), "not a dominant stuff bit between recessive bits");
    if early {
        p.shorten(s1 - 1, 1);
    }
    p.glitch(At::tq(s1, 2), Span::Tq(1), true);
    p.set_level(s2, true).truncate(s2 + 1).push_recessive(6 + 8 + 8 + 3);
    let r = play(lb, &p)?;
    let b1 = iut_rec(&r, Field::Ident, 5, true)?;
    ensure!(!b1.level, "the IUT read the stuff bit recessive:{}", r.dump(0));
    sampled_at(lb, &r, s1, &b1, 0, "stuff bit with two edges")?;
    let b2 = iut_rec(&r, Field::Ident, 10, true)?;
    let fl = one_error_then_flag(&r, EV_STUFF_ERR, &b2)?;
    sampled_at(lb, &r, s1, &fl, 7, "first error flag bit")?;
    ensure!(lb.b.rec(0) == 1, "REC {}, expected 1", lb.b.rec(0));
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_7_7".into(), vcd: None, results: vec![] };
    for t in timings().into_iter().filter(applicable) {
        let mut lb = LtBench::new(vec![iut_with(t)]);
        let r = double_edge_step(&mut lb, false);
        ctx.record(&format!("iso_7_7_7_{}", timing_name(&t)), r);
    }
    ctx.results
}
