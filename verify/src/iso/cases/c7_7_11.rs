//! ISO 16845-1:2016 clause 7.7.11 — resynchronisation of a receiving IUT
//! on an early edge (negative phase error, |e| ≤ SJW) at its own ACK bit.
//!
//! What the case checks (in our words): the LT sends a valid frame; the bus
//! is forced dominant during the last e TQ of the CRC delimiter, so the ACK
//! slot's edge comes e TQ early, while the IUT is about to send its ACK.
//! The IUT must resynchronise (its ACK bit restarts at the edge) and sample
//! its ACK bit SP TQ after the edge. To make that visible, the bus is also
//! forced recessive during the last PH2 + e TQ of the nominal ACK slot:
//! this leaves the resynchronised sample point on dominant, but an IUT that
//! kept its old bit timing would read its ACK recessive (a bit error). The
//! IUT must acknowledge and deliver the frame without any error, with its
//! ACK slot sampled dominant exactly SP TQ after the early edge.
//!
//! e = 1 .. min(SJW, PH2): ISO 11898-1 bounds SJW by PH2, canstar does not
//! (C22); an early edge is at most PH2 TQ early (a larger e would move the
//! edge before the CRC delimiter's sample point, a form error). Timings:
//! every timing of [`super::c7_7_1::timings`].
//!
//! Elementary tests: `iso_7_7_11_<timing>_e<E>`.

use super::super::{At, LtBench, Plan, Span};
use super::c7_7_1::*;
use super::common::receive_plan;
use crate::conformance::{ensure, Ctx, StepResult};
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

fn step(lb: &mut LtBench, e: u32) -> Result<(), String> {
    let t = lb.timing;
    let f = Frame::std(0x4B3, &[0x81, 0x7E]);
    lb.begin_step("early ACK edge");
    lb.preset(0, 0, 0);
    let mut p = Plan::frame(t, &f, BuildOptions::default());
    p.push_recessive(3);
    let cd = p.find(Field::CrcDel, 1, false).ok_or("no CRC delimiter")?;
    let ack = cd + 1;
    p.glitch(At::tq(cd, t.ntq() - e), Span::Tq(e), false);
    p.glitch(At::tq(ack, t.sp() - e), Span::Tq(t.ph2 + e), true);
    let r = receive_plan(lb, &p, std::slice::from_ref(&f), &[ack])?;
    let a = iut_rec(&r, Field::AckSlot, 1, false)?;
    ensure!(!a.level, "the IUT read its ACK recessive:{}", r.dump(0));
    let edge = r.bit_start(0, ack) - e as u64 * r.tq_ps;
    sampled_after(lb, &r, edge, &a, 0, "ACK slot")?;
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_7_11".into(), vcd: None, results: vec![] };
    for t in timings() {
        let mut lb = LtBench::new(vec![iut_with(t)]);
        for e in 1..=t.sjw.min(t.ph2) {
            let r = step(&mut lb, e);
            ctx.record(&format!("iso_7_7_11_{}_e{e}", timing_name(&t)), r);
        }
    }
    ctx.results
}
