//! ISO 16845-1:2016 clause 8.5.1 — an error-passive transmitter does not
//! take an active error flag overlapping its passive error flag for a new
//! error.
//!
//! What the case checks (in our words): the IUT is error-passive (TEC 128)
//! and transmits a base-format data frame; the LT overwrites the first
//! recessive data bit the IUT sends with a dominant one, so the IUT reports
//! a bit error (TEC 136) and sends a passive error flag (6 recessive bits,
//! checked on the IUT's TX). Meanwhile the LT sends an active error flag (6
//! dominant bits) starting at the first, the third or the sixth bit of that
//! passive flag. The dominant bits must not count as a new error: only the
//! one bit error is reported, the IUT's passive flag completes on the 6
//! dominant bits, and after error delimiter, intermission and suspend
//! transmission the IUT sends the frame again, which the LT acknowledges
//! and checks, its SOF 19 bit times after the last dominant bit of the
//! LT's flag; TEC is 135 at the end and the frame was sent once.
//!
//! Elementary tests: `iso_8_5_1_active_flag_at_<1|3|6>`.

use super::super::{LtBench, Plan, Trigger};
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// One step: the bit error, the passive flag with 6 dominant bits from the
/// LT starting at flag bit `start` (1-based; 7 = right after the flag),
/// and the second SOF exactly `gap` bit times after the corrupted bit.
pub fn step(lb: &mut LtBench, f: &Frame, start: usize, gap: u64) -> Result<(), String> {
    let mut p = Plan::answer(lb.timing, f, BuildOptions::default(), 0);
    let (i, at) = first_recessive_data_bit(&p)?;
    corrupt(&mut p, i);
    let flag = i + 1;
    lb.begin_step("passive flag overlapped");
    lb.preset(0, 128, 0);
    ensure!(lb.b.state(0) == 1, "not error-passive");
    let sent0 = lb.b.node(0).sent().len();
    lb.b.node_mut(0).request(f.clone());
    lb.wait(Trigger::at(Field::Sof, 1), 30)?;
    p.truncate(i + 1).push_recessive(start - 1 + 6 + 6 + 4);
    for k in 0..6 {
        p.set_level(flag + start - 1 + k, false);
        p.expect(flag + k, true, "passive error flag");
    }
    let k = lb.play(&p);
    let t2 = lb.wait(Trigger::at(Field::Sof, 1).nth(2), p.bits.len() as u64 + 8 + 3 + 8 + 30)?;
    lb.play_and_run(&Plan::answer(lb.timing, f, BuildOptions::default(), 3));
    lb.run_idle(30)?;
    let r = lb.end_step();
    r.check_expects()?;
    let end = r.bit_start(k, i + 1);
    let g = (t2 - end) as f64 / lb.b.bit_ps as f64;
    ensure!(g == gap as f64, "second SOF {g} bit times after the corrupted bit, expected {gap}:{}", r.dump(0));
    let e = errors(&r);
    ensure!(e.len() == 1, "{} errors, expected one:{}", e.len(), r.dump(0));
    ensure!(e[0].has(EV_BIT_ERR) && (e[0].field, e[0].pos) == at, "error at {}, expected a bit error at {} {}", e[0], at.0.name(), at.1);
    ensure!(e[0].tec == 136, "TEC {} after the bit error, expected 136", e[0].tec);
    ensure!(r.iut_events(EV_PEF).len() == 1 && r.iut_events(EV_AEF).is_empty(), "error flags:{}", r.dump(0));
    ensure!(r.iut_events(EV_TX_OK).len() == 1, "no successful retransmission:{}", r.dump(0));
    ensure!(lb.b.tec(0) == 135 && lb.b.rec(0) == 0, "TEC {} REC {} at the end, expected TEC 135", lb.b.tec(0), lb.b.rec(0));
    let sent = lb.b.node(0).sent();
    ensure!(sent.len() == sent0 + 1 && sent[sent0] == *f, "sent {:?}", &sent[sent0..]);
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_5_1".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let f = Frame::std(0x2B4, &[0x96, 0x3C]);
    // the flag ends on the 6th dominant bit, then delimiter 8, intermission 3, suspend 8
    for start in [1, 3, 6] {
        let r = step(&mut lb, &f, start, (start + 5 + 19) as u64);
        ctx.record(&format!("iso_8_5_1_active_flag_at_{start}"), r);
    }
    ctx.results
}
