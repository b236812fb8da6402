//! ISO 16845-1:2016 clause 8.6.21 — TEC unchanged by an error in a frame
//! the IUT receives after losing arbitration.
//!
//! What the case checks (in our words): with TEC preset to 8, the IUT
//! starts a frame (identifier 0x051) and the LT sends, from the same SOF, a
//! frame of higher priority (0x050): the IUT loses arbitration at the last
//! identifier bit and receives. The LT sends its first data stuff bit at
//! the wrong level: the IUT, now a receiver, reports a stuff error, sends
//! an active error flag (six dominant bits, checked) and its REC goes to
//! 1 while TEC stays 8 (checked after the error and up to the IUT's
//! retransmission). The LT then acknowledges the retransmitted frame
//! (checked bit by bit), which takes TEC to 7 as any successful
//! transmission does (8.6.11); REC stays 1.
//!
//! Elementary test: `iso_8_6_21_error_after_arbitration_lost` (the
//! classical-CAN test; the CAN FD variant of the standard does not apply).

use super::super::{LtBench, Plan, Trigger};
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

fn step(lb: &mut LtBench) -> Result<(), String> {
    let iut = Frame::std(0x051, &[0x80]);
    let lt = Frame::std(0x050, &[0x00, 0xFF]);
    let mut p = Plan::frame(lb.timing, &lt, BuildOptions::default());
    let s = p.stuff_bits().into_iter().find(|&i| p.bits[i].label.is_some_and(|l| l.field == Field::Data)).ok_or("no data stuff bit")?;
    let l = p.bits[s].level;
    p.set_level(s, !l).truncate(s + 1).push_recessive(6 + 8 + 3 + 2);
    for k in 0..6 {
        p.expect(s + 1 + k, false, "active error flag");
    }
    p.expect(s + 7, true, "error delimiter");
    lb.begin_step("error after arbitration lost");
    lb.preset(0, 8, 0);
    let (got0, sent0) = (lb.b.node(0).received().len(), lb.b.node(0).sent().len());
    lb.b.node_mut(0).request(iut.clone());
    lb.wait(Trigger::at(Field::Sof, 1), 30)?;
    lb.play(&p);
    lb.wait(Trigger::at(Field::Sof, 1).nth(2), p.bits.len() as u64 + 30)?;
    lb.play_and_run(&Plan::answer(lb.timing, &iut, BuildOptions::default(), 3));
    lb.run_idle(30)?;
    let r = lb.end_step();
    r.check_expects()?;
    let lost = r.iut_events(EV_ARB_LOST);
    ensure!(lost.len() == 1 && (lost[0].field, lost[0].pos) == (Field::Ident, 11), "arbitration lost at {lost:?}, expected Identifier 11");
    let e = errors(&r);
    ensure!(e.len() == 1 && e[0].has(EV_STUFF_ERR) && e[0].field == Field::Data, "errors {e:?}, expected one stuff error in the data field");
    ensure!(!e[0].tx_role, "the IUT was still a transmitter at the error: {}", e[0]);
    ensure!(e[0].tec == 8 && e[0].rec == 1, "TEC {} REC {} after the error, expected TEC 8 and REC 1", e[0].tec, e[0].rec);
    ensure!(r.iut_events(EV_AEF).len() == 1, "error flags:{}", r.dump(0));
    let sof2 = r.iut().iter().filter(|b| b.has(EV_SOF)).nth(1).copied().ok_or("no second SOF")?;
    let changed: Vec<_> = r.iut().iter().filter(|b| b.t > e[0].t && b.t < sof2.t && b.tec != 8).collect();
    ensure!(changed.is_empty(), "TEC changed before the retransmission: {changed:?}");
    ensure!(r.iut_events(EV_TX_OK).len() == 1, "no successful retransmission:{}", r.dump(0));
    ensure!(lb.b.tec(0) == 7 && lb.b.rec(0) == 1, "TEC {} REC {} at the end, expected 7 and 1", lb.b.tec(0), lb.b.rec(0));
    ensure!(lb.b.node(0).received().len() == got0, "a frame was delivered");
    let sent = lb.b.node(0).sent();
    ensure!(sent.len() == sent0 + 1 && sent[sent0] == iut, "sent {:?}", &sent[sent0..]);
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_6_21".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = step(&mut lb);
    ctx.record("iso_8_6_21_error_after_arbitration_lost", r);
    ctx.results
}
