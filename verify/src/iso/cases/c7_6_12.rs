//! ISO 16845-1:2016 clause 7.6.12 — REC +1 for a form error in the
//! IUT's error delimiter.
//!
//! What the case checks (in our words): after a stuff error in the data
//! field (REC 1) and the IUT's active error flag, the LT drives the 2nd or
//! the 7th bit of the error delimiter dominant. The IUT must report a form
//! error at that delimiter bit, with REC 2 after it, and send a new active
//! error flag from the next bit.
//!
//! Elementary tests: `iso_7_6_12_error_delimiter_bit<N>`, N = 2, 7.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

/// After the IUT's flag (error flag after a data stuff error, or overload
/// flag after a valid frame) the LT drives delimiter bit `n` dominant
/// (bit 1 = the first recessive bit after the flag); returns the record.
pub fn delimiter_dominant(lb: &mut LtBench, overload: bool, n: usize, rec0: u32) -> Result<super::super::StepRecord, String> {
    let (mut p, f) = if overload { overload_after_frame(lb) } else { error_in_data(lb) };
    p.push_recessive(6 + 8 + 8 + 8 + 3);
    p.set_level(f + 6 + n - 1, false);
    play_step(lb, &p, rec0)
}

pub fn delimiter_form_error(lb: &mut LtBench, overload: bool, n: u32) -> Result<(), String> {
    let r = delimiter_dominant(lb, overload, n as usize, 0)?;
    let (field, rec) = if overload { (Field::OvlDel, 1) } else { (Field::ErrDel, 2) };
    let e = errors(&r);
    let b = e.last().ok_or("no error")?;
    ensure!(b.has(EV_FORM_ERR) && (b.field, b.pos) == (field, n), "error at {b}, expected a form error at {} {n}:{}", field.name(), r.dump(0));
    ensure!(b.rec == rec && b.has(EV_AEF), "REC {} after the form error (expected {rec}), active error flag: {}", b.rec, b.has(EV_AEF));
    ensure!(lb.b.rec(0) == rec, "REC {} at the end, expected {rec}", lb.b.rec(0));
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_12".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [2, 7] {
        let r = delimiter_form_error(&mut lb, false, n);
        ctx.record(&format!("iso_7_6_12_error_delimiter_bit{n}"), r);
    }
    ctx.results
}
