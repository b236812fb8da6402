//! ISO 16845-1:2016 clause 8.2.2 — bit errors in an extended-format frame
//! the IUT transmits.
//!
//! What the case checks (in our words): as 8.2.1 for an extended frame:
//! a bit of each level (dominant only inside the arbitration field: base
//! identifier, SRR, IDE, extension, RTR) in every field up to the CRC
//! sequence is read inverted by the IUT; it must report the bit error
//! there (TEC +8), send an active error flag from the next bit and send
//! the frame again successfully (TEC 7).
//!
//! Elementary tests: `iso_8_2_2_<field><pos>_<D|R>`.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::Frame;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_2_2".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    super::c8_2_1::bit_errors(&mut ctx, &mut lb, "8_2_2", &Frame::ext(0x0AB5_4C3A, &[0x96, 0x3C]));
    ctx.results
}
