//! The compiled models and the rust-hdl designs give byte-identical results: the can-protocol.md §18
//! per-bit trace, the candump log and the VCD of a bus scenario, a fuzz run's report
//! and a conformance program's step results.
use canstar_verify::node::Engine;
use canstar_verify::scenario::{run, RunOptions, Scenario};

fn load(name: &str) -> Scenario {
    let p = format!("{}/../examples/{name}", env!("CARGO_MANIFEST_DIR"));
    Scenario::from_toml(&std::fs::read_to_string(p).unwrap()).unwrap()
}

#[test]
fn bus_scenario_trace_log_and_vcd_are_identical_on_both_engines() {
    let dir = tempfile::tempdir().unwrap();
    let mut out = vec![];
    for e in Engine::ALL {
        let vcd = dir.path().join(format!("{e}.vcd"));
        let r = run(&load("arbitration.toml"), &RunOptions { trace: true, vcd: Some(vcd.clone()), engine: e, ..Default::default() }).unwrap();
        let v = std::fs::read(&vcd).unwrap();
        out.push((r.trace, r.candump, format!("{:?}", r.nodes), v));
    }
    let (a, b) = (&out[0], &out[1]);
    assert!(a.0.len() > 1000 && a.1.len() >= 5 && a.3.len() > 100_000, "the scenario ran: {} trace lines", a.0.len());
    assert_eq!(a.0, b.0, "can-protocol.md §18 trace");
    assert_eq!(a.1, b.1, "candump log");
    assert_eq!(a.2, b.2, "node summaries");
    assert!(a.3 == b.3, "VCD differs ({} vs {} bytes)", a.3.len(), b.3.len());
}

#[test]
fn disturbed_bus_trace_is_identical_on_both_engines() {
    let r: Vec<_> = Engine::ALL.iter().map(|&e| run(&load("disturbance.toml"), &RunOptions { trace: true, engine: e, ..Default::default() }).unwrap()).collect();
    assert!(r[0].trace.iter().any(|l| l.contains("_ERR")), "the disturbance causes errors");
    assert_eq!(r[0].trace, r[1].trace);
    assert_eq!(r[0].candump, r[1].candump);
}

#[test]
fn fuzz_run_and_conformance_program_are_identical_on_both_engines() {
    use canstar_verify::{conformance, fuzz};
    let reports: Vec<String> = Engine::ALL
        .iter()
        .map(|&engine| format!("{:?}", fuzz::run_seed(3, &fuzz::RunOptions { frames: 4, engine, ..Default::default() })))
        .collect();
    assert_eq!(reports[0], reports[1]);
    let steps: Vec<String> = Engine::ALL
        .iter()
        .map(|&engine| {
            let r = conformance::run_program_with("stufferr", &conformance::RunOptions { engine, ..Default::default() }).unwrap();
            assert!(!r.results.is_empty() && r.results.iter().all(|s| s.pass), "{:?}", r.results);
            format!("{:?}", r.results)
        })
        .collect();
    assert_eq!(steps[0], steps[1]);
}
