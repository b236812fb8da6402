//! ISO 16845-1:2016 clause 7.4.1 — overload frame for a dominant bit in
//! the first two intermission bits after a received frame.
//!
//! What the case checks (in our words): after a valid frame the LT drives
//! intermission bit 1 or 2 dominant. The IUT must deliver the frame, take
//! the dominant bit as an overload condition (no error) and send an
//! overload flag (six dominant bits) from the next bit.
//!
//! Elementary tests: `iso_7_4_1_intermission<M>_dominant`, M = 1, 2.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

use super::super::Plan;
use canstar_controller::frame::{BuildOptions, Frame};

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_4_1".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for m in [1usize, 2] {
        let r = (|| {
            let f = Frame::std(0x2C6, &[0x3E]);
            let mut p = Plan::frame(lb.timing, &f, BuildOptions::default());
            let i = p.bits.len() + m - 1;
            p.push_recessive(m - 1).push_levels(&[false]).push_recessive(6 + 8 + 3 + 2);
            for k in 1..=6 {
                p.expect(i + k, false, "overload flag");
            }
            p.expect(i + 7, true, "overload delimiter");
            let r = play_step(&mut lb, &p, 0)?;
            r.check_expects()?;
            ensure!(lb.b.node(0).received().last() == Some(&f), "frame not delivered");
            ensure!(errors(&r).is_empty(), "errors {:?}", errors(&r));
            event_at(&r, EV_OLF, Field::Inter, m as u32)?;
            Ok(())
        })();
        ctx.record(&format!("iso_7_4_1_intermission{m}_dominant"), r);
    }
    ctx.results
}
