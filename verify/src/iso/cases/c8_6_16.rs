//! ISO 16845-1:2016 clause 8.6.16 — no TEC change for a dominant last bit
//! of the transmitting IUT's error delimiter.
//!
//! What the case checks (in our words): after a bit error in the data
//! field of the IUT's frame (TEC 8) and its active error flag, the LT
//! drives the 8th error delimiter bit dominant: an overload flag from the
//! next bit, no further error, TEC 8 (7 after the retransmission).
//!
//! Elementary test: `iso_8_6_16_error_delimiter_bit8`.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_6_16".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let (r, _) = tx_flag_scenario(&mut lb, Start::ErrorInData, &[delim(8)], &[], Some((delim(8) + 1, false)), 0)?;
        let b = event_at(&r, EV_OLF, Field::ErrDel, 8)?;
        ensure!(b.tec == 8 && errors(&r).len() == 1, "TEC {} after the dominant bit, errors {:?}", b.tec, errors(&r));
        ensure!(lb.b.tec(0) == 7, "TEC {} at the end, expected 7", lb.b.tec(0));
        Ok(())
    })();
    ctx.record("iso_8_6_16_error_delimiter_bit8", r);
    ctx.results
}
