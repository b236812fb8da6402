//! ISO 16845-1:2016 clause 8.7.4 — resynchronisation of a transmitting IUT
//! on an early edge (negative phase error, |e| ≤ SJW).
//!
//! What the case checks (in our words): the IUT uses T10/6/2 (10 TQ per
//! bit, sample point after 6 TQ, SJW 2, PH2 4, IPT 2) and transmits a
//! base-format frame. In the arbitration field, at a recessive identifier
//! bit the IUT sends before a dominant one, the LT drives the bus dominant
//! |e| TQ before the IUT's own edge (so the recessive bit appears |e| TQ
//! short) and keeps it dominant through the IUT's dominant bit; from then
//! on the LT's answer follows the IUT's expected new bit grid. The IUT must
//! resynchronise on that edge: every edge it sends afterwards (up to the
//! ACK slot) lies an integer number of bit times after the LT's edge, its
//! sample points of the two bits lie 10 − |e| TQ apart, and the frame
//! completes without error (every bit it drives checked by the LT).
//!
//! Edges are compared as the IUT perceives them: the IUT's TX edge of a bit
//! comes a fixed time after the bit's start as the IUT reads the bus (its
//! RX latency), measured on the frame's own SOF ([`tx_offset`]).
//!
//! Elementary tests: `iso_8_7_4_e<E>`, |e| = 1 .. min(SJW, PH2 − IPT).
//! The helpers serve 8.7.5, 8.7.6 and 8.7.8 as well.

use super::super::{At, LtBench, Plan, Span, StepRecord, Trigger};
use super::common::*;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// The `nth` (from 0) plan bit of an answer plan that the IUT sends
/// recessive, followed by a bit it sends dominant, both in `field`.
pub fn rd_pair(p: &Plan, field: Field, nth: usize) -> Option<usize> {
    let lvl = |i: usize| p.expects.iter().find(|e| e.bit == i).map(|e| e.level);
    let in_field = |i: usize| p.bits[i].label.is_some_and(|l| l.field == field);
    (0..p.bits.len() - 1).filter(|&i| in_field(i) && in_field(i + 1) && lvl(i) == Some(true) && lvl(i + 1) == Some(false)).nth(nth)
}

/// What an early-edge step recorded.
pub struct EarlyEdge {
    pub r: StepRecord,
    /// Index of the LT's play.
    pub k: usize,
    /// Plan bit the LT shortened (the IUT's recessive bit).
    pub x: usize,
    /// Time (ps) of the LT's edge.
    pub t_lt: u64,
    /// The IUT's TX offset ([`tx_offset`]).
    pub o: u64,
    /// TQ by which the IUT's next bits are expected later than the LT's
    /// edge + n bit times: |e| − min(|e|, SJW).
    pub shift: u32,
}

/// The IUT transmits `f` (counters 0); the LT answers it and, in plan bit
/// `x = pick(plan)` (recessive for the IUT, the next bit dominant), drives
/// the bus dominant from `e` TQ before the end of bit `x` on, through bit
/// `x + 1`; it shortens bit `x` by min(e, SJW) only (forcing the bus
/// dominant for the rest of the early part), so that its later bits follow
/// the bit grid the IUT must take. With `glitch = Some((q, n))` the
/// bus is forced recessive for `n` TQ from TQ `q` of bit `x + 1`. The
/// frame must complete without error and be reported sent.
pub fn early_edge(lb: &mut LtBench, f: &Frame, pick: impl Fn(&Plan) -> Option<usize>, e: u32, glitch: Option<(u32, u32)>) -> Result<EarlyEdge, String> {
    let corr = e.min(lb.timing.sjw);
    lb.begin_step("early edge");
    lb.preset(0, 0, 0);
    let sent0 = lb.b.node(0).sent().len();
    lb.b.node_mut(0).request(f.clone());
    lb.wait(Trigger::at(Field::Sof, 1), 30)?;
    let mut p = Plan::answer(lb.timing, f, BuildOptions::default(), 3);
    let x = pick(&p).ok_or("no recessive bit followed by a dominant one")?;
    // the LT's bit x as long as the IUT's must become; the part of the
    // early dominant level beyond that forced on the bus
    p.shorten(x, corr).set_level(x + 1, false);
    let ntq = lb.timing.ntq();
    if e > corr {
        p.glitch(At::tq(x, ntq - e), Span::Tq(e - corr), false);
    }
    if let Some((q, n)) = glitch {
        p.glitch(At::tq(x + 1, q), Span::Tq(n), true);
    }
    let (r, k) = play_tx_ok(lb, &p, f, sent0)?;
    let t_lt = r.plan_time(k, p.clock_of(At::tq(x, ntq - e)));
    let o = tx_offset(&r, k)?;
    Ok(EarlyEdge { r, k, x, t_lt, o, shift: e - corr })
}

impl EarlyEdge {
    fn plan(&self) -> &Plan {
        &self.r.plays[self.k].plan
    }

    /// TQ between the IUT's sample points of plan bits `x` and `x + 1`.
    pub fn sample_gap_tq(&self) -> Result<u64, String> {
        super::c7_7_3::sample_gap_tq(&self.r, self.plan(), self.x)
    }

    /// The IUT's TX edges after its sample point of plan bit `x + 1` and
    /// before the ACK slot, as (ps after the LT's edge, corrected by the
    /// IUT's TX offset, new level).
    pub fn later_edges(&self) -> Result<Vec<(i64, bool)>, String> {
        let lab = self.plan().bits[self.x + 1].label.unwrap();
        let sp = self.r.iut().iter().find(|b| (b.field, b.pos, b.stuff) == (lab.field, lab.pos, lab.stuff)).ok_or("no IUT bit for plan bit x + 1")?.t;
        let ack = self.plan().find(Field::AckSlot, 1, false).ok_or("no ACK slot")?;
        let end = self.r.bit_start(self.k, ack);
        Ok(iut_tx_edges(&self.r).into_iter().filter(|&(t, _)| t > sp && t < end).map(|(t, l)| (t as i64 - self.o as i64 - self.t_lt as i64, l)).collect())
    }

    /// Every later edge lies `shift` TQ plus an integer number of bit times
    /// after the LT's edge, and there is at least one.
    pub fn check_grid(&self) -> Result<(), String> {
        let bit = (self.plan().timing.ntq() as u64 * self.r.tq_ps) as i64;
        let tq = self.r.tq_ps as i64;
        let edges = self.later_edges()?;
        ensure!(!edges.is_empty(), "no IUT edge after the resynchronised bit");
        let bad: Vec<String> = edges.iter().filter(|&&(d, _)| (d - self.shift as i64 * tq).rem_euclid(bit) != 0).map(|&(d, _)| format!("{:.2}", d as f64 / tq as f64)).collect();
        ensure!(bad.is_empty(), "IUT edges at {bad:?} TQ after the LT's edge, expected {} TQ + n bit times", self.shift);
        Ok(())
    }
}

/// The frame of the transmitter bit-timing cases (identifier 0x2A5: SOF D,
/// identifier 0 1 0 1 ..., so identifier bit 2 is recessive before a
/// dominant bit 3).
pub fn frame() -> Frame {
    super::c7_7_3::frame()
}

/// One early-edge step in the arbitration field with |e| TQ; the IUT's
/// sample points `10 − min(|e|, SJW)` apart and its later edges on the
/// grid of the LT's edge shifted by |e| − min(|e|, SJW).
pub fn arbitration_step(lb: &mut LtBench, e: u32) -> Result<(), String> {
    let s = early_edge(lb, &frame(), |p| rd_pair(p, Field::Ident, 0), e, None)?;
    let want = (lb.timing.ntq() - e.min(lb.timing.sjw)) as u64;
    let gap = s.sample_gap_tq()?;
    ensure!(gap == want, "sample points {gap} TQ apart, expected {want}");
    s.check_grid()
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_7_4".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut").timing(1, 1, 4, 2)]);
    let t = lb.timing;
    for e in 1..=t.sjw.min(t.ph2 - t.ipt()) {
        let r = arbitration_step(&mut lb, e);
        ctx.record(&format!("iso_8_7_4_e{e}"), r);
    }
    ctx.results
}

/// The IUT of the sampling-point sweeps of 8.7: 10 TQ of 4 clocks per bit
/// (so that a clock is a "minimum time quantum" shorter than the TQ, and a
/// PH2 of 1 TQ outlasts the IUT's RX latency of 3 clocks, which the LT's
/// trigger needs to start a plan exactly at the IUT's bit start),
/// sample point after `sp` TQ (PROP 1, PH1 `sp − 2`, PH2 `10 − sp`), SJW
/// min(2, PH1).
pub fn sp_config(sp: u32) -> NodeConfig {
    let mut c = NodeConfig::named("iut").timing(4, 1, sp - 2, (sp - 2).min(2));
    c.timing = c.timing.with_ph2(10 - sp);
    c
}
