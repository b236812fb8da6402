//! ISO 16845-1:2016 clause 7.7.2 — hard synchronisation of a receiving
//! IUT on an early SOF, delayed by e TQ into the third intermission bit.
//!
//! What the case checks (in our words): the LT sends a frame that the IUT
//! rejects with an active error frame (a stuff error in the data field,
//! as in 7.3.2), leaves the error delimiter and two intermission bits
//! recessive, makes the third intermission bit only e TQ long (e = 1 ..
//! NTQ; e = NTQ is a SOF at the normal time) and then sends a SOF followed
//! by five dominant bits. The IUT must hard-synchronise on the SOF's edge,
//! whether it comes before the sample point of the third intermission bit
//! or after it: its SOF is sampled exactly SP TQ after the edge, the sixth
//! dominant bit (where a recessive stuff bit is due) gives a stuff error,
//! and its active error flag starts exactly 6 bit times after the edge
//! (ISO allows 6 bits − 1 TQ to 6 bits, the TQ in which the edge falls
//! being the SOF's synchronisation segment; checked on the IUT's sample
//! points of SOF and of the first flag bit, to the clock with a 1-clock TQ,
//! within the TQ otherwise). The IUT's TX is also checked at the nominal
//! sample points of both flags. REC ends at 2 (one per error).
//!
//! Sample points as the IUT offers them: every timing of
//! [`super::c7_7_1::timings`].
//!
//! Elementary tests: `iso_7_7_2_<timing>_e<E>`.

use super::super::LtBench;
use super::c7_7_1::*;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use canstar_controller::fsm::*;

fn step(lb: &mut LtBench, e: u32) -> Result<(), String> {
    let ntq = lb.timing.ntq();
    let (mut p, f) = error_in_data(lb);
    p.push_recessive(6 + 8 + 2 + 1);
    let i3 = p.bits.len() - 1;
    if e < ntq {
        p.shorten(i3, ntq - e);
    }
    let sof = p.bits.len();
    p.push_levels(&[false; 6]).push_recessive(6 + 8 + 3 + 4);
    for k in 0..6 {
        p.expect(sof + 6 + k, false, "active error flag");
    }
    p.expect(sof + 12, true, "error delimiter");
    for k in 0..6 {
        p.expect(f + k, false, "first active error flag");
    }
    let r = play(lb, &p)?;
    let t_sof = r.bit_start(0, sof);
    let s = iut_sof_after(&r, t_sof)?;
    sampled_at(lb, &r, sof, &s, 0, "SOF")?;
    let err = iut_rec_after(&r, t_sof, Field::Ident, 4, true)?;
    let e2 = errors(&r);
    ensure!(e2.len() == 2 && e2[1].t == err.t, "errors {e2:?}, expected the stuff error of the data field and one after Identifier 4:{}", r.dump(0));
    let fl = flag_after(&r, EV_STUFF_ERR, &err)?;
    sampled_at(lb, &r, sof, &fl, 6, "first error flag bit")?;
    ensure!(lb.b.rec(0) == 2, "REC {}, expected 2", lb.b.rec(0));
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_7_2".into(), vcd: None, results: vec![] };
    for t in timings() {
        let mut lb = LtBench::new(vec![iut_with(t)]);
        for e in 1..=t.ntq() {
            let r = step(&mut lb, e);
            ctx.record(&format!("iso_7_7_2_{}_e{e}", timing_name(&t)), r);
        }
    }
    ctx.results
}
