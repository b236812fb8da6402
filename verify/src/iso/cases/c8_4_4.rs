//! ISO 16845-1:2016 clause 8.4.4 — bit error in the transmitting IUT's
//! overload flag.
//!
//! What the case checks (in our words): after its successful frame the IUT
//! answers a dominant first intermission bit with an overload flag; the LT
//! forces the bus recessive during the first, second or sixth flag bit.
//! The IUT must report a bit error there (TEC 0 + 8, clause 8.6.2) and send
//! an active error flag from the next bit.
//!
//! Elementary tests: `iso_8_4_4_overload_flag_bit<N>`, N = 1, 2, 6.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_4_4".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [1usize, 2, 6] {
        let r = (|| {
            let (r, _) = tx_flag_scenario(&mut lb, Start::OverloadAfterFrame, &[], &[n - 1], Some((n, false)), 0)?;
            let b = event_at(&r, EV_BIT_ERR, Field::OvlFlag, n as u32)?;
            ensure!(b.has(EV_AEF) && b.tec == 8, "at {b}: an active error flag and TEC 8 expected");
            ensure!(lb.b.tec(0) == 8, "TEC {} at the end, expected 8", lb.b.tec(0));
            Ok(())
        })();
        ctx.record(&format!("iso_8_4_4_overload_flag_bit{n}"), r);
    }
    ctx.results
}
