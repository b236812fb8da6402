//! ISO 16845-1:2016 clause 8.7.1 — the sample point of a transmitting IUT.
//!
//! What the case checks (in our words): the IUT transmits a frame whose
//! data byte 0x55 gives several dominant bits that follow a recessive one.
//! At the first of them (data bit 3) the LT forces the bus recessive from
//! one clock (the minimum time quantum; a TQ is 4 clocks here) after the
//! sample point to the end of the bit: the IUT has already sampled the
//! bit dominant and must go on without error. At the second (data bit 5)
//! the LT forces the bus recessive from 1 TQ + 1 clock before the sample
//! point to the end of the bit: the IUT samples it recessive and must
//! report a bit error there (TEC 8), send an active error flag (six
//! dominant bits, checked) from the next bit on, and then send the frame
//! again, which the LT acknowledges and checks (TEC 7).
//!
//! Run for every sample point 3..9 TQ of a 10-TQ bit (4 clocks per TQ, see
//! [`super::c8_7_4::sp_config`]).
//!
//! Elementary tests: `iso_8_7_1_sp<SP>`.

use super::super::{Action, At, Disturbance, LtBench, Plan, Span, Target};
use super::c8_7_4::{rd_pair, sp_config};
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// Bus forced recessive from `from` to the end of its (nominal-length) bit.
fn force_to_end(p: &mut Plan, from: At) {
    let bit = p.timing.ntq() * p.timing.brp;
    let start = from.tq * p.timing.brp + from.clocks;
    p.disturb(Disturbance { at: from, span: Span::Clocks(bit - start), action: Action::Force(true), target: Target::Bus });
}

fn step(lb: &mut LtBench) -> Result<(), String> {
    let f = Frame::std(0x2A5, &[0x55]);
    let t = lb.timing;
    let mut p = Plan::answer(t, &f, BuildOptions::default(), 0);
    let d1 = rd_pair(&p, Field::Data, 0).ok_or("no recessive-dominant pair")? + 1;
    let d2 = rd_pair(&p, Field::Data, 1).ok_or("no second recessive-dominant pair")? + 1;
    force_to_end(&mut p, At { bit: d1, tq: t.sp(), clocks: 1 });
    force_to_end(&mut p, At { bit: d2, tq: t.sp() - 2, clocks: t.brp - 1 });
    let at = p.bits[d2].label.map(|l| (l.field, l.pos)).unwrap();
    let l1 = p.bits[d1].label.unwrap();
    let r = transmit_error(lb, &f, 0, p, d2, d2 + 1, EV_BIT_ERR, at, 8, false)?;
    let b1 = r.iut().iter().find(|b| (b.field, b.pos, b.stuff) == (l1.field, l1.pos, l1.stuff)).ok_or("no IUT bit for the first disturbed bit")?;
    ensure!(!b1.level, "IUT sampled {b1} recessive: the force began after its sample point");
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_7_1".into(), vcd: None, results: vec![] };
    for sp in 3..=9 {
        let mut lb = LtBench::new(vec![sp_config(sp)]);
        let r = step(&mut lb);
        ctx.record(&format!("iso_8_7_1_sp{sp}"), r);
    }
    ctx.results
}
