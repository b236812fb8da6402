//! ISO 16845-1:2016 clause 8.4.3 — after an overload frame, the IUT
//! transmits when it sees a start of frame in the third intermission bit.
//!
//! What the case checks (in our words): the IUT is error-active (TEC 0) and
//! transmits a base-format data frame; the LT overwrites its first
//! recessive data bit with a dominant one (bit error, TEC 8). After the
//! IUT's active error flag (six dominant bits) and 7 recessive delimiter
//! bits the LT drives the eighth error delimiter bit dominant: the IUT must
//! send an overload flag (six dominant bits) from the next bit. After the
//! overload delimiter the LT leaves two intermission bits recessive and
//! drives the third dominant. The IUT must take that bit as the start of
//! frame and repeat its frame from the first identifier bit without a SOF
//! of its own (recessive in that bit): the LT checks every bit the IUT
//! drives, acknowledges, and the IUT reports success (TEC 7). Once with an
//! identifier starting with four dominant bits (with the LT's SOF five, so
//! a stuff bit follows), once with five recessive bits.
//!
//! Elementary tests: `iso_8_4_3_id<ID>`.

use super::super::LtBench;
use super::c8_5_2::{bit_error_first, passive_tx, Scenario};
use super::common::{delim, event_at};
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::Frame;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_4_3".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for id in [0x07Au32, 0x7CA] {
        let r = (|| {
            let mut v = vec![true; delim(8)];
            v.push(false);
            let o = v.len();
            v.extend([true; 6 + 8 + 2]);
            let mut dom: Vec<usize> = (0..6).collect();
            dom.extend(o..o + 6);
            let s = Scenario { tec0: 0, levels: v, iut_dom: dom, tx: Some(Frame::std(id, &[0x5A, 0x81])), lt_sof: true, ..Default::default() };
            let out = passive_tx(&mut lb, &s)?;
            bit_error_first(&out, 8, 1)?;
            event_at(&out.r, EV_OLF, Field::ErrDel, 8)?;
            ensure!(out.r.iut_events(EV_AEF).len() == 1 && out.r.iut_events(EV_OLF).len() == 1, "flags:{}", out.r.dump(0));
            ensure!(lb.b.tec(0) == 7, "TEC {} at the end, expected 7", lb.b.tec(0));
            Ok(())
        })();
        ctx.record(&format!("iso_8_4_3_id{id:03x}"), r);
    }
    ctx.results
}
