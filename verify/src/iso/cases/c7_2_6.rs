//! ISO 16845-1:2016 clause 7.2.6 — a CRC error and a form error at the
//! CRC delimiter of the same frame give one error flag.
//!
//! What the case checks (in our words): the LT sends a frame with one CRC
//! bit inverted (stuffing unchanged, as in 7.2.5) and a dominant CRC
//! delimiter. The IUT must report the form error at the CRC delimiter,
//! start one six-bit active error flag with the next bit (the ACK slot,
//! not after the ACK delimiter as for a CRC error alone), report no CRC
//! error of its own later, deliver nothing and count REC +1 once.
//!
//! Elementary test: `iso_7_2_6_crc_and_crc_delimiter_errors`.

use super::super::{LtBench, Plan};
use super::c7_2_5::crc_flip;
use super::common::{receive_error, RxError};
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_2_6".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let f = Frame::std(0x35C, &[0x96, 0x0E]);
        let mut p = Plan::frame(lb.timing, &f, BuildOptions::default());
        let i = crc_flip(&p, false).ok_or("no CRC bit to invert")?;
        p.set_level(i, true);
        let cd = p.find(Field::CrcDel, 1, false).unwrap();
        p.set_level(cd, false);
        let r = receive_error(&mut lb, p, cd, RxError { ev: EV_FORM_ERR, at: (Field::CrcDel, 1), flag: cd + 1, rec: None }, 0)?;
        ensure!(r.iut_events(EV_CRC_ERR).is_empty(), "a CRC error reported as well:{}", r.dump(0));
        Ok(())
    })();
    ctx.record("iso_7_2_6_crc_and_crc_delimiter_errors", r);
    ctx.results
}
