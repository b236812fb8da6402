//! ISO 16845-1:2016 clause 8.7.6 — a transmitting IUT synchronises only
//! once between two sample points.
//!
//! What the case checks (in our words): the IUT transmits a base-format
//! frame; at its first recessive identifier bit followed by a dominant one,
//! the LT drives the bus dominant 1 TQ early (a resynchronisation with
//! e = −1), then forces the bus recessive for the second TQ of the dominant
//! bit, which makes a second recessive-to-dominant edge before the next
//! sample point. The IUT must synchronise on the first edge only: its
//! sample points lie NTQ − 1 TQ apart, every edge it sends afterwards (up
//! to the ACK slot) lies an integer number of bit times after the LT's
//! first edge, and the frame completes without error.
//!
//! Run for every sample point 3..9 TQ of a 10-TQ bit (4 clocks per TQ, see
//! [`super::c8_7_4::sp_config`]).
//!
//! Elementary tests: `iso_8_7_6_sp<SP>`.

use super::super::LtBench;
use super::c8_7_4::{early_edge, frame, rd_pair, sp_config};
use crate::conformance::{ensure, Ctx, StepResult};
use canstar_controller::fsm::Field;

fn step(lb: &mut LtBench) -> Result<(), String> {
    let s = early_edge(lb, &frame(), |p| rd_pair(p, Field::Ident, 0), 1, Some((1, 1)))?;
    let want = (lb.timing.ntq() - 1) as u64;
    let gap = s.sample_gap_tq()?;
    ensure!(gap == want, "sample points {gap} TQ apart, expected {want}");
    s.check_grid()
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_7_6".into(), vcd: None, results: vec![] };
    for sp in 3..=9 {
        let mut lb = LtBench::new(vec![sp_config(sp)]);
        let r = step(&mut lb);
        ctx.record(&format!("iso_8_7_6_sp{sp}"), r);
    }
    ctx.results
}
