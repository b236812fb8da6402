//! The compiled models and the rust-hdl designs give identical ReCANcentrate runs:
//! the run result, the driver trace and the VCD of every signal of both hubs and all
//! six controllers, without and with a fault that the hubs isolate.
use canstar_models::Engine;
use canstar_recan::{run, CtrlRef, Dir, FaultKind, FaultSpec, FaultTarget, NetworkSpec, RunResult, RunSpec};

fn both(spec: &RunSpec, vcd: bool) -> Vec<(RunResult, Vec<u8>)> {
    let dir = tempfile::tempdir().unwrap();
    Engine::ALL
        .iter()
        .map(|&e| {
            let mut s = spec.clone();
            s.engine = e;
            let p = dir.path().join(format!("{e}.vcd"));
            if vcd {
                s.vcd = Some(p.clone());
            }
            let r = run(&s);
            (r, if vcd { std::fs::read(&p).unwrap() } else { vec![] })
        })
        .collect()
}

#[test]
fn network_file_run_and_vcd_are_identical_on_both_engines() {
    let text = std::fs::read_to_string(format!("{}/../examples/recancentrate.toml", env!("CARGO_MANIFEST_DIR"))).unwrap();
    let net = NetworkSpec::from_toml(&text).unwrap();
    let mut spec = RunSpec::new(net, 1, 0);
    spec.max_time_ps = Some(300_000_000); // 0.3 ms
    spec.trace = true;
    let r = both(&spec, true);
    assert!(r[0].0.delivered >= 2 && r[0].1.len() > 1_000_000, "the run did something: {} frames", r[0].0.delivered);
    assert_eq!(r[0].0, r[1].0);
    assert!(r[0].1 == r[1].1, "VCD differs ({} vs {} bytes)", r[0].1.len(), r[1].1.len());
}

#[test]
fn faulty_uplink_run_is_identical_on_both_engines() {
    let mut spec = RunSpec::new(NetworkSpec::fast(), 5, 4);
    spec.faults = vec![FaultSpec::new(FaultTarget::Link { node: 0, ctrl: CtrlRef::Tx, dir: Dir::Up }, FaultKind::Sad, canstar_recan::FaultStart::At { t_ps: 150_000_000 })];
    spec.max_time_ps = Some(1_000_000_000);
    spec.trace = true;
    let r = both(&spec, false);
    assert!(!r[0].0.isolated.is_empty(), "the stuck uplink is isolated: {:?}", r[0].0);
    assert_eq!(r[0].0, r[1].0);
}
