//! ISO 16845-1:2016 clause 7.6.9 — REC +1 for a stuff error.
//!
//! What the case checks (in our words): stuff errors (a sixth equal bit)
//! at a recessive and at a dominant stuff bit in each of the arbitration
//! field, the control field, the data field and the CRC sequence; each
//! must raise REC from 0 to exactly 1 at that bit, with an active error
//! flag from the next bit (the step of 7.2.2).
//!
//! Elementary tests: `iso_7_6_9_<field>_<D|R>` (8).

use super::super::{LtBench, Plan};
use crate::conformance::{Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

use canstar_controller::frame::BuildOptions;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_6_9".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let mut done = vec![];
    for f in super::c7_2_2::frames() {
        let p = Plan::frame(lb.timing, &f, BuildOptions::default());
        for s in p.stuff_bits() {
            let l = p.bits[s].label.unwrap();
            let group = match l.field {
                Field::Ident | Field::Rtr => "arbitration",
                Field::Ide | Field::Resv | Field::Dlc => "control",
                Field::Data => "data",
                _ => "crc",
            };
            let key = (group, p.bits[s].level);
            if done.contains(&key) {
                continue;
            }
            done.push(key);
            let r = super::c7_2_2::stuff_error_at(&mut lb, &f, s);
            ctx.record(&format!("iso_7_6_9_{group}_{}", if key.1 { "R" } else { "D" }), r);
        }
    }
    ctx.results.sort_by(|a, b| a.name.cmp(&b.name));
    ctx.results
}
