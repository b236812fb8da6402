//! ISO 16845-1:2016 clause 8.6.15 — no TEC change for a dominant last bit
//! of the transmitting IUT's overload delimiter.
//!
//! What the case checks (in our words): after its successful frame (TEC 0)
//! and an overload flag, the LT drives the 8th overload delimiter bit
//! dominant: the IUT sends another overload flag from the next bit, detects
//! no error, and TEC stays 0.
//!
//! Elementary test: `iso_8_6_15_overload_delimiter_bit8`.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_6_15".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let (r, _) = tx_flag_scenario(&mut lb, Start::OverloadAfterFrame, &[delim(8)], &[], Some((delim(8) + 1, false)), 0)?;
        event_at(&r, EV_OLF, Field::OvlDel, 8)?;
        ensure!(errors(&r).is_empty() && lb.b.tec(0) == 0, "errors {:?}, TEC {}", errors(&r), lb.b.tec(0));
        Ok(())
    })();
    ctx.record("iso_8_6_15_overload_delimiter_bit8", r);
    ctx.results
}
