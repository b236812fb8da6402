//! Steps shared by several ISO cases: a frame the IUT must receive and
//! acknowledge, a frame the IUT must transmit, and a receiver error at a
//! given bit of the LT's frame. Each case file says which it uses and what
//! it asserts on top.

use super::super::{LtBench, Plan, StepRecord, Trigger};
use crate::conformance::{ensure, BitRec};
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// The error events (bit, stuff, CRC, form, ACK).
pub const ERRORS: u32 = (1 << EV_BIT_ERR) | (1 << EV_STUFF_ERR) | (1 << EV_CRC_ERR) | (1 << EV_FORM_ERR) | (1 << EV_ACK_ERR);

/// The IUT's bits that carry an error event.
pub fn errors(r: &StepRecord) -> Vec<BitRec> {
    r.iut().iter().filter(|b| b.ev & ERRORS != 0).copied().collect()
}

/// The LT plays plan `p` (frames from SOF, ACK slots expected dominant)
/// in the current step and ends it; the IUT must drive dominant only in
/// the plan bits `acks`, deliver exactly `want` (in order) and detect no
/// error. Returns the step record for further checks.
pub fn receive_plan(lb: &mut LtBench, p: &Plan, want: &[Frame], acks: &[usize]) -> Result<StepRecord, String> {
    let got0 = lb.b.node(0).received().len();
    lb.play_and_run(p);
    lb.run_idle(30)?;
    let r = lb.end_step();
    r.check_expects()?;
    for i in 0..p.bits.len() {
        if !acks.contains(&i) {
            ensure!(r.iut_tx_at(0, i) == Some(true), "IUT drove dominant in plan bit {i} ({:?}), not an ACK slot", p.bits[i].label);
        }
    }
    let got = lb.b.node(0).received();
    ensure!(got.len() == got0 + want.len() && got[got0..] == *want, "IUT delivered {:?}, expected {want:?}", &got[got0..]);
    let e = errors(&r);
    ensure!(e.is_empty(), "IUT detected errors: {e:?}");
    Ok(r)
}

/// One frame `f` built with options `o`, sent by the LT and followed by 3
/// recessive bits: the IUT acknowledges it, delivers it and detects no
/// error (see [`receive_plan`]). Starts its own step.
pub fn receive_frame(lb: &mut LtBench, f: &Frame, o: BuildOptions) -> Result<StepRecord, String> {
    lb.begin_step("rx");
    let mut p = Plan::frame(lb.timing, f, o);
    p.push_recessive(3);
    let ack = p.find(Field::AckSlot, 1, false).ok_or("no ACK slot in the plan")?;
    receive_plan(lb, &p, std::slice::from_ref(f), &[ack])
}

/// The IUT transmits `f` (requested in a new step, after the counters are
/// preset to `tec`/`rec`), the LT acknowledges it and checks every bit the
/// IUT drives up to the end of End_Of_Frame; the IUT reports one successful
/// transmission and detects no error. Returns the step record.
pub fn transmit_frame(lb: &mut LtBench, f: &Frame, tec: u32, rec: u32) -> Result<StepRecord, String> {
    lb.begin_step("tx");
    lb.preset(0, tec, rec);
    let sent0 = lb.b.node(0).sent().len();
    lb.b.node_mut(0).request(f.clone());
    lb.wait(Trigger::at(Field::Sof, 1), 30)?;
    let p = Plan::answer(lb.timing, f, BuildOptions::default(), 3);
    lb.play_and_run(&p);
    lb.run_idle(30)?;
    let r = lb.end_step();
    r.check_expects()?;
    ensure!(r.iut_events(EV_TX_OK).len() == 1, "no successful transmission:{}", r.dump(0));
    let e = errors(&r);
    ensure!(e.is_empty(), "IUT detected errors: {e:?}");
    ensure!(!lb.b.node(0).pending(), "the frame is still pending");
    let sent = lb.b.node(0).sent();
    ensure!(sent.len() == sent0 + 1 && sent[sent0] == *f, "the IUT reports {:?} as sent", &sent[sent0..]);
    Ok(r)
}

/// What a receiver error step expects.
pub struct RxError {
    /// The error event (`EV_*`).
    pub ev: usize,
    /// FIELD and POSITION of the IUT bit that carries the event.
    pub at: (Field, u32),
    /// Plan bit in which the IUT's active error flag begins.
    pub flag: usize,
    /// REC expected at the end (`None`: one more than before).
    pub rec: Option<u32>,
}

/// A receiver error: the IUT (counters preset to TEC 0 / REC `rec0`)
/// receives plan `p` (already made faulty by the caller), of which the LT
/// plays bits up to and including `last` and then stays recessive. The IUT
/// must detect exactly one error, of kind `w.ev` at `w.at`, drive an active
/// error flag of six dominant bits from plan bit `w.flag` followed by a
/// recessive bit, deliver no frame and end with REC `w.rec` (by default
/// `rec0 + 1`). Starts its
/// own step; returns the record.
pub fn receive_error(lb: &mut LtBench, mut p: Plan, last: usize, w: RxError, rec0: u32) -> Result<StepRecord, String> {
    lb.begin_step("rx error");
    lb.preset(0, 0, rec0);
    let got0 = lb.b.node(0).received().len();
    p.truncate(last + 1).push_recessive(w.flag.saturating_sub(last) + 8 + 8 + 3);
    for k in 0..6 {
        p.expect(w.flag + k, false, "active error flag");
    }
    p.expect(w.flag + 6, true, "error delimiter");
    lb.play_and_run(&p);
    lb.run_idle(40)?;
    let r = lb.end_step();
    let e = errors(&r);
    ensure!(e.len() == 1, "{} errors detected, expected one:{}", e.len(), r.dump(0));
    ensure!(e[0].has(w.ev) && (e[0].field, e[0].pos) == w.at, "error at {}, expected event {} at {} {}", e[0], w.ev, w.at.0.name(), w.at.1);
    ensure!(r.iut_events(EV_AEF).len() == 1, "active error flags:{}", r.dump(0));
    r.check_expects()?;
    let want = w.rec.unwrap_or(rec0 + 1);
    ensure!(lb.b.rec(0) == want && lb.b.tec(0) == 0, "TEC {} REC {} (REC {rec0} before), expected TEC 0 and REC {want}:{}", lb.b.tec(0), lb.b.rec(0), r.dump(0));
    ensure!(lb.b.node(0).received().len() == got0, "a frame was delivered");
    Ok(r)
}

/// The frame whose data field carries the stuff error of [`error_in_data`].
pub fn error_frame_source() -> Frame {
    Frame::std(0x078, &[0x00, 0xFF])
}

/// "The IUT sends an active error frame in the data field": the LT's
/// frame with its first data stuff bit sent at the wrong level (a stuff
/// error for the IUT, REC +1), cut after that bit. Returns the plan and the
/// plan index of the IUT's first error flag bit; the caller appends what
/// the LT drives from there on.
pub fn error_in_data(lb: &LtBench) -> (Plan, usize) {
    let mut p = Plan::frame(lb.timing, &error_frame_source(), BuildOptions::default());
    let s = p.stuff_bits().into_iter().find(|&i| p.bits[i].label.is_some_and(|l| l.field == Field::Data)).expect("a data stuff bit");
    let l = p.bits[s].level;
    p.set_level(s, !l).truncate(s + 1);
    (p, s + 1)
}

/// "The IUT sends an overload frame after a data frame": the LT's valid
/// frame (acknowledged by the IUT) with Intermission bit 1 dominant. Returns
/// the plan (up to that bit) and the plan index of the IUT's first overload
/// flag bit.
pub fn overload_after_frame(lb: &LtBench) -> (Plan, usize) {
    let mut p = Plan::frame(lb.timing, &Frame::std(0x2C6, &[0x3E]), BuildOptions::default());
    p.push_levels(&[false]);
    let i = p.bits.len();
    (p, i)
}

/// The IUT's bit record for plan bit `i` of play `k` (the bit whose sample
/// point lies in that plan bit).
pub fn iut_bit_at(r: &StepRecord, k: usize, i: usize) -> Option<BitRec> {
    let s = r.bit_start(k, i);
    let e = r.bit_start(k, i + 1);
    r.iut().iter().find(|b| b.t >= s && b.t < e).copied()
}

/// Play `p` in a new step after presetting REC to `rec0`, run until idle;
/// the record.
pub fn play_step(lb: &mut LtBench, p: &Plan, rec0: u32) -> Result<StepRecord, String> {
    lb.begin_step("step");
    lb.preset(0, 0, rec0);
    lb.play_and_run(p);
    lb.run_idle(60)?;
    Ok(lb.end_step())
}

/// How a flag scenario starts (see [`flag_scenario`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Start {
    /// A stuff error in the data field of the LT's frame ([`error_in_data`]):
    /// the IUT sends an active error flag (REC +1).
    ErrorInData,
    /// A valid frame with a dominant first intermission bit
    /// ([`overload_after_frame`]): the IUT sends an overload flag.
    OverloadAfterFrame,
    /// As `OverloadAfterFrame` with intermission bit 1 recessive and bit 2
    /// dominant.
    OverloadAtIntermission2,
}

/// Offset (from the IUT's first flag bit) of delimiter bit `n` (1..8).
pub fn delim(n: usize) -> usize {
    6 + n - 1
}

/// Offset (from the IUT's first flag bit) of intermission bit `m` (1..3)
/// after an undisturbed flag and delimiter.
pub fn inter(m: usize) -> usize {
    6 + 8 + m - 1
}

/// A flag scenario: after `start`, the LT drives recessive from the IUT's
/// first flag bit on, except dominant at the offsets `dom`, and forces the
/// bus recessive (for every node) during the offsets `forced_rec`. If
/// `flag` is given, the IUT must drive six dominant bits from that offset
/// and a recessive bit after them. REC is preset to `rec0`. Returns the
/// record and the plan index of the first flag bit.
pub fn flag_scenario(lb: &mut LtBench, start: Start, dom: &[usize], forced_rec: &[usize], flag: Option<usize>, rec0: u32) -> Result<(StepRecord, usize), String> {
    use super::super::{Action, At, Disturbance, Span, Target};
    let (mut p, f) = match start {
        Start::ErrorInData => error_in_data(lb),
        Start::OverloadAfterFrame => overload_after_frame(lb),
        Start::OverloadAtIntermission2 => {
            let (mut p, i) = overload_after_frame(lb);
            p.set_level(i - 1, true).push_levels(&[false]);
            (p, i + 1)
        }
    };
    p.push_recessive(6 + 8 + 8 + 8 + 8 + 3);
    for &d in dom {
        p.set_level(f + d, false);
    }
    for &d in forced_rec {
        p.disturb(Disturbance { at: At::tq(f + d, 0), span: Span::Bits(1), action: Action::Force(true), target: Target::Bus });
    }
    if let Some(o) = flag {
        for k in 0..6 {
            p.expect(f + o + k, false, "flag");
        }
        p.expect(f + o + 6, true, "delimiter after the flag");
    }
    let r = play_step(lb, &p, rec0)?;
    r.check_expects()?;
    Ok((r, f))
}

/// The IUT's bit (`field`, `pos`) (first occurrence, no stuff bit) carries
/// event `ev`.
pub fn event_at(r: &StepRecord, ev: usize, field: Field, pos: u32) -> Result<BitRec, String> {
    let b = r.iut().iter().find(|b| b.field == field && b.pos == pos && !b.stuff).copied().ok_or_else(|| format!("no IUT bit {} {pos}:{}", field.name(), r.dump(0)))?;
    ensure!(b.has(ev), "IUT bit {b}: event {ev} expected:{}", r.dump(0));
    Ok(b)
}

/// A transmitter error: the IUT (TEC preset `tec0`, REC 0) transmits `f`;
/// the LT plays `p` (the answer plan of `f`, already made faulty by the
/// caller) up to and including plan bit `last`, then stays recessive. The
/// IUT must detect exactly one error, `ev` at `at`, with TEC `tec_err`
/// after that bit, send one error flag (active: six dominant bits from plan
/// bit `flag`; passive when `passive`: recessive there), then send `f`
/// again, which the LT acknowledges and checks; at the end TEC is
/// `tec_err - 1` (the success) and the frame was sent once.
#[allow(clippy::too_many_arguments)]
pub fn transmit_error(lb: &mut LtBench, f: &Frame, tec0: u32, mut p: Plan, last: usize, flag: usize, ev: usize, at: (Field, u32), tec_err: u32, passive: bool) -> Result<StepRecord, String> {
    lb.begin_step("tx error");
    lb.preset(0, tec0, 0);
    let sent0 = lb.b.node(0).sent().len();
    lb.b.node_mut(0).request(f.clone());
    lb.wait(Trigger::at(Field::Sof, 1), 30)?;
    p.truncate(last + 1).push_recessive(flag - last + 6 + 4);
    for k in 0..6 {
        p.expect(flag + k, passive, if passive { "passive error flag" } else { "active error flag" });
    }
    p.expect(flag + 6, true, "after the flag");
    lb.play(&p);
    lb.wait(Trigger::at(Field::Sof, 1).nth(2), p.bits.len() as u64 + 8 + 3 + 8 + 30)?;
    lb.play_and_run(&Plan::answer(lb.timing, f, BuildOptions::default(), 3));
    lb.run_idle(30)?;
    let r = lb.end_step();
    r.check_expects()?;
    let e = errors(&r);
    ensure!(e.len() == 1, "{} errors, expected one:{}", e.len(), r.dump(0));
    ensure!(e[0].has(ev) && (e[0].field, e[0].pos) == at, "error at {}, expected event {ev} at {} {}", e[0], at.0.name(), at.1);
    ensure!(e[0].tec == tec_err, "TEC {} after the error (TEC {tec0} before), expected {tec_err}", e[0].tec);
    let flags = r.iut_events(if passive { EV_PEF } else { EV_AEF });
    ensure!(flags.len() == 1, "error flags:{}", r.dump(0));
    ensure!(r.iut_events(EV_TX_OK).len() == 1, "no successful retransmission:{}", r.dump(0));
    let want = tec_err.saturating_sub(1);
    ensure!(lb.b.tec(0) == want && lb.b.rec(0) == 0, "TEC {} REC {} at the end, expected TEC {want}", lb.b.tec(0), lb.b.rec(0));
    let sent = lb.b.node(0).sent();
    ensure!(sent.len() == sent0 + 1 && sent[sent0] == *f, "sent {:?}", &sent[sent0..]);
    Ok(r)
}

/// Make plan bit `i` of an answer plan wrong for the IUT: a recessive bit
/// of the IUT is driven dominant by the LT, a dominant one is forced
/// recessive on the bus (for every node).
pub fn corrupt(p: &mut Plan, i: usize) {
    use super::super::{Action, At, Disturbance, Span, Target};
    let iut_level = p.expects.iter().find(|e| e.bit == i).map(|e| e.level).expect("an IUT bit");
    if iut_level {
        p.set_level(i, false);
    } else {
        p.disturb(Disturbance { at: At::tq(i, 0), span: Span::Bits(1), action: Action::Force(true), target: Target::Bus });
    }
}

/// The frame the IUT transmits in the transmitter flag scenarios.
pub fn tx_source() -> Frame {
    Frame::std(0x0F5, &[0x39, 0xC6])
}

/// A flag scenario with the IUT as transmitter (TEC preset `tec0`): it
/// sends [`tx_source`], which the LT answers; with [`Start::ErrorInData`]
/// the LT forces the first dominant data bit recessive (a bit error, TEC
/// +8, an active error flag from the next bit, or a passive one when
/// error-passive); with [`Start::OverloadAfterFrame`] the LT acknowledges
/// the frame and drives the first intermission bit dominant (an overload
/// flag). From the IUT's first flag bit on the LT drives recessive except
/// at the offsets `dom`, forces the bus recessive at `forced_rec`, and
/// expects six bits of level `flag.1` from offset `flag.0`, followed by a
/// recessive bit. After an error the IUT's retransmission is answered and
/// must succeed. Returns the record and the plan index of the first flag
/// bit.
pub fn tx_flag_scenario(lb: &mut LtBench, start: Start, dom: &[usize], forced_rec: &[usize], flag: Option<(usize, bool)>, tec0: u32) -> Result<(StepRecord, usize), String> {
    use super::super::{Action, At, Disturbance, Span, Target};
    let f = tx_source();
    lb.begin_step("tx flag scenario");
    lb.preset(0, tec0, 0);
    lb.b.node_mut(0).request(f.clone());
    lb.wait(Trigger::at(Field::Sof, 1), 30)?;
    let mut p = Plan::answer(lb.timing, &f, BuildOptions::default(), 0);
    let first = match start {
        Start::ErrorInData => {
            let i = (0..p.bits.len()).find(|&i| p.bits[i].label.is_some_and(|l| l.field == Field::Data && !l.stuff) && p.expects.iter().any(|e| e.bit == i && !e.level)).ok_or("no dominant data bit")?;
            corrupt(&mut p, i);
            p.truncate(i + 1);
            i + 1
        }
        Start::OverloadAfterFrame => {
            p.push_levels(&[false]);
            p.bits.len()
        }
        Start::OverloadAtIntermission2 => {
            p.push_levels(&[true, false]);
            p.bits.len()
        }
    };
    p.push_recessive(6 + 8 + 8 + 8 + 8 + 3);
    for &d in dom {
        p.set_level(first + d, false);
    }
    for &d in forced_rec {
        p.disturb(Disturbance { at: At::tq(first + d, 0), span: Span::Bits(1), action: Action::Force(true), target: Target::Bus });
    }
    if let Some((o, level)) = flag {
        for k in 0..6 {
            p.expect(first + o + k, level, "flag");
        }
        p.expect(first + o + 6, true, "after the flag");
    }
    lb.play(&p);
    if start == Start::ErrorInData {
        lb.wait(Trigger::at(Field::Sof, 1).nth(2), p.bits.len() as u64 + 60)?;
        lb.play_and_run(&Plan::answer(lb.timing, &f, BuildOptions::default(), 3));
    } else {
        lb.run_plan();
    }
    lb.run_idle(60)?;
    let r = lb.end_step();
    r.check_expects()?;
    if start == Start::ErrorInData {
        ensure!(r.iut_events(EV_TX_OK).len() == 1, "no successful retransmission:{}", r.dump(0));
    }
    ensure!(!lb.b.node(0).pending(), "frame still pending");
    Ok((r, first))
}

/// TEC after the IUT's bit (`field`, `pos`), its first occurrence.
pub fn tec_at(r: &StepRecord, field: Field, pos: u32) -> Result<u32, String> {
    r.iut().iter().find(|b| b.field == field && b.pos == pos && !b.stuff).map(|b| b.tec).ok_or_else(|| format!("no IUT bit {} {pos}:{}", field.name(), r.dump(0)))
}

/// The IUT's TX transitions in a step: (time of the first clock sample
/// showing the new level, new level; true = recessive).
pub fn iut_tx_edges(r: &StepRecord) -> Vec<(u64, bool)> {
    r.samples.windows(2).filter(|w| w[0].iut_tx != w[1].iut_tx).map(|w| (w[1].t, w[1].iut_tx)).collect()
}

/// Time from the start of a bit as the IUT perceives it (a plan's bit
/// start, see [`super::super::trigger`]) to its TX edge at that bit's
/// start, measured on the IUT's first SOF after the start of play `k`
/// (which must start at that SOF, as after `Trigger::at(Field::Sof, 1)`).
pub fn tx_offset(r: &StepRecord, k: usize) -> Result<u64, String> {
    let t0 = r.plays[k].t0;
    let e = iut_tx_edges(r).into_iter().find(|&(t, l)| t >= t0 && !l).ok_or("no dominant IUT TX edge after the play's start")?;
    Ok(e.0 - t0)
}

/// Append plan `q` to plan `p` (bits, expectations and disturbances, the
/// latter two moved to the new bit indices); returns the index of `q`'s
/// first bit in `p`.
pub fn append_plan(p: &mut Plan, q: &Plan) -> usize {
    let n = p.bits.len();
    p.bits.extend(q.bits.iter().copied());
    for e in &q.expects {
        p.expects.push(super::super::Expect { bit: e.bit + n, ..*e });
    }
    for d in &q.disturbances {
        let mut d = *d;
        d.at.bit += n;
        p.disturbances.push(d);
    }
    n
}

/// The first data bit of an answer plan that the IUT sends recessive and
/// that is not a stuff bit: its plan index and its (field, position).
pub fn first_recessive_data_bit(p: &Plan) -> Result<(usize, (Field, u32)), String> {
    let i = (0..p.bits.len())
        .find(|&i| {
            let l = p.bits[i].label.unwrap();
            l.field == Field::Data && !l.stuff && p.expects.iter().any(|e| e.bit == i && e.level)
        })
        .ok_or("no recessive data bit")?;
    let l = p.bits[i].label.unwrap();
    Ok((i, (l.field, l.pos)))
}

/// Play `p` (the LT's answer to the IUT's frame `f`), let the bus go idle and
/// end the step: every expectation met, no error, one successful
/// transmission, `f` the one frame sent since `sent0`. Returns the record
/// and the play index.
pub fn play_tx_ok(lb: &mut LtBench, p: &Plan, f: &Frame, sent0: usize) -> Result<(StepRecord, usize), String> {
    let k = lb.play_and_run(p);
    lb.run_idle(30)?;
    let r = lb.end_step();
    r.check_expects()?;
    let errs = errors(&r);
    ensure!(errs.is_empty(), "IUT detected errors: {errs:?}");
    ensure!(r.iut_events(EV_TX_OK).len() == 1, "no successful transmission:{}", r.dump(0));
    let sent = lb.b.node(0).sent();
    ensure!(sent.len() == sent0 + 1 && sent[sent0] == *f, "sent {:?}", &sent[sent0..]);
    Ok((r, k))
}
