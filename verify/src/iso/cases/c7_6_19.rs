//! ISO 16845-1:2016 clause 7.6.19 — no REC change for a dominant last bit
//! of the IUT's error delimiter.
//!
//! What the case checks (in our words): after a stuff error in the data
//! field (REC 1) and the IUT's active error flag, the LT drives the 8th
//! bit of the error delimiter dominant. That is an overload condition, not
//! an error: the IUT sends an overload flag from the next bit, detects no
//! further error, and its REC stays 1.
//!
//! Elementary test: `iso_7_6_19_error_delimiter_bit8`.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn delimiter8(lb: &mut LtBench, overload: bool) -> Result<(), String> {
    let r = super::c7_6_12::delimiter_dominant(lb, overload, 8, 0)?;
    let (field, rec, nerr) = if overload { (Field::OvlDel, 0, 0) } else { (Field::ErrDel, 1, 1) };
    let e = errors(&r);
    ensure!(e.len() == nerr, "errors {e:?}");
    let o: Vec<_> = r.iut_events(EV_OLF).into_iter().filter(|b| b.field == field).collect();
    ensure!(o.len() == 1 && o[0].pos == 8, "overload flag after {} 8: {o:?}:{}", field.name(), r.dump(0));
    ensure!(lb.b.rec(0) == rec, "REC {}, expected {rec}", lb.b.rec(0));
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_19".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = delimiter8(&mut lb, false);
    ctx.record("iso_7_6_19_error_delimiter_bit8", r);
    ctx.results
}
