//! ISO 16845-1:2016 clause 8.6.18 — TEC +8 for an ACK error of an
//! error-passive transmitter whose passive flag sees a dominant bit.
//!
//! What the case checks (in our words): with TEC preset to 128
//! (error-passive), the IUT transmits a frame the LT does not acknowledge.
//! The IUT reports the ACK error and sends a passive error flag from the
//! ACK delimiter on; the LT drives the sixth bit of that flag dominant.
//! Exception 1 of the TEC rules (no increment for a passive ACK error)
//! does not apply then: TEC must be 136 before the retransmission. The
//! dominant bit restarts the six equal bits the passive flag waits for, so
//! the flag ends six bits later, and after error delimiter, intermission
//! and suspend transmission the IUT sends its frame again 31 bit times
//! after the start of the ACK delimiter; the LT acknowledges and checks
//! it, and TEC ends at 135. The only error reported is the ACK error.
//!
//! Elementary test: `iso_8_6_18_passive_ack_error_dominant_flag_bit` (the
//! classical-CAN test; the CAN FD variant of the standard does not apply).

use super::super::{LtBench, Plan, Trigger};
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

fn step(lb: &mut LtBench) -> Result<(), String> {
    let f = Frame::std(0x3A1, &[0xC0, 0xFF, 0x01]);
    let mut p = Plan::answer(lb.timing, &f, BuildOptions::default(), 0);
    let ack = p.find(Field::AckSlot, 1, false).unwrap();
    let flag = ack + 1;
    p.set_level(ack, true).truncate(flag).push_recessive(6 + 6 + 8 + 3 + 4);
    p.set_level(flag + 5, false);
    for k in 0..12 {
        p.expect(flag + k, true, "passive error flag");
    }
    lb.begin_step("passive ack error, dominant flag bit");
    lb.preset(0, 128, 0);
    ensure!(lb.b.state(0) == 1, "not error-passive");
    let sent0 = lb.b.node(0).sent().len();
    lb.b.node_mut(0).request(f.clone());
    lb.wait(Trigger::at(Field::Sof, 1), 30)?;
    let k = lb.play(&p);
    let t2 = lb.wait(Trigger::at(Field::Sof, 1).nth(2), p.bits.len() as u64 + 8 + 30)?;
    lb.play_and_run(&Plan::answer(lb.timing, &f, BuildOptions::default(), 3));
    lb.run_idle(30)?;
    let r = lb.end_step();
    r.check_expects()?;
    let e = errors(&r);
    ensure!(e.len() == 1 && e[0].has(EV_ACK_ERR) && e[0].field == Field::AckSlot, "errors {e:?}, expected one ACK error at the ACK slot");
    ensure!(r.iut_events(EV_PEF).len() == 1 && r.iut_events(EV_EXC1).is_empty(), "flags / exception 1:{}", r.dump(0));
    let sof2 = r.iut().iter().filter(|b| b.has(EV_SOF)).nth(1).copied().ok_or("no second SOF")?;
    let before = r.iut().iter().rev().find(|b| b.t < sof2.t).copied().unwrap();
    ensure!(before.tec == 136, "TEC {} before the retransmission, expected 136:{}", before.tec, r.dump(0));
    let g = (t2 - r.bit_start(k, flag)) as f64 / lb.b.bit_ps as f64;
    ensure!(g == 31.0, "second SOF {g} bit times after the ACK delimiter's start, expected 31:{}", r.dump(0));
    ensure!(r.iut_events(EV_TX_OK).len() == 1, "no successful retransmission:{}", r.dump(0));
    ensure!(lb.b.tec(0) == 135 && lb.b.rec(0) == 0, "TEC {} REC {} at the end, expected 135 and 0", lb.b.tec(0), lb.b.rec(0));
    let sent = lb.b.node(0).sent();
    ensure!(sent.len() == sent0 + 1 && sent[sent0] == f, "sent {:?}", &sent[sent0..]);
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_6_18".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = step(&mut lb);
    ctx.record("iso_8_6_18_passive_ack_error_dominant_flag_bit", r);
    ctx.results
}
