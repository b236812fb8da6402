//! ISO 16845-1:2016 clause 8.5.8 — an error-passive transmitter that lost
//! arbitration repeats its frame without a suspend.
//!
//! What the case checks (in our words): the IUT is error-passive (TEC 128)
//! and starts a base-format data frame; the LT sends a frame with a lower
//! identifier (differing in the first identifier bit), so the IUT loses
//! arbitration there and becomes a receiver: it must acknowledge and
//! deliver the LT's frame and stay recessive in its other bits. Having
//! been a receiver, it owes no suspend: its frame must start again right
//! after the 3 intermission bits, 1 + 7 + 3 bit times after its ACK bit
//! (the LT checks every bit of it there). TEC is 127 at the end.
//!
//! Elementary test: `iso_8_5_8_no_suspend_after_arbitration_loss`.

use super::super::{LtBench, Plan, Trigger};
use super::c8_5_2::push_answer;
use super::common::errors;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_5_8".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let (f, g) = (Frame::std(0x44A, &[0xAA]), Frame::std(0x24A, &[0xAA]));
        lb.begin_step("arbitration lost while error-passive");
        lb.preset(0, 128, 0);
        ensure!(lb.b.state(0) == 1, "not error-passive");
        let sent0 = lb.b.node(0).sent().len();
        let got0 = lb.b.node(0).received().len();
        lb.b.node_mut(0).request(f.clone());
        lb.wait(Trigger::at(Field::Sof, 1), 30)?;
        let mut p = Plan::frame(lb.timing, &g, BuildOptions::default());
        p.push_recessive(3);
        let lost = p.find(Field::Ident, 1, false).ok_or("no identifier")?;
        let ack = p.find(Field::AckSlot, 1, false).ok_or("no ACK slot")?;
        for k in lost + 1..p.bits.len() {
            if k != ack {
                p.expect(k, true, "IUT recessive (receiver)");
            }
        }
        push_answer(&mut p, &f, 3);
        lb.play_and_run(&p);
        lb.run_idle(40)?;
        let r = lb.end_step();
        r.check_expects()?;
        ensure!(errors(&r).is_empty(), "errors {:?}", errors(&r));
        let a = r.iut_events(EV_ARB_LOST);
        ensure!(a.len() == 1 && a[0].field == Field::Ident && a[0].pos == 1, "arbitration:{}", r.dump(0));
        ensure!(lb.b.node(0).received()[got0..] == [g.clone()], "LT frame not delivered:{}", r.dump(0));
        ensure!(r.iut_events(EV_TX_OK).len() == 1 && lb.b.node(0).sent()[sent0..] == [f.clone()], "transmissions:{}", r.dump(0));
        let sof2 = r.iut().iter().enumerate().filter(|(_, b)| b.has(EV_SOF)).nth(1).map(|(i, _)| i).ok_or("no second SOF")?;
        ensure!(!r.iut()[..sof2].iter().any(|b| b.field == Field::Suspend), "a suspend before the repetition:{}", r.dump(0));
        ensure!(lb.b.tec(0) == 127, "TEC {}, expected 127", lb.b.tec(0));
        Ok(())
    })();
    ctx.record("iso_8_5_8_no_suspend_after_arbitration_loss", r);
    ctx.results
}
