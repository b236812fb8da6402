//! ISO 16845-1:2016 clause 8.3.2 — after its error frame, the IUT
//! transmits when it sees a start of frame in the third intermission bit.
//!
//! What the case checks (in our words): the IUT transmits; the LT forces a
//! dominant data bit recessive (a bit error, TEC 8) and, after the IUT's
//! active error flag (six dominant bits, checked), leaves the bus recessive
//! for the error delimiter and two intermission bits, then drives the
//! third intermission bit dominant. The IUT must take that bit as the
//! start of frame and repeat its frame from the first identifier bit
//! without a SOF of its own (recessive in that bit): the LT checks every
//! bit the IUT drives, acknowledges, and the IUT reports success (TEC 7).
//! Once with an identifier starting with four dominant bits (with the
//! LT's SOF five: a stuff bit follows), once with five recessive bits.
//!
//! Elementary tests: `iso_8_3_2_id<ID>`.

use super::super::{LtBench, Plan, Trigger};
use super::common::{corrupt, errors};
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_3_2".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for id in [0x07Au32, 0x7CA] {
        let f = Frame::std(id, &[0x5A, 0x81]);
        let r = (|| {
            lb.begin_step("sof in intermission 3 after an error frame");
            lb.preset(0, 0, 0);
            let sent0 = lb.b.node(0).sent().len();
            lb.b.node_mut(0).request(f.clone());
            lb.wait(Trigger::at(Field::Sof, 1), 30)?;
            let mut p = Plan::answer(lb.timing, &f, BuildOptions::default(), 0);
            let i = (0..p.bits.len()).find(|&i| p.bits[i].label.is_some_and(|l| l.field == Field::Data && !l.stuff) && p.expects.iter().any(|e| e.bit == i && !e.level)).ok_or("no dominant data bit")?;
            corrupt(&mut p, i);
            p.truncate(i + 1).push_recessive(6 + 8 + 2);
            for k in 1..=6 {
                p.expect(i + k, false, "active error flag");
            }
            let s = p.bits.len();
            let a = Plan::answer(lb.timing, &f, BuildOptions::default(), 3);
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
            ensure!(e.len() == 1 && e[0].has(EV_BIT_ERR), "errors {e:?}");
            ensure!(r.iut_events(EV_TX_OK).len() == 1, "transmissions:{}", r.dump(0));
            let sent = lb.b.node(0).sent();
            ensure!(sent.len() == sent0 + 1 && sent[sent0] == f, "sent {:?}", &sent[sent0..]);
            ensure!(lb.b.tec(0) == 7, "TEC {}, expected 7:{}", lb.b.tec(0), r.dump(0));
            Ok(())
        })();
        ctx.record(&format!("iso_8_3_2_id{id:03x}"), r);
    }
    ctx.results
}
