//! ISO 16845-1:2016 clause 8.5.7 — an error-passive transmitter suspends
//! its next transmission after a frame.
//!
//! What the case checks (in our words): the IUT, error-passive (TEC 200,
//! still passive after the success decrement), transmits a frame that the
//! LT acknowledges; a second frame is requested while the first one's
//! intermission runs, and the LT leaves the bus recessive. The IUT must
//! wait for the 3 intermission bits and the 8 bits of suspend transmission,
//! so its second SOF starts exactly 11 bit times after the end of the first
//! frame's End_Of_Frame (an error-active IUT would start after 3); the LT
//! then acknowledges and checks the second frame.
//!
//! Elementary test: `iso_8_5_7_suspend_after_frame`.

use super::super::{LtBench, Plan, Trigger};
use super::common::errors;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_5_7".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let (f1, f2) = (Frame::std(0x222, &[0x01]), Frame::std(0x333, &[0x02]));
        lb.begin_step("suspend");
        lb.preset(0, 200, 0);
        ensure!(lb.b.state(0) == 1, "not error-passive");
        lb.b.node_mut(0).request(f1.clone());
        lb.wait(Trigger::at(Field::Sof, 1), 30)?;
        let p = Plan::answer(lb.timing, &f1, BuildOptions::default(), 0);
        let k = lb.play(&p);
        lb.run_plan();
        lb.b.node_mut(0).request(f2.clone());
        let t2 = lb.wait(Trigger::at(Field::Sof, 1).nth(2), 30)?;
        lb.play_and_run(&Plan::answer(lb.timing, &f2, BuildOptions::default(), 3));
        lb.run_idle(30)?;
        let r = lb.end_step();
        r.check_expects()?;
        let end = r.bit_start(k, p.bits.len());
        let gap = (t2 - end) as f64 / lb.b.bit_ps as f64;
        ensure!(gap == 11.0, "second SOF {gap} bit times after the end of EOF, expected 11 (intermission 3 + suspend 8)");
        let sof2 = r.iut().iter().enumerate().filter(|(_, b)| b.has(EV_SOF)).nth(1).map(|(i, _)| i).ok_or("no second SOF")?;
        let susp = r.iut()[..sof2].iter().filter(|b| b.field == Field::Suspend).count();
        ensure!(susp == 8, "{susp} suspend bits before the second SOF:{}", r.dump(0));
        ensure!(errors(&r).is_empty() && r.iut_events(EV_TX_OK).len() == 2, "errors {:?}:{}", errors(&r), r.dump(0));
        ensure!(lb.b.tec(0) == 198, "TEC {}, expected 198", lb.b.tec(0));
        Ok(())
    })();
    ctx.record("iso_8_5_7_suspend_after_frame", r);
    ctx.results
}
