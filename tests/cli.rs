//! End-to-end tests of the `canstar` command line.
use std::path::Path;
use std::process::Command;

fn canstar(args: &[&str], cwd: &Path) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_canstar")).args(args).current_dir(cwd).output().unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn files_under(p: &Path) -> Vec<String> {
    let mut v = vec![];
    if p.exists() {
        for e in walk(p) {
            v.push(e);
        }
    }
    v.sort();
    v
}

fn walk(p: &Path) -> Vec<String> {
    let mut v = vec![];
    for e in std::fs::read_dir(p).unwrap() {
        let e = e.unwrap().path();
        if e.is_dir() {
            v.extend(walk(&e));
        } else {
            v.push(e.display().to_string());
        }
    }
    v
}

#[test]
fn generate_then_check_round_trip() {
    let d = tempfile::tempdir().unwrap();
    let (ok, out, err) = canstar(&["generate", "--out", "v", "--constraints", "c"], d.path());
    assert!(ok, "{out}{err}");
    assert!(!files_under(&d.path().join("v")).is_empty());
    let (ok, out, err) = canstar(&["generate", "--out", "v", "--constraints", "c", "--check"], d.path());
    assert!(ok && out.contains("up to date"), "{out}{err}");
    // Tamper with one file: --check must fail and name it.
    let f = files_under(&d.path().join("v")).remove(0);
    std::fs::write(&f, "tampered").unwrap();
    let (ok, _, err) = canstar(&["generate", "--out", "v", "--constraints", "c", "--check"], d.path());
    assert!(!ok && err.contains("out of date"), "{err}");
}

#[test]
fn bad_config_fails_cleanly_and_writes_nothing() {
    let d = tempfile::tempdir().unwrap();
    for (name, text, expect) in [
        ("unknown_key.toml", "[bit_timing]\nbrp = 1\nwibble = 3\n", "unknown field"),
        ("bad_timing.toml", "[bit_timing]\nprop = 1\nph1 = 2\nsjw = 1\n", "must be 8..=25"),
        ("bad_sjw.toml", "[bit_timing]\nph1 = 2\nsjw = 4\n", "exceeds ph1"),
        ("malformed.toml", "[bit_timing\n", "malformed"),
        ("bad_depth.toml", "[rtl]\nsync_depth = 3\n", "sync_depth"),
        ("bad_eof7.toml", "[controller]\nrec_rule = \"bosch\"\n", "rec_rule"),
    ] {
        std::fs::write(d.path().join(name), text).unwrap();
        let (ok, out, err) = canstar(&["generate", "--config", name, "--out", "v", "--constraints", "c"], d.path());
        assert!(!ok, "{name} accepted: {out}");
        assert!(err.contains(expect), "{name}: {err}");
        assert!(files_under(&d.path().join("v")).is_empty() && files_under(&d.path().join("c")).is_empty(), "{name} wrote files");
    }
}

#[test]
fn committed_generated_files_are_current() {
    // The same check CI runs: verilog-out/ and constraints/ equal the generator's output.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let (ok, out, err) = canstar(&["generate", "--check"], root);
    assert!(ok, "{out}{err}");
}

#[test]
fn bench_vcd_dumps_all_or_a_selection_deterministically() {
    let d = tempfile::tempdir().unwrap();
    let args = ["bench", "--nodes", "2", "--cycles", "4000", "--vcd"];
    let (ok, out, err) = canstar(&[&args[..], &["all.vcd"]].concat(), d.path());
    assert!(ok, "{out}{err}");
    let (ok, _, _) = canstar(&[&args[..], &["all2.vcd"]].concat(), d.path());
    assert!(ok);
    let all = std::fs::read_to_string(d.path().join("all.vcd")).unwrap();
    assert_eq!(all, std::fs::read_to_string(d.path().join("all2.vcd")).unwrap(), "same seed, same VCD");
    // Every instance has its scope with its signals, and the bus wires are there.
    for s in ["$scope module btl0", "$scope module btl1", " sample ", " busmon ", " level "] {
        assert!(all.contains(s), "missing `{s}`");
    }
    let (ok, out, err) = canstar(&[&args[..], &["sel.vcd", "--signals", "btl0.sample,bus.level"]].concat(), d.path());
    assert!(ok, "{out}{err}");
    let sel = std::fs::read_to_string(d.path().join("sel.vcd")).unwrap();
    assert!(sel.contains(" sample ") && sel.contains(" level "));
    assert!(!sel.contains(" busmon ") && sel.len() < all.len() / 2);
}

#[test]
fn sim_runs_an_example_and_rejects_a_malformed_scenario() {
    let d = tempfile::tempdir().unwrap();
    let ex = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/arbitration.toml");
    let (ok, out, err) = canstar(&["sim", ex.to_str().unwrap(), "--log", "a.log", "--trace", "a.trace", "--vcd", "a.vcd"], d.path());
    assert!(ok, "{out}{err}");
    let log = std::fs::read_to_string(d.path().join("a.log")).unwrap();
    assert!(log.lines().all(|l| l.starts_with('(') && l.contains(") can") && l.contains('#')), "{log}");
    assert!(std::fs::read_to_string(d.path().join("a.vcd")).unwrap().contains("$scope module ecu_a"));
    std::fs::write(d.path().join("bad.toml"), "duration_us = 10\n[[node]]\nname = \"a\"\n[[frame]]\nnode = \"a\"\nat_us = 1\nid = 0x800\n").unwrap();
    let (ok, _, err) = canstar(&["sim", "bad.toml", "--log", "b.log"], d.path());
    assert!(!ok && err.contains("does not fit a 11-bit frame"), "{err}");
    assert!(!d.path().join("b.log").exists());
}

#[test]
fn hub_generation_pins_and_bad_hub_configs() {
    let d = tempfile::tempdir().unwrap();
    let (ok, out, err) = canstar(&["generate", "hub", "--board", "xsa-3s1000", "--out", "v", "--constraints", "c"], d.path());
    assert!(ok, "{out}{err}");
    let ucf = std::fs::read_to_string(d.path().join("c/xsa-3s1000/canstar_hub.ucf")).unwrap();
    assert!(canstar::boards::pinfile::ucf_well_formed(&ucf));
    assert!(ucf.contains("NET rx<2> LOC=G12;") && ucf.contains("NET hub_tx<1> LOC=G13;"), "{ucf}");
    assert!(ucf.contains("without a free pin"), "the board has fewer debug pins than the hub has debug bits");
    let v = std::fs::read_to_string(d.path().join("v/hub/canstar_hub.v")).unwrap();
    assert!(v.contains("module canstar_hub(") && v.contains("input wire [2:0] rx;") && v.contains("output wire [1:0] hub_tx;"));
    let cc = std::fs::read_to_string(d.path().join("v/hub/canstar_cancentrate.v")).unwrap();
    assert!(!cc.contains("hub_tx"), "a CANcentrate hub has no interlinks");
    for (name, text, expect) in [
        ("zero_ports.toml", "[hub]\nports = 0\n", "ports must be >= 1"),
        ("hub_key.toml", "[hub]\nportz = 3\n", "unknown field"),
        ("hub_timing.toml", "[hub.timing]\nsjw = 3\nph1 = 1\n", "bit timing"),
    ] {
        std::fs::write(d.path().join(name), text).unwrap();
        let (ok, _, err) = canstar(&["generate", "--config", name, "--out", "v2", "--constraints", "c2"], d.path());
        assert!(!ok && err.contains(expect), "{name}: {err}");
        assert!(!d.path().join("v2").exists() && !d.path().join("c2").exists(), "{name} wrote files");
    }
    let (ok, _, err) = canstar(&["generate", "hub", "--board", "no-such-board", "--out", "v3"], d.path());
    assert!(!ok && err.contains("unknown board `no-such-board`"), "{err}");
    assert!(!d.path().join("v3").exists());
    // More ports than the board has pins for: a clear error, nothing written.
    std::fs::write(d.path().join("big.toml"), "[hub]\nports = 4\n").unwrap();
    let (ok, _, err) = canstar(&["generate", "hub", "--config", "big.toml", "--board", "xsa-3s1000", "--out", "v4", "--constraints", "c4"], d.path());
    assert!(!ok && err.contains("no pin for port bit `rx[3]`"), "{err}");
    assert!(!d.path().join("v4").exists() && !d.path().join("c4").exists());
}

#[test]
fn rec_rule_is_a_generation_time_constant_of_core_and_top() {
    // C13: the 1999 rule changes one constant in each controller design, nothing else.
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("bosch.toml"), "[controller]\nrec_rule = \"bosch-1999\"\n").unwrap();
    let (ok, out, err) = canstar(&["generate", "controller", "--out", "iso"], d.path());
    assert!(ok, "{out}{err}");
    let (ok, out, err) = canstar(&["generate", "controller", "--config", "bosch.toml", "--out", "bosch"], d.path());
    assert!(ok, "{out}{err}");
    for f in ["controller/canstar_can_core.v", "controller/canstar_sja1000.v"] {
        let iso = std::fs::read_to_string(d.path().join("iso").join(f)).unwrap();
        let bosch = std::fs::read_to_string(d.path().join("bosch").join(f)).unwrap();
        let diff: Vec<(&str, &str)> = iso.lines().zip(bosch.lines()).filter(|(a, b)| a != b).collect();
        assert_eq!(iso.lines().count(), bosch.lines().count(), "{f}");
        assert_eq!(diff.len(), 1, "{f}: {diff:?}");
        assert!(diff[0].0.ends_with("rec_iso = 1'b1;") && diff[0].1.ends_with("rec_iso = 1'b0;"), "{f}: {diff:?}");
    }
    // the key's former name is still read
    std::fs::write(d.path().join("old.toml"), "[controller]\neof7_rec = \"bosch-1999\"\n").unwrap();
    let (ok, out, err) = canstar(&["generate", "controller", "--config", "old.toml", "--out", "old"], d.path());
    assert!(ok, "{out}{err}");
    let f = "controller/canstar_can_core.v";
    assert_eq!(std::fs::read_to_string(d.path().join("old").join(f)).unwrap(), std::fs::read_to_string(d.path().join("bosch").join(f)).unwrap());
}

#[test]
fn controller_pinout_and_host_interface_switch() {
    let d = tempfile::tempdir().unwrap();
    let (ok, out, err) = canstar(&["generate", "controller", "--board", "xsa-3s1000", "--out", "v", "--constraints", "c"], d.path());
    assert!(ok, "{out}{err}");
    let ucf = std::fs::read_to_string(d.path().join("c/xsa-3s1000/canstar_sja1000_board.ucf")).unwrap();
    assert!(canstar::boards::pinfile::ucf_well_formed(&ucf), "{ucf}");
    // CAN on node port 0's transceiver pins, reset on the nRST switch, 14.74 MHz clock.
    for line in [
        "NET rx LOC=H15;",
        "NET tx LOC=G15;",
        "NET rst_n LOC=E11;",
        "NET wb_dat_r<7> LOC=P1;",
        "PERIOD clock 67.84 ns",
    ] {
        assert!(ucf.contains(line), "missing {line} in\n{ucf}");
    }
    let v = std::fs::read_to_string(d.path().join("v/controller/canstar_sja1000.v")).unwrap();
    assert!(v.contains("module canstar_sja1000_board(") && v.contains(".rst(~rst_n)"));
    // No host interface: only the core, no SJA1000 top and no controller pin files.
    std::fs::write(d.path().join("native.toml"), "[controller]\nhost_interface = false\n").unwrap();
    let (ok, out, err) = canstar(&["generate", "controller", "--config", "native.toml", "--out", "v2", "--constraints", "c2"], d.path());
    assert!(ok, "{out}{err}");
    let files = files_under(&d.path().join("v2"));
    assert!(files.iter().any(|f| f.ends_with("canstar_can_core.v")) && !files.iter().any(|f| f.contains("sja1000")), "{files:?}");
    assert!(files_under(&d.path().join("c2")).is_empty());
    // A board without a controller pinout: a clear error, nothing written.
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("boards/xsa-3s1000.toml")).unwrap();
    let hub_only = text.split("[controller.pins]").next().unwrap();
    std::fs::write(d.path().join("hubonly.toml"), hub_only).unwrap();
    let (ok, _, err) = canstar(&["generate", "controller", "--board", "hubonly.toml", "--out", "v3", "--constraints", "c3"], d.path());
    assert!(!ok && err.contains("no controller pinout"), "{err}");
    assert!(!d.path().join("v3").exists() && !d.path().join("c3").exists());
    // Two controller roles on one pin.
    let clash = text.replace("\"wb_we\" = \"D16\"", "\"wb_we\" = \"H15\"");
    std::fs::write(d.path().join("clash.toml"), clash).unwrap();
    let (ok, _, err) = canstar(&["generate", "controller", "--board", "clash.toml", "--out", "v4"], d.path());
    assert!(!ok && err.contains("pin conflict: pin H15"), "{err}");
}

#[test]
fn conformance_iso_suite_runs_cases_by_clause() {
    let d = tempfile::tempdir().unwrap();
    let (ok, out, err) = canstar(&["conformance", "--suite", "iso", "--case", "7.2.2"], d.path());
    assert!(ok, "{out}{err}");
    assert!(out.contains("iso_7_2_2_stuff_error") && !out.contains("iso_7_1_1"), "{out}");
    let last = out.lines().last().unwrap();
    assert!(last.ends_with(" passed, 0 failed") && !last.starts_with("0 "), "{last}");
    let (ok, out, err) = canstar(&["conformance", "--suite", "iso", "--case", "9.9"], d.path());
    assert!(!ok && out.is_empty() && err.contains("no ISO case matches `9.9`") && err.contains("7.1.1"), "{out}{err}");
    let (ok, _, err) = canstar(&["conformance", "--case", "7.1.1"], d.path());
    assert!(!ok && err.contains("--suite iso"), "{err}");
    let (ok, _, err) = canstar(&["conformance", "--suite", "iso", "--program", "idle"], d.path());
    assert!(!ok && err.contains("bosch suite"), "{err}");
    assert!(files_under(d.path()).is_empty(), "the ISO suite writes nothing");
}

#[test]
fn conformance_iso_suite_writes_a_vcd_per_case_bench() {
    let d = tempfile::tempdir().unwrap();
    // 7.6.16 runs two controllers (ISO and 1999 REC rules): two benches, two files
    let (ok, out, err) = canstar(&["conformance", "--suite", "iso", "--case", "7.6.16", "--vcd", "w"], d.path());
    assert!(ok, "{out}{err}");
    let mut names: Vec<String> = std::fs::read_dir(d.path().join("w")).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    assert_eq!(names, ["iso_7_6_16_eof7_rec.vcd", "iso_7_6_16_eof7_rec_2.vcd"]);
    let v = std::fs::read_to_string(d.path().join("w/iso_7_6_16_eof7_rec.vcd")).unwrap();
    assert!(v.contains("$enddefinitions") && v.lines().any(|l| l.contains("$scope") && l.split_whitespace().any(|w| w == "lt")), "a VCD with the LT's nets");
    assert!(v.lines().filter(|l| l.starts_with('#')).count() > 100, "time stamps");
    // an unwritable directory: an error naming it, nothing written
    std::fs::write(d.path().join("file"), "").unwrap();
    let (ok, _, err) = canstar(&["conformance", "--suite", "iso", "--case", "7.6.16", "--vcd", "file/sub"], d.path());
    assert!(!ok && err.contains("file/sub"), "{err}");
    assert_eq!(files_under(d.path()).len(), 3, "only the first run's files and `file`");
}
