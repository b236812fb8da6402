//! ISO 16845-1:2016 clause 7.2.7 — the IUT as receiver: form error at the
//! CRC delimiter.
//!
//! What the case checks (in our words): the LT sends a frame whose CRC
//! delimiter is dominant. The IUT must report a form error at that bit,
//! drive an active error flag from the next bit (the ACK slot) on, deliver
//! nothing and count REC +1.
//!
//! Elementary test: `iso_7_2_7_crc_delimiter_dominant`.

use super::super::{LtBench, Plan};
use super::common::{receive_error, RxError};
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// A form error: bit (`field`, `pos`) of the LT's frame sent dominant, REC
/// `rec0` before, REC `rec` expected after (default `rec0 + 1`) (7.2.7, 7.2.9, 7.2.10, 7.2.11 and the 7.6 REC cases).
pub fn form_error_at(lb: &mut LtBench, field: Field, pos: u32, rec0: u32, rec: Option<u32>) -> Result<(), String> {
    let f = Frame::std(0x1B7, &[0x5E, 0x01, 0xC8]);
    let mut p = Plan::frame(lb.timing, &f, BuildOptions::default());
    let i = p.find(field, pos, false).ok_or("bit not in the frame")?;
    p.set_level(i, false);
    receive_error(lb, p, i, RxError { ev: EV_FORM_ERR, at: (field, pos), flag: i + 1, rec }, rec0).map(|_| ())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_2_7".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = form_error_at(&mut lb, Field::CrcDel, 1, 0, None);
    ctx.record("iso_7_2_7_crc_delimiter_dominant", r);
    ctx.results
}
