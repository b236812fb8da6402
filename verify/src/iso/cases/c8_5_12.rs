//! ISO 16845-1:2016 clause 8.5.12 — an error-passive transmitter needs six
//! equal consecutive bits to complete its passive error flag.
//!
//! What the case checks (in our words): the IUT is error-passive (TEC 128)
//! and transmits a base-format data frame; the LT overwrites its first
//! recessive data bit with a dominant one (bit error, TEC 136). During the
//! IUT's passive error flag the LT sends 5 dominant, 5 recessive and 6
//! dominant bits: only the last six are equal and complete the flag. The LT
//! then sends 8 recessive bits (the error delimiter, counted from the
//! first recessive bit after the flag) and one dominant bit, the first
//! intermission bit. The IUT must drive recessive up to that bit, answer it
//! with an overload flag (six dominant bits) from the next bit, with no new
//! error, and after overload delimiter, intermission and suspend
//! transmission repeat its frame (the LT checks every bit of it at that
//! position). An IUT that completed its flag too early would see the
//! dominant bit inside its delimiter or intermission at another place and
//! not match. TEC is 135 at the end.
//!
//! Elementary test: `iso_8_5_12_5d_5r_6d`.

use super::super::LtBench;
use super::c8_5_2::{bit_error_first, passive_tx, Scenario};
use super::common::event_at;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_5_12".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let mut v = vec![false; 5];
        v.extend([true; 5]);
        v.extend([false; 6]);
        v.extend([true; 8]);
        v.push(false);
        let o = v.len();
        v.extend([true; 6 + 8 + 3 + 8]);
        let s = Scenario { tec0: 128, levels: v, iut_dom: (o..o + 6).collect(), ..Default::default() };
        let out = passive_tx(&mut lb, &s)?;
        bit_error_first(&out, 136, 1)?;
        event_at(&out.r, EV_OLF, Field::Inter, 1)?;
        ensure!(out.r.iut_events(EV_PEF).len() == 1 && out.r.iut_events(EV_AEF).is_empty(), "error flags:{}", out.r.dump(0));
        ensure!(lb.b.tec(0) == 135, "TEC {} at the end, expected 135", lb.b.tec(0));
        Ok(())
    })();
    ctx.record("iso_8_5_12_5d_5r_6d", r);
    ctx.results
}
