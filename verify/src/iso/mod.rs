//! The ISO 16845-1 lower tester (GitHub issue #17) and the ISO conformance
//! cases built on it.
//!
//! # The lower tester
//!
//! ISO 16845-1 tests an implementation (IUT) through a *lower tester* (LT):
//! a bus participant that is not a conforming CAN node. Here the LT is a
//! kernel component on a slot of the Bosch bench's wired-AND bus
//! ([`crate::conformance::Bench`], reused unchanged apart from the slot):
//!
//! - [`plan`]: what the LT does in a step: a bit sequence at time-quantum
//!   resolution (from a frame through the controller's frame builder, with
//!   FIELD/POSITION labels, or raw levels), bits lengthened or shortened by
//!   k TQ, glitches and disturbances of the bus as every node sees it or of
//!   one node's receive path, and the IUT responses it expects;
//! - [`tester`]: the component that drives the plan's levels and records
//!   the bus clock by clock;
//! - [`trigger`]: "bit P of the n-th occurrence of field F since the step
//!   start, q TQ into the bit", including Bus_Off, the bus-off recovery and
//!   Reset, derived from the IUT's debug bundle without RTL changes;
//! - [`bench`]: [`LtBench`], steps (record, occurrence counting, VCD),
//!   counter presets through the counter-load port, the step reset,
//!   waiting for triggers and playing plans;
//! - [`record`]: [`StepRecord`], what a step recorded, for assertions.
//!
//! # Cases
//!
//! [`cases`] holds the ISO 16845-1 cases implemented so far, one file per
//! case, named by clause (`iso_7_1_1`); [`run_iso`] runs those matching a
//! filter and returns one [`crate::conformance::StepResult`] per elementary
//! test (`iso_7_1_1_id2aa_dlc3`); `canstar conformance --suite iso [--case C]`
//! prints them ([`run_iso_cli`]).
//!
//! # Limits
//!
//! - The LT and every node run on the IUT's clock: no oscillator tolerance
//!   and no other bit rate (no classical case of 7.7/8.7 needs them; 7.8
//!   and 8.8, data-phase bit timing, are CAN FD only).
//! - A trigger places the bit start from the previous bit's sample point and
//!   the nominal PH2; a resynchronisation in that PH2 is not accounted for.
//! - Disturbances of two plans that overlap in time are not composed with
//!   each other (those of one plan are).
//! - Counter presets are invisible to the golden model: do not run an LT
//!   bench in lock-step mode (`crate::conformance::set_lockstep`).

pub mod bench;
pub mod cases;
pub mod plan;
pub mod record;
pub mod tester;
pub mod trigger;

pub use bench::LtBench;
pub use plan::{Action, At, Disturbance, Expect, Label, Plan, PlanBit, Span, Target};
pub use record::{Played, StepRecord};
pub use tester::{ClockSample, LowerTester};
pub use trigger::{Trigger, Where};

use crate::conformance::StepResult;

/// One ISO case.
pub struct IsoCase {
    /// Clause, e.g. `7.1.1`.
    pub clause: &'static str,
    /// `iso_7_1_1_<what>`.
    pub name: &'static str,
    /// Runs the case; one result per elementary test.
    pub run: fn() -> Vec<StepResult>,
}

impl IsoCase {
    /// Does filter `f` select this case: its clause, a clause above it
    /// (`7.2` selects 7.2.x, not 7.20), or its name?
    pub fn matches(&self, f: &str) -> bool {
        self.name == f || self.clause == f || self.clause.starts_with(&format!("{f}."))
    }
}

/// The implemented cases in clause order.
pub fn cases() -> Vec<IsoCase> {
    cases::all()
}

/// Run the cases whose clause or name matches `filter` (all with `None`):
/// a clause matches itself and its sub-clauses (`7.2` runs 7.2.x), a name
/// matches exactly. A panicking case gives one failed result `<name>_panic`.
pub fn run_iso(filter: Option<&str>) -> Vec<(String, Vec<StepResult>)> {
    run_iso_vcd(filter, None)
}

/// As [`run_iso`], each case writing VCD files into `vcd_dir`
/// ([`bench::with_case_vcd`]: `<case>.vcd`, the whole bench from start-up).
pub fn run_iso_vcd(filter: Option<&str>, vcd_dir: Option<&std::path::Path>) -> Vec<(String, Vec<StepResult>)> {
    let mut out = vec![];
    for c in cases() {
        if !filter.is_none_or(|f| c.matches(f)) {
            continue;
        }
        let r = std::panic::catch_unwind(|| bench::with_case_vcd(vcd_dir, c.name, c.run)).unwrap_or_else(|e| {
            let m = e.downcast_ref::<String>().cloned().or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string())).unwrap_or_default();
            vec![StepResult { name: format!("{}_panic", c.name), pass: false, msg: m }]
        });
        out.push((c.name.to_string(), r));
    }
    out
}

/// `canstar conformance --suite iso [--case C]`: runs the matching cases,
/// prints one line per case, the failed elementary tests with their message
/// (a known failure, [`cases::KNOWN_FAILURES`], with its reason and the
/// first line of its message) and a final `N passed, M failed` line (with
/// the number of known failures among them); returns (passed, failed). A filter
/// that matches no case prints the list of cases and counts one failure.
pub fn run_iso_cli(filter: Option<&str>, out: &mut dyn std::io::Write) -> std::io::Result<(usize, usize)> {
    run_iso_cli_vcd(filter, None, out)
}

/// As [`run_iso_cli`], writing one VCD per case bench into `vcd_dir`; a VCD
/// file that cannot be written is an error naming it.
pub fn run_iso_cli_vcd(filter: Option<&str>, vcd_dir: Option<&std::path::Path>, out: &mut dyn std::io::Write) -> std::io::Result<(usize, usize)> {
    drop(crate::conformance::take_run_log());
    let runs = run_iso_vcd(filter, vcd_dir);
    let vcd_errors = crate::conformance::take_run_log().vcd_errors;
    if !vcd_errors.is_empty() {
        return Err(std::io::Error::other(format!("cannot write VCD: {}", vcd_errors.join("; "))));
    }
    if runs.is_empty() {
        let names: Vec<String> = cases().iter().map(|c| format!("{} ({})", c.clause, c.name)).collect();
        writeln!(out, "no ISO case matches {}; cases: {}", filter.unwrap_or(""), names.join(", "))?;
        writeln!(out, "0 passed, 1 failed")?;
        return Ok((0, 1));
    }
    let (mut tp, mut tf, mut tk) = (0, 0, 0);
    for (name, res) in &runs {
        let pass = res.iter().filter(|r| r.pass).count();
        let fail = res.len() - pass;
        tp += pass;
        tf += fail;
        writeln!(out, "{name:<32} {:>4} tests, {pass:>4} passed, {fail:>3} failed", res.len())?;
        for r in res.iter().filter(|r| !r.pass) {
            match cases::known_failure(&r.name) {
                Some(why) => {
                    tk += 1;
                    let first = r.msg.lines().next().unwrap_or("");
                    writeln!(out, "  FAIL (known: {why}) {}: {first}", r.name)?;
                }
                None => writeln!(out, "  FAIL {}: {}", r.name, r.msg)?,
            }
        }
    }
    if tk > 0 {
        writeln!(out, "{tp} passed, {tf} failed ({tk} of them known failures)")?;
    } else {
        writeln!(out, "{tp} passed, {tf} failed")?;
    }
    Ok((tp, tf))
}
