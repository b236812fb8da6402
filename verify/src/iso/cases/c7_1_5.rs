//! ISO 16845-1:2016 clause 7.1.5 — the IUT as receiver accepts
//! non-nominal SRR and reserved bits in a valid extended-format frame.
//!
//! What the case checks (in our words): in an extended frame the LT sends
//! every combination of SRR (nominally recessive), r1 (FDF in CAN FD) and
//! r0 (both nominally dominant) except the nominal one; the classical-CAN
//! IUT must acknowledge each frame, deliver it unchanged and detect no
//! error (canstar's choices C8, C9: SRR and reserved bits accepted at
//! either level). The nominal combination is run as well, as a reference.
//!
//! Elementary tests: `iso_7_1_5_srr<S>_r1<A>_r0<B>` (1 = recessive),
//! the seven of the standard plus the nominal one.

use super::super::LtBench;
use super::common::receive_frame;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_1_5".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let f = Frame::ext(0x0F0F_3C5A, &[0xA5, 0x3C, 0x01]);
    for (srr, r1, r0) in [(true, true, true), (true, true, false), (true, false, true), (false, true, true), (false, true, false), (false, false, true), (false, false, false), (true, false, false)] {
        let o = BuildOptions { srr, r1, r0 };
        let r = (|| {
            receive_frame(&mut lb, &f, o)?;
            ensure!(lb.b.rec(0) == 0, "REC {}", lb.b.rec(0));
            Ok(())
        })();
        ctx.record(&format!("iso_7_1_5_srr{}_r1{}_r0{}", srr as u8, r1 as u8, r0 as u8), r);
    }
    ctx.results
}
