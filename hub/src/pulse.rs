//! Pulse-width check of one hub input ([`PulseCheck`]), the evidence of the glitch rule
//! (hub.md §5.8, [`crate::judge`]).
//!
//! A CAN controller changes its TX only at its own bit boundaries, and a resynchronisation
//! shortens a bit by at most SJW: on a healthy uplink every run of equal level lasts at
//! least one bit minus SJW (7 TQ = 14 clocks with the reference timing; the shortest run the
//! fault-free soak measured on a port input is 14 clocks, `canstar soak`). A sublink carries
//! the peer hub's coupled contribution, whose runs are as long except for the 1-2 clock
//! slivers left when a port is isolated or an error flag starts in the middle of a bit.
//! Those slivers are recessive: the gap between a dominant run that ends and the isolation
//! or error flag that follows it. A dominant run shorter than the recessive minimum has no
//! such cause (hub.md §5.15), so the minimum is set per level: a completed recessive run
//! of `min..=max` clocks, or dominant run of `dmin..=max` clocks, is a glitch of the input
//! itself: a flipped or disturbed link, seen where it enters the hub whatever the sample
//! points of the hub and of the nodes.
//!
//! `glitch` is a combinational strobe in the clock where the run ends (the input changes
//! level). The first edge after reset is never a glitch.

use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct PulseCheck {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    /// The input as the hub samples it (0 = dominant).
    pub c: Signal<In, Bit>,
    /// A run of `min..=max` clocks ended in this clock.
    pub glitch: Signal<Out, Bit>,
    /// `min - 1` and `max`: `run + 1` is in range iff `run == min - 1`, or `run` is in
    /// range and not `max`.
    min_m1: Constant<Bits<5>>,
    max: Constant<Bits<5>>,
    /// A run of length 1 is in range (`min == 1`).
    one_in: Constant<Bit>,
    /// The same for dominant runs (`dmin`).
    dmin_m1: Constant<Bits<5>>,
    done_in: Constant<Bit>,
    prev: DFF<Bit>,
    run: DFF<Bits<5>>,
    /// `run` is in `min..=max`, kept with `run` (timing: no comparator after `run`).
    in_r: DFF<Bit>,
    /// `run` is in `dmin..=max`.
    din_r: DFF<Bit>,
    chg: Signal<Local, Bit>,
}

impl PulseCheck {
    /// Recessive runs of `min..=max` clocks and dominant runs of `dmin..=max` clocks
    /// (1..=30) are glitches.
    pub fn new(min: u64, dmin: u64, max: u64) -> Self {
        assert!(
            (1..=30).contains(&min) && (1..=30).contains(&dmin) && (min.max(dmin)..=30).contains(&max),
            "glitch ranges {min}..={max}, {dmin}..={max} out of 1..=30"
        );
        Self {
            clock: Default::default(),
            reset: Default::default(),
            c: Default::default(),
            glitch: Default::default(),
            min_m1: Constant::new((min - 1).into()),
            max: Constant::new(max.into()),
            one_in: Constant::new(min == 1),
            dmin_m1: Constant::new((dmin - 1).into()),
            done_in: Constant::new(dmin == 1),
            prev: Default::default(),
            run: Default::default(),
            in_r: Default::default(),
            din_r: Default::default(),
            chg: Default::default(),
        }
    }
}

impl Logic for PulseCheck {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, prev, run, in_r, din_r);
        self.chg.next = self.c.val() != self.prev.q.val();
        // `in_r` = (`run` >= min) & (`run` <= max), updated with `run` (31 is never in
        // range: max <= 30; after reset and at power-up `run` is 31 or 0, out of range)
        // `prev` is the level of the run that ends (true = recessive)
        self.glitch.next = self.chg.val() & ((self.prev.q.val() & self.in_r.q.val()) | (!self.prev.q.val() & self.din_r.q.val()));
        self.prev.d.next = self.c.val();
        if self.chg.val() {
            self.run.d.next = 1.into();
            self.in_r.d.next = self.one_in.val();
            self.din_r.d.next = self.done_in.val();
        } else if self.run.q.val() != 31 {
            self.run.d.next = self.run.q.val() + 1;
            self.in_r.d.next = (self.run.q.val() == self.min_m1.val()) | (self.in_r.q.val() & (self.run.q.val() != self.max.val()));
            self.din_r.d.next = (self.run.q.val() == self.dmin_m1.val()) | (self.din_r.q.val() & (self.run.q.val() != self.max.val()));
        }
        if self.reset.val() {
            self.prev.d.next = true;
            self.run.d.next = 31.into();
            self.in_r.d.next = false;
            self.din_r.d.next = false;
        }
    }
}

canstar_hdl::impl_clocked!(PulseCheck);

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::drive;

    /// Drive `levels` (one per clock) and return the clocks with a glitch strobe.
    fn glitches(min: u64, max: u64, levels: &[bool]) -> Vec<usize> {
        glitches_by_level(min, min, max, levels)
    }

    fn glitches_by_level(min: u64, dmin: u64, max: u64, levels: &[bool]) -> Vec<usize> {
        let mut p = PulseCheck::new(min, dmin, max);
        p.c.next = true;
        p.reset.next = true;
        drive::init(&mut p);
        drive::cycle(&mut p);
        p.reset.next = false;
        let mut out = vec![];
        for (i, &l) in levels.iter().enumerate() {
            p.c.next = l;
            drive::settle(&mut p);
            if p.glitch.val() {
                out.push(i);
            }
            drive::cycle(&mut p);
        }
        out
    }

    fn wave(runs: &[(bool, usize)]) -> Vec<bool> {
        runs.iter().flat_map(|&(l, n)| std::iter::repeat_n(l, n)).collect()
    }

    #[test]
    fn short_runs_of_either_level_are_glitches() {
        // recessive idle, a 5-clock dominant pulse, 20 recessive, a 16-clock dominant bit,
        // 11 recessive (a glitch: it ends at the next edge), 12 dominant, 3 recessive
        let w = wave(&[(true, 20), (false, 5), (true, 20), (false, 16), (true, 11), (false, 12), (true, 3)]);
        // strobes in the clock where the short run ends: the 5-clock pulse ends at 25,
        // the 11-clock recessive run at 72
        assert_eq!(glitches(1, 11, &w), vec![25, 72]);
        // with max 12 the 12-clock dominant run counts too (it ends at 84)
        assert_eq!(glitches(1, 12, &w), vec![25, 72, 84]);
        // a lower bound of 6 ignores the 5-clock pulse
        assert_eq!(glitches(6, 11, &w), vec![72]);
    }

    #[test]
    fn the_minimum_is_set_per_level() {
        // a 2-clock dominant pulse (ends at 22), a 2-clock recessive sliver between two
        // dominant runs (ends at 58), a 3-clock recessive run (ends at 77), a 1-clock
        // dominant pulse (ends at 78)
        let w = wave(&[(true, 20), (false, 2), (true, 18), (false, 16), (true, 2), (false, 16), (true, 3), (false, 1), (true, 20)]);
        // sublink default: recessive runs from 3 clocks, dominant runs from 1
        assert_eq!(glitches_by_level(3, 1, 11, &w), vec![22, 77, 78]);
        // both from 3: only the 3-clock recessive run
        assert_eq!(glitches(3, 11, &w), vec![77]);
        // both from 1: every short run
        assert_eq!(glitches(1, 11, &w), vec![22, 58, 77, 78]);
        // dominant from 2: the 1-clock pulse is ignored
        assert_eq!(glitches_by_level(3, 2, 11, &w), vec![22, 77]);
    }

    #[test]
    fn bits_of_legal_length_never_glitch() {
        // a bit shortened by SJW (14 clocks) and longer runs
        let w = wave(&[(true, 30), (false, 14), (true, 14), (false, 16), (true, 80), (false, 96), (true, 40)]);
        assert!(glitches(1, 11, &w).is_empty());
        // reset counts as a long recessive run: an input dominant right after reset is no glitch
        assert!(glitches(1, 11, &wave(&[(false, 20), (true, 20)])).is_empty());
    }
}
