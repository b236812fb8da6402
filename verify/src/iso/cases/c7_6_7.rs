//! ISO 16845-1:2016 clause 7.6.7 — REC after a form error at the ACK
//! delimiter of a frame that was error-free up to the ACK slot.
//!
//! What the case checks (in our words): from REC 9 the LT sends a frame,
//! the IUT acknowledges it, and the LT drives the ACK delimiter dominant.
//! The IUT must flag the form error (active error flag from EOF 1) and
//! deliver nothing; per ISO its REC first drops by 1 (frame error-free up
//! to the ACK slot) and then rises by 1: REC 9 at the end.
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
//! Elementary tests: `iso_7_6_7_ack_delimiter_form_error_iso_rule` and
//! `iso_7_6_7_ack_delimiter_form_error_bosch1999_rule`.

use super::super::LtBench;
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::core::RecRule;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_7".into(), vcd: None, results: vec![] };
    for (rule, tag, want) in [(RecRule::Iso, "iso_rule", 9), (RecRule::Bosch1999, "bosch1999_rule", 10)] {
        let mut cfg = NodeConfig::named("iut");
        cfg.rec_rule = rule;
        let mut lb = LtBench::new(vec![cfg]);
        let r = super::c7_2_7::form_error_at(&mut lb, Field::AckDel, 1, 9, Some(want));
        ctx.record(&format!("iso_7_6_7_ack_delimiter_form_error_{tag}"), r);
    }
    ctx.results
}
