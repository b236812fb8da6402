//! ISO 16845-1:2016 clause 7.1.8 — the IUT as receiver of a classical
//! frame whose DLC is greater than 8.
//!
//! What the case checks (in our words): the LT sends data frames with the
//! DLC codes 9..15, each followed by eight data bytes; the IUT must
//! acknowledge, detect no error, and deliver the frame with the DLC code
//! as sent and the eight bytes (canstar's choice C10: codes 9..15 mean 8
//! bytes, the raw code is reported).
//!
//! Elementary tests: `iso_7_1_8_dlc<N>`, N = 9..15.

use super::super::LtBench;
use super::common::receive_frame;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_1_8".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for dlc in 9..=15u8 {
        let data: Vec<u8> = (0..8u8).map(|i| i.wrapping_mul(0x35) ^ dlc).collect();
        let f = Frame::data(false, 0x4B1, dlc, &data);
        let r = (|| {
            receive_frame(&mut lb, &f, BuildOptions::default())?;
            let got = lb.b.node(0).received();
            let g = got.last().ok_or("nothing delivered")?;
            ensure!(g.dlc == dlc && g.data.len() == 8, "delivered DLC {} with {} bytes", g.dlc, g.data.len());
            ensure!(lb.b.rec(0) == 0, "REC {}", lb.b.rec(0));
            Ok(())
        })();
        ctx.record(&format!("iso_7_1_8_dlc{dlc}"), r);
    }
    ctx.results
}
