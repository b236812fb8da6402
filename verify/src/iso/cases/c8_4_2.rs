//! ISO 16845-1:2016 clause 8.4.2 — a transmitter answers a dominant eighth
//! bit of an error or overload delimiter with an overload frame.
//!
//! What the case checks (in our words): the IUT is error-passive (TEC 128)
//! and transmits a base-format data frame.
//! - Error delimiter: the LT overwrites the first recessive data bit with a
//!   dominant one (bit error, TEC 136); after the IUT's passive error flag
//!   and 7 recessive delimiter bits the LT drives the eighth delimiter bit
//!   dominant. The IUT must drive recessive up to there, send an overload
//!   flag (six dominant bits) from the next bit, and after overload
//!   delimiter, intermission and suspend transmission repeat its frame,
//!   which the LT checks bit by bit at that position (TEC 135 at the end).
//! - Overload delimiter: the LT acknowledges the frame (TEC 127) and drives
//!   the first intermission bit dominant; after the IUT's overload flag and
//!   7 recessive delimiter bits it drives the eighth overload delimiter bit
//!   dominant. The IUT must send a second overload flag from the next bit,
//!   detect no error and not send the frame again.
//!
//! Elementary tests: `iso_8_4_2_error_delimiter_bit8`,
//! `iso_8_4_2_overload_delimiter_bit8`.

use super::super::LtBench;
use super::c8_5_2::{bit_error_first, passive_tx, Scenario};
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_4_2".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let mut v = vec![true; delim(8)];
        v.push(false);
        let o = v.len();
        v.extend([true; 6 + 8 + 3 + 8]);
        let out = passive_tx(&mut lb, &Scenario { tec0: 128, levels: v, iut_dom: (o..o + 6).collect(), ..Default::default() })?;
        bit_error_first(&out, 136, 1)?;
        event_at(&out.r, EV_OLF, Field::ErrDel, 8)?;
        ensure!(out.r.iut_events(EV_PEF).len() == 1 && out.r.iut_events(EV_OLF).len() == 1, "flags:{}", out.r.dump(0));
        ensure!(lb.b.tec(0) == 135, "TEC {} at the end, expected 135", lb.b.tec(0));
        Ok(())
    })();
    ctx.record("iso_8_4_2_error_delimiter_bit8", r);
    let r = (|| {
        let sent0 = lb.b.node(0).sent().len();
        let (r, first) = tx_flag_scenario(&mut lb, Start::OverloadAfterFrame, &[delim(8)], &[], Some((delim(8) + 1, false)), 128)?;
        for k in 0..6 {
            ensure!(r.iut_tx_at(0, first + k) == Some(false), "IUT not dominant in bit {} of its first overload flag:{}", k + 1, r.dump(0));
        }
        for k in 6..delim(8) + 1 {
            ensure!(r.iut_tx_at(0, first + k) == Some(true), "IUT dominant in overload delimiter bit {}:{}", k - 5, r.dump(0));
        }
        event_at(&r, EV_OLF, Field::Inter, 1)?;
        event_at(&r, EV_OLF, Field::OvlDel, 8)?;
        ensure!(r.iut_events(EV_OLF).len() == 2, "overload flags:{}", r.dump(0));
        ensure!(errors(&r).is_empty(), "errors {:?}", errors(&r));
        ensure!(r.iut_events(EV_TX_OK).len() == 1 && lb.b.node(0).sent().len() == sent0 + 1, "transmissions:{}", r.dump(0));
        ensure!(lb.b.tec(0) == 127, "TEC {} at the end, expected 127", lb.b.tec(0));
        Ok(())
    })();
    ctx.record("iso_8_4_2_overload_delimiter_bit8", r);
    ctx.results
}
