//! ISO 16845-1:2016 clause 8.4.1 — overload frame of an error-passive
//! transmitter for a dominant bit in the first two intermission bits.
//!
//! What the case checks (in our words): the IUT, error-passive (TEC 128),
//! transmits a frame that the LT acknowledges (TEC 127 afterwards, the IUT
//! error-active again); the LT then drives intermission bit 1 or 2
//! dominant. The IUT must send an overload flag (six dominant bits) from
//! the next bit, detect no error and not send the frame again.
//!
//! Elementary tests: `iso_8_4_1_intermission<M>_dominant`, M = 1, 2.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_4_1".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for m in [1usize, 2] {
        let r = (|| {
            let start = if m == 1 { Start::OverloadAfterFrame } else { Start::OverloadAtIntermission2 };
            let (r, _) = tx_flag_scenario(&mut lb, start, &[], &[], Some((0, false)), 128)?;
            event_at(&r, EV_OLF, Field::Inter, m as u32)?;
            ensure!(errors(&r).is_empty(), "errors {:?}", errors(&r));
            ensure!(r.iut_events(EV_TX_OK).len() == 1 && lb.b.tec(0) == 127, "TEC {}:{}", lb.b.tec(0), r.dump(0));
            Ok(())
        })();
        ctx.record(&format!("iso_8_4_1_intermission{m}_dominant"), r);
    }
    ctx.results
}
