//! ISO 16845-1:2016 clause 7.3.3 — bit error in the IUT's active error
//! flag.
//!
//! What the case checks (in our words): after a stuff error in the data
//! field, the LT forces the bus recessive during the first, third or
//! sixth bit of the IUT's active error flag. The IUT must report a bit
//! error at that flag bit and start a new active error flag (six dominant
//! bits) with the next bit.
//!
//! Elementary tests: `iso_7_3_3_flag_bit<N>`, N = 1, 3, 6.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_3_3".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [1usize, 3, 6] {
        let r = (|| {
            let (r, _) = flag_scenario(&mut lb, Start::ErrorInData, &[], &[n - 1], Some(n), 0)?;
            let b = event_at(&r, EV_BIT_ERR, Field::ActFlag, n as u32)?;
            ensure!(b.has(EV_AEF), "no new active error flag after {b}");
            Ok(())
        })();
        ctx.record(&format!("iso_7_3_3_flag_bit{n}"), r);
    }
    ctx.results
}
