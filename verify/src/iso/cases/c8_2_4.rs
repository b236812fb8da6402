//! ISO 16845-1:2016 clause 8.2.4 — stuff bits of an extended-format frame
//! the IUT transmits, read inverted.
//!
//! What the case checks (in our words): as 8.2.3 with the extended frames
//! of 8.1.7: every stuff bit read inverted gives an error at that bit
//! (bit error for a dominant stuff bit, stuff error for a recessive one),
//! an active error flag from the next bit and a successful retransmission;
//! TEC +8 except for a recessive stuff bit inside the extended arbitration
//! field (base identifier to RTR, exception 2).
//!
//! Elementary tests: `iso_8_2_4_f<k>_<field><pos>_<D|R>`.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_2_4".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for (k, (id, ctrl, data)) in [(0x07C3_0F0Fu32, 0x188u16, vec![0x3Cu8; 8]), (0x07C0_F0F0, 0x181, vec![0x00]), (0x1FB8_0000, 0x181, vec![0xA0])].into_iter().enumerate() {
        let (f, _) = super::c7_1_10::decode(true, id, ctrl, &data);
        super::c8_2_3::stuff_errors(&mut ctx, &mut lb, "8_2_4", k, &f);
    }
    ctx.results
}
