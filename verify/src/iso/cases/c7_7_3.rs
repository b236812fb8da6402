//! ISO 16845-1:2016 clause 7.7.3 — resynchronisation of a receiving IUT
//! on a late edge (positive phase error e ≤ SJW).
//!
//! What the case checks (in our words): the IUT uses T10/6/2 (10 TQ per
//! bit, sample point after 6 TQ, SJW 2, phase segment 2 of 4 TQ); the LT
//! sends a frame in which one recessive data bit followed by a dominant
//! bit is lengthened by e TQ, so the recessive-to-dominant edge comes e TQ
//! late. The IUT must lengthen its phase segment 1 by e: its sample points
//! of the two bits lie 10 + e TQ apart (measured on the IUT's bit
//! records), and it receives the frame without error.
//!
//! The LT shares the IUT's clock: the phase error comes from the LT's
//! edge placement, no oscillator difference is needed (ISO's 7.8 and 8.8
//! data-phase clauses are CAN FD only).
//!
//! Elementary tests: `iso_7_7_3_e<E>`, e = 1..SJW.

use super::super::{LtBench, Plan, StepRecord};
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// The IUT's timing in the bit-timing cases: T10/6/2 (PH2 4).
pub fn iut() -> NodeConfig {
    NodeConfig::named("iut").timing(1, 1, 4, 2)
}

/// The frame of the bit-timing cases.
pub fn frame() -> Frame {
    Frame::std(0x2A5, &[0x3C, 0xA5])
}

/// Plan bit `x`: a recessive data bit (not a stuff bit) followed by a
/// dominant one (not a stuff bit).
pub fn rd_edge(p: &Plan) -> usize {
    (0..p.bits.len() - 1)
        .find(|&i| p.bits[i].level && !p.bits[i + 1].level && p.bits[i].label.is_some_and(|l| l.field == Field::Data && !l.stuff) && p.bits[i + 1].label.is_some_and(|l| !l.stuff))
        .expect("a recessive-dominant edge in the data field")
}

/// Time in TQ between the IUT's sample points of plan bits `x` and `x + 1`.
pub fn sample_gap_tq(r: &StepRecord, p: &Plan, x: usize) -> Result<u64, String> {
    let lab = |i: usize| p.bits[i].label.unwrap();
    let find = |i: usize| r.iut().iter().position(|b| (b.field, b.pos, b.stuff) == (lab(i).field, lab(i).pos, lab(i).stuff)).ok_or(format!("no IUT bit for plan bit {i}"));
    let (a, b) = (find(x)?, find(x + 1)?);
    ensure!(b == a + 1, "IUT bits not consecutive");
    Ok((r.iut()[b].t - r.iut()[a].t) / r.tq_ps)
}

/// Bit `x` of the frame lengthened (`k` > 0) or shortened (`k` < 0) by
/// |k| TQ; the IUT must sample the next bit `want` TQ after bit `x`'s
/// sample point and receive the frame without error.
pub fn resync_step(lb: &mut LtBench, k: i32, want: u64) -> Result<(), String> {
    let f = frame();
    lb.begin_step("resync");
    let mut p = Plan::frame(lb.timing, &f, BuildOptions::default());
    let x = rd_edge(&p);
    if k > 0 {
        p.lengthen(x, k as u32);
    } else {
        p.shorten(x, (-k) as u32);
    }
    p.push_recessive(3);
    let ack = p.find(Field::AckSlot, 1, false).unwrap();
    let r = receive_plan(lb, &p, std::slice::from_ref(&f), &[ack])?;
    let gap = sample_gap_tq(&r, &p, x)?;
    ensure!(gap == want, "sample points {gap} TQ apart, expected {want}");
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_7_3".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![iut()]);
    let sjw = lb.timing.sjw;
    for e in 1..=sjw {
        let r = resync_step(&mut lb, e as i32, 10 + e as u64);
        ctx.record(&format!("iso_7_7_3_e{e}"), r);
    }
    ctx.results
}
