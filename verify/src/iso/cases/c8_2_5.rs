//! ISO 16845-1:2016 clause 8.2.5 — form errors in a frame the IUT
//! transmits.
//!
//! What the case checks (in our words): the IUT transmits a frame, the LT
//! acknowledges it but drives one fixed-form bit dominant: the CRC
//! delimiter, the ACK delimiter, EOF bit 1, 4 or 7. The IUT must report a
//! form error at that bit (TEC +8; a transmitter has no last-bit rule, so
//! EOF 7 too), send an active error flag from the next bit and send the
//! frame again successfully (TEC 7).
//!
//! Elementary tests: `iso_8_2_5_<field><pos>`.

use super::super::{LtBench, Plan};
use super::common::*;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_2_5".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let f = Frame::std(0x49C, &[0x0F, 0x5A]);
    for (field, pos) in [(Field::CrcDel, 1), (Field::AckDel, 1), (Field::Eof, 1), (Field::Eof, 4), (Field::Eof, 7)] {
        let mut p = Plan::answer(lb.timing, &f, BuildOptions::default(), 0);
        let i = p.find(field, pos, false).unwrap();
        p.set_level(i, false);
        let r = transmit_error(&mut lb, &f, 0, p, i, i + 1, EV_FORM_ERR, (field, pos), 8, false).map(|_| ());
        ctx.record(&format!("iso_8_2_5_{}{pos}", super::c8_2_1::short(field)), r);
    }
    ctx.results
}
