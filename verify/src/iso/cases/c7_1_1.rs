//! ISO 16845-1:2016 clause 7.1.1 — the IUT as receiver of valid base-format
//! data frames: identifier and number of data bytes.
//!
//! What the case checks (in our words): the lower tester sends well-formed
//! standard (11-bit) data frames over a spread of identifiers (all
//! dominant, all recessive, alternating patterns, single bits) and every
//! data length 0..8. For each frame, the IUT must drive the ACK slot
//! dominant (and only the ACK slot), deliver exactly the frame that was
//! sent, detect no error, and keep its receive counter at 0.
//!
//! Elementary tests: `iso_7_1_1_id<ID>_dlc<N>`, one LT step each, on one
//! bench (the IUT alone with the LT, default timing T10/6/4).

use super::super::{LtBench, Plan};
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// The identifiers of the case.
pub const IDS: [u32; 8] = [0x000, 0x7FF, 0x555, 0x2AA, 0x001, 0x400, 0x0F0, 0x70F];

/// Data bytes of a frame with `dlc` bytes: a pattern that varies with the
/// identifier and the byte index.
fn data(id: u32, dlc: usize) -> Vec<u8> {
    (0..dlc).map(|i| (id as u8).wrapping_mul(31).wrapping_add(0x3B * i as u8) ^ (i as u8).rotate_left(3)).collect()
}

/// One elementary test: the LT sends `f`; the IUT acknowledges and delivers it.
pub fn receive_one(lb: &mut LtBench, f: &Frame) -> Result<(), String> {
    let got0 = lb.b.node(0).received().len();
    lb.begin_step("rx");
    let mut p = Plan::frame(lb.timing, f, BuildOptions::default());
    p.push_recessive(3);
    lb.play_and_run(&p);
    lb.run_idle(20)?;
    let r = lb.end_step();
    r.check_expects()?;
    let ack = p.find(Field::AckSlot, 1, false).ok_or("no ACK slot in the plan")?;
    for (i, b) in p.bits.iter().enumerate() {
        if i != ack {
            ensure!(r.iut_tx_at(0, i) == Some(true), "IUT drove dominant in plan bit {i} ({:?}) besides the ACK slot", b.label);
        }
    }
    let got = lb.b.node(0).received();
    ensure!(got.len() == got0 + 1 && got[got0] == *f, "IUT delivered {:?}, expected {f:?}", &got[got0..]);
    let errs: Vec<_> = r.iut().iter().filter(|b| b.ev & ((1 << EV_BIT_ERR) | (1 << EV_STUFF_ERR) | (1 << EV_CRC_ERR) | (1 << EV_FORM_ERR) | (1 << EV_ACK_ERR)) != 0).collect();
    ensure!(errs.is_empty(), "IUT detected errors: {errs:?}");
    ensure!(lb.b.rec(0) == 0 && lb.b.tec(0) == 0, "counters TEC {} REC {}", lb.b.tec(0), lb.b.rec(0));
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_1_1".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for id in IDS {
        for dlc in 0..=8usize {
            let f = Frame::std(id, &data(id, dlc));
            let r = receive_one(&mut lb, &f);
            ctx.record(&format!("iso_7_1_1_id{id:03x}_dlc{dlc}"), r);
        }
    }
    ctx.results
}
