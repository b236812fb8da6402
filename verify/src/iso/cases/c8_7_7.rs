//! ISO 16845-1:2016 clause 8.7.7 — no resynchronisation of a transmitting
//! IUT on a late edge while it sends a dominant bit.
//!
//! What the case checks (in our words): the IUT transmits a base-format
//! frame; at every recessive-to-dominant edge the IUT itself sends (SOF to
//! the end of the CRC, stuff bits included) the LT forces the bus recessive
//! for the first 2 TQ of the dominant bit, so every such edge reaches the
//! IUT 2 TQ late (a positive phase error while it drives dominant). The IUT
//! must not resynchronise: its sample points stay exactly one bit time
//! apart from SOF to the ACK slot, every edge it sends lies an integer
//! number of bit times after its SOF, and the frame completes without
//! error (every bit it drives checked). The ACK slot, where the LT and not
//! the IUT drives the dominant bit, is left alone.
//!
//! Run for every sample point 3..9 TQ of a 10-TQ bit (4 clocks per TQ, see
//! [`super::c8_7_4::sp_config`]).
//!
//! Elementary tests: `iso_8_7_7_sp<SP>`.

use super::super::{At, LtBench, Plan, Span, Trigger};
use super::c8_7_4::{frame, sp_config};
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use canstar_controller::frame::BuildOptions;
use canstar_controller::fsm::*;

fn step(lb: &mut LtBench) -> Result<(), String> {
    let f = frame();
    lb.begin_step("late edges");
    let sent0 = lb.b.node(0).sent().len();
    lb.b.node_mut(0).request(f.clone());
    lb.wait(Trigger::at(Field::Sof, 1), 30)?;
    let mut p = Plan::answer(lb.timing, &f, BuildOptions::default(), 3);
    let ack = p.find(Field::AckSlot, 1, false).ok_or("no ACK slot")?;
    let lvl = |p: &Plan, i: usize| p.expects.iter().find(|e| e.bit == i).map(|e| e.level);
    let mut delayed = 0;
    for i in 0..ack {
        // SOF follows the recessive bus idle
        if lvl(&p, i) == Some(false) && (i == 0 || lvl(&p, i - 1) == Some(true)) {
            p.glitch(At::tq(i, 0), Span::Tq(2), true);
            delayed += 1;
        }
    }
    let (r, k) = play_tx_ok(lb, &p, &f, sent0)?;
    ensure!(delayed >= 10, "only {delayed} edges delayed");
    let bit = lb.b.bit_ps;
    let (t0, t_ack) = (r.bit_start(k, 0), r.bit_start(k, ack + 1));
    let recs: Vec<_> = r.iut().iter().filter(|b| b.t >= t0 && b.t < t_ack).collect();
    ensure!(recs.len() == ack + 1, "{} IUT bits from SOF to the ACK slot, expected {}", recs.len(), ack + 1);
    let bad: Vec<_> = recs.windows(2).filter(|w| w[1].t - w[0].t != bit).map(|w| format!("{} -> {}", w[0], w[1])).collect();
    ensure!(bad.is_empty(), "sample points not one bit time apart: {bad:?}");
    let o = tx_offset(&r, k)?;
    let tq = r.tq_ps;
    let off: Vec<String> = iut_tx_edges(&r).into_iter().filter(|&(t, _)| t >= t0 && t < r.bit_start(k, ack)).filter(|&(t, _)| (t - o - t0) % bit != 0).map(|(t, _)| format!("{:.2}", (t - o - t0) as f64 / tq as f64)).collect();
    ensure!(off.is_empty(), "IUT edges off the SOF's bit grid, at TQ {off:?} after SOF");
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_7_7".into(), vcd: None, results: vec![] };
    for sp in 3..=9 {
        let mut lb = LtBench::new(vec![sp_config(sp)]);
        let r = step(&mut lb);
        ctx.record(&format!("iso_8_7_7_sp{sp}"), r);
    }
    ctx.results
}
