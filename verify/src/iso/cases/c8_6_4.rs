//! ISO 16845-1:2016 clause 8.6.4 — TEC +8 for each eighth dominant bit
//! after the passive error flag of an error-passive transmitter.
//!
//! What the case checks (in our words): the IUT is error-passive (TEC
//! preset to 128) and transmits a frame; the LT forces its first dominant
//! data bit recessive, so the IUT reports a bit error (TEC 136) and sends a
//! passive error flag (six recessive bits, checked on the IUT's TX). Right
//! after the flag the LT keeps the bus dominant for n bits, n = 1, 6, 8, 9
//! or 16. TEC must not change for dominant bits 1..7, rise by 8 at the 8th
//! (144) and by 8 again at the 16th (152); the retransmission, which the
//! LT acknowledges, then takes one off. Only the bit error counts as an
//! error.
//!
//! Elementary tests: `iso_8_6_4_<n>_dominant_after_passive_flag` (the five
//! classical-CAN tests; the CAN FD variant of the standard does not apply).

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

/// TEC expected after `k` (1-based) dominant bits following the passive flag.
fn tec_after(k: usize) -> u32 {
    136 + 8 * (k / 8) as u32
}

fn step(lb: &mut LtBench, n: usize) -> Result<(), String> {
    let dom: Vec<usize> = (6..6 + n).collect();
    let (r, first) = tx_flag_scenario(lb, Start::ErrorInData, &dom, &[], Some((0, true)), 128)?;
    let e = errors(&r);
    ensure!(e.len() == 1 && e[0].has(EV_BIT_ERR) && e[0].tec == 136, "errors {e:?}, expected one bit error with TEC 136");
    ensure!(r.iut_events(EV_PEF).len() == 1 && r.iut_events(EV_AEF).is_empty(), "error flags:{}", r.dump(0));
    // the IUT's bit records of the first play from the first flag bit on,
    // up to the retransmission's SOF
    let t_flag = r.bit_start(0, first);
    let after: Vec<_> = r.iut().iter().filter(|b| b.t >= t_flag).take_while(|b| !b.has(EV_SOF)).copied().collect();
    ensure!(after.len() > 6 + n, "too few IUT bits after the flag:{}", r.dump(0));
    for k in 1..=n {
        let b = after[5 + k];
        ensure!(!b.level, "IUT bit {b} ({k}th after the flag) not read dominant");
        ensure!(b.tec == tec_after(k), "TEC {} after dominant bit {k} after the passive flag, expected {}:{}", b.tec, tec_after(k), r.dump(0));
    }
    let last = after.last().unwrap();
    ensure!(last.tec == tec_after(n), "TEC {} before the retransmission, expected {}", last.tec, tec_after(n));
    ensure!(lb.b.tec(0) == tec_after(n) - 1, "TEC {} at the end, expected {}", lb.b.tec(0), tec_after(n) - 1);
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_6_4".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [1, 6, 8, 9, 16] {
        let r = step(&mut lb, n);
        ctx.record(&format!("iso_8_6_4_{n}_dominant_after_passive_flag"), r);
    }
    ctx.results
}
