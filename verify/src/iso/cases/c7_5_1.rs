//! ISO 16845-1:2016 clause 7.5.1 — an error-passive receiver completes
//! its passive error flag on six equal bits, also when another node's
//! active error flag overlaps it.
//!
//! What the case checks (in our words): the IUT is error-passive (REC
//! preset 128); after a stuff error in the data field it sends a passive
//! error flag (recessive). The LT superimposes an active error flag (six
//! dominant bits) starting at the first, third or sixth bit of the passive
//! flag, then leaves the bus recessive for 8 + 2 bits and starts a valid
//! frame in the third intermission bit. The IUT must drive recessive
//! throughout, detect no further error, and acknowledge and deliver the
//! frame (so its flag, delimiter and intermission ended exactly then).
//!
//! Elementary tests: `iso_7_5_1_active_flag_at_bit<N>`, N = 1, 3, 6.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// A passive receiver (REC 128) after a stuff error in the data field: the
/// LT drives `levels` from the IUT's first flag bit on, then starts a
/// valid frame; the IUT must stay recessive up to that frame, detect
/// nothing but the stuff error, and acknowledge and deliver the frame.
pub fn passive_then_frame(lb: &mut LtBench, levels: &[bool]) -> Result<(), String> {
    let (mut p, f) = error_in_data(lb);
    p.push_levels(levels);
    let g = Frame::std(0x1E5, &[0x99]);
    let s = p.push_frame(&g, BuildOptions::default());
    p.push_recessive(3);
    for i in f..s {
        p.expect(i, true, "recessive (passive flag, delimiter, intermission)");
    }
    let r = play_step(lb, &p, 128)?;
    r.check_expects()?;
    let e = errors(&r);
    ensure!(e.len() == 1 && e[0].has(EV_STUFF_ERR) && e[0].has(EV_PEF), "errors {e:?}");
    ensure!(lb.b.node(0).received().last() == Some(&g), "frame not delivered:{}", r.dump(0));
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_5_1".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for n in [1usize, 3, 6] {
        let mut v = vec![true; n - 1];
        v.extend([false; 6]);
        v.extend([true; 8 + 2]);
        let r = passive_then_frame(&mut lb, &v);
        ctx.record(&format!("iso_7_5_1_active_flag_at_bit{n}"), r);
    }
    ctx.results
}
