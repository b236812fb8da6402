//! Campaign results: one [`RunOutcome`] per run, aggregated per class into
//! [`ClassSummary`]s, rendered as a table, written and read as JSON, merged from shards.

use super::{classes, CampaignError, Settings, Shard};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// The result of one run, reduced to what a campaign reports.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
pub struct RunOutcome {
    pub class: String,
    pub rep: u32,
    pub seed: u64,
    /// Every pass criterion held.
    pub pass: bool,
    /// Violated pass criteria (empty when `pass`).
    pub failures: Vec<String>,
    /// Frames of other nodes the Receiver missed (sender and counter value).
    pub lost: Vec<String>,
    /// Highest TEC or REC reached by a controller whose own links are fault-free.
    pub worst_healthy: u32,
    /// Highest TEC and REC of those controllers separately.
    pub worst_healthy_tec: u32,
    pub worst_healthy_rec: u32,
    /// Bit times from the fault to the first isolation by a hub, if any.
    pub isolation_latency_bits: Option<u32>,
    /// Isolations as `hub:what@bit` (bit time since the start of the run).
    pub isolations: Vec<String>,
    /// Quarantined controllers as `node/ctrl@bit`.
    pub quarantined: Vec<String>,
    /// Most retransmissions of one frame by the node model.
    pub max_retransmissions: u32,
    /// Duplicate frames seen by the Receiver (allowed).
    pub duplicates: u32,
    /// Frames delivered to the Receiver.
    pub delivered: u32,
    /// Simulated clock cycles (all components).
    pub sim_cycles: u64,
    /// The faults as resolved at their start, with their start in bit times.
    pub faults: Vec<String>,
    /// Remarks that are not failures (losses of excused nodes, known deviations).
    pub notes: Vec<String>,
    /// Shortest pulse (hub clocks) seen on a healthy port's input / on any sublink input
    /// of either hub (None: none shorter than 32).
    #[serde(default)]
    pub min_pulse_healthy_port: Option<u32>,
    #[serde(default)]
    pub min_pulse_sublink: Option<u32>,
}

/// Per-class aggregate.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ClassSummary {
    pub class: String,
    pub runs: u32,
    pub passes: u32,
    pub worst_healthy: u32,
    pub worst_healthy_tec: u32,
    pub worst_healthy_rec: u32,
    /// Isolation latency in bits over the runs with an isolation: (min, median, max).
    pub isolation_bits: Option<(u32, u32, u32)>,
    pub runs_isolated: u32,
    pub runs_quarantined: u32,
    pub runs_with_duplicates: u32,
    pub lost_frames: u32,
    pub max_retransmissions: u32,
    /// (rep, seed, messages) of every failing run.
    pub failing: Vec<(u32, u64, Vec<String>)>,
}

/// A campaign's settings and per-run outcomes (all of them, or one shard's).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CampaignReport {
    /// Format version of the JSON file.
    pub format: u32,
    pub settings: Settings,
    /// Class names of the whole campaign (before sharding), catalogue order.
    pub classes: Vec<String>,
    /// Shards this report holds (empty = all runs).
    pub shards: Vec<Shard>,
    /// Outcomes in plan order (class-major, then repetition).
    pub runs: Vec<RunOutcome>,
}

pub const FORMAT: u32 = 1;

fn median(v: &mut [u32]) -> u32 {
    v.sort_unstable();
    v[(v.len() - 1) / 2]
}

impl CampaignReport {
    pub fn new(settings: Settings, classes: &[super::Class], shard: Option<Shard>, mut runs: Vec<RunOutcome>) -> Self {
        let names: Vec<String> = classes.iter().map(|c| c.name.clone()).collect();
        sort_runs(&names, &mut runs);
        CampaignReport { format: FORMAT, settings, classes: names, shards: shard.into_iter().collect(), runs }
    }

    /// All runs passed.
    pub fn ok(&self) -> bool {
        self.runs.iter().all(|r| r.pass)
    }

    /// Per-class summaries, catalogue order (classes without runs are left out).
    pub fn summaries(&self) -> Vec<ClassSummary> {
        let mut out = vec![];
        for c in &self.classes {
            let rs: Vec<&RunOutcome> = self.runs.iter().filter(|r| &r.class == c).collect();
            if rs.is_empty() {
                continue;
            }
            let mut lat: Vec<u32> = rs.iter().filter_map(|r| r.isolation_latency_bits).collect();
            let isolation_bits = if lat.is_empty() {
                None
            } else {
                let lo = *lat.iter().min().unwrap();
                let hi = *lat.iter().max().unwrap();
                Some((lo, median(&mut lat), hi))
            };
            out.push(ClassSummary {
                class: c.clone(),
                runs: rs.len() as u32,
                passes: rs.iter().filter(|r| r.pass).count() as u32,
                worst_healthy: rs.iter().map(|r| r.worst_healthy).max().unwrap_or(0),
                worst_healthy_tec: rs.iter().map(|r| r.worst_healthy_tec).max().unwrap_or(0),
                worst_healthy_rec: rs.iter().map(|r| r.worst_healthy_rec).max().unwrap_or(0),
                runs_isolated: rs.iter().filter(|r| !r.isolations.is_empty()).count() as u32,
                isolation_bits,
                runs_quarantined: rs.iter().filter(|r| !r.quarantined.is_empty()).count() as u32,
                runs_with_duplicates: rs.iter().filter(|r| r.duplicates > 0).count() as u32,
                lost_frames: rs.iter().map(|r| r.lost.len() as u32).sum(),
                max_retransmissions: rs.iter().map(|r| r.max_retransmissions).max().unwrap_or(0),
                failing: rs.iter().filter(|r| !r.pass).map(|r| (r.rep, r.seed, r.failures.clone())).collect(),
            });
        }
        out
    }

    /// The per-class table, then one line per failing run with the command that reruns it.
    pub fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{:<28} {:>5} {:>5} {:>4} {:>8} {:>4} {:>14} {:>5} {:>5} {:>5} {:>5}  verdict",
            "class", "runs", "pass", "max", "TEC/REC", "iso", "iso bits", "quar", "retx", "dup", "lost"
        );
        let sums = self.summaries();
        let (mut runs, mut passes) = (0, 0);
        for c in &sums {
            runs += c.runs;
            passes += c.passes;
            let iso = match c.isolation_bits {
                Some((a, b, d)) => format!("{a}/{b}/{d}"),
                None => "-".into(),
            };
            let _ = writeln!(
                s,
                "{:<28} {:>5} {:>5} {:>4} {:>8} {:>4} {:>14} {:>5} {:>5} {:>5} {:>5}  {}",
                c.class,
                c.runs,
                c.passes,
                c.worst_healthy,
                format!("{}/{}", c.worst_healthy_tec, c.worst_healthy_rec),
                c.runs_isolated,
                iso,
                c.runs_quarantined,
                c.max_retransmissions,
                c.runs_with_duplicates,
                c.lost_frames,
                if c.passes == c.runs { "PASS" } else { "FAIL" }
            );
        }
        let _ = writeln!(s, "total: {passes} of {runs} runs passed in {} classes", sums.len());
        let _ = writeln!(
            s,
            "(max: highest TEC or REC of a healthy controller; TEC/REC: highest of each, sampled at every delivery and \
             quarantine; iso: runs with a hub isolation; iso bits: min/median/max bit times from the fault to the first \
             isolation; quar: runs with a quarantine; retx: most retransmissions of one frame; dup: runs with \
             duplicates at a node; lost: frames missed by the Receiver)"
        );
        let eof: Vec<&ClassSummary> = sums.iter().filter(|c| c.class.starts_with("eof-")).collect();
        if !eof.is_empty() {
            let _ = writeln!(s, "inconsistency scenarios (disturbance at the last/penultimate EOF bit seen by a subset of controllers):");
            for c in eof {
                let runs: Vec<&RunOutcome> = self.runs.iter().filter(|r| r.class == c.class).collect();
                let omitted = runs.iter().filter(|r| !r.lost.is_empty() || r.notes.iter().any(|n| n.contains(" missed "))).count();
                let _ = writeln!(
                    s,
                    "  {:<26} duplication in {}/{} runs, omission in {}/{} runs: {}",
                    c.class,
                    c.runs_with_duplicates,
                    c.runs,
                    omitted,
                    c.runs,
                    if omitted == 0 && c.passes == c.runs { "tolerated" } else { "NOT tolerated" }
                );
            }
        }
        let mut first = true;
        for c in &sums {
            for (rep, seed, msgs) in &c.failing {
                if first {
                    let _ = writeln!(s, "failing runs (rerun one with `canstar campaign --class CLASS --run-seed SEED`):");
                    first = false;
                }
                let _ = writeln!(s, "  {} rep {} seed {}: {}", c.class, rep, seed, msgs.join("; "));
            }
        }
        s
    }

    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("report serialises")
    }

    /// Parse a report written by [`Self::to_json`]; `what` names the source in errors.
    pub fn from_json(text: &str, what: &str) -> Result<Self, CampaignError> {
        let r: CampaignReport =
            serde_json::from_str(text).map_err(|e| CampaignError::BadReport(format!("{what}: not a campaign report: {e}")))?;
        if r.format != FORMAT {
            return Err(CampaignError::BadReport(format!("{what}: report format {} (expected {FORMAT})", r.format)));
        }
        if let Some(c) = unknown_class(&r.classes) {
            return Err(CampaignError::BadReport(format!("{what}: unknown class `{c}`")));
        }
        for run in &r.runs {
            if !r.classes.contains(&run.class) {
                return Err(CampaignError::BadReport(format!("{what}: run of class `{}` not in its class list", run.class)));
            }
            if run.rep >= r.settings.reps {
                return Err(CampaignError::BadReport(format!("{what}: {} rep {} beyond reps {}", run.class, run.rep, r.settings.reps)));
            }
        }
        Ok(r)
    }

    /// Combine reports of one campaign configuration (equal settings): shards of one
    /// campaign, campaigns over different classes, or both. A run's seed depends only on
    /// the settings' seed, its class and its repetition, so the result is the report of
    /// one campaign over the union of the class lists (catalogue order). No run may
    /// appear twice.
    pub fn merge(parts: &[CampaignReport]) -> Result<CampaignReport, CampaignError> {
        let first = parts.first().ok_or_else(|| CampaignError::BadReport("nothing to merge".into()))?;
        let mut runs = vec![];
        let mut shards = vec![];
        for (i, p) in parts.iter().enumerate() {
            if p.settings != first.settings {
                return Err(CampaignError::BadReport(format!(
                    "report {} is from a different campaign (its settings differ from report 1's)",
                    i + 1
                )));
            }
            if let Some(c) = unknown_class(&p.classes) {
                return Err(CampaignError::BadReport(format!("report {}: unknown class `{c}`", i + 1)));
            }
            shards.extend(p.shards.iter().copied());
            runs.extend(p.runs.iter().cloned());
        }
        let classes: Vec<String> =
            classes::catalogue().into_iter().map(|k| k.name).filter(|k| parts.iter().any(|p| p.classes.contains(k))).collect();
        sort_runs(&classes, &mut runs);
        for w in runs.windows(2) {
            if w[0].class == w[1].class && w[0].rep == w[1].rep {
                return Err(CampaignError::BadReport(format!("run {} rep {} appears twice (overlapping reports)", w[0].class, w[0].rep)));
            }
        }
        shards.sort_by_key(|s| (s.count, s.index));
        shards.dedup();
        let complete = runs.len() == classes.len() * first.settings.reps as usize;
        Ok(CampaignReport {
            format: FORMAT,
            settings: first.settings.clone(),
            classes,
            shards: if complete { vec![] } else { shards },
            runs,
        })
    }

    /// Number of runs a complete report of this campaign has.
    pub fn expected_runs(&self) -> usize {
        self.classes.len() * self.settings.reps as usize
    }
}

/// The first of `names` that is not a class of the catalogue.
fn unknown_class(names: &[String]) -> Option<&String> {
    let known = classes::catalogue();
    names.iter().find(|c| !known.iter().any(|k| &k.name == *c))
}

fn sort_runs(classes: &[String], runs: &mut [RunOutcome]) {
    runs.sort_by_key(|r| (classes.iter().position(|c| c == &r.class).unwrap_or(usize::MAX), r.rep));
}
