//! ISO 16845-1:2016 clause 8.7.8 — resynchronisation of a transmitting IUT
//! on an edge right after the sample point.
//!
//! What the case checks (in our words): the IUT transmits a frame whose
//! data byte 0x55 gives alternating dominant and recessive bits. The LT
//! shortens the first recessive data bit by PH2 (it drives the bus
//! dominant from the IUT's sample point of that bit on) and keeps the bus
//! dominant through the IUT's next, dominant, bit. The IUT must shorten its
//! PH2 by min(PH2, SJW): its next recessive-to-dominant edge comes two bit
//! times + PH2 − min(PH2, SJW) after the LT's edge, every later edge it
//! sends (up to the ACK slot) on that grid, and the frame completes
//! without error (the LT's answer follows the grid).
//!
//! Run for every sample point 3..9 TQ of a 10-TQ bit (4 clocks per TQ, see
//! [`super::c8_7_4::sp_config`]).
//!
//! Elementary tests: `iso_8_7_8_sp<SP>`.

use super::super::LtBench;
use super::c8_7_4::{early_edge, rd_pair, sp_config};
use crate::conformance::{ensure, Ctx, StepResult};
use canstar_controller::frame::Frame;
use canstar_controller::fsm::Field;

fn step(lb: &mut LtBench) -> Result<(), String> {
    let t = lb.timing;
    let s = early_edge(lb, &Frame::std(0x2A5, &[0x55]), |p| rd_pair(p, Field::Data, 0), t.ph2, None)?;
    let tq = s.r.tq_ps as i64;
    let want = (2 * t.ntq() + t.ph2 - t.ph2.min(t.sjw)) as i64 * tq;
    let next = s.later_edges()?.into_iter().find(|&(_, l)| !l).ok_or("no recessive-to-dominant IUT edge after the resynchronisation")?;
    ensure!(next.0 == want, "next recessive-to-dominant IUT edge {:.2} TQ after the LT's edge, expected {}", next.0 as f64 / tq as f64, want / tq);
    s.check_grid()
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_7_8".into(), vcd: None, results: vec![] };
    for sp in 3..=9 {
        let mut lb = LtBench::new(vec![sp_config(sp)]);
        let r = step(&mut lb);
        ctx.record(&format!("iso_8_7_8_sp{sp}"), r);
    }
    ctx.results
}
