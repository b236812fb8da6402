//! ISO 16845-1:2016 clause 7.6.21 — a successful transmission does not
//! decrement REC.
//!
//! What the case checks (in our words): the IUT starts a frame and loses
//! arbitration to the LT's frame, which carries a stuff error in its data
//! field: the IUT, now a receiver, flags it and counts REC +1. The IUT
//! then repeats its own frame, which the LT acknowledges; that success
//! must leave REC at 1 (only TEC is decremented for a transmitter; TEC
//! stays 0).
//!
//! Elementary test: `iso_7_6_21_rec_after_own_frame`.

use super::super::{LtBench, Plan};
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

use super::super::Trigger;
use canstar_controller::frame::{BuildOptions, Frame};

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_21".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        lb.begin_step("lost, error, retry");
        let iut = Frame::std(0x7F0, &[0x12]);
        lb.b.node_mut(0).request(iut.clone());
        lb.wait(Trigger::at(Field::Sof, 1), 30)?;
        let (mut p, _) = error_in_data(&lb);
        p.push_recessive(6 + 8 + 3);
        lb.play(&p);
        lb.wait(Trigger::at(Field::Sof, 1).nth(2), 200)?;
        ensure!(lb.b.rec(0) == 1, "REC {} after the receive error, expected 1", lb.b.rec(0));
        lb.play_and_run(&Plan::answer(lb.timing, &iut, BuildOptions::default(), 3));
        lb.run_idle(30)?;
        let r = lb.end_step();
        r.check_expects()?;
        ensure!(r.iut_events(EV_ARB_LOST).len() == 1 && r.iut_events(EV_TX_OK).len() == 1, "arbitration / success:{}", r.dump(0));
        ensure!(lb.b.rec(0) == 1 && lb.b.tec(0) == 0, "REC {} TEC {} after the successful transmission, expected 1 and 0", lb.b.rec(0), lb.b.tec(0));
        Ok(())
    })();
    ctx.record("iso_7_6_21_rec_after_own_frame", r);
    ctx.results
}
