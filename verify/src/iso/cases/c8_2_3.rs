//! ISO 16845-1:2016 clause 8.2.3 — stuff bits of a base-format frame
//! the IUT transmits, read inverted.
//!
//! What the case checks (in our words): the IUT transmits the stuffing
//! frames of 8.1.6; for every stuff bit the LT makes the IUT read the
//! opposite level (forcing a dominant stuff bit recessive, overwriting a
//! recessive one with a dominant bit, which gives six equal bits). The IUT
//! must detect the error at that stuff bit (a bit error for a dominant
//! stuff bit, a stuff error for a recessive one), send an active error
//! flag from the next bit, and send the frame again successfully. TEC: +8,
//! except a recessive stuff bit in the arbitration field (no increment,
//! can-protocol.md §13.3 exception 2).
//!
//! Elementary tests: `iso_8_2_3_f<k>_<field><pos>_<D|R>` (k: frame of
//! 8.1.6; the level the IUT sends).

use super::super::{LtBench, Plan};
use super::common::*;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// Stuff bits of `f` sent inverted to the transmitting IUT: a dominant
/// stuff bit read recessive is a bit error (TEC +8); a recessive one read
/// dominant is a stuff error, without TEC increment inside the arbitration
/// field (exception 2: identifier and RTR of a base frame, including a
/// stuff bit after RTR; base identifier, SRR, IDE, extension and RTR of an
/// extended frame), +8 elsewhere.
pub fn stuff_errors(ctx: &mut Ctx, lb: &mut LtBench, clause: &str, k: usize, f: &Frame) {
    let a = Plan::answer(lb.timing, f, BuildOptions::default(), 0);
    for i in a.stuff_bits() {
        let l = a.bits[i].label.unwrap();
        let lvl = a.expects.iter().find(|e| e.bit == i).unwrap().level;
        let arb = matches!(l.field, Field::Ident) || (!f.ide && l.field == Field::Rtr) || (f.ide && matches!(l.field, Field::Srr | Field::Ide | Field::ExIdent));
        let (ev, tec) = if !lvl { (EV_BIT_ERR, 8) } else if arb { (EV_STUFF_ERR, 0) } else { (EV_STUFF_ERR, 8) };
        let mut p = a.clone();
        corrupt(&mut p, i);
        let r = transmit_error(lb, f, 0, p, i, i + 1, ev, (l.field, l.pos), tec, false).map(|_| ());
        ctx.record(&format!("iso_{clause}_f{}_{}{}_{}", k + 1, super::c8_2_1::short(l.field), l.pos, if lvl { "R" } else { "D" }), r);
    }
}
pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_2_3".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for (k, (id, ctrl, data)) in super::c8_1_6::table().into_iter().enumerate() {
        let (f, _) = super::c7_1_10::decode(false, id, ctrl, &data);
        stuff_errors(&mut ctx, &mut lb, "8_2_3", k, &f);
    }
    ctx.results
}
