//! The record of one lower-tester step ([`StepRecord`]): the bus, the LT's
//! and the IUT's TX clock by clock, every node's processed bits (events and
//! counters after each bit), and the plans the LT played with their start
//! times, so that a case asserts on what happened and where.
//!
//! # Design
//!
//! Clock samples come from the LT component ([`ClockSample`]: the levels
//! during the clock period ending at the sample's edge); bit records from
//! the shared bench ([`BitRec`], read from the debug bundle). Positions in a
//! plan are turned into times with the plan's start time, so "what did the
//! IUT drive at the sample point of plan bit 37" is a lookup
//! ([`StepRecord::iut_tx_at`]); [`StepRecord::check_expects`] checks every
//! expectation the played plans carry. [`StepRecord::per_tq`] thins the
//! clock samples to one per TQ of the IUT's nominal timing, on the grid of
//! the first plan played.

use super::plan::Plan;
use super::tester::ClockSample;
use crate::conformance::BitRec;

/// A plan as played: its first clock's time (ps) and the plan.
#[derive(Clone, Debug)]
pub struct Played {
    pub t0: u64,
    pub plan: Plan,
}

/// Everything one step recorded (see the module documentation).
#[derive(Clone, Debug)]
pub struct StepRecord {
    pub name: String,
    /// Step start and end (ps).
    pub t0: u64,
    pub t_end: u64,
    /// The IUT's clock period and TQ (ps).
    pub clock_ps: u64,
    pub tq_ps: u64,
    pub samples: Vec<ClockSample>,
    /// The bits every bench node processed during the step (node 0: the IUT).
    pub bits: Vec<Vec<BitRec>>,
    pub plays: Vec<Played>,
}

impl StepRecord {
    /// The IUT's bits.
    pub fn iut(&self) -> &[BitRec] {
        &self.bits[0]
    }

    /// The clock sample describing instant `t` (the first edge after it).
    pub fn at(&self, t: u64) -> Option<&ClockSample> {
        let i = self.samples.partition_point(|s| s.t <= t);
        self.samples.get(i)
    }

    /// Time (ps) of clock `c` of played plan `play`.
    pub fn plan_time(&self, play: usize, c: u64) -> u64 {
        self.plays[play].t0 + c * self.clock_ps
    }

    /// Start time (ps) of bit `bit` of played plan `play`.
    pub fn bit_start(&self, play: usize, bit: usize) -> u64 {
        self.plan_time(play, self.plays[play].plan.bit_starts()[bit])
    }

    /// The IUT's TX at the nominal sample point of bit `bit` of plan `play`.
    pub fn iut_tx_at(&self, play: usize, bit: usize) -> Option<bool> {
        let t = self.plan_time(play, self.plays[play].plan.sample_clock(bit));
        self.at(t).map(|s| s.iut_tx)
    }

    /// The bus as every node saw it at the nominal sample point of bit `bit`.
    pub fn bus_at(&self, play: usize, bit: usize) -> Option<bool> {
        let t = self.plan_time(play, self.plays[play].plan.sample_clock(bit));
        self.at(t).map(|s| s.bus)
    }

    /// Check every expectation of every played plan against the IUT's TX.
    pub fn check_expects(&self) -> Result<(), String> {
        let mut bad = vec![];
        for (k, p) in self.plays.iter().enumerate() {
            for e in &p.plan.expects {
                let got = self.iut_tx_at(k, e.bit);
                if got != Some(e.level) {
                    let l = |v: bool| if v { "R" } else { "D" };
                    let label = p.plan.bits.get(e.bit).and_then(|b| b.label).map(|l| format!(" ({} {}{})", l.field.name(), l.pos, if l.stuff { " stuff" } else { "" })).unwrap_or_default();
                    bad.push(format!(
                        "{}: plan {k} bit {}{label}: IUT drove {}, expected {}",
                        e.what,
                        e.bit,
                        got.map_or("nothing recorded", l),
                        l(e.level)
                    ));
                }
            }
        }
        if bad.is_empty() {
            Ok(())
        } else {
            Err(bad.join("; "))
        }
    }

    /// One sample per TQ, from the first plan's start (or the step start).
    pub fn per_tq(&self) -> Vec<ClockSample> {
        let t0 = self.plays.first().map_or(self.t0, |p| p.t0);
        let mut out = vec![];
        let mut t = t0;
        while let Some(s) = self.at(t) {
            out.push(*s);
            t += self.tq_ps;
        }
        out
    }

    /// The IUT's bit records carrying event `ev` (`EV_*`).
    pub fn iut_events(&self, ev: usize) -> Vec<BitRec> {
        self.iut().iter().filter(|r| r.has(ev)).copied().collect()
    }

    /// The IUT's bits one per line (for failure messages).
    pub fn dump(&self, node: usize) -> String {
        self.bits[node].iter().map(|r| format!("\n    {r}")).collect()
    }

    /// The bus levels per TQ as a string of `0`/`1` (`0` dominant).
    pub fn bus_string(&self) -> String {
        self.per_tq().iter().map(|s| if s.bus { '1' } else { '0' }).collect()
    }
}
