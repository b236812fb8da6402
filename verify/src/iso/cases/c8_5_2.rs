//! ISO 16845-1:2016 clause 8.5.2 — an error-passive transmitter receives a
//! frame that starts in the third intermission bit after its error frame.
//!
//! What the case checks (in our words): the IUT is error-passive (TEC 128)
//! and transmits a base-format data frame; the LT overwrites its first
//! recessive data bit with a dominant one (bit error, TEC 136), so the IUT
//! sends a passive error flag. The LT superimposes an active error flag (six
//! dominant bits) on the whole passive flag, which completes on them; then
//! the LT leaves the bus recessive for 8 + 2 bits (error delimiter and two
//! intermission bits) and sends a valid frame of its own, whose SOF is the
//! third intermission bit. The IUT, owing a suspend, must not transmit
//! there: it stays recessive from its flag to the end of the LT's frame
//! except for the ACK of that frame, delivers it, and sends its own frame
//! again right after the 3 intermission bits that follow (no suspend: it
//! was a receiver of the last frame). The LT checks every bit of the
//! retransmission at that position; TEC is 135 at the end.
//!
//! Elementary test: `iso_8_5_2_frame_at_intermission_3`.
//!
//! The module also holds the step shared by the error-passive transmitter
//! cases ([`passive_tx`]).

use super::super::{Action, At, Disturbance, LtBench, Plan, Span, StepRecord, Target, Trigger};
use super::common::{errors, first_recessive_data_bit};
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// The frame the IUT transmits in the error-passive transmitter cases.
pub fn source() -> Frame {
    Frame::std(0x0F5, &[0x96, 0x3C])
}

/// The LT's frame (lower priority than [`source`]).
pub fn lt_frame() -> Frame {
    Frame::std(0x5A3, &[0x11])
}

/// What the LT does in a [`passive_tx`] step from the IUT's first error
/// flag bit (offset 0) on.
#[derive(Default)]
pub struct Scenario {
    /// TEC preset before the request (REC is 0).
    pub tec0: u32,
    /// The LT's levels from offset 0 on.
    pub levels: Vec<bool>,
    /// Offsets at which the bus is forced recessive for every node.
    pub forced: Vec<usize>,
    /// Offsets at which the IUT must drive dominant (recessive at every
    /// other offset of `levels`).
    pub iut_dom: Vec<usize>,
    /// A frame the LT sends after `levels` (the IUT must acknowledge it and
    /// stay recessive in its other bits and the 3 intermission bits after).
    pub frame: Option<Frame>,
    /// The frame the IUT transmits (default [`source`]).
    pub tx: Option<Frame>,
    /// The LT drives the SOF of the retransmission (a dominant third
    /// intermission bit): the IUT must be recessive there and go on with
    /// its identifier.
    pub lt_sof: bool,
    /// LT levels after the End_Of_Frame of the retransmission (instead of
    /// 3 recessive bits); the IUT must drive dominant at offsets `tail_dom`
    /// of them and recessive elsewhere; the bus is forced recessive at
    /// offsets `tail_forced`.
    pub tail: Option<Vec<bool>>,
    pub tail_forced: Vec<usize>,
    pub tail_dom: Vec<usize>,
    /// A frame the LT sends after `tail` that the IUT must ignore
    /// (bus-off: recessive in every bit, ACK slot included).
    pub tail_frame: Option<Frame>,
    /// Bit times to wait for bus idle at the end (default 60).
    pub idle_bits: u64,
}

/// What a [`passive_tx`] step gives back.
pub struct Outcome {
    pub r: StepRecord,
    /// FIELD and POSITION of the corrupted data bit.
    pub at: (Field, u32),
    /// Frames the IUT reported sent during the step.
    pub sent: Vec<Frame>,
}

/// Append the LT's answer to the IUT's frame `f` (see [`Plan::answer`]),
/// the IUT's SOF expected in the next plan bit; `tail` recessive bits
/// after it. Returns the index of that SOF.
pub fn push_answer(p: &mut Plan, f: &Frame, tail: usize) -> usize {
    let s = p.bits.len();
    let a = Plan::answer(p.timing, f, BuildOptions::default(), tail);
    p.bits.extend(a.bits.iter().copied());
    for e in &a.expects {
        p.expect(s + e.bit, e.level, e.what);
    }
    s
}

/// The error-passive transmitter step: the IUT (TEC `s.tec0`) transmits
/// `s.tx` (default [`source`]); the LT overwrites the first recessive data bit with a
/// dominant one (a bit error) and from the next bit (offset 0, the IUT's
/// first flag bit) plays `s.levels` with the disturbances `s.forced`,
/// expecting the IUT dominant at `s.iut_dom` and recessive elsewhere; then
/// the LT's `s.frame` (acknowledged by the IUT) with 3 intermission bits;
/// then the IUT's retransmission of the frame must start in the very next
/// bit (or, with `s.lt_sof`, the LT drives that SOF and the IUT must be
/// recessive in it), and the LT acknowledges and checks it; then `s.tail`
/// and `s.tail_frame` if given. The IUT must report one
/// successful transmission and have no frame pending.
pub fn passive_tx(lb: &mut LtBench, s: &Scenario) -> Result<Outcome, String> {
    let f = s.tx.clone().unwrap_or_else(source);
    let mut p = Plan::answer(lb.timing, &f, BuildOptions::default(), 0);
    let (i, at) = first_recessive_data_bit(&p)?;
    p.set_level(i, false).truncate(i + 1);
    let flag = i + 1;
    p.push_levels(&s.levels);
    for k in 0..s.levels.len() {
        let d = s.iut_dom.contains(&k);
        p.expect(flag + k, !d, if d { "IUT dominant (flag)" } else { "IUT recessive" });
    }
    for &k in &s.forced {
        p.disturb(Disturbance { at: At::tq(flag + k, 0), span: Span::Bits(1), action: Action::Force(true), target: Target::Bus });
    }
    if let Some(g) = &s.frame {
        let g0 = p.push_frame(g, BuildOptions::default());
        p.push_recessive(3);
        let ack = (g0..p.bits.len()).find(|&a| p.bits[a].label.is_some_and(|l| l.field == Field::AckSlot)).ok_or("no ACK slot")?;
        for k in g0..p.bits.len() {
            if k != ack {
                p.expect(k, true, "IUT recessive (receiver)");
            }
        }
    }
    let sof = push_answer(&mut p, &f, if s.tail.is_some() { 0 } else { 3 });
    if s.lt_sof {
        p.set_level(sof, false);
        for e in p.expects.iter_mut().filter(|e| e.bit == sof) {
            e.level = true;
            e.what = "no SOF from the IUT";
        }
    }
    if let Some(t) = &s.tail {
        let t0 = p.bits.len();
        p.push_levels(t);
        for k in 0..t.len() {
            let d = s.tail_dom.contains(&k);
            p.expect(t0 + k, !d, if d { "IUT dominant (flag)" } else { "IUT recessive" });
        }
        for &k in &s.tail_forced {
            p.disturb(Disturbance { at: At::tq(t0 + k, 0), span: Span::Bits(1), action: Action::Force(true), target: Target::Bus });
        }
    }
    if let Some(g) = &s.tail_frame {
        let g0 = p.push_frame(g, BuildOptions::default());
        p.push_recessive(3);
        p.expects.retain(|e| e.bit < g0);
        for k in g0..p.bits.len() {
            p.expect(k, true, "IUT silent (bus-off)");
        }
    }
    lb.begin_step("error-passive transmitter");
    lb.preset(0, s.tec0, 0);
    let sent0 = lb.b.node(0).sent().len();
    let got0 = lb.b.node(0).received().len();
    lb.b.node_mut(0).request(f.clone());
    lb.wait(Trigger::at(Field::Sof, 1), 30)?;
    lb.play_and_run(&p);
    lb.run_idle(if s.idle_bits == 0 { 60 } else { s.idle_bits })?;
    let r = lb.end_step();
    r.check_expects()?;
    ensure!(r.iut_events(EV_TX_OK).len() == 1, "no successful retransmission:{}", r.dump(0));
    ensure!(!lb.b.node(0).pending(), "frame still pending");
    let sent = lb.b.node(0).sent()[sent0..].to_vec();
    ensure!(sent == [f], "sent {sent:?}");
    let got = lb.b.node(0).received()[got0..].to_vec();
    let want: Vec<Frame> = s.frame.iter().cloned().collect();
    ensure!(got == want, "delivered {got:?}, expected {want:?}");
    Ok(Outcome { r, at, sent })
}

/// The first error is the bit error at `o.at`, with TEC `tec` after it and
/// a passive error flag; `n` errors in all.
pub fn bit_error_first(o: &Outcome, tec: u32, n: usize) -> Result<(), String> {
    let e = errors(&o.r);
    ensure!(e.len() == n, "{} errors, expected {n}:{}", e.len(), o.r.dump(0));
    ensure!(e[0].has(EV_BIT_ERR) && (e[0].field, e[0].pos) == o.at, "first error at {}, expected a bit error at {} {}", e[0], o.at.0.name(), o.at.1);
    ensure!(e[0].tec == tec, "TEC {} after the bit error, expected {tec}", e[0].tec);
    Ok(())
}

/// A passive transmitter (TEC 128) with a bit error in the data field whose
/// passive flag sees `levels` from the LT, which then sends its frame: one
/// bit error, one passive flag, no active one, TEC 135 at the end.
pub fn frame_after(lb: &mut LtBench, levels: Vec<bool>) -> Result<(), String> {
    let o = passive_tx(lb, &Scenario { tec0: 128, levels, frame: Some(lt_frame()), ..Default::default() })?;
    bit_error_first(&o, 136, 1)?;
    ensure!(o.r.iut_events(EV_PEF).len() == 1 && o.r.iut_events(EV_AEF).is_empty(), "error flags:{}", o.r.dump(0));
    ensure!(lb.b.tec(0) == 135 && lb.b.rec(0) == 0, "TEC {} REC {} at the end, expected TEC 135 REC 0", lb.b.tec(0), lb.b.rec(0));
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_5_2".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let mut v = vec![false; 6];
    v.extend([true; 8 + 2]);
    let r = frame_after(&mut lb, v);
    ctx.record("iso_8_5_2_frame_at_intermission_3", r);
    ctx.results
}
