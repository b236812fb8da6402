//! ISO 16845-1:2016 clause 8.1.3 — the IUT as transmitter loses
//! arbitration at every recessive identifier bit of a base-format frame.
//!
//! What the case checks (in our words): the IUT sends a base-format data
//! frame; the LT sends, from the same SOF, a frame whose identifier equals
//! the IUT's up to one recessive identifier bit, which the LT's has
//! dominant. This is done for every recessive identifier bit of 0x7EF
//! (ten bits) and for the single recessive bit of 0x010. At that bit the
//! IUT must become a receiver: no error, no dominant bit but the ACK slot
//! of the LT's frame, the LT's frame delivered; it then repeats its own
//! frame as soon as the bus is idle, which the LT acknowledges and checks
//! bit by bit.
//!
//! Elementary tests: `iso_8_1_3_id<ID>_at_id<P>` (P: identifier position).

use super::super::LtBench;
use super::c7_1_3::lose_and_retry;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::Frame;
use canstar_controller::fsm::Field;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_1_3".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for id in [0x7EFu32, 0x010] {
        let iut = Frame::std(id, &[0xA5, 0x5A]);
        for pos in 1..=11u32 {
            let bit = 1 << (11 - pos);
            if id & bit == 0 {
                continue;
            }
            let lt = Frame::std(id & !bit, &[0x0F]);
            let r = lose_and_retry(&mut lb, &iut, &lt, (Field::Ident, pos));
            ctx.record(&format!("iso_8_1_3_id{id:03x}_at_id{pos}"), r);
        }
    }
    ctx.results
}
