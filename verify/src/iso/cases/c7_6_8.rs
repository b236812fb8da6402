//! ISO 16845-1:2016 clause 7.6.8 — REC after a form error in
//! End_Of_Frame of a frame that was error-free up to the ACK slot.
//!
//! What the case checks (in our words): from REC 9 the LT sends a frame,
//! the IUT acknowledges it, and the LT drives EOF bit 2, 3 or 5 dominant.
//! The IUT must flag the form error from the next bit and deliver nothing;
//! per ISO REC drops by 1 at the ACK slot and rises by 1 at the form
//! error: REC 9 at the end.
//!
//! **Disagreement (README "Disagreements", D2; can-protocol.md C13).**
//! ISO 11898-1 counts a reception as successful once the receiver has read
//! its own ACK back dominant, so an ISO receiver decrements REC at the ACK
//! slot and the later form error adds 1: ISO 16845-1 expects REC unchanged
//! (9). The 1999 Bosch reference model decrements only at a recessive
//! End_Of_Frame bit 7, so REC ends at 10. canstar makes this a
//! generation-time option ([`crate::node::NodeConfig::rec_rule`]); the ISO
//! rule is the default. The case runs both controllers: the default one must
//! end at 9, the Bosch-rule one at 10.
//!
//! Elementary tests: `iso_7_6_8_eof<N>_form_error_<rule>`, N = 2, 3, 5,
//! rule `iso_rule` or `bosch1999_rule`.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::core::RecRule;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_8".into(), vcd: None, results: vec![] };
    for (rule, tag, want) in [(RecRule::Iso, "iso_rule", 9), (RecRule::Bosch1999, "bosch1999_rule", 10)] {
        let mut cfg = NodeConfig::named("iut");
        cfg.rec_rule = rule;
        let mut lb = LtBench::new(vec![cfg]);
        for n in [2, 3, 5] {
            let r = super::c7_2_7::form_error_at(&mut lb, Field::Eof, n, 9, Some(want));
            ctx.record(&format!("iso_7_6_8_eof{n}_form_error_{tag}"), r);
        }
    }
    ctx.results
}
