//! The shipped example scenarios run on the RTL controller and give the
//! outcome their comments describe.
use canstar_verify::scenario::{run, RunOptions, Scenario};

fn load(name: &str) -> Scenario {
    let p = format!("{}/../examples/{name}", env!("CARGO_MANIFEST_DIR"));
    Scenario::from_toml(&std::fs::read_to_string(p).unwrap()).unwrap()
}

#[test]
fn arbitration_example_delivers_in_priority_order_without_errors() {
    let r = run(&load("arbitration.toml"), &RunOptions { trace: true, ..Default::default() }).unwrap();
    // Node 1 (ecu_b) sees every frame except its own in this order.
    let can1: Vec<&str> = r.candump.iter().filter(|l| l.contains(" can1 ")).map(|l| l.split(' ').nth(2).unwrap()).collect();
    assert_eq!(can1, vec!["100#0102030405060708", "04000000#55", "101#DEAD", "2A0#R4", "2A0#CAFEBABE"]);
    for n in &r.nodes {
        assert_eq!((n.errors, n.tec, n.rec, n.pending), (0, 0, 0, false), "{n:?}");
        assert_eq!(n.sent + n.received, 5, "{n:?}");
    }
    // The trace has every node and the arbitration loss of ecu_a and ecu_c.
    assert!(r.trace[0].starts_with("# t_ns"));
    assert!(r.trace.iter().filter(|l| l.contains("ARB_LOST")).count() >= 2);
    for d in ["D1", "D2", "D3"] {
        assert!(r.trace.iter().any(|l| l.split_whitespace().nth(1) == Some(d)));
    }
}

#[test]
fn disturbance_example_shows_errors_and_retransmission() {
    let r = run(&load("disturbance.toml"), &RunOptions { trace: true, ..Default::default() }).unwrap();
    let (sender, receiver) = (&r.nodes[0], &r.nodes[1]);
    assert_eq!(sender.sent, 2);
    assert_eq!(receiver.received, 2, "both frames arrive once despite the disturbance");
    assert!(receiver.errors >= 2 && sender.errors >= 1);
    assert!(receiver.rec > 0);
    // The first error at the receiver is detected in the data field or CRC (the
    // inverted data bit), while it receives.
    let first_err = r.trace.iter().find(|l| l.contains(" D2 ") && l.contains("_ERR")).unwrap();
    assert!(first_err.contains("Rx_Data_Field") || first_err.contains("Rx_CRC") || first_err.contains("Rx_ACK"), "{first_err}");
}

#[test]
fn bad_scenarios_are_rejected_before_running() {
    let mut s = load("arbitration.toml");
    s.frames[0].node = "nobody".into();
    assert!(run(&s, &RunOptions::default()).unwrap_err().contains("unknown node `nobody`"));
}

#[test]
#[ignore = "needs python3 with python-can: run scripts/test-all.sh"]
fn python_can_reads_the_candump_log() {
    let r = run(&load("arbitration.toml"), &RunOptions::default()).unwrap();
    let d = tempfile::tempdir().unwrap();
    let log = d.path().join("arb.log");
    std::fs::write(&log, r.candump.join("\n") + "\n").unwrap();
    let script = "import can, sys\nfor m in can.LogReader(sys.argv[1]):\n    print(m.channel, '%X' % m.arbitration_id, int(m.is_extended_id), int(m.is_remote_frame), m.dlc, m.data.hex().upper())\n";
    let out = std::process::Command::new("python3").arg("-c").arg(script).arg(&log).output().expect("python3");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let lines: Vec<String> = String::from_utf8_lossy(&out.stdout).lines().map(|s| s.to_string()).collect();
    assert_eq!(lines.len(), r.candump.len());
    assert!(lines.contains(&"can1 100 0 0 8 0102030405060708".to_string()), "{lines:?}");
    assert!(lines.contains(&"can1 4000000 1 0 1 55".to_string()), "{lines:?}");
    assert!(lines.contains(&"can1 2A0 0 1 4 ".to_string()), "{lines:?}");
}
