//! ISO 16845-1:2016 clause 7.1.9 — the IUT as receiver of two frames not
//! separated by a bus idle period.
//!
//! What the case checks (in our words): the LT sends two frames back to
//! back; the second frame's SOF comes either in the third intermission bit
//! of the first frame (only two recessive intermission bits) or in the
//! first bit after the intermission. The IUT must acknowledge both frames
//! (dominant in both ACK slots and nowhere else), deliver both, and detect
//! no error: a dominant third intermission bit is a start of frame, not an
//! overload condition.
//!
//! Elementary tests: `iso_7_1_9_sof_at_intermission_3`,
//! `iso_7_1_9_sof_after_intermission`.

use super::super::{LtBench, Plan};
use super::common::receive_plan;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_1_9".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let (f1, f2) = (Frame::std(0x2B3, &[0x11, 0x22]), Frame::std(0x0C5, &[0xF0]));
    for (gap, name) in [(2usize, "sof_at_intermission_3"), (3, "sof_after_intermission")] {
        let r = (|| {
            lb.begin_step("two frames");
            let mut p = Plan::frame(lb.timing, &f1, BuildOptions::default());
            let ack1 = p.find(Field::AckSlot, 1, false).unwrap();
            p.push_recessive(gap);
            let s2 = p.push_frame(&f2, BuildOptions::default());
            let ack2 = s2 + p.bits[s2..].iter().position(|b| b.label.is_some_and(|l| l.field == Field::AckSlot)).unwrap();
            p.push_recessive(3);
            let r = receive_plan(&mut lb, &p, &[f1.clone(), f2.clone()], &[ack1, ack2])?;
            ensure!(r.iut_events(EV_OLF).is_empty() && r.iut_events(EV_OVL).is_empty(), "overload frame:{}", r.dump(0));
            ensure!(r.iut_events(EV_RX_OK).len() == 2, "receptions:{}", r.dump(0));
            ensure!(lb.b.rec(0) == 0, "REC {}", lb.b.rec(0));
            Ok(())
        })();
        ctx.record(&format!("iso_7_1_9_{name}"), r);
    }
    ctx.results
}
