//! ISO 16845-1:2016 clause 7.2.11 — the last instant at which a received
//! frame is still invalid for the IUT.
//!
//! What the case checks (in our words): the LT sends a frame (the IUT
//! acknowledges it) whose sixth End_Of_Frame bit is dominant. Up to that
//! bit the frame is not yet valid for a receiver: the IUT must report a
//! form error there, send an active error flag from EOF bit 7 on, count
//! REC +1 and deliver nothing (its host keeps the frame received before).
//!
//! Elementary test: `iso_7_2_11_eof6_dominant`.

use super::super::LtBench;
use super::c7_2_7::form_error_at;
use super::common::receive_frame;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::Field;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_2_11".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        // the IUT holds other data first
        let before = Frame::std(0x700, &[0xEE; 4]);
        receive_frame(&mut lb, &before, BuildOptions::default())?;
        form_error_at(&mut lb, Field::Eof, 6, 0, None)?;
        ensure!(lb.b.node(0).received().last() == Some(&before), "the last delivered frame changed");
        Ok(())
    })();
    ctx.record("iso_7_2_11_eof6_dominant", r);
    ctx.results
}
