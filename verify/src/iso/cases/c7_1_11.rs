//! ISO 16845-1:2016 clause 7.1.11 — the IUT as receiver of
//! extended-format frames with critical stuffing patterns.
//!
//! What the case checks (in our words): as 7.1.10 for 29-bit identifiers:
//! the LT sends valid extended frames whose base identifier, SRR/IDE,
//! identifier extension, RTR, r1/r0 (recessive in some frames), DLC and
//! data put stuff bits at field boundaries and make stuff bits begin new
//! runs. The IUT must acknowledge each frame, deliver it unchanged and
//! detect no error.
//!
//! Elementary tests: `iso_7_1_11_f<k>_id<ID>`, the seven classical-CAN
//! frames of the standard (control value: bit 8 SRR, bit 7 IDE, bit 6 RTR,
//! bit 5 r1, bit 4 r0, bits 3..0 DLC).

use super::super::LtBench;
use super::c7_1_10::decode;
use super::common::receive_frame;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;

/// (identifier, control, data) of the standard's seven elementary tests.
pub fn table() -> Vec<(u32, u16, Vec<u8>)> {
    vec![
        (0x07C3_0F0F, 0x188, vec![0x3C; 8]),
        (0x07C0_F0F0, 0x181, vec![0x00]),
        (0x01E3_1717, 0x19F, vec![0x0F; 8]),
        (0x01E0_0FF0, 0x1BC, vec![0x1F, 0x0F, 0xE0, 0xF0, 0x7F, 0xE0, 0xFF, 0x20]),
        (0x1FB8_0000, 0x181, vec![0xA0]),
        (0x00BC_540F, 0x1E0, vec![]),
        (0x155D_5557, 0x1FF, vec![]),
    ]
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_1_11".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for (k, (id, ctrl, data)) in table().into_iter().enumerate() {
        let (f, o) = decode(true, id, ctrl, &data);
        let r = (|| {
            receive_frame(&mut lb, &f, o)?;
            ensure!(lb.b.rec(0) == 0, "REC {}", lb.b.rec(0));
            Ok(())
        })();
        ctx.record(&format!("iso_7_1_11_f{}_id{id:08x}", k + 1), r);
    }
    ctx.results
}
