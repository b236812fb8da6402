//! ISO 16845-1:2016 clause 8.7.3 — hard synchronisation of an IUT with a
//! pending transmission on a dominant bit after the sample point of the
//! third intermission bit.
//!
//! What the case checks (in our words): as 8.7.2 (a bit error in the data
//! field, an active error flag, the frame pending), but the LT starts its
//! dominant bit IPT (2 TQ) after the IUT's sample point of the third
//! intermission bit, in PH2. The IUT has sampled that bit recessive and
//! must hard-synchronise on the edge: it sends its own SOF from the next
//! TQ after the LT's edge on (its TX edge measured against the LT's edge,
//! as the IUT perceives both), the bit starting at the edge (measured on
//! its sample point of the SOF), and then its frame on that grid, which the
//! LT answers (every bit checked) and acknowledges: one successful
//! transmission, TEC 7.
//!
//! Run for every sample point 3..7 TQ of a 10-TQ bit (4 clocks per TQ, see
//! [`super::c8_7_4::sp_config`]; PH2 > IPT so that the edge lies inside
//! the bit).
//!
//! Elementary tests: `iso_8_7_3_sp<SP>`.

use super::super::LtBench;
use super::c8_7_2::intermission_sof;
use super::c8_7_4::sp_config;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use canstar_controller::frame::Frame;

fn step(lb: &mut LtBench) -> Result<(), String> {
    let t = lb.timing;
    let f = Frame::std(0x2A5, &[0x3C, 0xA5]);
    let s = intermission_sof(lb, &f, t.sp() + t.ipt(), 0, false)?;
    let tq = s.r.tq_ps as i64;
    let start = s.sof2_start()? as i64 - s.t_edge as i64;
    ensure!(start == 0, "the hard-synchronised SOF starts {:.2} TQ after the LT's edge, expected 0", start as f64 / tq as f64);
    let sof = iut_tx_edges(&s.r).into_iter().find(|&(tt, l)| tt > s.t_edge && !l).ok_or("no SOF from the IUT")?;
    let d = sof.0 as i64 - s.o as i64 - s.t_edge as i64;
    ensure!(d == tq, "the IUT's SOF begins {:.2} TQ after the LT's edge, expected 1 (the next TQ)", d as f64 / tq as f64);
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_7_3".into(), vcd: None, results: vec![] };
    for sp in 3..=7 {
        let mut lb = LtBench::new(vec![sp_config(sp)]);
        let r = step(&mut lb);
        ctx.record(&format!("iso_8_7_3_sp{sp}"), r);
    }
    ctx.results
}
