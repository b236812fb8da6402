//! ISO 16845-1:2016 clause 8.5.5 — an error-passive transmitter suspends
//! its retransmission after an error frame.
//!
//! What the case checks (in our words): the IUT is error-passive (TEC 128)
//! and transmits a base-format data frame; the LT overwrites its first
//! recessive data bit with a dominant one (bit error, TEC 136) and then
//! leaves the bus recessive for the passive error flag (6), error delimiter
//! (8), intermission (3) and suspend transmission (8). The IUT must drive
//! recessive throughout and start its retransmission exactly in the bit
//! after the eighth suspend bit (the LT checks every bit of it at that
//! position; an IUT without the suspend would start 8 bits earlier). TEC is
//! 135 at the end; exactly 8 Suspend_Transmission bits are recorded before the
//! retransmission.
//!
//! Elementary test: `iso_8_5_5_suspend_after_error_frame`.

use super::super::LtBench;
use super::c8_5_2::{bit_error_first, passive_tx, Scenario};
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_5_5".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let o = passive_tx(&mut lb, &Scenario { tec0: 128, levels: vec![true; 6 + 8 + 3 + 8], ..Default::default() })?;
        bit_error_first(&o, 136, 1)?;
        ensure!(o.r.iut_events(EV_PEF).len() == 1 && o.r.iut_events(EV_AEF).is_empty(), "error flags:{}", o.r.dump(0));
        let sof2 = o.r.iut().iter().enumerate().filter(|(_, b)| b.has(EV_SOF)).nth(1).map(|(i, _)| i).ok_or("no second SOF")?;
        let susp = o.r.iut()[..sof2].iter().filter(|b| b.field == Field::Suspend).count();
        ensure!(susp == 8, "{susp} suspend bits before the retransmission:{}", o.r.dump(0));
        ensure!(lb.b.tec(0) == 135, "TEC {} at the end, expected 135", lb.b.tec(0));
        Ok(())
    })();
    ctx.record("iso_8_5_5_suspend_after_error_frame", r);
    ctx.results
}
