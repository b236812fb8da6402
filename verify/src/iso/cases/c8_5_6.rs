//! ISO 16845-1:2016 clause 8.5.6 — an error-passive transmitter suspends
//! its next transmission after an overload frame.
//!
//! What the case checks (in our words): the IUT is error-passive (TEC 200,
//! still error-passive after the success decrement) and has two frames to
//! send. The LT acknowledges the first and checks it bit by bit, then
//! drives the first intermission bit dominant: the IUT must send an
//! overload flag (six dominant bits). The LT then leaves the bus recessive
//! for the overload delimiter, the intermission and the suspend
//! transmission; the IUT must stay recessive and start its second frame
//! exactly in the bit after the eighth suspend bit (the LT checks every bit
//! of it there; an IUT without the suspend would start 8 bits earlier).
//! TEC is 198 at the end.
//!
//! Elementary test: `iso_8_5_6_suspend_after_overload_frame`.

use super::super::{LtBench, Plan, Trigger};
use super::c8_5_2::push_answer;
use super::common::{errors, event_at};
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_5_6".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let (f1, f2) = (Frame::std(0x222, &[0x01]), Frame::std(0x333, &[0x02]));
        lb.begin_step("suspend after overload");
        lb.preset(0, 200, 0);
        ensure!(lb.b.state(0) == 1, "not error-passive");
        let sent0 = lb.b.node(0).sent().len();
        lb.b.node_mut(0).request(f1.clone());
        lb.b.node_mut(0).request(f2.clone());
        lb.wait(Trigger::at(Field::Sof, 1), 30)?;
        let mut p = Plan::answer(lb.timing, &f1, BuildOptions::default(), 0);
        p.push_levels(&[false]);
        let o = p.bits.len();
        p.push_recessive(6 + 8 + 3 + 8);
        for k in o..p.bits.len() {
            p.expect(k, k >= o + 6, if k < o + 6 { "overload flag" } else { "IUT recessive" });
        }
        push_answer(&mut p, &f2, 3);
        lb.play_and_run(&p);
        lb.run_idle(40)?;
        let r = lb.end_step();
        r.check_expects()?;
        event_at(&r, EV_OLF, Field::Inter, 1)?;
        ensure!(errors(&r).is_empty() && r.iut_events(EV_TX_OK).len() == 2, "errors {:?}:{}", errors(&r), r.dump(0));
        let sent = lb.b.node(0).sent()[sent0..].to_vec();
        ensure!(sent == [f1, f2], "sent {sent:?}");
        ensure!(lb.b.tec(0) == 198, "TEC {}, expected 198", lb.b.tec(0));
        Ok(())
    })();
    ctx.record("iso_8_5_6_suspend_after_overload_frame", r);
    ctx.results
}
