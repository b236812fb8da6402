//! The bit plan of a lower-tester step: what the lower tester (LT) drives
//! onto the bus, at time-quantum resolution, and what it expects of the
//! implementation under test (IUT).
//!
//! # Design
//!
//! A [`Plan`] is a sequence of [`PlanBit`]s. Every bit has a level and a
//! length in time quanta (TQ) of the IUT's bit timing: nominally NTQ, made
//! longer or shorter by k TQ with [`Plan::lengthen`] / [`Plan::shorten`]. A
//! bit built from a frame carries the label the controller's frame builder
//! gives it ([`canstar_controller::frame::bus_bits`]: FIELD, POSITION and the
//! stuff flag), so a case can find "the stuff bit after Identifier 5" with
//! [`Plan::find`] instead of counting. The LT drives its TX with these levels;
//! its TX is one input of the bus' wired AND, so a recessive plan bit lets
//! the IUT's dominant bits through.
//!
//! On top of the bit sequence, [`Disturbance`]s change what nodes *read*:
//! - [`Target::Bus`]: the bus as every node sees it (the LT's own receiver
//!   included). A forced recessive level therefore overrides the wired AND
//!   for all receivers, which the LT's TX alone could never do;
//! - [`Target::Node`]`(i)`: the receive path of bench node `i` only.
//!
//! A disturbance starts at a given bit of the plan plus an offset in TQ and
//! clocks ([`At`]) and lasts a [`Span`] (TQ, clocks or nominal bits). A
//! *glitch* is a short forced level ([`Plan::glitch`]). Where two
//! disturbances of the same target overlap, the later one in the plan wins;
//! a node disturbance applies on top of a bus disturbance (see
//! `bench::compose`).
//!
//! [`Expect`]s say where the LT expects the IUT to drive a level (the ACK
//! slot of a frame the LT sends, the first bit of an error flag): the step
//! checks the IUT's TX at the nominal sample point of that plan bit
//! ([`crate::iso::StepRecord::check_expects`]).
//!
//! Everything here is plain data: times are in clocks of the IUT's clock
//! from the start of the plan ([`Plan::bit_starts`], [`Plan::windows`]); the
//! bench turns them into simulation times when the plan is played.

use canstar_controller::frame::{bus_bits, BuildOptions, Frame};
use canstar_controller::fsm::Field;
use canstar_hdl::timing::BtlConfig;

/// FIELD, POSITION and stuff flag of a plan bit built from a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Label {
    pub field: Field,
    pub pos: u32,
    pub stuff: bool,
}

/// One bit the LT drives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlanBit {
    /// Level (true = recessive).
    pub level: bool,
    /// Length in TQ of the IUT's timing (nominally NTQ).
    pub tq: u32,
    pub label: Option<Label>,
}

/// A length of time.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Span {
    /// Time quanta of the IUT's timing.
    Tq(u32),
    /// Clocks of the IUT's clock.
    Clocks(u32),
    /// Nominal bit times.
    Bits(u32),
}

/// A point of the plan: `tq` TQ and `clocks` clocks after the start of plan
/// bit `bit`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct At {
    pub bit: usize,
    pub tq: u32,
    pub clocks: u32,
}

impl At {
    /// `tq` TQ into plan bit `bit`.
    pub fn tq(bit: usize, tq: u32) -> At {
        At { bit, tq, clocks: 0 }
    }
}

/// What a disturbance does to the level read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Action {
    /// Read this level (true = recessive) whatever the bus carries.
    Force(bool),
    /// Read the complement.
    Invert,
}

/// Whose reading a disturbance changes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// The bus as every node (the LT included) sees it.
    Bus,
    /// The receive path of bench node `i` only.
    Node(usize),
}

/// A disturbance of the plan (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Disturbance {
    pub at: At,
    pub span: Span,
    pub action: Action,
    pub target: Target,
}

/// An expected level of the IUT's TX at the nominal sample point of plan
/// bit `bit`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Expect {
    pub bit: usize,
    /// true = recessive.
    pub level: bool,
    /// What is expected, for messages ("ACK", "error flag").
    pub what: &'static str,
}

/// A disturbance resolved to clocks from the plan start: `[start, end)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Window {
    pub start: u64,
    pub end: u64,
    pub action: Action,
    pub target: Target,
}

/// The plan of one LT transmission (see the module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// The IUT's bit timing (TQ length, NTQ, sample point).
    pub timing: BtlConfig,
    pub bits: Vec<PlanBit>,
    pub disturbances: Vec<Disturbance>,
    pub expects: Vec<Expect>,
}

impl Plan {
    /// An empty plan for an IUT with bit timing `timing`.
    pub fn new(timing: BtlConfig) -> Plan {
        Plan { timing, bits: vec![], disturbances: vec![], expects: vec![] }
    }

    /// Raw levels (true = recessive), nominal length, no labels.
    pub fn raw(timing: BtlConfig, levels: &[bool]) -> Plan {
        let mut p = Plan::new(timing);
        p.push_levels(levels);
        p
    }

    /// Frame `f` as a transmitter sends it (SOF to the last EOF bit, stuffed,
    /// with the `o` levels of SRR/r1/r0), every bit labelled, the ACK slot
    /// recessive and expected dominant from the IUT.
    pub fn frame(timing: BtlConfig, f: &Frame, o: BuildOptions) -> Plan {
        let mut p = Plan::new(timing);
        p.push_frame(f, o);
        p
    }

    /// The LT's answer to frame `f` sent by the IUT (played from the IUT's
    /// SOF, `Trigger::at(Field::Sof, 1)`): recessive except a dominant ACK
    /// slot, every bit of the IUT's frame from SOF to the ACK delimiter and
    /// the End_Of_Frame expected on the IUT's TX, then `tail` recessive bits.
    /// The template of the cases with the IUT as transmitter.
    pub fn answer(timing: BtlConfig, f: &Frame, o: BuildOptions, tail: usize) -> Plan {
        let mut p = Plan::new(timing);
        let ntq = timing.ntq();
        for b in bus_bits(f, o, false) {
            let ack = b.field == Field::AckSlot;
            let label = Label { field: b.field, pos: b.pos as u32, stuff: b.stuff };
            p.expects.push(Expect { bit: p.bits.len(), level: b.level, what: "IUT frame bit" });
            p.bits.push(PlanBit { level: !ack, tq: ntq, label: Some(label) });
        }
        p.push_recessive(tail);
        p
    }

    /// Append frame `f` (see [`Plan::frame`]); returns the index of its SOF.
    pub fn push_frame(&mut self, f: &Frame, o: BuildOptions) -> usize {
        let first = self.bits.len();
        let ntq = self.timing.ntq();
        for b in bus_bits(f, o, false) {
            let label = Label { field: b.field, pos: b.pos as u32, stuff: b.stuff };
            if b.field == Field::AckSlot {
                self.expects.push(Expect { bit: self.bits.len(), level: false, what: "ACK" });
            }
            self.bits.push(PlanBit { level: b.level, tq: ntq, label: Some(label) });
        }
        first
    }

    /// Append raw levels of nominal length.
    pub fn push_levels(&mut self, levels: &[bool]) -> &mut Self {
        let ntq = self.timing.ntq();
        self.bits.extend(levels.iter().map(|&level| PlanBit { level, tq: ntq, label: None }));
        self
    }

    /// Append `n` recessive bits (intermission, idle, room for the IUT's flags).
    pub fn push_recessive(&mut self, n: usize) -> &mut Self {
        self.push_levels(&vec![true; n])
    }

    /// Index of the bit labelled (field, pos, stuff) (the first one).
    pub fn find(&self, field: Field, pos: u32, stuff: bool) -> Option<usize> {
        self.bits.iter().position(|b| b.label == Some(Label { field, pos, stuff }))
    }

    /// Indices of all stuff bits.
    pub fn stuff_bits(&self) -> Vec<usize> {
        (0..self.bits.len()).filter(|&i| self.bits[i].label.is_some_and(|l| l.stuff)).collect()
    }

    /// Make bit `i` `k` TQ longer.
    pub fn lengthen(&mut self, i: usize, k: u32) -> &mut Self {
        self.bits[i].tq += k;
        self
    }

    /// Make bit `i` `k` TQ shorter (at least 1 TQ remains).
    pub fn shorten(&mut self, i: usize, k: u32) -> &mut Self {
        assert!(k < self.bits[i].tq, "bit {i} of {} TQ cannot lose {k} TQ", self.bits[i].tq);
        self.bits[i].tq -= k;
        self
    }

    /// Set the level of bit `i` (e.g. a stuff bit of the wrong level).
    pub fn set_level(&mut self, i: usize, level: bool) -> &mut Self {
        self.bits[i].level = level;
        self
    }

    /// Drop the bits from `n` on, and the expectations about them.
    pub fn truncate(&mut self, n: usize) -> &mut Self {
        self.bits.truncate(n);
        self.expects.retain(|e| e.bit < n);
        self
    }

    /// Expect the IUT to drive `level` at the sample point of bit `bit`.
    pub fn expect(&mut self, bit: usize, level: bool, what: &'static str) -> &mut Self {
        self.expects.push(Expect { bit, level, what });
        self
    }

    /// Add a disturbance.
    pub fn disturb(&mut self, d: Disturbance) -> &mut Self {
        self.disturbances.push(d);
        self
    }

    /// A glitch on the bus as every node sees it: `level` for `width` from `at`.
    pub fn glitch(&mut self, at: At, width: Span, level: bool) -> &mut Self {
        self.disturb(Disturbance { at, span: width, action: Action::Force(level), target: Target::Bus })
    }

    /// Clocks per TQ.
    pub fn tq_clocks(&self) -> u64 {
        self.timing.brp as u64
    }

    /// A span in clocks.
    pub fn clocks(&self, s: Span) -> u64 {
        match s {
            Span::Tq(n) => n as u64 * self.tq_clocks(),
            Span::Clocks(n) => n as u64,
            Span::Bits(n) => n as u64 * self.timing.ntq() as u64 * self.tq_clocks(),
        }
    }

    /// Start of every bit in clocks from the plan start, plus the end of the
    /// last bit (`bits.len() + 1` values).
    pub fn bit_starts(&self) -> Vec<u64> {
        let mut v = Vec::with_capacity(self.bits.len() + 1);
        let mut t = 0;
        v.push(0);
        for b in &self.bits {
            t += b.tq as u64 * self.tq_clocks();
            v.push(t);
        }
        v
    }

    /// Length of the plan in clocks.
    pub fn total_clocks(&self) -> u64 {
        *self.bit_starts().last().unwrap()
    }

    /// Clock (from the plan start) of a point of the plan. A point in the
    /// bit after the last one is allowed (the end of the plan).
    pub fn clock_of(&self, at: At) -> u64 {
        let s = self.bit_starts();
        assert!(at.bit < s.len(), "plan point in bit {} of a {}-bit plan", at.bit, self.bits.len());
        s[at.bit] + at.tq as u64 * self.tq_clocks() + at.clocks as u64
    }

    /// Clock (from the plan start) of the nominal sample point of bit `i`
    /// (the start of its TQ number SP; the IUT samples at the end of TQ SP−1).
    pub fn sample_clock(&self, i: usize) -> u64 {
        self.bit_starts()[i] + self.timing.sp() as u64 * self.tq_clocks()
    }

    /// The LT's TX as runs of (clocks, level).
    pub fn tx_runs(&self) -> Vec<(u64, bool)> {
        let mut v: Vec<(u64, bool)> = vec![];
        for b in &self.bits {
            let n = b.tq as u64 * self.tq_clocks();
            match v.last_mut() {
                Some(last) if last.1 == b.level => last.0 += n,
                _ => v.push((n, b.level)),
            }
        }
        v
    }

    /// The disturbances resolved to clocks from the plan start, in plan order.
    pub fn windows(&self) -> Vec<Window> {
        self.disturbances
            .iter()
            .map(|d| {
                let start = self.clock_of(d.at);
                Window { start, end: start + self.clocks(d.span), action: d.action, target: d.target }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: BtlConfig = BtlConfig::T10_6_4;

    #[test]
    fn a_frame_plan_is_the_builders_bits_with_labels_and_an_ack_expectation() {
        let f = Frame::std(0x078, &[0xAA]);
        let p = Plan::frame(T, &f, BuildOptions::default());
        let bb = bus_bits(&f, BuildOptions::default(), false);
        assert_eq!(p.bits.len(), bb.len());
        assert!(p.bits.iter().zip(&bb).all(|(a, b)| a.level == b.level && a.tq == 10 && a.label.unwrap().field == b.field));
        let ack = p.find(Field::AckSlot, 1, false).unwrap();
        assert_eq!(p.expects, vec![Expect { bit: ack, level: false, what: "ACK" }]);
        assert!(p.bits[ack].level, "the LT leaves the ACK slot recessive");
        // 0x078 = 0000 1111 000: SOF + ID 1..4 are five dominant bits, a stuff bit follows ID 4
        let s = p.find(Field::Ident, 4, true).unwrap();
        assert_eq!(s, 5);
        assert!(p.bits[s].level);
        assert!(p.stuff_bits().contains(&s));
    }

    #[test]
    fn lengths_and_times_follow_the_tq_changes() {
        let mut p = Plan::raw(T.with_ph2(4), &[false, true, false]);
        p.lengthen(0, 3).shorten(1, 2);
        assert_eq!(p.bit_starts(), vec![0, 13, 21, 31]);
        assert_eq!(p.tx_runs(), vec![(13, false), (8, true), (10, false)]);
        assert_eq!(p.sample_clock(1), 13 + 6);
        let p4 = Plan::raw(BtlConfig::new(4, 1, 4, 4), &[true, true]);
        assert_eq!(p4.bit_starts(), vec![0, 40, 80], "BRP 4: 4 clocks per TQ");
        assert_eq!(p4.tx_runs(), vec![(80, true)]);
    }

    #[test]
    fn disturbances_resolve_to_clock_windows() {
        let mut p = Plan::raw(BtlConfig::new(2, 1, 4, 4), &[true; 4]);
        p.glitch(At::tq(1, 3), Span::Tq(2), false);
        p.disturb(Disturbance { at: At { bit: 2, tq: 0, clocks: 1 }, span: Span::Clocks(3), action: Action::Invert, target: Target::Node(1) });
        p.disturb(Disturbance { at: At::tq(3, 0), span: Span::Bits(1), action: Action::Force(true), target: Target::Bus });
        assert_eq!(
            p.windows(),
            vec![
                Window { start: 20 + 6, end: 20 + 10, action: Action::Force(false), target: Target::Bus },
                Window { start: 41, end: 44, action: Action::Invert, target: Target::Node(1) },
                Window { start: 60, end: 80, action: Action::Force(true), target: Target::Bus },
            ]
        );
    }

    #[test]
    fn truncate_drops_later_expectations() {
        let f = Frame::std(0x123, &[]);
        let mut p = Plan::frame(T, &f, BuildOptions::default());
        p.expect(3, false, "flag");
        p.truncate(10);
        assert_eq!(p.expects.len(), 1);
        assert_eq!(p.bits.len(), 10);
    }
}
