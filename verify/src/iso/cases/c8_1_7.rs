//! ISO 16845-1:2016 clause 8.1.7 — the IUT inserts stuff bits correctly
//! when transmitting extended-format frames.
//!
//! What the case checks (in our words): as 8.1.6 with three extended
//! frames whose identifier extension and data put stuff bits at field
//! boundaries; every bit the IUT drives, stuff bits included, must match
//! the frame builder's stuffed frame, and the transmission must succeed
//! without error.
//!
//! Elementary tests: `iso_8_1_7_f<k>_id<ID>`, the three of the standard.

use super::super::LtBench;
use super::c7_1_10::decode;
use super::common::transmit_frame;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_1_7".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for (k, (id, ctrl, data)) in [(0x07C3_0F0Fu32, 0x188u16, vec![0x3Cu8; 8]), (0x07C0_F0F0, 0x181, vec![0x00]), (0x1FB8_0000, 0x181, vec![0xA0])].into_iter().enumerate() {
        let (f, _) = decode(true, id, ctrl, &data);
        let r = (|| {
            transmit_frame(&mut lb, &f, 0, 0)?;
            ensure!(lb.b.tec(0) == 0, "TEC {}", lb.b.tec(0));
            Ok(())
        })();
        ctx.record(&format!("iso_8_1_7_f{}_id{id:08x}", k + 1), r);
    }
    ctx.results
}
