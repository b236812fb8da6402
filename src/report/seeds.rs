//! Several place-and-route seeds of one design: the best fmax, the median run,
//! and a line for every seed that gave no figures.

use crate::report::pnr::{Outcome, Pnr, SeedRun};
use anyhow::Result;
use std::path::Path;

/// The runs of one design, seed 1, 2, ... in order.
#[derive(Debug, Clone, PartialEq)]
pub struct Seeds {
    /// Frequency nextpnr was asked to meet, in MHz.
    pub freq_mhz: f64,
    pub runs: Vec<SeedRun>,
}

/// A placed run's figures.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placed {
    pub seed: u64,
    pub lc: usize,
    pub fmax_mhz: f64,
}

impl Seeds {
    /// The runs that placed and routed, slowest first (ties by seed).
    pub fn placed(&self) -> Vec<Placed> {
        let mut v: Vec<Placed> = self
            .runs
            .iter()
            .filter_map(|r| match r.outcome {
                Outcome::Placed { lc, fmax_mhz } => Some(Placed { seed: r.seed, lc, fmax_mhz }),
                _ => None,
            })
            .collect();
        v.sort_by(|a, b| a.fmax_mhz.total_cmp(&b.fmax_mhz).then(a.seed.cmp(&b.seed)));
        v
    }

    /// The fastest placed run.
    pub fn best(&self) -> Option<Placed> {
        self.placed().last().copied()
    }

    /// The median placed run (the slower of the two middle ones for an even
    /// count, so that its fmax and logic cells are those of one real run).
    /// Stalled and failed seeds are not counted.
    pub fn median(&self) -> Option<Placed> {
        let p = self.placed();
        p.get(p.len().checked_sub(1)? / 2).copied()
    }

    /// A line for the seeds without figures, if any: "d: not placed (seed 1: ...;
    /// seed 2: ...)" when no seed placed, "d: 2 of 3 seeds placed (seed 3: ...)"
    /// otherwise.
    pub fn note(&self, design: &str) -> Option<String> {
        let missing: Vec<String> = self.runs.iter().filter(|r| !matches!(r.outcome, Outcome::Placed { .. })).map(SeedRun::describe).collect();
        if missing.is_empty() {
            return None;
        }
        let n = self.placed().len();
        Some(if n == 0 {
            format!("{design}: not placed ({})", missing.join("; "))
        } else {
            format!("{design}: {n} of {} seeds placed ({})", self.runs.len(), missing.join("; "))
        })
    }
}

/// Place and route `json` with seeds 1..=`seeds`, one after the other; `on_run`
/// sees each run as it ends.
pub fn place(pnr: &Pnr, json: &Path, seeds: u64, on_run: &mut dyn FnMut(&SeedRun)) -> Result<Seeds> {
    let mut runs = vec![];
    for seed in 1..=seeds {
        let r = pnr.run(json, seed)?;
        on_run(&r);
        runs.push(r);
    }
    Ok(Seeds { freq_mhz: pnr.freq_mhz, runs })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(seed: u64, outcome: Outcome) -> SeedRun {
        SeedRun { seed, outcome, secs: 1.0 }
    }

    fn placed(seed: u64, lc: usize, fmax_mhz: f64) -> SeedRun {
        run(seed, Outcome::Placed { lc, fmax_mhz })
    }

    fn seeds(runs: Vec<SeedRun>) -> Seeds {
        Seeds { freq_mhz: 50.0, runs }
    }

    #[test]
    fn best_and_median_of_three_placed_seeds() {
        let s = seeds(vec![placed(1, 100, 47.4), placed(2, 101, 51.5), placed(3, 102, 46.2)]);
        assert_eq!(s.best(), Some(Placed { seed: 2, lc: 101, fmax_mhz: 51.5 }));
        assert_eq!(s.median(), Some(Placed { seed: 1, lc: 100, fmax_mhz: 47.4 }));
        assert_eq!(s.note("d"), None);
    }

    #[test]
    fn stalled_and_failed_seeds_are_not_counted() {
        let stalled = run(1, Outcome::Stalled { stall_s: 60.0 });
        let failed = run(4, Outcome::Failed("ERROR: boom".into()));
        // Two placed: the median is the slower of the two.
        let s = seeds(vec![stalled.clone(), placed(2, 200, 60.0), placed(3, 201, 55.0), failed.clone()]);
        assert_eq!(s.median(), Some(Placed { seed: 3, lc: 201, fmax_mhz: 55.0 }));
        assert_eq!(s.best().map(|p| p.seed), Some(2));
        let note = s.note("d").unwrap();
        assert!(note.starts_with("d: 2 of 4 seeds placed (seed 1: stalled: no router progress for 60 s"), "{note}");
        assert!(note.contains("seed 4: failed: ERROR: boom"), "{note}");
        // One placed among timeouts.
        let s = seeds(vec![run(1, Outcome::TimedOut), placed(2, 7, 99.0)]);
        assert_eq!(s.median(), s.best());
        // None placed.
        let s = seeds(vec![stalled, run(2, Outcome::TimedOut), failed]);
        assert_eq!((s.median(), s.best()), (None, None));
        let note = s.note("canstar_x").unwrap();
        assert!(note.starts_with("canstar_x: not placed (seed 1: stalled") && note.contains("; seed 2: did not finish") && note.contains("; seed 4: failed"), "{note}");
        assert_eq!(seeds(vec![]).median(), None);
    }

    #[test]
    fn a_stalled_seed_is_followed_by_the_next() {
        let d = tempfile::tempdir().unwrap();
        let program = crate::report::fake::fake(d.path(), crate::report::fake::SILENT);
        let pnr = Pnr { program, freq_mhz: 50.0, stall: std::time::Duration::from_secs(1), timeout: std::time::Duration::from_secs(30) };
        let mut seen = vec![];
        let s = place(&pnr, Path::new("x.json"), 2, &mut |r| seen.push(r.seed)).unwrap();
        assert_eq!(seen, vec![1, 2]);
        assert!(s.runs.iter().all(|r| matches!(r.outcome, Outcome::Stalled { .. })), "{s:?}");
        let note = s.note("canstar_x").unwrap();
        assert!(note.starts_with("canstar_x: not placed (seed 1: stalled: no router progress for 1 s") && note.contains("; seed 2: stalled"), "{note}");
        // Each seed started its own fake (two pids each: the script and its sleep).
        assert_eq!(std::fs::read_to_string(d.path().join("pids")).unwrap().lines().count(), 4);
        assert!(crate::report::fake::alive(d.path()).is_empty());
    }
}
