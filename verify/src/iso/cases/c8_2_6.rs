//! ISO 16845-1:2016 clause 8.2.6 — ACK error of the transmitting IUT.
//!
//! What the case checks (in our words): the IUT transmits a frame and the
//! LT leaves the ACK slot recessive. The IUT must report an ACK error at
//! the ACK slot (TEC +8), send an active error flag from the ACK delimiter
//! on, and send the frame again, which the LT then acknowledges (TEC 7).
//!
//! Elementary test: `iso_8_2_6_no_ack`.

use super::super::{LtBench, Plan};
use super::common::*;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// The step of 8.2.6, 8.6.8 (TEC `tec0` before) and, error-passive
/// (exception 1: no TEC increment when the passive flag sees no dominant
/// bit), 8.6.17.
pub fn ack_error(lb: &mut LtBench, tec0: u32, passive: bool) -> Result<(), String> {
    let f = Frame::std(0x3A1, &[0xC0, 0xFF, 0x01]);
    let mut p = Plan::answer(lb.timing, &f, BuildOptions::default(), 0);
    let ack = p.find(Field::AckSlot, 1, false).unwrap();
    p.set_level(ack, true);
    let tec_err = if passive { tec0 } else { tec0 + 8 };
    transmit_error(lb, &f, tec0, p, ack, ack + 1, EV_ACK_ERR, (Field::AckSlot, 1), tec_err, passive).map(|_| ())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_2_6".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = ack_error(&mut lb, 0, false);
    ctx.record("iso_8_2_6_no_ack", r);
    ctx.results
}
