//! ISO 16845-1:2016 clause 8.5.4 — an error-passive transmitter receives a
//! frame that starts during its suspend transmission.
//!
//! What the case checks (in our words): the IUT is error-passive (TEC 200,
//! still error-passive after the success decrement) and transmits a frame
//! that the LT acknowledges and checks bit by bit; after End_Of_Frame and
//! the 3 intermission bits the LT sends a frame of its own whose SOF falls
//! on the first, fourth or eighth bit of the IUT's suspend transmission.
//! The IUT must become a receiver: it stays recessive except for the ACK of
//! that frame, delivers it, detects no error, and its suspend shows exactly
//! N - 1 Suspend_Transmission bits before the LT's SOF. TEC is 199 at the
//! end.
//!
//! Elementary tests: `iso_8_5_4_sof_at_suspend<N>`, N = 1, 4, 8.

use super::super::{LtBench, Plan, Trigger};
use super::c8_5_2::{lt_frame, source};
use super::common::errors;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::BuildOptions;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_5_4".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [1usize, 4, 8] {
        let r = (|| {
            let (f, g) = (source(), lt_frame());
            lb.begin_step("frame during suspend");
            lb.preset(0, 200, 0);
            ensure!(lb.b.state(0) == 1, "not error-passive");
            let got0 = lb.b.node(0).received().len();
            lb.b.node_mut(0).request(f.clone());
            lb.wait(Trigger::at(Field::Sof, 1), 30)?;
            let mut p = Plan::answer(lb.timing, &f, BuildOptions::default(), 3 + n - 1);
            let e0 = p.bits.len() - (3 + n - 1);
            let g0 = p.push_frame(&g, BuildOptions::default());
            p.push_recessive(3);
            let ack = (g0..p.bits.len()).find(|&a| p.bits[a].label.is_some_and(|l| l.field == Field::AckSlot)).ok_or("no ACK slot")?;
            for k in e0..p.bits.len() {
                if k != ack {
                    p.expect(k, true, "IUT recessive (suspend, receiver)");
                }
            }
            lb.play_and_run(&p);
            lb.run_idle(40)?;
            let r = lb.end_step();
            r.check_expects()?;
            ensure!(errors(&r).is_empty(), "errors {:?}", errors(&r));
            ensure!(r.iut_events(EV_TX_OK).len() == 1 && !lb.b.node(0).pending(), "transmissions:{}", r.dump(0));
            let sof2 = r.iut().iter().enumerate().filter(|(_, b)| b.has(EV_SOF)).nth(1).map(|(i, _)| i).ok_or("no second SOF")?;
            let susp = r.iut()[..sof2].iter().filter(|b| b.field == Field::Suspend).count();
            ensure!(susp == n - 1, "{susp} suspend bits before the LT's SOF, expected {}:{}", n - 1, r.dump(0));
            ensure!(lb.b.node(0).received()[got0..] == [g.clone()], "LT frame not delivered:{}", r.dump(0));
            ensure!(lb.b.tec(0) == 199 && lb.b.rec(0) == 0, "TEC {} REC {}, expected 199 / 0", lb.b.tec(0), lb.b.rec(0));
            Ok(())
        })();
        ctx.record(&format!("iso_8_5_4_sof_at_suspend{n}"), r);
    }
    ctx.results
}
