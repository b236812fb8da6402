//! Shared by the ISO case tests (`iso_cases.rs`, `iso_cases_tx.rs`).

use canstar_verify::conformance::StepResult;
use canstar_verify::iso::run_iso;

/// The failed elementary tests of `r` with their messages.
pub fn failures(r: &[StepResult]) -> Vec<String> {
    r.iter().filter(|s| !s.pass).map(|s| format!("{}: {}", s.name, s.msg)).collect()
}

/// Run one case by clause; it must be the case `name` with `n` elementary
/// tests, all passing.
pub fn case(clause: &str, name: &str, n: usize) -> Vec<StepResult> {
    let runs = run_iso(Some(clause));
    assert_eq!(runs.len(), 1, "clause {clause}");
    let (got, r) = &runs[0];
    assert_eq!(got, name);
    assert_eq!(r.len(), n, "{name}: elementary tests {:?}", r.iter().map(|s| &s.name).collect::<Vec<_>>());
    let f = failures(r);
    assert!(f.is_empty(), "{} of {} failed:\n{}", f.len(), r.len(), f.join("\n"));
    r.clone()
}
