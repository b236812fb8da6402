//! ISO 16845-1:2016 clause 7.1.3 — the IUT loses arbitration and receives
//! the winning frame.
//!
//! What the case checks (in our words): the IUT starts a frame; the LT
//! starts its own frame in the same bit, identical up to one arbitration
//! bit where the LT's is dominant and the IUT's recessive: RTR (both
//! base format), SRR or IDE (LT base format, IUT extended), the last base
//! identifier bit (LT extended, IUT base format), the last extension bit or
//! RTR (both extended). The IUT must lose arbitration exactly there, drive
//! nothing but the ACK slot of the LT's frame, deliver the LT's frame,
//! detect no error, and send its own frame again once the bus is idle
//! (which the LT acknowledges and checks bit by bit).
//!
//! Elementary tests: `iso_7_1_3_lt_<fmt>_iut_<fmt>_at_<bit>`, the six
//! classical-CAN tests of the standard.

use super::super::{LtBench, Plan, Trigger};
use super::common::errors;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// The IUT requests `iut`; the LT sends `lt` from the IUT's SOF on. The
/// IUT must lose arbitration at `lost` (FIELD, POSITION), acknowledge and
/// deliver `lt`, detect no error, then transmit `iut` (the LT acknowledges
/// and checks every bit of it) once, successfully. Starts its own step.
pub fn lose_and_retry(lb: &mut LtBench, iut: &Frame, lt: &Frame, lost: (Field, u32)) -> Result<(), String> {
    lb.begin_step("arbitration");
    let (got0, sent0) = (lb.b.node(0).received().len(), lb.b.node(0).sent().len());
    lb.b.node_mut(0).request(iut.clone());
    lb.wait(Trigger::at(Field::Sof, 1), 30)?;
    let p = Plan::frame(lb.timing, lt, BuildOptions::default());
    let ack = p.find(Field::AckSlot, 1, false).unwrap();
    let k = lb.play(&p);
    lb.wait(Trigger::at(Field::Sof, 1).nth(2), p.bits.len() as u64 + 30)?;
    let a = Plan::answer(lb.timing, iut, BuildOptions::default(), 3);
    lb.play_and_run(&a);
    lb.run_idle(30)?;
    let r = lb.end_step();
    r.check_expects()?;
    let lost_at = r.iut_events(EV_ARB_LOST);
    ensure!(lost_at.len() == 1 && (lost_at[0].field, lost_at[0].pos) == lost, "arbitration lost at {lost_at:?}, expected {} {}", lost.0.name(), lost.1);
    // after losing, the IUT drives recessive except the ACK slot of the LT's frame
    let li = p.bits.iter().position(|b| b.label.is_some_and(|l| (l.field, l.pos, l.stuff) == (lost.0, lost.1, false) || (lost.0 == Field::Srr && l.field == Field::Rtr && l.pos == 1 && !lt.ide))).ok_or("loss bit not in the LT's frame")?;
    for i in li..p.bits.len() {
        if i != ack {
            ensure!(r.iut_tx_at(k, i) == Some(true), "IUT drove dominant in plan bit {i} ({:?}) after losing", p.bits[i].label);
        }
    }
    let got = lb.b.node(0).received();
    ensure!(got.len() == got0 + 1 && got[got0] == *lt, "IUT delivered {:?}, expected {lt:?}", &got[got0..]);
    let e = errors(&r);
    ensure!(e.is_empty(), "errors detected: {e:?}");
    ensure!(r.iut_events(EV_TX_OK).len() == 1, "transmissions:{}", r.dump(0));
    let sent = lb.b.node(0).sent();
    ensure!(sent.len() == sent0 + 1 && sent[sent0] == *iut, "IUT sent {:?}", &sent[sent0..]);
    ensure!(lb.b.tec(0) == 0 && lb.b.rec(0) == 0, "TEC {} REC {}", lb.b.tec(0), lb.b.rec(0));
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_1_3".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let (b, x) = (0x2A5u32, 0x2A5u32 << 18 | 0x1_3579);
    let cases: Vec<(&str, Frame, Frame, (Field, u32))> = vec![
        ("lt_base_iut_base_at_rtr", Frame::std(b, &[0x11]), Frame::remote(false, b, 1), (Field::Rtr, 1)),
        ("lt_base_iut_ext_at_srr", Frame::std(b, &[0x22]), Frame::ext(x, &[0x22]), (Field::Srr, 1)),
        ("lt_base_iut_ext_at_ide", Frame::remote(false, b, 0), Frame::ext(x, &[0x33]), (Field::Ide, 1)),
        ("lt_ext_iut_base_at_id11", Frame::ext((b & !1) << 18 | 0x2_4680, &[0x44]), Frame::std(b, &[0x44]), (Field::Ident, 11)),
        ("lt_ext_iut_ext_at_ex18", Frame::ext(x & !1, &[0x55]), Frame::ext(x, &[0x55]), (Field::ExIdent, 18)),
        ("lt_ext_iut_ext_at_rtr", Frame::ext(x, &[0x66]), Frame::remote(true, x, 1), (Field::Rtr, 1)),
    ];
    for (name, lt, iut, lost) in cases {
        let r = lose_and_retry(&mut lb, &iut, &lt, lost);
        ctx.record(&format!("iso_7_1_3_{name}"), r);
    }
    ctx.results
}
