//! ISO 16845-1:2016 clause 7.1.12 — the instant at which a received frame
//! becomes valid for the IUT.
//!
//! What the case checks (in our words): the LT sends a valid frame whose
//! last End_Of_Frame bit it drives dominant. For a receiver the frame is
//! already valid after the sixth EOF bit, so the IUT must acknowledge it,
//! deliver it, signal no error, and treat the dominant seventh bit as an
//! overload condition: an overload flag (six dominant bits) from the next
//! bit, then a recessive overload delimiter. (The REC change at that bit is
//! clause 7.6.16.)
//!
//! Elementary test: `iso_7_1_12_eof7_dominant`.

use super::super::{LtBench, Plan};
use super::common::errors;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// The step of 7.1.12 and 7.4.2: a valid frame with a dominant EOF bit 7.
pub fn eof7_overload(lb: &mut LtBench) -> Result<(), String> {
    let f = Frame::std(0x5A3, &[0xC3, 0x3C, 0x81]);
    {
        lb.begin_step("eof7 dominant");
        let mut p = Plan::frame(lb.timing, &f, BuildOptions::default());
        let e7 = p.find(Field::Eof, 7, false).unwrap();
        p.set_level(e7, false).push_recessive(6 + 8 + 3 + 2);
        for k in 1..=6 {
            p.expect(e7 + k, false, "overload flag");
        }
        p.expect(e7 + 7, true, "overload delimiter");
        lb.play_and_run(&p);
        lb.run_idle(30)?;
        let r = lb.end_step();
        r.check_expects()?;
        ensure!(lb.b.node(0).received().last() == Some(&f), "frame not delivered: {:?}", lb.b.node(0).received().last());
        let e = errors(&r);
        ensure!(e.is_empty(), "errors detected: {e:?}");
        ensure!(r.iut_events(EV_AEF).is_empty() && r.iut_events(EV_PEF).is_empty(), "error flag:{}", r.dump(0));
        let olf = r.iut_events(EV_OLF);
        ensure!(olf.len() == 1 && (olf[0].field, olf[0].pos) == (Field::Eof, 7), "overload flags {olf:?}");
        Ok(())
    }
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_1_12".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = eof7_overload(&mut lb);
    ctx.record("iso_7_1_12_eof7_dominant", r);
    ctx.results
}
