//! ISO 16845-1:2016 clause 8.5.15 — an error-active transmitter becomes
//! error-passive through bit errors in its active error flag and then
//! recovers as an error-passive node.
//!
//! What the case checks (in our words): the IUT starts error-active (TEC 0)
//! and transmits a base-format data frame; the LT overwrites its first
//! recessive data bit with a dominant one (bit error, TEC 8) and forces the
//! bus recessive for the next 16 bit times, each a bit error in the IUT's
//! active error flag (TEC +8 each) that restarts the flag. The 15th brings
//! TEC to 128 (error-passive), the flag it starts is still active (the
//! flag type comes from the state before the error, can-protocol.md §10);
//! the 16th, seen while error-passive, brings TEC to 136 and starts a
//! passive error flag. The IUT must drive dominant during the 16 forced
//! bits and recessive after them, and repeat its frame 6 + 8 + 3 + 8 bit
//! times after the last forced bit (passive flag, error delimiter,
//! intermission, suspend); the LT checks every bit of it there. TEC is 135
//! at the end.
//!
//! Elementary test: `iso_8_5_15_active_to_passive_recovery`.

use super::super::LtBench;
use super::c8_5_2::{bit_error_first, passive_tx, Scenario};
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_5_15".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let s = Scenario { tec0: 0, levels: vec![true; 16 + 6 + 8 + 3 + 8], forced: (0..16).collect(), iut_dom: (0..16).collect(), ..Default::default() };
        let o = passive_tx(&mut lb, &s)?;
        bit_error_first(&o, 8, 17)?;
        let bits = o.r.iut_events(EV_BIT_ERR);
        ensure!(bits.len() == 17, "{} bit errors:{}", bits.len(), o.r.dump(0));
        ensure!(bits[15].tec == 128 && bits[15].state == 1 && bits[15].has(EV_AEF), "after the 15th flag bit error: {}", bits[15]);
        ensure!(bits[16].tec == 136 && bits[16].has(EV_PEF), "after the 16th flag bit error: {}", bits[16]);
        ensure!(o.r.iut_events(EV_PEF).len() == 1 && o.r.iut_events(EV_AEF).len() == 16, "error flags:{}", o.r.dump(0));
        ensure!(lb.b.tec(0) == 135, "TEC {} at the end, expected 135", lb.b.tec(0));
        Ok(())
    })();
    ctx.record("iso_8_5_15_active_to_passive_recovery", r);
    ctx.results
}
