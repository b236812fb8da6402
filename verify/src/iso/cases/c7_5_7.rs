//! ISO 16845-1:2016 clause 7.5.7 — an error-active receiver becomes
//! error-passive.
//!
//! What the case checks (in our words): from REC 0, a stuff error in the
//! data field (REC 1) starts the IUT's active error flag; the LT forces the
//! bus recessive for 17 consecutive flag bits, each a bit error that
//! restarts the flag. The 16th brings REC from 121 to 129: the IUT is
//! error-passive, but the flag it starts for that error is still active
//! (the flag type comes from the state before the error, can-protocol.md
//! §10); the 17th bit error, seen while passive, must start a passive
//! (recessive) error flag. The LT then sends a valid frame 6 + 8 + 3 bits
//! after its last recessive bit, which the IUT must acknowledge and
//! deliver (REC back to 127).
//!
//! Elementary test: `iso_7_5_7_active_to_passive`.

use super::super::LtBench;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

use super::super::{Action, At, Disturbance, Span, Target};

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_5_7".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let (mut p, f) = error_in_data(&lb);
        p.push_recessive(17 + 6 + 8 + 3);
        p.disturb(Disturbance { at: At::tq(f, 0), span: Span::Bits(17), action: Action::Force(true), target: Target::Bus });
        let g = Frame::std(0x0B3, &[0x44]);
        p.push_frame(&g, BuildOptions::default());
        p.push_recessive(3);
        for i in f + 17..f + 17 + 6 {
            p.expect(i, true, "passive error flag");
        }
        let r = play_step(&mut lb, &p, 0)?;
        r.check_expects()?;
        let bits = r.iut_events(EV_BIT_ERR);
        ensure!(bits.len() == 17, "{} bit errors:{}", bits.len(), r.dump(0));
        ensure!(bits[14].rec == 121 && bits[15].rec == 129 && bits[15].state == 1, "REC after the 15th/16th bit errors: {} / {}", bits[14], bits[15]);
        ensure!(bits[15].has(EV_AEF) && bits[16].has(EV_PEF), "flags after the 16th/17th bit errors: {} / {}", bits[15], bits[16]);
        ensure!(lb.b.node(0).received().last() == Some(&g), "frame not delivered");
        ensure!(lb.b.rec(0) == 127 && lb.b.state(0) == 0, "REC {} state {}", lb.b.rec(0), lb.b.state(0));
        Ok(())
    })();
    ctx.record("iso_7_5_7_active_to_passive", r);
    ctx.results
}
