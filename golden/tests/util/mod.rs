//! Shared helpers for the golden-model tests.
#![allow(dead_code)]

use canstar_golden::{Event, Field, Frame, GoldenBus, Role, RxOverride, StepOut};

pub const D: bool = false;
pub const R: bool = true;

/// `n` nodes, integrated (11 recessive bits) and in Bus_Idle.
pub fn idle_bus(n: usize) -> GoldenBus {
    let mut b = GoldenBus::new(n);
    assert!(b.run_to_idle(20), "integration");
    b
}

/// As [`idle_bus`], every node with the 1999 REC rule at a dominant End_Of_Frame 7 (C13),
/// for the steps of the reference programs that depend on it.
#[allow(dead_code)]
pub fn idle_bus_1999(n: usize) -> GoldenBus {
    let cfg = canstar_golden::Config { rec_bosch_1999: true, ..Default::default() };
    let mut b = GoldenBus::with_nodes((0..n).map(|_| canstar_golden::GoldenNode::new(cfg)).collect());
    assert!(b.run_to_idle(20), "integration");
    b
}

/// Tokens of node `n`'s events from bit `from` on, in order.
pub fn tokens(b: &GoldenBus, n: usize, from: u64) -> Vec<String> {
    b.since(n, from).iter().flat_map(|o| o.events.iter().map(|e| e.token())).collect()
}

pub fn count(b: &GoldenBus, n: usize, from: u64, tok: &str) -> usize {
    tokens(b, n, from).iter().filter(|t| t.as_str() == tok).count()
}

/// Frames delivered by node `n` from bit `from` on.
pub fn delivered(b: &GoldenBus, n: usize, from: u64) -> Vec<Frame> {
    b.since(n, from).iter().filter_map(|o| o.delivered().cloned()).collect()
}

pub fn is_error(e: &Event) -> bool {
    matches!(e, Event::Error(_) | Event::Aef | Event::Pef | Event::Olf | Event::Ovl)
}

/// Run until node `tx` reports TX_OK (returns the bit index of that step).
pub fn run_to_tx_ok(b: &mut GoldenBus, tx: usize, max: u64) -> u64 {
    for _ in 0..max {
        let o = b.step();
        if o[tx].has("TX_OK") {
            return b.bit - 1;
        }
    }
    panic!("no TX_OK at node {tx} within {max} bits");
}

/// Step until node `n`'s current bit matches, then force it for `bits` bits; returns the
/// results of the forced bits.
#[allow(clippy::too_many_arguments)]
pub fn force_at(
    b: &mut GoldenBus,
    n: usize,
    role: Role,
    field: Field,
    pos: u32,
    stuff: bool,
    o: RxOverride,
    bits: u64,
) -> Vec<Vec<StepOut>> {
    assert!(b.run_to(n, role, field, pos, stuff, 3000), "did not reach {role:?} {field:?} {pos} stuff={stuff}");
    b.force(n, o, bits)
}

/// A standard data frame with the given id and 1 data byte.
pub fn std1(id: u32) -> Frame {
    Frame::std_data(id, 1, &[0xA5])
}

use canstar_golden::frame::frame_bits;
use canstar_golden::{BitInfo, FrameVariant};

/// The first frame of `cands` whose wire bits satisfy `pred`.
pub fn find_frame(cands: impl IntoIterator<Item = Frame>, pred: impl Fn(&[BitInfo]) -> bool) -> Frame {
    cands
        .into_iter()
        .find(|f| pred(&frame_bits(f, FrameVariant::default())))
        .expect("no frame meets the condition")
}

/// Like [`find_frame`], `None` if no candidate fits.
pub fn try_find_frame(cands: impl IntoIterator<Item = Frame>, pred: impl Fn(&[BitInfo]) -> bool) -> Option<Frame> {
    cands.into_iter().find(|f| pred(&frame_bits(f, FrameVariant::default())))
}

/// Has a stuff bit of level `level` right after non-stuff bit (field, pos)?
pub fn stuff_after(bits: &[BitInfo], field: Field, pos: u16, level: bool) -> bool {
    bits.iter().any(|b| b.stuff && b.field == field && b.pos == pos && b.bit == level)
}

/// Level of non-stuff bit (field, pos).
pub fn bit_at(bits: &[BitInfo], field: Field, pos: u16) -> bool {
    bits.iter().find(|b| !b.stuff && b.field == field && b.pos == pos).expect("bit").bit
}

pub fn std_frames() -> impl Iterator<Item = Frame> {
    (0..0x800u32).map(|id| Frame::std_data(id, 1, &[0x55]))
}
pub fn std_remotes() -> impl Iterator<Item = Frame> {
    (0..0x800u32).map(|id| Frame::std_remote(id, 1))
}
pub fn ext_frames() -> impl Iterator<Item = Frame> {
    (0..0x40000u32).map(|k| Frame::ext_data(k.wrapping_mul(0x9E37) & 0x1FFF_FFFF, 1, &[0x55]))
}

/// Force several nodes at once for `bits` bits.
pub fn force_many(b: &mut GoldenBus, nodes: &[usize], o: RxOverride, bits: u64) -> Vec<Vec<StepOut>> {
    for &n in nodes {
        b.overrides[n] = o;
    }
    let r = (0..bits).map(|_| b.step()).collect();
    for &n in nodes {
        b.overrides[n] = RxOverride::None;
    }
    r
}
