//! ISO 16845-1:2016 clause 8.1.6 — the IUT inserts stuff bits correctly
//! when transmitting base-format frames.
//!
//! What the case checks (in our words): the IUT transmits the
//! critical-stuffing frames of 7.1.10 that a classical transmitter can
//! send (r0 dominant): stuff bits at field boundaries and stuff bits that
//! begin new runs. The LT acknowledges and compares every bit the IUT
//! drives, stuff bits included, with the frame builder's stuffed frame;
//! the IUT reports success and detects no error.
//!
//! Elementary tests: `iso_8_1_6_f<k>_id<ID>`, the six of the standard.

use super::super::LtBench;
use super::c7_1_10::decode;
use super::common::transmit_frame;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;

pub fn table() -> Vec<(u32, u16, Vec<u8>)> {
    let mut first = vec![0xE1u8; 8];
    first[0] = 0x01;
    vec![(0x078, 0x08, first), (0x41F, 0x01, vec![0x00]), (0x47F, 0x01, vec![0x1F]), (0x758, 0x00, vec![]), (0x777, 0x01, vec![0x1F]), (0x7EF, 0x42, vec![])]
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_1_6".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for (k, (id, ctrl, data)) in table().into_iter().enumerate() {
        let (f, _) = decode(false, id, ctrl, &data);
        let r = (|| {
            transmit_frame(&mut lb, &f, 0, 0)?;
            ensure!(lb.b.tec(0) == 0, "TEC {}", lb.b.tec(0));
            Ok(())
        })();
        ctx.record(&format!("iso_8_1_6_f{}_id{id:03x}", k + 1), r);
    }
    ctx.results
}
