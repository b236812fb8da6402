//! The ISO 16845-1 cases implemented on the lower tester (`canstar_verify::iso::cases`),
//! run through `run_iso` as `canstar conformance --suite iso` will.

use canstar_verify::conformance::StepResult;
use canstar_verify::iso::run_iso;

fn failures(r: &[StepResult]) -> Vec<String> {
    r.iter().filter(|s| !s.pass).map(|s| format!("{}: {}", s.name, s.msg)).collect()
}

#[test]
fn iso_7_1_1_identifier_and_dlc() {
    let runs = run_iso(Some("7.1.1"));
    assert_eq!(runs.len(), 1);
    let (name, r) = &runs[0];
    assert_eq!(name, "iso_7_1_1_identifier_and_dlc");
    assert_eq!(r.len(), 8 * 9, "8 identifiers x DLC 0..8");
    assert!(r.iter().any(|s| s.name == "iso_7_1_1_id7ff_dlc8"));
    let f = failures(r);
    assert!(f.is_empty(), "{} failed:\n{}", f.len(), f.join("\n"));
}

#[test]
fn iso_7_2_2_stuff_error() {
    let runs = run_iso(Some("iso_7_2_2_stuff_error"));
    assert_eq!(runs.len(), 1);
    let r = &runs[0].1;
    assert!(r.len() >= 30, "{} elementary tests", r.len());
    for field in ["_id_", "_dlc_", "_data_", "_crc_"] {
        assert!(r.iter().any(|s| s.name.contains(field)), "no elementary test in {field}");
    }
    let f = failures(r);
    assert!(f.is_empty(), "{} of {} failed:\n{}", f.len(), r.len(), f.join("\n"));
}

#[test]
fn iso_8_1_1_identifier_and_dlc() {
    let runs = run_iso(Some("8.1.1"));
    assert_eq!(runs.len(), 1);
    let r = &runs[0].1;
    assert_eq!(r.len(), 8 * 9, "8 identifiers x DLC 0..8");
    let f = failures(r);
    assert!(f.is_empty(), "{} failed:\n{}", f.len(), f.join("\n"));
}

#[test]
fn filters_select_by_clause_prefix_and_name() {
    assert!(run_iso(Some("9.9")).is_empty());
    let all: Vec<String> = run_iso(None).into_iter().map(|(n, _)| n).collect();
    assert_eq!(all, ["iso_7_1_1_identifier_and_dlc", "iso_7_2_2_stuff_error", "iso_8_1_1_identifier_and_dlc"]);
    assert_eq!(run_iso(Some("8")).len(), 1);
    assert!(run_iso(Some("7.1")).iter().all(|(n, _)| n.starts_with("iso_7_1_")));
    // "7.1" must not select 7.10 .. 7.19 by accident
    assert!(!run_iso(Some("7.1")).iter().any(|(n, _)| n.starts_with("iso_7_2")));
}
