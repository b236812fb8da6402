//! ISO 16845-1:2016 clause 8.7.2 — hard synchronisation of an IUT with a
//! pending transmission on a dominant bit before the sample point of the
//! third intermission bit.
//!
//! What the case checks (in our words): the IUT transmits a frame whose
//! identifier starts recessive (0x4A5); the LT forces its first dominant
//! data bit recessive, so the IUT reports a bit error (TEC 8), sends an
//! active error flag (checked) and keeps the frame pending. In the third
//! intermission bit after the error delimiter the LT starts a dominant bit
//! 1 TQ + 1 clock (the minimum time quantum; a TQ is 4 clocks here) before
//! the IUT's sample point. The IUT must hard-synchronise on that edge, take
//! the dominant bit as a SOF without sending one itself (its TX recessive
//! there, checked) and send its frame from the first identifier bit on:
//! the bit it hard-synchronised starts at most 1 TQ before the LT's edge
//! and not after it (measured on the IUT's sample point of that SOF), and
//! its first edge in the arbitration field comes an integer number of bit
//! times − (0 .. 1 TQ) after the LT's edge. The LT answers the frame on
//! that grid (every bit checked, SOF recessive for the IUT) and
//! acknowledges it: one successful transmission, TEC 7.
//!
//! Run for every sample point 3..9 TQ of a 10-TQ bit (4 clocks per TQ, see
//! [`super::c8_7_4::sp_config`]).
//!
//! Elementary tests: `iso_8_7_2_sp<SP>`. The helper serves 8.7.3.

use super::super::{Action, At, Disturbance, LtBench, Plan, Span, StepRecord, Target, Trigger};
use super::c8_7_4::sp_config;
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// What [`intermission_sof`] recorded.
pub struct InterSof {
    pub r: StepRecord,
    /// Time (ps) of the LT's edge in intermission bit 3.
    pub t_edge: u64,
    /// The IUT's TX offset ([`tx_offset`]).
    pub o: u64,
    /// Time from the start of a bit as the IUT perceives it to the bit
    /// record of its sample point, measured on the first SOF.
    pub c: u64,
}

/// The IUT transmits `f`; its first dominant data bit is forced recessive
/// (a bit error, an active error flag), then the LT stays recessive through
/// error delimiter and intermission bits 1 and 2, and starts a SOF of its
/// own `edge_tq` TQ into intermission bit 3, kept recessive on the bus for
/// `delay` more clocks; from that SOF on it answers `f` (its ACK, every bit
/// of the IUT checked, the IUT's TX at SOF expected `iut_sof`). The IUT
/// must report that one bit error, TEC 8, send the frame once successfully
/// and end with TEC 7.
pub fn intermission_sof(lb: &mut LtBench, f: &Frame, edge_tq: u32, delay: u32, iut_sof: bool) -> Result<InterSof, String> {
    let t = lb.timing;
    let mut p = Plan::answer(t, f, BuildOptions::default(), 0);
    let i = (0..p.bits.len()).find(|&i| p.bits[i].label.is_some_and(|l| l.field == Field::Data && !l.stuff) && p.expects.iter().any(|e| e.bit == i && !e.level)).ok_or("no dominant data bit")?;
    let at = p.bits[i].label.map(|l| (l.field, l.pos)).unwrap();
    corrupt(&mut p, i);
    p.truncate(i + 1).push_recessive(6 + 8 + 3);
    let flag = i + 1;
    for k in 0..6 {
        p.expect(flag + k, false, "active error flag");
    }
    p.expect(flag + 6, true, "error delimiter");
    let int3 = flag + 6 + 8 + 2;
    p.bits[int3].tq = edge_tq;
    let mut q = Plan::answer(t, f, BuildOptions::default(), 3);
    q.set_level(0, false);
    q.expects.retain(|e| e.bit != 0);
    q.expect(0, iut_sof, "IUT's TX in the SOF");
    if delay > 0 {
        q.disturb(Disturbance { at: At::tq(0, 0), span: Span::Clocks(delay), action: Action::Force(true), target: Target::Bus });
    }
    let s = append_plan(&mut p, &q);
    lb.begin_step("sof in intermission 3");
    lb.preset(0, 0, 0);
    let sent0 = lb.b.node(0).sent().len();
    lb.b.node_mut(0).request(f.clone());
    lb.wait(Trigger::at(Field::Sof, 1), 30)?;
    let k = lb.play_and_run(&p);
    lb.run_idle(30)?;
    let r = lb.end_step();
    r.check_expects()?;
    let e = errors(&r);
    ensure!(e.len() == 1 && e[0].has(EV_BIT_ERR) && (e[0].field, e[0].pos) == at && e[0].tec == 8, "errors {e:?}, expected one bit error at {} {} with TEC 8", at.0.name(), at.1);
    ensure!(r.iut_events(EV_AEF).len() == 1, "error flags:{}", r.dump(0));
    ensure!(r.iut_events(EV_TX_OK).len() == 1, "no successful transmission:{}", r.dump(0));
    ensure!(lb.b.tec(0) == 7 && lb.b.rec(0) == 0, "TEC {} REC {} at the end, expected 7 and 0", lb.b.tec(0), lb.b.rec(0));
    let sent = lb.b.node(0).sent();
    ensure!(sent.len() == sent0 + 1 && sent[sent0] == *f, "sent {:?}", &sent[sent0..]);
    let t_edge = r.plan_time(k, p.clock_of(At { bit: s, tq: 0, clocks: delay }));
    let o = tx_offset(&r, k)?;
    let sof1 = r.iut().iter().find(|b| b.has(EV_SOF)).ok_or("no SOF")?;
    let c = sof1.t - r.plays[k].t0;
    Ok(InterSof { r, t_edge, o, c })
}

impl InterSof {
    /// Start (ps, as the IUT perceives the bus) of the IUT's bit in which
    /// it sampled the second SOF.
    pub fn sof2_start(&self) -> Result<u64, String> {
        let b = self.r.iut().iter().filter(|b| b.has(EV_SOF)).nth(1).ok_or("no second SOF")?;
        Ok(b.t - self.c)
    }
}

fn step(lb: &mut LtBench) -> Result<(), String> {
    let t = lb.timing;
    let f = Frame::std(0x4A5, &[0x3C, 0xA5]);
    let s = intermission_sof(lb, &f, t.sp() - 2, t.brp - 1, true)?;
    let tq = s.r.tq_ps as i64;
    let bit = tq * t.ntq() as i64;
    let start = s.sof2_start()? as i64 - s.t_edge as i64;
    ensure!((-tq..=0).contains(&start), "the hard-synchronised bit starts {:.2} TQ after the LT's edge, expected -1..0", start as f64 / tq as f64);
    let first = iut_tx_edges(&s.r).into_iter().find(|&(tt, l)| tt > s.t_edge && !l).ok_or("no dominant IUT edge after the LT's SOF")?;
    let d = first.0 as i64 - s.o as i64 - s.t_edge as i64;
    let m = (d + tq).rem_euclid(bit);
    ensure!(d >= bit - tq && m <= tq, "first IUT edge of the arbitration field {:.2} TQ after the LT's edge, expected n bit times - (0..1 TQ)", d as f64 / tq as f64);
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_7_2".into(), vcd: None, results: vec![] };
    for sp in 3..=9 {
        let mut lb = LtBench::new(vec![sp_config(sp)]);
        let r = step(&mut lb);
        ctx.record(&format!("iso_8_7_2_sp{sp}"), r);
    }
    ctx.results
}
