//! ISO 16845-1:2016 clause 8.5.13 — form error in the error delimiter of an
//! error-passive transmitter.
//!
//! What the case checks (in our words): the IUT is error-passive (TEC 128)
//! and transmits a base-format data frame; the LT overwrites its first
//! recessive data bit with a dominant one (bit error, TEC 136) and, after
//! the passive error flag, drives the 2nd, 4th or 7th error delimiter bit
//! dominant. The IUT must report a form error there (TEC 144) and start a
//! new passive error flag; the LT then sends 6 + 7 recessive bits and a
//! dominant one, the last bit of the new error delimiter. The IUT must
//! drive recessive up to that bit, answer it with an overload flag (six
//! dominant bits) from the next bit, and after overload delimiter,
//! intermission and suspend transmission repeat its frame (the LT checks
//! every bit of it at that position). TEC is 143 at the end.
//!
//! Elementary tests: `iso_8_5_13_error_delimiter_bit<N>`, N = 2, 4, 7.

use super::super::LtBench;
use super::c8_5_2::{bit_error_first, passive_tx, Scenario};
use super::common::{delim, event_at};
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_5_13".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [2usize, 4, 7] {
        let r = (|| {
            let mut v = vec![true; delim(n)];
            v.push(false);
            v.extend([true; 6 + 7]);
            v.push(false);
            let o = v.len();
            v.extend([true; 6 + 8 + 3 + 8]);
            let s = Scenario { tec0: 128, levels: v, iut_dom: (o..o + 6).collect(), ..Default::default() };
            let out = passive_tx(&mut lb, &s)?;
            bit_error_first(&out, 136, 2)?;
            let b = event_at(&out.r, EV_FORM_ERR, Field::ErrDel, n as u32)?;
            ensure!(b.tec == 144 && b.has(EV_PEF), "at {b}: TEC 144 and a new passive flag expected");
            event_at(&out.r, EV_OLF, Field::ErrDel, 8)?;
            ensure!(out.r.iut_events(EV_PEF).len() == 2 && out.r.iut_events(EV_AEF).is_empty(), "error flags:{}", out.r.dump(0));
            ensure!(lb.b.tec(0) == 143, "TEC {} at the end, expected 143", lb.b.tec(0));
            Ok(())
        })();
        ctx.record(&format!("iso_8_5_13_error_delimiter_bit{n}"), r);
    }
    ctx.results
}
