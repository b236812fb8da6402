//! ISO 16845-1:2016 clause 8.1.8 — after losing arbitration, the IUT
//! transmits when it sees a start of frame in the third intermission bit.
//!
//! What the case checks (in our words): the IUT starts a frame and loses
//! arbitration against the LT's frame (lower identifier); after that frame
//! the LT leaves two intermission bits recessive and drives the third
//! dominant. The IUT, with its frame pending, must take that bit as the
//! start of frame and go on with the first identifier bit without sending
//! a SOF of its own: the LT checks every bit the IUT drives from that SOF
//! on (the IUT recessive in the SOF bit itself), acknowledges the frame,
//! and the IUT reports success without error. Once with an identifier
//! starting with four dominant bits (with the LT's SOF they make five, so
//! a stuff bit follows) and once with five recessive bits.
//!
//! Elementary tests: `iso_8_1_8_id<ID>`.

use super::super::{LtBench, Plan, Trigger};
use super::common::errors;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_1_8".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for (iut_id, lt_id) in [(0x07Au32, 0x072u32), (0x7CAu32, 0x7C2u32)] {
        let iut = Frame::std(iut_id, &[0x81, 0x7E]);
        let lt = Frame::std(lt_id, &[0x42]);
        let r = (|| {
            lb.begin_step("sof in intermission 3");
            let sent0 = lb.b.node(0).sent().len();
            lb.b.node_mut(0).request(iut.clone());
            lb.wait(Trigger::at(Field::Sof, 1), 30)?;
            let mut p = Plan::frame(lb.timing, &lt, BuildOptions::default());
            p.push_recessive(2);
            let s = p.bits.len();
            let a = Plan::answer(lb.timing, &iut, BuildOptions::default(), 3);
            p.bits.extend(a.bits.iter().copied());
            for e in &a.expects {
                p.expect(s + e.bit, e.level || e.bit == 0, if e.bit == 0 { "no SOF from the IUT" } else { e.what });
            }
            p.set_level(s, false);
            lb.play_and_run(&p);
            lb.run_idle(30)?;
            let r = lb.end_step();
            r.check_expects()?;
            let e = errors(&r);
            ensure!(e.is_empty(), "errors detected: {e:?}");
            ensure!(r.iut_events(EV_ARB_LOST).len() == 1, "arbitration:{}", r.dump(0));
            ensure!(lb.b.node(0).received().last() == Some(&lt), "LT frame not delivered");
            ensure!(r.iut_events(EV_TX_OK).len() == 1, "transmissions:{}", r.dump(0));
            let sent = lb.b.node(0).sent();
            ensure!(sent.len() == sent0 + 1 && sent[sent0] == iut, "sent {:?}", &sent[sent0..]);
            ensure!(lb.b.tec(0) == 0 && lb.b.rec(0) == 0, "TEC {} REC {}", lb.b.tec(0), lb.b.rec(0));
            Ok(())
        })();
        ctx.record(&format!("iso_8_1_8_id{iut_id:03x}"), r);
    }
    ctx.results
}
