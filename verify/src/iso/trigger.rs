//! Triggers: "the IUT is at bit P of the n-th occurrence of field F since
//! the start of the test step, q TQ into that bit".
//!
//! # Design
//!
//! The IUT's debug bundle shows, between two sample points, the FIELD,
//! POSITION and stuff flag of the bit in progress (`dbg_field`, `dbg_pos`,
//! `dbg_stuff`), and the bench records every processed bit
//! ([`crate::conformance::BitRec`]). Nothing here needs a new RTL signal:
//!
//! - **Occurrences** are counted on the sequence of bits the IUT processes,
//!   from the start of the step ([`Occurrences`]): a bit of field F begins a
//!   new occurrence when the bit before it was of another field, or when its
//!   POSITION does not follow on (a flag restarted by a bit error in the
//!   flag: Active_Error_Flag 3, then Active_Error_Flag 1). Stuff bits never
//!   begin one. Bus_Idle, Wait_For_Bus_Idle and Bus_Off begin an occurrence
//!   only when entered from another field (their POSITION restarts inside
//!   one occurrence: a dominant bit during integration, every 11-bit
//!   recovery run). A bit belongs to the step when it begins at or after the
//!   step's start; the bit in progress when the step starts does not.
//!   Limitation: the first Wait_For_Bus_Idle bit after a reset is shown
//!   without a bit before it, so it cannot be a trigger target (position 2
//!   and later can).
//! - **The bit start** is the instant the bus level that the IUT reads in
//!   the bit's SYNC_SEG was on the bus: the clock carrying the previous
//!   bit's events plus the rest of its PH2 minus the IUT's RX latency, as the
//!   Bosch bench's WAIT_FOR computes it
//!   ([`crate::conformance::Bench::ph2_rest_ps`]). The trigger fires `q` TQ
//!   later (TQ of the IUT's nominal timing).
//! - **Bus-off recovery** (ISO 11898-1's 128 × 11 recessive bits, which
//!   ISO 16845 places in Wait_For_Bus_Idle) is part of the Bus_Off field in
//!   canstar (can-protocol.md §14): [`Where::Recovery`] is derived from
//!   POSITION (bit of the current run) and `dbg_runs` (completed runs).
//!   canstar's own Wait_For_Bus_Idle is the integration after reset (and
//!   after a counter load that leaves Bus_Off).
//! - **Reset** has no bits: [`Where::Reset`] fires when the IUT's
//!   `dbg_field` shows Reset (held in reset) for the n-th time in the step,
//!   q TQ after the first clock of it.

use canstar_controller::fsm::Field;

/// Where a trigger fires.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Where {
    /// Bit (field, pos, stuff) of an occurrence of `field`.
    Bit { field: Field, pos: u32, stuff: bool },
    /// Bit `bit` (1..=11) of bus-off recovery run `run` (1..=128), in an
    /// occurrence of Bus_Off.
    Recovery { run: u32, bit: u32 },
    /// The IUT is held in reset.
    Reset,
}

/// A trigger: `at`, in the `nth` occurrence (from 1) of its field since the
/// step start, `tq` TQ after the start of the bit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Trigger {
    pub at: Where,
    pub nth: u32,
    pub tq: u32,
}

impl Trigger {
    /// Bit `pos` of the first occurrence of `field` in the step, TQ 0.
    pub fn at(field: Field, pos: u32) -> Trigger {
        Trigger { at: Where::Bit { field, pos, stuff: false }, nth: 1, tq: 0 }
    }
    /// The stuff bit after bit `pos` of `field`.
    pub fn stuff_after(field: Field, pos: u32) -> Trigger {
        Trigger { at: Where::Bit { field, pos, stuff: true }, nth: 1, tq: 0 }
    }
    /// Bit `bit` of bus-off recovery run `run` (first Bus_Off of the step).
    pub fn recovery(run: u32, bit: u32) -> Trigger {
        Trigger { at: Where::Recovery { run, bit }, nth: 1, tq: 0 }
    }
    /// The IUT held in reset.
    pub fn reset() -> Trigger {
        Trigger { at: Where::Reset, nth: 1, tq: 0 }
    }
    /// In the `n`-th occurrence of the field (from 1).
    pub fn nth(mut self, n: u32) -> Trigger {
        assert!(n >= 1, "occurrences count from 1");
        self.nth = n;
        self
    }
    /// `q` TQ into the bit.
    pub fn tq(mut self, q: u32) -> Trigger {
        self.tq = q;
        self
    }
    /// The field whose occurrences count.
    pub fn field(&self) -> Field {
        match self.at {
            Where::Bit { field, .. } => field,
            Where::Recovery { .. } => Field::BusOff,
            Where::Reset => Field::Reset,
        }
    }
    /// Does the bit (field, pos, stuff), with `runs` completed recovery runs,
    /// sit where the trigger points (occurrence aside)?
    pub fn matches(&self, field: Field, pos: u32, stuff: bool, runs: u32) -> bool {
        match self.at {
            Where::Bit { field: f, pos: p, stuff: s } => field == f && pos == p && stuff == s,
            Where::Recovery { run, bit } => field == Field::BusOff && pos == bit && !stuff && runs + 1 == run,
            Where::Reset => field == Field::Reset,
        }
    }
}

/// Does the bit `cur` (field, pos, stuff) begin a new occurrence of its
/// field, coming after the bit `prev` (field, pos)? See the module
/// documentation.
pub fn begins_occurrence(prev: (Field, u32), cur: (Field, u32, bool)) -> bool {
    let (f, p, s) = cur;
    if s {
        return false;
    }
    if prev.0 != f {
        return true;
    }
    !matches!(f, Field::Idle | Field::WaitIdle | Field::BusOff) && p <= prev.1
}

/// Occurrence counts of every field since the step start.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Occurrences {
    counts: [u32; 25],
}

impl Occurrences {
    /// Count the bit `cur` that follows `prev`.
    pub fn note(&mut self, prev: (Field, u32), cur: (Field, u32, bool)) {
        if begins_occurrence(prev, cur) {
            self.counts[cur.0.code() as usize] += 1;
        }
    }
    /// Occurrences of `f` so far.
    pub fn of(&self, f: Field) -> u32 {
        self.counts[f.code() as usize]
    }
    /// Count an occurrence of `f` directly (Reset, seen per clock).
    pub fn bump(&mut self, f: Field) {
        self.counts[f.code() as usize] += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Field::*;

    fn count(seq: &[(Field, u32, bool)], f: Field) -> u32 {
        let mut o = Occurrences::default();
        for w in seq.windows(2) {
            o.note((w[0].0, w[0].1), w[1]);
        }
        o.of(f)
    }

    #[test]
    fn occurrences_of_flags_frames_and_states() {
        let seq = [
            (Idle, 5, false),
            (Sof, 1, false),
            (Ident, 1, false),
            (Ident, 1, true),
            (Ident, 2, false),
            (ActFlag, 1, false),
            (ActFlag, 2, false),
            (ActFlag, 3, false),
            (ActFlag, 1, false), // restarted by a bit error in the flag
            (ActFlag, 2, false),
            (ErrDel, 1, false),
            (Inter, 1, false),
            (Idle, 1, false),
            (Idle, 2, false),
            (Sof, 1, false),
        ];
        assert_eq!(count(&seq, Sof), 2);
        assert_eq!(count(&seq, Ident), 1, "a stuff bit continues its field");
        assert_eq!(count(&seq, ActFlag), 2);
        assert_eq!(count(&seq, Idle), 1, "the idle in progress before the sequence is not counted");
        let off = [(Eof, 3, false), (BusOff, 1, false), (BusOff, 11, false), (BusOff, 1, false), (BusOff, 1, false), (WaitIdle, 1, false)];
        assert_eq!(count(&off, BusOff), 1, "runs and restarts stay in one Bus_Off");
        assert_eq!(count(&off, WaitIdle), 1);
    }

    #[test]
    fn matching() {
        let t = Trigger::recovery(2, 11);
        assert!(t.matches(BusOff, 11, false, 1));
        assert!(!t.matches(BusOff, 11, false, 0));
        assert_eq!(t.field(), BusOff);
        let t = Trigger::stuff_after(Ident, 4).nth(2).tq(3);
        assert!(t.matches(Ident, 4, true, 0) && !t.matches(Ident, 4, false, 0));
        assert_eq!((t.nth, t.tq), (2, 3));
        assert!(Trigger::reset().matches(Reset, 0, false, 0));
    }
}
