//! ISO 16845-1:2016 clause 7.7.1 — the position of a receiving IUT's
//! sample point.
//!
//! What the case checks (in our words): the LT sends a base frame with
//! identifier 0x7FF, whose identifier holds two dominant stuff bits (after
//! identifier bits 5 and 10, each after five recessive bits). The first
//! one is shortened by PH2: its dominant level still covers the IUT's
//! sample point (exactly SP TQ after its edge) and the IUT reads it
//! correctly. The second one is shortened by PH2 + 1 TQ, so its dominant
//! level ends one TQ before the sample point: the IUT reads a recessive
//! stuff bit, detects a stuff error there (and nowhere before), and starts
//! its active error flag with the next bit. Together the two bits pin the
//! sample point to exactly SP TQ after the edge. (Between the two, the LT's
//! bits are PH2 TQ ahead of the IUT; the edge of the second stuff bit is an
//! early edge the IUT corrects by up to SJW, which the case does not
//! measure: 7.7.5/7.7.6 do.)
//!
//! The standard runs the case for the sample points the IUT offers (its
//! 6.2.3): here the timings of [`timings`] (sample points from 30 % to
//! 90 % of the bit, 8 to 25 TQ per bit, SJW 1 to 4, TQ of 1, 2 and 4
//! clocks).
//!
//! Elementary tests: `iso_7_7_1_<timing>` (see [`timing_name`]).
//!
//! This file also holds what the other bit-timing cases of this group
//! (7.7.2, 7.7.7–7.7.11) share: the timings, the IUT configuration and the
//! measure of a sample point from an edge of the LT.

use super::super::{LtBench, Plan, StepRecord};
use super::common::*;
use crate::conformance::{ensure, BitRec, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;
use canstar_hdl::timing::BtlConfig;

/// The bit timings the bit-timing cases run on: T10/6/2 (the timing of
/// 7.7.3–7.7.6), an early (SP 3, PH2 7) and a late (SP 8) sample point,
/// T10/6/4 (SJW 4), 8 and 25 TQ per bit, and SP 9 with PH2 = 1 TQ on a
/// 2-clock TQ (PH2 = 1 needs BRP ≥ 2, can-protocol.md §2.5). The early
/// sample point runs on a 4-clock TQ: its 2 TQ before the sample point
/// must cover the IUT's own loop delay (TX to RX, about 4 clocks here),
/// which an IUT sending its ACK or a flag relies on (with 1-clock TQ the
/// IUT would read the bus before its own dominant ACK bit reaches it).
pub fn timings() -> Vec<BtlConfig> {
    vec![
        BtlConfig::T10_6_2,
        BtlConfig::new(4, 1, 1, 1).with_ph2(7),
        BtlConfig::T10_8_1,
        BtlConfig::T10_6_4,
        BtlConfig::new(1, 3, 2, 1),
        BtlConfig::T25_17_1,
        BtlConfig::new(2, 4, 4, 2).with_ph2(1),
    ]
}

/// `t<NTQ>_sp<SP>_sjw<SJW>`, with `_brp<B>` when a TQ is more than a clock.
pub fn timing_name(t: &BtlConfig) -> String {
    let b = if t.brp > 1 { format!("_brp{}", t.brp) } else { String::new() };
    format!("t{}_sp{}_sjw{}{b}", t.ntq(), t.sp(), t.sjw)
}

/// The IUT with bit timing `t`.
pub fn iut_with(t: BtlConfig) -> NodeConfig {
    let mut c = NodeConfig::named("iut");
    c.timing = t;
    c
}

/// Clocks from a bus level change to the clock that carries the events of
/// a bit sampled right after it: the IUT's RX latency (can-protocol.md
/// §1.5, the constant the bench's WAIT_FOR uses).
pub fn rx_latency_clocks(lb: &LtBench) -> u64 {
    canstar_controller::core::CanCore::l_rx(lb.b.node(0).config().sync_depth) as u64
}

/// Check that the IUT sampled bit `b` `n` bits plus SP TQ after the edge
/// the LT drove at time `edge` (ps): as a node hard- or resynchronised on
/// that edge does. The TQ in which the edge falls becomes the bit's
/// synchronisation segment, so with a TQ of BRP clocks the sample point
/// may come up to BRP − 1 clocks earlier. The IUT's record carries the
/// bit RX-latency clocks after its sample point.
/// `what` names the bit in the message.
pub fn sampled_after(lb: &LtBench, r: &StepRecord, edge: u64, b: &BitRec, n: u64, what: &str) -> Result<(), String> {
    let t = lb.timing;
    let t0 = edge + rx_latency_clocks(lb) * r.clock_ps;
    ensure!(b.t >= t0, "{what}: IUT bit {b} sampled before the edge");
    let got = (b.t - t0) / r.clock_ps;
    let want = (n * t.ntq() as u64 + t.sp() as u64) * t.brp as u64;
    ensure!(
        (want + 1 - t.brp as u64..=want).contains(&got),
        "{what}: the IUT sampled {b} {got} clocks after the edge, expected {n} bits + SP = {want} clocks (TQ of {} clocks):{}",
        t.brp,
        r.dump(0)
    );
    Ok(())
}

/// [`sampled_after`] the edge at the start of plan bit `i` (play 0).
pub fn sampled_at(lb: &LtBench, r: &StepRecord, i: usize, b: &BitRec, n: u64, what: &str) -> Result<(), String> {
    sampled_after(lb, r, r.bit_start(0, i), b, n, what)
}

/// The IUT's first bit record that is `field` `pos` (no stuff bit) or, when
/// `stuff`, the stuff bit after it.
pub fn iut_rec(r: &StepRecord, field: Field, pos: u32, stuff: bool) -> Result<BitRec, String> {
    iut_rec_after(r, 0, field, pos, stuff)
}

/// The IUT's first bit from time `t0` on that carries the SOF event (the
/// IUT records its SOF as the Bus_Idle or Intermission bit it was read in).
pub fn iut_sof_after(r: &StepRecord, t0: u64) -> Result<BitRec, String> {
    r.iut().iter().find(|b| b.t >= t0 && b.has(EV_SOF)).copied().ok_or_else(|| format!("no SOF:{}", r.dump(0)))
}

/// The IUT's first bit record from time `t0` on that is `field` `pos` (no
/// stuff bit) or, when `stuff`, the stuff bit after it.
pub fn iut_rec_after(r: &StepRecord, t0: u64, field: Field, pos: u32, stuff: bool) -> Result<BitRec, String> {
    r.iut().iter().find(|b| b.t >= t0 && b.field == field && b.pos == pos && b.stuff == stuff).copied().ok_or_else(|| format!("no IUT bit {} {pos}{}:{}", field.name(), if stuff { " stuff" } else { "" }, r.dump(0)))
}

/// The IUT's bit `at` carries error event `ev`, and the six bits after it
/// are the IUT's active error flag, driven dominant, followed by a
/// recessive bit. Returns the first flag bit.
pub fn flag_after(r: &StepRecord, ev: usize, at: &BitRec) -> Result<BitRec, String> {
    ensure!(at.has(ev), "IUT bit {at}: event {ev} expected:{}", r.dump(0));
    let k = r.iut().iter().position(|b| b.t == at.t).unwrap();
    let flag = &r.iut()[k + 1..];
    ensure!(flag.len() >= 7, "the step ends within the flag:{}", r.dump(0));
    for (n, b) in flag[..6].iter().enumerate() {
        ensure!(b.field == Field::ActFlag && b.pos == n as u32 + 1 && !b.drove, "flag bit {}: IUT bit {b}, expected Active_Error_Flag {} driven dominant:{}", n + 1, n + 1, r.dump(0));
    }
    ensure!(flag[6].drove, "the IUT drove a 7th dominant flag bit:{}", r.dump(0));
    Ok(flag[0])
}

/// Exactly one error in the step, of kind `ev` on the IUT's bit `at`,
/// followed by the IUT's active error flag ([`flag_after`]). Returns the
/// first flag bit.
pub fn one_error_then_flag(r: &StepRecord, ev: usize, at: &BitRec) -> Result<BitRec, String> {
    let e = errors(r);
    ensure!(e.len() == 1, "{} errors detected, expected one:{}", e.len(), r.dump(0));
    ensure!(e[0].t == at.t, "error at {}, expected at {at}:{}", e[0], r.dump(0));
    flag_after(r, ev, at)
}

/// Play `p` in a new step (counters 0), run until the bus is idle; the
/// record.
pub fn play(lb: &mut LtBench, p: &Plan) -> Result<StepRecord, String> {
    lb.begin_step("bit timing");
    lb.preset(0, 0, 0);
    let got0 = lb.b.node(0).received().len();
    lb.play_and_run(p);
    lb.run_idle(60)?;
    let r = lb.end_step();
    r.check_expects()?;
    ensure!(lb.b.node(0).received().len() == got0, "a frame was delivered");
    Ok(r)
}

/// The frame of 7.7.1, 7.7.7, 7.7.8 and 7.7.10: identifier 0x7FF, so the
/// identifier carries dominant stuff bits after bits 5 and 10.
pub fn stuff_frame() -> Frame {
    Frame::std(0x7FF, &[0x5A])
}

fn step(lb: &mut LtBench) -> Result<(), String> {
    let ph2 = lb.timing.ph2;
    let mut p = Plan::frame(lb.timing, &stuff_frame(), BuildOptions::default());
    let s1 = p.find(Field::Ident, 5, true).ok_or("no stuff bit after Identifier 5")?;
    let s2 = p.find(Field::Ident, 10, true).ok_or("no stuff bit after Identifier 10")?;
    ensure!(!p.bits[s1].level && !p.bits[s2].level && p.bits[s1 + 1].level && p.bits[s2 + 1].level, "the stuff bits are not dominant bits before recessive ones");
    p.shorten(s1, ph2).shorten(s2, ph2 + 1);
    p.truncate(s2 + 1).push_recessive(6 + 8 + 8 + 3);
    let r = play(lb, &p)?;
    let b1 = iut_rec(&r, Field::Ident, 5, true)?;
    ensure!(!b1.level, "the IUT read the stuff bit shortened by PH2 recessive:{}", r.dump(0));
    sampled_at(lb, &r, s1, &b1, 0, "stuff bit shortened by PH2")?;
    let b2 = iut_rec(&r, Field::Ident, 10, true)?;
    one_error_then_flag(&r, EV_STUFF_ERR, &b2)?;
    ensure!(lb.b.rec(0) == 1, "REC {}, expected 1", lb.b.rec(0));
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_7_1".into(), vcd: None, results: vec![] };
    for t in timings() {
        let mut lb = LtBench::new(vec![iut_with(t)]);
        let r = step(&mut lb);
        ctx.record(&format!("iso_7_7_1_{}", timing_name(&t)), r);
    }
    ctx.results
}
