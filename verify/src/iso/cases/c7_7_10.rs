//! ISO 16845-1:2016 clause 7.7.10 — a receiving IUT does not
//! resynchronise on an edge after a sample point that read dominant.
//!
//! What the case checks (in our words): the LT sends the frame of 7.7.1
//! (identifier 0x7FF) up to its first dominant stuff bit (after identifier
//! bit 5, following five recessive bits) and then five more dominant bits.
//! In the stuff bit's phase segment 2 the bus is forced recessive for one
//! TQ, from SP + 1 TQ after the stuff bit's edge (ISO: NTQ − PHASE_SEG2 +
//! 1), so a recessive-to-dominant edge follows at SP + 2 TQ. The IUT's last
//! sample point read dominant, so it must not resynchronise on that edge
//! (an early edge of phase error −(PH2 − 2) otherwise): it detects a stuff
//! error at the fifth dominant bit after the stuff bit and starts its
//! active error flag exactly 6 bit times after the stuff bit's edge
//! (checked on the IUT's sample points, with the stuff bit's own sample
//! point exactly SP TQ after the edge).
//!
//! Timings: those of [`super::c7_7_1::timings`] with PH2 ≥ 3 TQ, where the
//! glitch and the edge after it both lie inside phase segment 2 (with PH2
//! ≤ 2 the edge would fall on the next bit's synchronisation segment,
//! phase error 0, and show nothing).
//!
//! Elementary tests: `iso_7_7_10_<timing>`.

use super::super::{At, LtBench, Plan, Span};
use super::c7_7_1::*;
use crate::conformance::{ensure, Ctx, StepResult};
use canstar_controller::frame::BuildOptions;
use canstar_controller::fsm::*;

fn step(lb: &mut LtBench) -> Result<(), String> {
    let sp = lb.timing.sp();
    let mut p = Plan::frame(lb.timing, &stuff_frame(), BuildOptions::default());
    let s1 = p.find(Field::Ident, 5, true).ok_or("no stuff bit after Identifier 5")?;
    ensure!(!p.bits[s1].level && p.bits[s1 - 1].level, "not a dominant stuff bit after a recessive bit");
    p.truncate(s1 + 1).push_levels(&[false; 5]).push_recessive(6 + 8 + 8 + 3);
    p.glitch(At::tq(s1, sp + 1), Span::Tq(1), true);
    let r = play(lb, &p)?;
    let b1 = iut_rec(&r, Field::Ident, 5, true)?;
    ensure!(!b1.level, "the IUT read the stuff bit recessive:{}", r.dump(0));
    sampled_at(lb, &r, s1, &b1, 0, "stuff bit")?;
    let b2 = iut_rec(&r, Field::Ident, 9, true)?;
    let fl = one_error_then_flag(&r, EV_STUFF_ERR, &b2)?;
    sampled_at(lb, &r, s1, &fl, 6, "first error flag bit")?;
    ensure!(lb.b.rec(0) == 1, "REC {}, expected 1", lb.b.rec(0));
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_7_10".into(), vcd: None, results: vec![] };
    for t in timings().into_iter().filter(|t| t.ph2 >= 3) {
        let mut lb = LtBench::new(vec![iut_with(t)]);
        let r = step(&mut lb);
        ctx.record(&format!("iso_7_7_10_{}", timing_name(&t)), r);
    }
    ctx.results
}
