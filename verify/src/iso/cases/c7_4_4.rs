//! ISO 16845-1:2016 clause 7.4.4 — bit error in the IUT's overload flag.
//!
//! What the case checks (in our words): after a valid frame and a dominant
//! first intermission bit, the LT forces the bus recessive during the
//! first, third or sixth bit of the IUT's overload flag. The IUT must
//! report a bit error there and send an active error flag from the next
//! bit.
//!
//! Elementary tests: `iso_7_4_4_overload_flag_bit<N>`, N = 1, 3, 6.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_4_4".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [1usize, 3, 6] {
        let r = (|| {
            let (r, _) = flag_scenario(&mut lb, Start::OverloadAfterFrame, &[], &[n - 1], Some(n), 0)?;
            let b = event_at(&r, EV_BIT_ERR, Field::OvlFlag, n as u32)?;
            ensure!(b.has(EV_AEF), "no active error flag after {b}");
            Ok(())
        })();
        ctx.record(&format!("iso_7_4_4_overload_flag_bit{n}"), r);
    }
    ctx.results
}
