//! ISO 16845-1:2016 clause 8.5.11 — a bus-off IUT needs 128 occurrences of
//! 11 consecutive recessive bits before it may transmit again.
//!
//! What the case checks (in our words): the IUT (TEC preset 250,
//! error-passive) transmits a base-format data frame; the LT overwrites its
//! first recessive data bit with a dominant one: the bit error brings TEC
//! to 258, the IUT is bus-off from there and drives nothing. The LT then
//! plays a recovery profile, and the frame (still pending, can-protocol.md
//! §15) must not appear before the profile is over and must start right
//! after it, when the 128th run of 11 recessive bits completes (§14): the
//! LT checks that the IUT stays recessive during the profile and checks
//! every bit of the frame from that position; the IUT reports 128 runs,
//! one recovery, and TEC 0 / REC 0 at the end (counters reset by the
//! recovery).
//! - `recessive_1408`: 128 × 11 = 1408 recessive bits;
//! - `groups_10_21_11x127`: 10 recessive bits, a dominant bit, 21 recessive
//!   bits (one run only), a dominant bit, then 127 groups of 11 recessive
//!   bits separated by a dominant bit (the frame starts right after the
//!   last group).
//!
//! Elementary tests: `iso_8_5_11_recessive_1408`,
//! `iso_8_5_11_groups_10_21_11x127`.

use super::super::LtBench;
use super::c8_5_2::{bit_error_first, passive_tx, Scenario};
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_5_11".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let mut groups = vec![true; 10];
    groups.push(false);
    groups.extend([true; 21]);
    for _ in 0..127 {
        groups.push(false);
        groups.extend([true; 11]);
    }
    for (name, levels) in [("recessive_1408", vec![true; 1408]), ("groups_10_21_11x127", groups)] {
        let r = (|| {
            let o = passive_tx(&mut lb, &Scenario { tec0: 250, levels, ..Default::default() })?;
            bit_error_first(&o, 258, 1)?;
            let e = &o.r.iut_events(EV_BIT_ERR)[0];
            ensure!(e.state == 2, "not bus-off after the bit error: {e}");
            let runs = o.r.iut_events(EV_RUN).len();
            let rec = o.r.iut_events(EV_RECOVERED).len();
            ensure!(runs == 128 && rec == 1, "{runs} recovery runs, {rec} recoveries");
            ensure!(lb.b.tec(0) == 0 && lb.b.rec(0) == 0 && lb.b.state(0) == 0, "TEC {} REC {} state {} at the end", lb.b.tec(0), lb.b.rec(0), lb.b.state(0));
            Ok(())
        })();
        ctx.record(&format!("iso_8_5_11_{name}"), r);
    }
    ctx.results
}
