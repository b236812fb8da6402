//! ISO 16845-1:2016 clause 8.3.3 — bit error in the transmitting IUT's
//! active error flag.
//!
//! What the case checks (in our words): after a bit error in the data
//! field of the IUT's frame (TEC 8), the LT forces the bus recessive during
//! the first, fourth or sixth bit of the IUT's active error flag. The IUT
//! must report a bit error there (TEC 16, clause 8.6.1's +8) and restart its
//! active error flag with the next bit; it then sends the frame again
//! successfully (TEC 15).
//!
//! Elementary tests: `iso_8_3_3_flag_bit<N>`, N = 1, 4, 6.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_3_3".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [1usize, 4, 6] {
        let r = (|| {
            let (r, _) = tx_flag_scenario(&mut lb, Start::ErrorInData, &[], &[n - 1], Some((n, false)), 0)?;
            let b = event_at(&r, EV_BIT_ERR, Field::ActFlag, n as u32)?;
            ensure!(b.has(EV_AEF) && b.tec == 16, "at {b}: a new active flag and TEC 16 expected");
            ensure!(lb.b.tec(0) == 15, "TEC {} at the end, expected 15", lb.b.tec(0));
            Ok(())
        })();
        ctx.record(&format!("iso_8_3_3_flag_bit{n}"), r);
    }
    ctx.results
}
