//! ISO 16845-1:2016 clause 7.6.1 — REC +8 for a bit error in the IUT's
//! own active error flag.
//!
//! What the case checks (in our words): the IUT (REC 0) sends an active
//! error flag after a stuff error in the data field (REC 1); the LT forces
//! the bus recessive for the first, third or sixth flag bit. The IUT must
//! see a bit error at exactly that flag bit, with REC 1 + 8 = 9 after it,
//! and restart its flag.
//!
//! Elementary tests: `iso_7_6_1_flag_bit<N>`, N = 1, 3, 6.

use super::super::{Action, At, Disturbance, LtBench, Span, Target};
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;


pub fn flag_bit_error(lb: &mut LtBench, overload: bool, n: u32) -> Result<(), String> {
    let (mut p, f) = if overload { overload_after_frame(lb) } else { error_in_data(lb) };
    let at = f + n as usize - 1;
    p.push_recessive(50);
    p.disturb(Disturbance { at: At::tq(at, 0), span: Span::Bits(1), action: Action::Force(true), target: Target::Bus });
    let r = play_step(lb, &p, 0)?;
    let (field, before, after) = if overload { (Field::OvlFlag, 0, 8) } else { (Field::ActFlag, 1, 9) };
    let e = errors(&r);
    ensure!(e.len() == 1 + !overload as usize, "errors {e:?}");
    let b = e.last().unwrap();
    ensure!(b.has(EV_BIT_ERR) && (b.field, b.pos) == (field, n), "bit error at {b}, expected {} {n}", field.name());
    ensure!(b.rec == after, "REC {} after the bit error, expected {after} ({before} + 8):{}", b.rec, r.dump(0));
    ensure!(r.iut_events(EV_AEF).len() == 1 + !overload as usize, "the IUT did not restart with an active error flag:{}", r.dump(0));
    ensure!(lb.b.rec(0) == after, "REC {} at the end, expected {after}", lb.b.rec(0));
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_1".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [1, 3, 6] {
        let r = flag_bit_error(&mut lb, false, n);
        ctx.record(&format!("iso_7_6_1_flag_bit{n}"), r);
    }
    ctx.results
}
