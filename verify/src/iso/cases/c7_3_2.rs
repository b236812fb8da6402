//! ISO 16845-1:2016 clause 7.3.2 — the IUT receives a frame that starts
//! in the third intermission bit after its error frame.
//!
//! What the case checks (in our words): after a stuff error in the data
//! field, the IUT's active error flag and error delimiter, the LT leaves
//! two intermission bits recessive and starts a valid frame in the third.
//! The IUT must take that bit as SOF, acknowledge the frame and deliver it
//! (no overload frame, no further error).
//!
//! Elementary test: `iso_7_3_2_sof_at_intermission_3`.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

use canstar_controller::frame::{BuildOptions, Frame};

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_3_2".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let (mut p, _f) = error_in_data(&lb);
        p.push_recessive(6 + 8 + 2);
        let g = Frame::std(0x19A, &[0x5C, 0x07]);
        p.push_frame(&g, BuildOptions::default());
        p.push_recessive(3);
        let r = play_step(&mut lb, &p, 0)?;
        r.check_expects()?;
        ensure!(lb.b.node(0).received().last() == Some(&g), "frame not delivered");
        ensure!(errors(&r).len() == 1 && r.iut_events(EV_OLF).is_empty(), "errors {:?}:{}", errors(&r), r.dump(0));
        ensure!(lb.b.rec(0) == 0, "REC {} (1 after the stuff error, -1 for the frame)", lb.b.rec(0));
        Ok(())
    })();
    ctx.record("iso_7_3_2_sof_at_intermission_3", r);
    ctx.results
}
