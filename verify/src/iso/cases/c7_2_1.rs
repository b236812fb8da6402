//! ISO 16845-1:2016 clause 7.2.1 — bit error in the IUT's own ACK bit.
//!
//! What the case checks (in our words): the IUT receives a valid frame and
//! drives the ACK slot dominant; the LT overrides the bus to recessive for
//! that bit (for every node, so the IUT reads back recessive). The IUT
//! must see a bit error at the ACK slot, drive an active error flag from
//! the ACK delimiter on, deliver nothing and count REC +1.
//!
//! Elementary test: `iso_7_2_1_ack_forced_recessive`.

use super::super::{Action, At, Disturbance, LtBench, Plan, Span, Target};
use super::common::{receive_error, RxError};
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// The step of 7.2.1 (and 7.6.5): REC `rec0` before.
pub fn ack_bit_error(lb: &mut LtBench, rec0: u32) -> Result<(), String> {
    let f = Frame::std(0x6C9, &[0x12, 0x34]);
    let mut p = Plan::frame(lb.timing, &f, BuildOptions::default());
    let ack = p.find(Field::AckSlot, 1, false).unwrap();
    p.disturb(Disturbance { at: At::tq(ack, 0), span: Span::Bits(1), action: Action::Force(true), target: Target::Bus });
    receive_error(lb, p, ack, RxError { ev: EV_BIT_ERR, at: (Field::AckSlot, 1), flag: ack + 1, rec: None }, rec0).map(|_| ())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_2_1".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = ack_bit_error(&mut lb, 0);
    ctx.record("iso_7_2_1_ack_forced_recessive", r);
    ctx.results
}
