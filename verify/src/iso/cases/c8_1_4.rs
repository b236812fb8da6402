//! ISO 16845-1:2016 clause 8.1.4 — the IUT as transmitter loses
//! arbitration at every recessive arbitration bit of an extended frame.
//!
//! What the case checks (in our words): the IUT sends an extended data
//! frame without data; the LT sends, from the same SOF, a frame equal to it
//! up to one recessive arbitration bit of the IUT, which the LT's frame
//! has dominant: every recessive base-identifier and extension bit of
//! 0x1FBFFFFF (28), the single recessive base-identifier bit of 0x00400000,
//! and, against 0x00400000, SRR (the LT sends a base-format data frame,
//! whose RTR is dominant) and IDE (a base-format remote frame). At that
//! bit the IUT must become a receiver (no error, no dominant bit but the
//! ACK slot of the LT's frame, the LT's frame delivered) and then send its
//! frame again once the bus is idle (checked bit by bit by the LT).
//!
//! Elementary tests: `iso_8_1_4_id<ID>_at_<field><pos>` (31).

use super::super::LtBench;
use super::c7_1_3::lose_and_retry;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::Frame;
use canstar_controller::fsm::Field;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_1_4".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for id in [0x1FBF_FFFFu32, 0x0040_0000] {
        let iut = Frame::ext(id, &[]);
        for k in 0..29u32 {
            let bit = 1 << (28 - k);
            if id & bit == 0 {
                continue;
            }
            let (field, pos) = if k < 11 { (Field::Ident, k + 1) } else { (Field::ExIdent, k - 10) };
            let lt = Frame::ext(id & !bit, &[]);
            let r = lose_and_retry(&mut lb, &iut, &lt, (field, pos));
            ctx.record(&format!("iso_8_1_4_id{id:08x}_at_{}{pos}", if k < 11 { "id" } else { "exid" }), r);
        }
    }
    let id = 0x0040_0000u32;
    let iut = Frame::ext(id, &[]);
    let r = lose_and_retry(&mut lb, &iut, &Frame::std(id >> 18, &[]), (Field::Srr, 1));
    ctx.record("iso_8_1_4_id00400000_at_srr", r);
    let r = lose_and_retry(&mut lb, &iut, &Frame::remote(false, id >> 18, 0), (Field::Ide, 1));
    ctx.record("iso_8_1_4_id00400000_at_ide", r);
    ctx.results
}
