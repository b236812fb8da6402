//! ISO 16845-1:2016 clause 7.5.5 — an error-passive receiver restarts the
//! count of its passive error flag on dominant bits.
//!
//! What the case checks (in our words): the IUT is error-passive (REC
//! 128); during its passive error flag (after a stuff error in the data
//! field) the LT sends 5 dominant bits starting at the first, third or
//! sixth flag bit. The flag then needs six equal bits counted from the
//! first recessive bit after them; the LT sends 6 + 7 recessive bits and a
//! dominant bit, which is then the last bit of the IUT's error delimiter:
//! the IUT must answer it with an overload flag from the next bit (six
//! dominant bits), with no further error.
//!
//! Elementary tests: `iso_7_5_5_5_dominant_at_bit<N>`, N = 1, 3, 6.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

use super::super::Plan;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_5_5".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [1usize, 3, 6] {
        let r = (|| {
            let (mut p, f): (Plan, usize) = error_in_data(&lb);
            p.push_recessive(n - 1).push_levels(&[false; 5]).push_recessive(6 + 7).push_levels(&[false]);
            let d = p.bits.len() - 1;
            p.push_recessive(6 + 8 + 3 + 2);
            for i in f..d {
                p.expect(i, true, "recessive (passive flag, delimiter)");
            }
            for k in 1..=6 {
                p.expect(d + k, false, "overload flag");
            }
            let r = play_step(&mut lb, &p, 128)?;
            r.check_expects()?;
            event_at(&r, EV_OLF, Field::ErrDel, 8)?;
            ensure!(errors(&r).len() == 1, "errors {:?}", errors(&r));
            Ok(())
        })();
        ctx.record(&format!("iso_7_5_5_5_dominant_at_bit{n}"), r);
    }
    ctx.results
}
