//! ISO 16845-1:2016 clause 8.1.2 — the IUT as transmitter of
//! extended-format data frames: identifier and number of data bytes.
//!
//! What the case checks (in our words): as 8.1.1 with 29-bit identifiers
//! (those of 7.1.2) and every data length 0..8: the LT acknowledges each
//! frame and compares every bit the IUT drives from SOF to the end of
//! End_Of_Frame (SRR and IDE recessive, r1 and r0 dominant, stuffing,
//! CRC) with the frame builder's; the IUT reports one successful
//! transmission, detects no error and keeps TEC at 0.
//!
//! Elementary tests: `iso_8_1_2_id<ID>_dlc<N>`.

use super::super::LtBench;
use super::common::transmit_frame;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::Frame;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_1_2".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for id in super::c7_1_2::IDS {
        for dlc in 0..=8usize {
            let data: Vec<u8> = (0..dlc).map(|i| (id >> (i * 2)) as u8 ^ (0x3B_u8.wrapping_mul(i as u8 + 1))).collect();
            let f = Frame::ext(id, &data);
            let r = (|| {
                transmit_frame(&mut lb, &f, 0, 0)?;
                ensure!(lb.b.tec(0) == 0 && lb.b.rec(0) == 0, "counters TEC {} REC {}", lb.b.tec(0), lb.b.rec(0));
                Ok(())
            })();
            ctx.record(&format!("iso_8_1_2_id{id:08x}_dlc{dlc}"), r);
        }
    }
    ctx.results
}
