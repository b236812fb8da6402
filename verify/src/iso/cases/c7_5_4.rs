//! ISO 16845-1:2016 clause 7.5.4 — an error-passive receiver stays
//! error-passive on further errors.
//!
//! What the case checks (in our words): the IUT is error-passive (REC
//! 128); the LT sends nine frames in a row, each with its first data stuff
//! bit at the wrong level (a stuff error, REC +1) and cut there, each
//! followed by six recessive bits (the IUT's passive error flag), the error
//! delimiter and the intermission. The IUT must drive recessive in every
//! bit of the step (only passive error flags, never an active one), report
//! nine stuff errors each with a passive error flag, deliver no frame and
//! end error-passive (REC above 127; ISO asks for no particular value, and
//! canstar does not increment REC beyond 128, can-protocol.md C12).
//!
//! Elementary test: `iso_7_5_4_nine_errors_no_active_flag`.

use super::super::{LtBench, Plan};
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_5_4".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let mut p = Plan::new(lb.timing);
        for _ in 0..9 {
            let (q, _) = error_in_data(&lb);
            p.bits.extend(q.bits.iter().copied());
            p.push_recessive(6 + 8 + 3);
        }
        for i in 0..p.bits.len() {
            p.expect(i, true, "recessive (passive error flags only)");
        }
        let got0 = lb.b.node(0).received().len();
        let r = play_step(&mut lb, &p, 128)?;
        r.check_expects()?;
        let e = errors(&r);
        ensure!(e.len() == 9 && e.iter().all(|b| b.has(EV_STUFF_ERR) && b.has(EV_PEF) && b.field == Field::Data), "errors {e:?}");
        ensure!(r.iut_events(EV_AEF).is_empty(), "active error flags:{}", r.dump(0));
        ensure!(lb.b.node(0).received().len() == got0, "a frame was delivered");
        ensure!(lb.b.rec(0) >= 128 && lb.b.state(0) == 1, "REC {} state {}, expected error-passive:{}", lb.b.rec(0), lb.b.state(0), r.dump(0));
        Ok(())
    })();
    ctx.record("iso_7_5_4_nine_errors_no_active_flag", r);
    ctx.results
}
