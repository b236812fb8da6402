//! ISO 16845-1:2016 clause 7.5.6 — form error in the error delimiter of an
//! error-passive receiver.
//!
//! What the case checks (in our words): the IUT is error-passive (REC
//! 128); after a stuff error in the data field it sends a passive error
//! flag; the LT drives the 2nd, 4th or 7th bit of the following error
//! delimiter dominant. The IUT must report a form error there and start a
//! new passive error flag (REC stays above 127: canstar does not increment
//! REC beyond 128, can-protocol.md C12, and ISO checks no value here); the
//! LT then sends 6 + 7 recessive bits and a dominant one, the last bit of the new error delimiter. The IUT
//! must drive recessive up to that bit and answer it with an overload flag
//! (six dominant bits) from the next bit; no frame is delivered.
//!
//! Elementary tests: `iso_7_5_6_error_delimiter_bit<N>`, N = 2, 4, 7.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_5_6".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [2usize, 4, 7] {
        let r = (|| {
            let got0 = lb.b.node(0).received().len();
            let o = delim(n) + 1 + 6 + 7 + 1;
            let (r, f) = flag_scenario(&mut lb, Start::ErrorInData, &[delim(n), o - 1], &[], Some(o), 128)?;
            for k in 0..o {
                ensure!(r.iut_tx_at(0, f + k) == Some(true), "IUT dominant {k} bits after its first flag bit:{}", r.dump(0));
            }
            let e = errors(&r);
            ensure!(e.len() == 2 && e[0].has(EV_STUFF_ERR) && e[0].has(EV_PEF), "errors {e:?}");
            let b = event_at(&r, EV_FORM_ERR, Field::ErrDel, n as u32)?;
            ensure!(b.has(EV_PEF) && b.rec >= 128 && b.state == 1, "at {b}: a new passive flag expected, error-passive");
            event_at(&r, EV_OLF, Field::ErrDel, 8)?;
            ensure!(r.iut_events(EV_AEF).is_empty() && r.iut_events(EV_OLF).len() == 1, "flags:{}", r.dump(0));
            ensure!(lb.b.rec(0) >= 128 && lb.b.node(0).received().len() == got0, "REC {} at the end, expected error-passive (frames delivered {})", lb.b.rec(0), lb.b.node(0).received().len() - got0);
            Ok(())
        })();
        ctx.record(&format!("iso_7_5_6_error_delimiter_bit{n}"), r);
    }
    ctx.results
}
