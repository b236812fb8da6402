//! Automated fault campaigns on the ReCANcentrate system (recancentrate.md §4–6).
//!
//! A campaign is a list of *runs*: every selected scenario [class](classes::Class)
//! repeated `reps` times. Run `rep` of class `c` uses the seed
//! [`run_seed`]`(master, c, rep)`, which fixes everything random in it (injection
//! instant, traffic phase, oscillator offsets, flip patterns), so any run can be
//! reproduced alone from its class and seed, and the result of a run never depends on
//! the number of threads, on sharding or on the other selected classes.
//!
//! - [`plan`] lists the runs (optionally one [`Shard`] of them),
//! - [`execute`] runs them on a rayon pool (results in plan order),
//! - [`report::CampaignReport`] aggregates per class (runs, passes, worst healthy
//!   TEC/REC, isolation latency, failures with their seeds), renders the table, and
//!   round-trips through JSON so shards can be merged,
//! - [`plot`] draws the TEC/REC of every controller of one run as SVG,
//! - [`sweep`] builds the sweep classes and draws their isolation latency and worst
//!   healthy TEC/REC against the disturbance interval as SVG.
//!
//! The system model itself (network, nodes, applications, faults) is
//! [`crate::recan`]; [`classes`] turns a (class, seed) pair into its run
//! specification and pass criteria.

pub mod classes;
pub mod junit;
pub mod plot;
pub mod report;
pub mod sweep;
pub mod system;

use std::fmt;

pub use classes::{Class, ClassKind};
pub use report::{CampaignReport, ClassSummary, RunOutcome};

/// Errors of campaign inputs (class filters, shard specs, report files).
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum CampaignError {
    #[error("unknown scenario class `{0}` (see `canstar campaign --list`)")]
    UnknownClass(String),
    #[error("malformed shard `{0}`: expected i/n with 1 <= i <= n (e.g. 2/4), `auto` or `auto/n`")]
    BadShard(String),
    #[error("--shard auto: {0}")]
    NoScheduler(String),
    #[error("{0}")]
    BadReport(String),
}

/// FNV-1a hash of a class name (stable across platforms and releases).
fn name_hash(name: &str) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in name.as_bytes() {
        h ^= *b as u64;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

fn mix(mut x: u64) -> u64 {
    x ^= x >> 30;
    x = x.wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x ^= x >> 27;
    x = x.wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

/// Seed of repetition `rep` of class `class` in a campaign with master seed `master`.
pub fn run_seed(master: u64, class: &str, rep: u32) -> u64 {
    mix(mix(master ^ 0x5eed_c0de) ^ name_hash(class) ^ (rep as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15))
}

/// One shard `index/count` (1-based) of a campaign: the runs whose position in the
/// plan is `index - 1` modulo `count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Shard {
    pub index: u32,
    pub count: u32,
}

impl Shard {
    /// Parse `i/n` with `1 <= i <= n`.
    pub fn parse(s: &str) -> Result<Shard, CampaignError> {
        let bad = || CampaignError::BadShard(s.to_string());
        let (a, b) = s.split_once('/').ok_or_else(bad)?;
        let index: u32 = a.trim().parse().map_err(|_| bad())?;
        let count: u32 = b.trim().parse().map_err(|_| bad())?;
        if count == 0 || index == 0 || index > count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }

    /// `i/n`, or `auto` / `auto/n`: the shard of this array task of a batch scheduler,
    /// read with `env` (the process environment in the CLI):
    /// - Slurm: index from `SLURM_ARRAY_TASK_ID` (relative to `SLURM_ARRAY_TASK_MIN`,
    ///   divided by `SLURM_ARRAY_TASK_STEP`), count from `SLURM_ARRAY_TASK_COUNT`;
    /// - LSF: index from `LSB_JOBINDEX` (arrays `[1-n]`), count from `auto/n`, else from
    ///   `LSB_JOBINDEX_END`;
    /// - `auto/n` overrides the scheduler's count.
    pub fn parse_with_env(s: &str, env: impl Fn(&str) -> Option<String>) -> Result<Shard, CampaignError> {
        let t = s.trim();
        let Some(rest) = t.strip_prefix("auto") else { return Shard::parse(t) };
        let given: Option<u32> = match rest.strip_prefix('/') {
            Some(n) => Some(n.trim().parse().map_err(|_| CampaignError::BadShard(s.to_string()))?),
            None if rest.is_empty() => None,
            None => return Err(CampaignError::BadShard(s.to_string())),
        };
        let num = |k: &str| -> Result<Option<u64>, CampaignError> {
            match env(k) {
                None => Ok(None),
                Some(v) => v.trim().parse::<u64>().map(Some).map_err(|_| CampaignError::NoScheduler(format!("{k}={v} is not a number"))),
            }
        };
        let (index, count) = if let Some(id) = num("SLURM_ARRAY_TASK_ID")? {
            let min = num("SLURM_ARRAY_TASK_MIN")?.unwrap_or(0);
            let step = num("SLURM_ARRAY_TASK_STEP")?.unwrap_or(1).max(1);
            let count = given.map(u64::from).or(num("SLURM_ARRAY_TASK_COUNT")?);
            let count = count.ok_or_else(|| CampaignError::NoScheduler("SLURM_ARRAY_TASK_COUNT not set (use auto/n)".into()))?;
            if id < min {
                return Err(CampaignError::NoScheduler(format!("SLURM_ARRAY_TASK_ID {id} below SLURM_ARRAY_TASK_MIN {min}")));
            }
            ((id - min) / step + 1, count)
        } else if let Some(idx) = num("LSB_JOBINDEX")?.filter(|&i| i > 0) {
            let count = given.map(u64::from).or(num("LSB_JOBINDEX_END")?);
            let count = count.ok_or_else(|| CampaignError::NoScheduler("LSF sets no array size: use --shard auto/n".into()))?;
            (idx, count)
        } else {
            return Err(CampaignError::NoScheduler(
                "not an array task (neither SLURM_ARRAY_TASK_ID nor LSB_JOBINDEX is set)".into(),
            ));
        };
        if count == 0 || index == 0 || index > count || count > u32::MAX as u64 {
            return Err(CampaignError::NoScheduler(format!("array task {index} of {count} is not a shard")));
        }
        Ok(Shard { index: index as u32, count: count as u32 })
    }

    /// [`Shard::parse_with_env`] with the process environment.
    pub fn parse_auto(s: &str) -> Result<Shard, CampaignError> {
        Shard::parse_with_env(s, |k| std::env::var(k).ok())
    }

    /// Whether the run at position `k` of the full plan belongs to this shard.
    pub fn contains(&self, k: usize) -> bool {
        k % self.count as usize == (self.index - 1) as usize
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// One run of a campaign.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RunPlan {
    pub class: Class,
    pub rep: u32,
    pub seed: u64,
}

/// Settings shared by every run of a campaign.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Settings {
    /// Master seed.
    pub seed: u64,
    /// Repetitions per class.
    pub reps: u32,
    /// Delay between the two faults of the `double-*` classes, in bit times.
    pub double_delay_bits: u32,
    /// Simulation engine of the hubs and controllers (compiled models by default; not
    /// recorded: both engines give the same results).
    #[serde(skip)]
    pub engine: canstar_models::Engine,
    /// Configuration of both hubs instead of the reference hub (`None`); the network
    /// keeps N = 3 ports and M = 2 interlinks.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hub: Option<canstar_hub::config::HubConfig>,
}

impl Default for Settings {
    fn default() -> Self {
        Settings { seed: 1, reps: 100, double_delay_bits: classes::DEFAULT_DOUBLE_DELAY_BITS, engine: Default::default(), hub: None }
    }
}

/// The runs of `classes` × `0..settings.reps` in class-major order, or only those of
/// `shard`.
pub fn plan(classes: &[Class], settings: &Settings, shard: Option<Shard>) -> Vec<RunPlan> {
    let mut v = vec![];
    let mut k = 0usize;
    for c in classes {
        for rep in 0..settings.reps {
            if shard.is_none_or(|s| s.contains(k)) {
                v.push(RunPlan { class: c.clone(), rep, seed: run_seed(settings.seed, &c.name, rep) });
            }
            k += 1;
        }
    }
    v
}

/// Run every plan with `runner` on `jobs` worker threads; `progress` is called in the
/// calling thread after each finished run (in completion order). The result is in plan
/// order and does not depend on `jobs`.
pub fn execute<R, P>(plans: &[RunPlan], jobs: usize, runner: R, mut progress: P) -> Vec<RunOutcome>
where
    R: Fn(&RunPlan) -> RunOutcome + Sync,
    P: FnMut(&RunOutcome),
{
    let pool = rayon::ThreadPoolBuilder::new().num_threads(jobs.max(1)).build().expect("rayon pool");
    let (tx, rx) = std::sync::mpsc::channel::<(usize, RunOutcome)>();
    let mut out: Vec<Option<RunOutcome>> = vec![None; plans.len()];
    let runner = &runner;
    pool.in_place_scope(|s| {
        for (i, p) in plans.iter().enumerate() {
            let tx = tx.clone();
            s.spawn(move |_| {
                let _ = tx.send((i, runner(p)));
            });
        }
        drop(tx);
        for (i, o) in rx.iter() {
            progress(&o);
            out[i] = Some(o);
        }
    });
    out.into_iter().map(|o| o.expect("every run reports")).collect()
}

/// `*` / `?` glob match (no character classes).
pub fn glob_match(pat: &str, s: &str) -> bool {
    let p: Vec<char> = pat.chars().collect();
    let t: Vec<char> = s.chars().collect();
    let (mut pi, mut ti) = (0usize, 0usize);
    let mut star: Option<(usize, usize)> = None;
    while ti < t.len() {
        if pi < p.len() && (p[pi] == '?' || p[pi] == t[ti]) {
            pi += 1;
            ti += 1;
        } else if pi < p.len() && p[pi] == '*' {
            star = Some((pi, ti));
            pi += 1;
        } else if let Some((sp, st)) = star {
            pi = sp + 1;
            ti = st + 1;
            star = Some((sp, st + 1));
        } else {
            return false;
        }
    }
    while pi < p.len() && p[pi] == '*' {
        pi += 1;
    }
    pi == p.len()
}

/// The classes selected by a comma-separated list of names and globs (in catalogue
/// order, each once). Every item must match at least one class.
pub fn select(filter: &str) -> Result<Vec<Class>, CampaignError> {
    let all = classes::catalogue();
    let items: Vec<&str> = filter.split(',').map(str::trim).filter(|s| !s.is_empty()).collect();
    if items.is_empty() {
        return Err(CampaignError::UnknownClass(filter.to_string()));
    }
    let mut keep = vec![false; all.len()];
    for it in &items {
        let mut any = false;
        for (i, c) in all.iter().enumerate() {
            if glob_match(it, &c.name) {
                keep[i] = true;
                any = true;
            }
        }
        if !any {
            return Err(CampaignError::UnknownClass(it.to_string()));
        }
    }
    Ok(all.into_iter().zip(keep).filter(|(_, k)| *k).map(|(c, _)| c).collect())
}

/// The class called `name` (exact).
pub fn class(name: &str) -> Result<Class, CampaignError> {
    classes::catalogue().into_iter().find(|c| c.name == name).ok_or_else(|| CampaignError::UnknownClass(name.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn globs() {
        assert!(glob_match("pub*", "pub01"));
        assert!(glob_match("*", ""));
        assert!(glob_match("p?b0*", "pub07"));
        assert!(glob_match("flip-*-up-*", "flip-blinker-tx-up-p01"));
        assert!(!glob_match("flip-*-up-*", "flip-blinker-tx-down-p01"));
        assert!(!glob_match("pub1", "pub10"));
        assert!(glob_match("*b1", "pub1"));
    }

    #[test]
    fn shards_parse() {
        assert_eq!(Shard::parse("2/4"), Ok(Shard { index: 2, count: 4 }));
        for bad in ["3/2", "0/2", "1/0", "1", "a/b", "1/2/3", "", "-1/2"] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn shards_from_scheduler_variables() {
        let env = |vars: &'static [(&'static str, &'static str)]| move |k: &str| vars.iter().find(|v| v.0 == k).map(|v| v.1.to_string());
        // Slurm --array=0-9: task 0 is shard 1/10
        let slurm = env(&[("SLURM_ARRAY_TASK_ID", "0"), ("SLURM_ARRAY_TASK_MIN", "0"), ("SLURM_ARRAY_TASK_COUNT", "10")]);
        assert_eq!(Shard::parse_with_env("auto", slurm), Ok(Shard { index: 1, count: 10 }));
        // --array=1-20:2 (10 tasks), task 7 is the 4th
        let step = env(&[("SLURM_ARRAY_TASK_ID", "7"), ("SLURM_ARRAY_TASK_MIN", "1"), ("SLURM_ARRAY_TASK_STEP", "2"), ("SLURM_ARRAY_TASK_COUNT", "10")]);
        assert_eq!(Shard::parse_with_env("auto", step), Ok(Shard { index: 4, count: 10 }));
        // LSF [1-8]: the count comes from auto/n
        let lsf = env(&[("LSB_JOBINDEX", "8")]);
        assert_eq!(Shard::parse_with_env("auto/8", lsf), Ok(Shard { index: 8, count: 8 }));
        assert!(matches!(Shard::parse_with_env("auto", lsf), Err(CampaignError::NoScheduler(_))));
        assert!(matches!(Shard::parse_with_env("auto/4", lsf), Err(CampaignError::NoScheduler(_))), "index 8 of 4");
        // LSB_JOBINDEX 0 = not an array job
        assert!(Shard::parse_with_env("auto/4", env(&[("LSB_JOBINDEX", "0")])).is_err());
        assert!(Shard::parse_with_env("auto", env(&[])).is_err());
        assert!(Shard::parse_with_env("autox", env(&[])).is_err());
        assert_eq!(Shard::parse_with_env("2/3", env(&[])), Ok(Shard { index: 2, count: 3 }));
    }

    #[test]
    fn seeds_differ_by_class_rep_and_master() {
        let a = run_seed(1, "pub01", 0);
        assert_ne!(a, run_seed(1, "pub01", 1));
        assert_ne!(a, run_seed(1, "pub02", 0));
        assert_ne!(a, run_seed(2, "pub01", 0));
        assert_eq!(a, run_seed(1, "pub01", 0));
    }
}
