//! ISO 16845-1:2016 clause 7.3.1 — the IUT tolerates up to 7 dominant
//! bits after its active error flag.
//!
//! What the case checks (in our words): after a stuff error in the data
//! field the IUT sends its active error flag; the LT then keeps the bus
//! dominant for 1, 4 or 7 more bits. The IUT must drive recessive from the
//! end of its six flag bits on (no second flag, no further error), and
//! count only the +8 of the first dominant bit (REC 1 + 8 = 9).
//!
//! Elementary tests: `iso_7_3_1_flag_plus<K>_dominant`, K = 1, 4, 7.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_3_1".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for k in [1usize, 4, 7] {
        let r = (|| {
            let dom: Vec<usize> = (6..6 + k).collect();
            let (r, f) = flag_scenario(&mut lb, Start::ErrorInData, &dom, &[], Some(0), 0)?;
            for o in 6..6 + k + 8 {
                ensure!(r.iut_tx_at(0, f + o) == Some(true), "IUT dominant at offset {o} after its flag");
            }
            ensure!(errors(&r).len() == 1 && r.iut_events(EV_AEF).len() == 1, "errors {:?}:{}", errors(&r), r.dump(0));
            ensure!(lb.b.rec(0) == 9, "REC {}, expected 9", lb.b.rec(0));
            Ok(())
        })();
        ctx.record(&format!("iso_7_3_1_flag_plus{k}_dominant"), r);
    }
    ctx.results
}
