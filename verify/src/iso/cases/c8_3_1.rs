//! ISO 16845-1:2016 clause 8.3.1 — the transmitting IUT tolerates up to 7
//! dominant bits after its active error flag.
//!
//! What the case checks (in our words): the IUT transmits; the LT forces a
//! dominant data bit recessive (bit error, TEC 8) and, after the IUT's
//! active error flag, keeps the bus dominant for 1, 4 or 7 more bits. The
//! IUT must send one error frame only (recessive after its six flag bits,
//! no further error), TEC must stay 8 through those bits (a transmitter
//! gets nothing for the first dominant bit), and the IUT must send its
//! frame again after the intermission, successfully (TEC 7).
//!
//! Elementary tests: `iso_8_3_1_flag_plus<K>_dominant`, K = 1, 4, 7.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_3_1".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for k in [1usize, 4, 7] {
        let r = (|| {
            let dom: Vec<usize> = (6..6 + k).collect();
            let (r, f) = tx_flag_scenario(&mut lb, Start::ErrorInData, &dom, &[], Some((0, false)), 0)?;
            for o in 6..6 + k + 8 {
                ensure!(r.iut_tx_at(0, f + o) == Some(true), "IUT dominant at offset {o} after its flag");
            }
            ensure!(errors(&r).len() == 1 && r.iut_events(EV_AEF).len() == 1, "errors {:?}:{}", errors(&r), r.dump(0));
            ensure!(tec_at(&r, Field::ActFlag, 6 + k as u32)? == 8, "TEC after the dominant bits");
            ensure!(lb.b.tec(0) == 7, "TEC {} at the end, expected 7", lb.b.tec(0));
            Ok(())
        })();
        ctx.record(&format!("iso_8_3_1_flag_plus{k}_dominant"), r);
    }
    ctx.results
}
