//! ISO 16845-1:2016 clause 8.1.5 — the instant at which a transmitted
//! frame becomes valid for the IUT.
//!
//! What the case checks (in our words): the IUT transmits a frame, the LT
//! acknowledges it and then drives the first intermission bit dominant.
//! The frame was valid at the end of End_Of_Frame, so the IUT must count
//! the transmission as successful (TEC stays 0, one success, the frame not
//! sent again), signal no error, and answer the dominant intermission bit
//! with an overload flag (six dominant bits) from the next bit followed by
//! a recessive overload delimiter.
//!
//! Elementary test: `iso_8_1_5_intermission1_dominant`.

use super::super::{LtBench, Plan, Trigger};
use super::common::errors;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_1_5".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let f = Frame::std(0x1D4, &[0x0F, 0xF0]);
    let r = (|| {
        lb.begin_step("intermission 1 dominant");
        let sent0 = lb.b.node(0).sent().len();
        lb.b.node_mut(0).request(f.clone());
        lb.wait(Trigger::at(Field::Sof, 1), 30)?;
        let mut p = Plan::answer(lb.timing, &f, BuildOptions::default(), 1 + 6 + 8 + 3 + 2);
        let i1 = p.find(Field::Eof, 7, false).unwrap() + 1;
        p.set_level(i1, false);
        for k in 1..=6 {
            p.expect(i1 + k, false, "overload flag");
        }
        p.expect(i1 + 7, true, "overload delimiter");
        lb.play_and_run(&p);
        lb.run_idle(30)?;
        let r = lb.end_step();
        r.check_expects()?;
        let e = errors(&r);
        ensure!(e.is_empty(), "errors detected: {e:?}");
        let olf = r.iut_events(EV_OLF);
        ensure!(olf.len() == 1 && (olf[0].field, olf[0].pos) == (Field::Inter, 1), "overload flags {olf:?}");
        ensure!(r.iut_events(EV_TX_OK).len() == 1 && r.iut_events(EV_SOF).len() == 1, "transmissions / SOFs:{}", r.dump(0));
        ensure!(lb.b.node(0).sent().len() == sent0 + 1 && !lb.b.node(0).pending(), "sent {:?}", &lb.b.node(0).sent()[sent0..]);
        ensure!(lb.b.tec(0) == 0, "TEC {}", lb.b.tec(0));
        Ok(())
    })();
    ctx.record("iso_8_1_5_intermission1_dominant", r);
    ctx.results
}
