//! ISO 16845-1:2016 clause 7.1.4 — the IUT as receiver accepts a
//! non-nominal reserved bit in a valid base-format frame.
//!
//! What the case checks (in our words): a classical-CAN receiver must
//! accept the reserved bit r0 of a base-format frame (the bit after IDE;
//! FDF in CAN FD) sent recessive instead of dominant: the LT sends such
//! frames (several identifiers and lengths, so the recessive r0 meets
//! both levels of neighbouring bits), the IUT acknowledges, delivers the
//! frame and detects no error (canstar's choice C8). The CAN FD-enabled
//! variant (RRS recessive) is not applicable.
//!
//! Elementary tests: `iso_7_1_4_r0_recessive_f<k>` (the standard has one;
//! the further frames move the recessive r0 between other bit patterns).

use super::super::LtBench;
use super::common::receive_frame;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};

pub fn frames() -> Vec<Frame> {
    vec![Frame::std(0x245, &[0x5A, 0x00]), Frame::std(0x7FF, &[]), Frame::std(0x000, &[0xFF; 8]), Frame::remote(false, 0x3C3, 4)]
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_1_4".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let o = BuildOptions { r0: true, ..BuildOptions::default() };
    for (k, f) in frames().iter().enumerate() {
        let r = (|| {
            receive_frame(&mut lb, f, o)?;
            ensure!(lb.b.rec(0) == 0, "REC {}", lb.b.rec(0));
            Ok(())
        })();
        ctx.record(&format!("iso_7_1_4_r0_recessive_f{k}"), r);
    }
    ctx.results
}
