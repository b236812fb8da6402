//! ISO 16845-1:2016 clause 7.6.3 — REC +8 for each eighth dominant bit
//! after the IUT's active error flag.
//!
//! What the case checks (in our words): after a stuff error in the data
//! field (REC 1) and the IUT's active error flag, the LT keeps the bus
//! dominant for 16 more bits. The IUT's REC must rise by 8 at the first of
//! them (a dominant bit right after its own error flag), by 8 at the 8th
//! and by 8 at the 16th, and nowhere else: 9, 17 and 25.
//!
//! Elementary test: `iso_7_6_3_16_dominant_after_error_flag`.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

/// REC after the IUT's bit (`field`, `pos`), its first occurrence.
fn rec_at(r: &super::super::StepRecord, field: Field, pos: u32) -> Result<u32, String> {
    r.iut().iter().find(|b| b.field == field && b.pos == pos && !b.stuff).map(|b| b.rec).ok_or_else(|| format!("no IUT bit {} {pos}:{}", field.name(), r.dump(0)))
}

/// After the IUT's flag (`flag` plan bit 1 of it) the LT drives `n`
/// dominant bits; returns the record.
pub fn dominant_after_flag(lb: &mut LtBench, overload: bool, n: usize, rec0: u32) -> Result<super::super::StepRecord, String> {
    let (mut p, _f) = if overload { overload_after_frame(lb) } else { error_in_data(lb) };
    p.push_levels(&vec![false; 6 + n]).push_recessive(8 + 3 + 3);
    play_step(lb, &p, rec0)
}

/// Check REC after flag positions `pos` (7 = first dominant bit after the
/// flag) against `want`.
pub fn check_recs(r: &super::super::StepRecord, field: Field, want: &[(u32, u32)]) -> Result<(), String> {
    for &(pos, rec) in want {
        let got = rec_at(r, field, pos)?;
        ensure!(got == rec, "REC {got} after {} {pos} (dominant bit {} after the flag), expected {rec}:{}", field.name(), pos as i32 - 6, r.dump(0));
    }
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_3".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let r = dominant_after_flag(&mut lb, false, 16, 0)?;
        check_recs(&r, Field::ActFlag, &[(6, 1), (7, 9), (13, 9), (14, 17), (21, 17), (22, 25)])?;
        ensure!(lb.b.rec(0) == 25, "REC {} at the end", lb.b.rec(0));
        Ok(())
    })();
    ctx.record("iso_7_6_3_16_dominant_after_error_flag", r);
    ctx.results
}
