//! ISO 16845-1:2016 clause 8.2.1 — bit errors in a base-format frame the
//! IUT transmits.
//!
//! What the case checks (in our words): while the IUT sends a base-format
//! data frame, the LT makes it read the opposite of one bit it sends: a
//! dominant bit forced recessive, or a recessive bit overwritten by a
//! dominant one (not in the arbitration field, where that means a lost
//! arbitration). This is done for a bit of each level in SOF, identifier,
//! RTR, IDE, r0, DLC, data and CRC sequence. The IUT must report a bit error
//! at that bit (TEC 0 + 8), send an active error flag from the next bit,
//! then send the frame again (checked by the LT bit by bit) with success
//! (TEC 7).
//!
//! Elementary tests: `iso_8_2_1_<field><pos>_<D|R>` (the level the IUT
//! sends).

use super::super::{LtBench, Plan};
use super::common::*;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// Short field names for test names.
pub fn short(f: Field) -> &'static str {
    match f {
        Field::Sof => "sof",
        Field::Ident => "id",
        Field::Srr => "srr",
        Field::Ide => "ide",
        Field::ExIdent => "exid",
        Field::Rtr => "rtr",
        Field::Resv => "r",
        Field::Dlc => "dlc",
        Field::Data => "data",
        Field::Crc => "crc",
        Field::CrcDel => "crcdel",
        Field::AckDel => "ackdel",
        Field::Eof => "eof",
        _ => "other",
    }
}

/// Bit errors in every field of `f` the IUT sends: the first non-stuff
/// bit of each level in each field, except recessive bits of the
/// arbitration field (reading them dominant loses arbitration).
pub fn bit_errors(ctx: &mut Ctx, lb: &mut LtBench, clause: &str, f: &Frame) {
    let a = Plan::answer(lb.timing, f, BuildOptions::default(), 0);
    let arb = |fl: Field| matches!(fl, Field::Ident | Field::Rtr) || (f.ide && matches!(fl, Field::Srr | Field::Ide | Field::ExIdent));
    let mut seen = vec![];
    for (i, b) in a.bits.iter().enumerate() {
        let l = b.label.unwrap();
        let lvl = a.expects.iter().find(|e| e.bit == i).unwrap().level;
        if l.stuff || !matches!(l.field, Field::Sof | Field::Ident | Field::Srr | Field::Ide | Field::ExIdent | Field::Rtr | Field::Resv | Field::Dlc | Field::Data | Field::Crc) {
            continue;
        }
        if (lvl && arb(l.field)) || seen.contains(&(l.field, lvl)) {
            continue;
        }
        seen.push((l.field, lvl));
        let mut p = a.clone();
        corrupt(&mut p, i);
        let r = transmit_error(lb, f, 0, p, i, i + 1, EV_BIT_ERR, (l.field, l.pos), 8, false).map(|_| ());
        ctx.record(&format!("iso_{clause}_{}{}_{}", short(l.field), l.pos, if lvl { "R" } else { "D" }), r);
    }
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_2_1".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    bit_errors(&mut ctx, &mut lb, "8_2_1", &Frame::std(0x2B4, &[0x96, 0x3C]));
    ctx.results
}
