//! ISO 16845-1:2016 clause 7.6.16 — REC at a dominant last End_Of_Frame
//! bit.
//!
//! What the case checks (in our words): from REC 9 the LT sends a valid
//! frame whose last EOF bit is dominant. The frame counts as received
//! (delivered, overload flag from the next bit) and ISO 16845-1 expects
//! REC 8.
//!
//! **Disagreement (README "Disagreements", D1; can-protocol.md C13).** The
//! 1999 Bosch reference programs expect REC unchanged (9). canstar makes
//! this a generation-time option ([`crate::node::NodeConfig::rec_rule`]); the
//! ISO rule is the default. The case runs both controllers: the default
//! one must end at 8, the Bosch-rule one at 9.
//!
//! Elementary tests: `iso_7_6_16_eof7_dominant_iso_rule` and
//! `iso_7_6_16_eof7_dominant_bosch1999_rule`.

use super::super::{LtBench, Plan};
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

use canstar_controller::core::RecRule;
use canstar_controller::frame::{BuildOptions, Frame};

fn eof7_step(lb: &mut LtBench, want: u32) -> Result<(), String> {
    let f = Frame::std(0x5A3, &[0xC3, 0x3C]);
    let mut p = Plan::frame(lb.timing, &f, BuildOptions::default());
    let e7 = p.find(Field::Eof, 7, false).unwrap();
    p.set_level(e7, false).push_recessive(6 + 8 + 3 + 2);
    for k in 1..=6 {
        p.expect(e7 + k, false, "overload flag");
    }
    let r = play_step(lb, &p, 9)?;
    r.check_expects()?;
    ensure!(lb.b.node(0).received().last() == Some(&f), "frame not delivered");
    ensure!(errors(&r).is_empty(), "errors {:?}", errors(&r));
    ensure!(lb.b.rec(0) == want, "REC {} after the frame (9 before), expected {want}", lb.b.rec(0));
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_16".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = eof7_step(&mut lb, 8);
    ctx.record("iso_7_6_16_eof7_dominant_iso_rule", r);
    let mut cfg = NodeConfig::named("iut");
    cfg.rec_rule = RecRule::Bosch1999;
    let mut lb = LtBench::new(vec![cfg]);
    let r = eof7_step(&mut lb, 9);
    ctx.record("iso_7_6_16_eof7_dominant_bosch1999_rule", r);
    ctx.results
}
