//! Regression tests of issue #15, one per defect found with hostile inputs:
//! no panic, no stray output, no silent nonsense. Each runs the `canstar`
//! binary in a scratch folder and checks the message, the exit status and
//! that nothing was written.
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn example(name: &str) -> String {
    root().join("examples").join(name).display().to_string()
}

struct Run {
    ok: bool,
    code: Option<i32>,
    out: String,
    err: String,
}

fn run(args: &[&str], cwd: &Path) -> Run {
    let o: Output = Command::new(env!("CARGO_BIN_EXE_canstar")).args(args).current_dir(cwd).output().unwrap();
    let r = Run {
        ok: o.status.success(),
        code: o.status.code(),
        out: String::from_utf8_lossy(&o.stdout).into_owned(),
        err: String::from_utf8_lossy(&o.stderr).into_owned(),
    };
    assert!(!r.err.contains("panicked"), "{args:?} panicked:\n{}", r.err);
    r
}

/// Every file and folder under `d`, relative, sorted.
fn tree(d: &Path) -> Vec<String> {
    fn walk(d: &Path, base: &Path, v: &mut Vec<String>) {
        for e in std::fs::read_dir(d).unwrap().flatten() {
            let p = e.path();
            v.push(p.strip_prefix(base).unwrap().display().to_string());
            if p.is_dir() && !p.is_symlink() {
                walk(&p, base, v);
            }
        }
    }
    let mut v = vec![];
    walk(d, d, &mut v);
    v.sort();
    v
}

/// A scratch folder with a file `afile` and an empty folder `adir`.
fn scratch() -> tempfile::TempDir {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("afile"), "x").unwrap();
    std::fs::create_dir(d.path().join("adir")).unwrap();
    d
}

/// `args` fails with a message containing `msg` and writes nothing.
fn fails_cleanly(args: &[&str], d: &Path, msg: &str) -> Run {
    let before = tree(d);
    let r = run(args, d);
    assert!(!r.ok, "{args:?} should fail:\n{}{}", r.out, r.err);
    assert!(r.err.contains(msg), "{args:?}: stderr should mention {msg:?}:\n{}", r.err);
    assert!(r.err.starts_with("error: ") || r.err.contains("\nerror: "), "{args:?}: {}", r.err);
    assert_eq!(tree(d), before, "{args:?} wrote something");
    r
}

fn write(d: &Path, name: &str, text: &str) -> PathBuf {
    let p = d.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

// ---- defect 1: panics in the network simulation

#[test]
fn network_sim_with_an_unwritable_output_fails_before_running() {
    let d = scratch();
    let net = example("recancentrate.toml");
    for (vcd, msg) in [
        ("/no/such/dir/n.vcd", "directory /no/such/dir does not exist"),
        ("adir", "adir is a directory"),
        ("afile/n.vcd", "afile is not a directory"),
    ] {
        let r = fails_cleanly(&["sim", &net, "--ms", "0.1", "--vcd", vcd], d.path(), msg);
        assert!(!r.out.contains("simulated"), "nothing ran: {}", r.out);
    }
    if Path::new("/proc/self").exists() {
        // A place nobody can create files in, root included.
        fails_cleanly(&["sim", &net, "--ms", "0.1", "--vcd", "/proc/n.vcd"], d.path(), "cannot write /proc/n.vcd");
    }
}

#[test]
fn network_clocks_that_round_to_a_zero_period_are_rejected() {
    let d = scratch();
    let text = std::fs::read_to_string(example("recancentrate.toml")).unwrap();
    let zero_delays = text.replace("_ps = 10000", "_ps = 0");
    let hub = zero_delays.replace("clock_hz = 14740000", "clock_hz = 10000000000000");
    write(d.path(), "hub.toml", &hub);
    fails_cleanly(&["sim", "hub.toml", "--ms", "0.01"], d.path(), "hub.toml: hub: clock_hz = 10000000000000");
    let ctrl = zero_delays.replacen("\nclock_hz = 29480000", "\nclock_hz = 10000000000000", 1);
    write(d.path(), "ctrl.toml", &ctrl);
    fails_cleanly(&["sim", "ctrl.toml", "--ms", "0.01"], d.path(), "ctrl.toml: nodes[0].a.clock_hz: 10000000000000");
}

#[test]
fn a_driver_copy_limit_beyond_a_counter_is_rejected() {
    let d = scratch();
    let text = std::fs::read_to_string(example("recancentrate.toml")).unwrap();
    write(d.path(), "net.toml", &text.replace("copy_tec = 8 ", "copy_tec = 256 "));
    fails_cleanly(&["sim", "net.toml", "--ms", "0.01"], d.path(), "net.toml: driver.copy_tec: 256");
}

#[test]
fn a_driver_resend_switch_that_is_not_a_boolean_is_rejected() {
    let d = scratch();
    let text = std::fs::read_to_string(example("recancentrate.toml")).unwrap();
    assert!(text.contains("resend_unconfirmed = true "));
    write(d.path(), "net.toml", &text.replace("resend_unconfirmed = true ", "resend_unconfirmed = 1 "));
    let r = fails_cleanly(&["sim", "net.toml", "--ms", "0.01"], d.path(), "expected a boolean");
    assert!(r.err.contains("net.toml: ") && r.err.contains("resend_unconfirmed = 1"), "{}", r.err);
}

// ---- defect 2: board names used as folder names

#[test]
fn board_names_that_are_not_folder_names_are_rejected() {
    let d = scratch();
    let board = std::fs::read_to_string(root().join("boards/xsa-3s1000.toml")).unwrap();
    assert!(board.contains("name = \"xsa-3s1000\""));
    for (file, name) in [("empty.toml", ""), ("escape.toml", "../../escaped"), ("abs.toml", "/tmp/x"), ("dot.toml", "..")] {
        write(d.path(), file, &board.replace("name = \"xsa-3s1000\"", &format!("name = {name:?}")));
        let msg = format!("{file}: name: {name:?} must be");
        fails_cleanly(&["generate", "hub", "--board", file, "--out", "v", "--constraints", "c"], d.path(), &msg);
    }
    // An empty pin, a pin with a quote, a description over two lines: none reaches a pin file.
    for (file, from, to, msg) in [
        ("pin.toml", "\"rx[1]\" = \"H14\"", "\"rx[1]\" = \"\"", "pins.\"rx[1]\": \"\" must be"),
        ("quote.toml", "\"rx[1]\" = \"H14\"", "\"rx[1]\" = \"H1\\\"4\"", "pins.\"rx[1]\""),
        ("desc.toml", "description = \"", "description = \"two\\nlines ", "description:"),
    ] {
        assert!(board.contains(from), "{from}");
        write(d.path(), file, &board.replacen(from, to, 1));
        fails_cleanly(&["generate", "hub", "--board", file, "--out", "v", "--constraints", "c"], d.path(), msg);
    }
}

// ---- defect 3: generate writes the set or nothing

fn canstar_temps(d: &Path) -> Vec<String> {
    tree(d).into_iter().filter(|p| p.contains("canstar-tmp") || p.contains("canstar-old")).collect()
}

#[test]
fn generate_failing_after_rendering_leaves_nothing() {
    let d = scratch();
    fails_cleanly(&["generate", "hub", "--out", "v", "--constraints", "afile"], d.path(), "afile is not a directory");
    fails_cleanly(&["generate", "blocks", "--out", "afile/v"], d.path(), "afile is not a directory");
    // A destination that is a folder: the old set stays as it was, no temporary is left.
    let r = run(&["generate", "blocks", "--out", "v"], d.path());
    assert!(r.ok, "{}", r.err);
    let old = write(d.path(), "v/blocks/canstar_synchroniser.v", "old");
    std::fs::remove_file(d.path().join("v/blocks/canstar_crc15.v")).unwrap();
    std::fs::create_dir(d.path().join("v/blocks/canstar_crc15.v")).unwrap();
    let before = tree(d.path());
    let r = run(&["generate", "blocks", "--out", "v"], d.path());
    assert!(!r.ok && r.err.contains("canstar_crc15.v is a directory"), "{}", r.err);
    assert_eq!(tree(d.path()), before);
    assert_eq!(std::fs::read_to_string(old).unwrap(), "old");
}

#[test]
fn generate_cleans_stale_temporaries_and_creates_no_empty_folder() {
    let d = scratch();
    let r = run(&["generate", "blocks", "--out", "v", "--constraints", "c"], d.path());
    assert!(r.ok, "{}", r.err);
    assert!(!d.path().join("c").exists(), "blocks have no pin files: no empty constraints folder");
    // Left by a killed run (pid 0 never runs a user process) and by older versions.
    write(d.path(), "v/blocks/canstar_crc15.v.0.canstar-tmp", "partial");
    write(d.path(), "v/blocks/canstar_crc15.canstar-tmp", "partial");
    let r = run(&["generate", "blocks", "--out", "v"], d.path());
    assert!(r.ok, "{}", r.err);
    assert_eq!(canstar_temps(d.path()), Vec::<String>::new());
}

#[test]
fn generate_killed_at_any_moment_leaves_the_old_or_the_new_set() {
    let d = scratch();
    write(d.path(), "one.toml", "[rtl]\nsync_depth = 1\n");
    let r = run(&["generate", "blocks", "--config", "one.toml", "--out", "old"], d.path());
    assert!(r.ok, "{}", r.err);
    let r = run(&["generate", "blocks", "--out", "new"], d.path());
    assert!(r.ok, "{}", r.err);
    let files: Vec<String> = tree(&d.path().join("new")).into_iter().filter(|f| f.ends_with(".v")).collect();
    let read = |dir: &str| -> Vec<String> { files.iter().map(|f| std::fs::read_to_string(d.path().join(dir).join(f)).unwrap()).collect() };
    let (old, new) = (read("old"), read("new"));
    assert_ne!(old, new);
    for k in 0..12u64 {
        // Start from the old set, kill after 0..11 ms (the command takes about 10 ms).
        let _ = std::fs::remove_dir_all(d.path().join("v"));
        let r = run(&["generate", "blocks", "--config", "one.toml", "--out", "v"], d.path());
        assert!(r.ok);
        let child = Command::new(env!("CARGO_BIN_EXE_canstar"))
            .args(["generate", "blocks", "--out", "v"])
            .current_dir(d.path())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        std::thread::sleep(std::time::Duration::from_micros(k * 1000));
        let _ = Command::new("kill").args(["-TERM", &child.id().to_string()]).status();
        let o = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!err.contains("panicked"), "{err}");
        let now = read("v");
        assert!(now == old || now == new, "kill after {k} ms left a mix of old and new files");
        assert_eq!(canstar_temps(d.path()), Vec::<String>::new(), "kill after {k} ms left temporaries");
    }
}

// ---- defect 4: overflow and NaN

const SCENARIO: &str = "duration_us = 100\n[[node]]\nname = \"n1\"\n[[node]]\nname = \"n2\"\nppm = 50\n\
    [[frame]]\nnode = \"n1\"\nat_us = 5\nid = 0x123\ndata = [1, 2]\n\
    [[interference]]\nnode = \"n2\"\nmode = \"invert\"\nat_us = 40.0\nbits = 1\n";

#[test]
fn overflowing_and_nan_numbers_are_rejected_naming_file_and_key() {
    let d = scratch();
    for (edit, msg) in [
        (SCENARIO.replace("duration_us = 100", "duration_us = 18446744073710"), "s.toml: duration_us: 18446744073710"),
        (SCENARIO.replace("at_us = 5", "at_us = 18446744073710"), "s.toml: frame[0].at_us: 18446744073710"),
        (SCENARIO.replace("ppm = 50", "ppm = nan"), "s.toml: node[1].ppm: NaN"),
        (SCENARIO.replace("at_us = 40.0", "at_us = nan"), "s.toml: interference[0].at_us: NaN"),
        (SCENARIO.replace("at_us = 40.0", "at_us = -inf"), "s.toml: interference[0].at_us: -inf"),
        (SCENARIO.replace("name = \"n2\"", "name = \"n 2\""), "s.toml: node[1].name: name `n 2`"),
    ] {
        write(d.path(), "s.toml", &edit);
        let before = tree(d.path());
        let r = run(&["sim", "s.toml", "--vcd", "s.vcd"], d.path());
        assert!(!r.ok && r.err.contains(msg), "expected {msg:?} in {}", r.err);
        assert_eq!(tree(d.path()), before);
    }
    write(d.path(), "s.toml", SCENARIO);
    for ms in ["0", "-1", "nan", "inf", "-inf", "1e300"] {
        if !ms.starts_with("-i") {
            fails_cleanly(&["sim", "s.toml", "--ms", ms], d.path(), "--ms");
        }
        fails_cleanly(&["sim", &example("recancentrate.toml"), &format!("--ms={ms}")], d.path(), "--ms");
    }
    // A network node name that is no VCD scope.
    let net = std::fs::read_to_string(example("recancentrate.toml")).unwrap().replace("name = \"counter\"", "name = \"my counter\"");
    write(d.path(), "n.toml", &net);
    fails_cleanly(&["sim", "n.toml", "--ms", "0.01"], d.path(), "n.toml: nodes[0].name: name `my counter`");
    // A valid scenario cut short by --ms runs.
    let r = run(&["sim", "s.toml", "--ms", "0.02"], d.path());
    assert!(r.ok && r.out.contains("n1"), "{}{}", r.out, r.err);
}

// ---- defect 5: outputs checked before the run, none ignored

#[test]
fn outputs_are_checked_before_the_run_and_none_is_ignored() {
    let d = scratch();
    let arb = example("arbitration.toml");
    fails_cleanly(&["sim", &arb, "--vcd", "a.vcd", "--trace", "a.trace", "--log", "/no/dir/a.log"], d.path(), "/no/dir does not exist");
    fails_cleanly(&["sim", &arb, "--vcd", "same", "--log", "same"], d.path(), "same is given for two outputs");
    fails_cleanly(&["sim", &example("recancentrate.toml"), "--ms", "0.01", "--log", "x.log"], d.path(), "--log");
    fails_cleanly(&["campaign", "--classes", "pub01", "--vcd", "x.vcd"], d.path(), "--vcd writes the details of one run: it needs --class");
    fails_cleanly(&["campaign", "--classes", "pub01", "--plot", "x.svg"], d.path(), "needs --class");
    let r = fails_cleanly(&["campaign", "--classes", "pub01", "--reps", "1", "--json", "afile/o.json"], d.path(), "afile is not a directory");
    assert!(!r.out.contains("total:") && !r.err.contains("runs in"), "the campaign did not run");
    let r = fails_cleanly(&["campaign", "--class", "pub01", "--vcd", "adir"], d.path(), "adir is a directory");
    assert!(!r.out.contains("FAIL"), "an output problem is no failed run: {}", r.out);
    fails_cleanly(&["conformance", "--program", "idle", "--vcd", "afile"], d.path(), "afile is not a directory");
    fails_cleanly(&["fuzz", "--frames", "1", "--vcd-dir", "afile"], d.path(), "afile is not a directory");
    fails_cleanly(&["bench", "--cycles", "100", "--vcd", "no/such/b.vcd"], d.path(), "does not exist");
    // The conformance VCDs arrive together, with no staging folder left.
    let r = run(&["conformance", "--program", "idle", "--vcd", "vcds"], d.path());
    assert!(r.ok, "{}{}", r.out, r.err);
    assert_eq!(tree(&d.path().join("vcds")), ["idle.vcd"]);
}

// ---- also seen

#[test]
fn unknown_program_is_named_as_such() {
    let d = scratch();
    let r = fails_cleanly(&["conformance", "--program", "nosuch"], d.path(), "unknown program `nosuch`");
    assert!(!r.out.contains("passed"), "{}", r.out);
}

#[test]
fn huge_hubs_are_refused_before_rendering() {
    let d = scratch();
    write(d.path(), "big.toml", "[hub]\nports = 1000\n");
    fails_cleanly(&["generate", "hub", "--config", "big.toml", "--out", "v", "--constraints", "c"], d.path(), "big.toml: hub: invalid [hub] configuration: ports = 1000 (at most 128)");
    write(d.path(), "four.toml", "[hub]\nports = 4\n");
    fails_cleanly(&["generate", "hub", "--config", "four.toml", "--board", "xsa-3s1000", "--out", "v"], d.path(), "no pin for port bit `rx[3]`");
    fails_cleanly(&["report", "--freq", "nan"], d.path(), "--freq");
}

#[test]
fn input_files_are_read_bounded_and_named_in_every_message() {
    let d = scratch();
    if Path::new("/dev/zero").exists() {
        fails_cleanly(&["generate", "--config", "/dev/zero", "--check"], d.path(), "/dev/zero: larger than 16 MiB");
        fails_cleanly(&["sim", "/dev/zero"], d.path(), "/dev/zero: larger than 16 MiB");
    }
    fails_cleanly(&["generate", "--config", "adir", "--check"], d.path(), "adir: is a directory");
    fails_cleanly(&["sim", "adir"], d.path(), "adir: is a directory");
    std::fs::create_dir(d.path().join("dir.toml")).unwrap();
    fails_cleanly(&["generate", "hub", "--board", "dir.toml", "--check"], d.path(), "dir.toml: is a directory");
    std::fs::write(d.path().join("bin.toml"), b"[rtl]\n\xff\n").unwrap();
    fails_cleanly(&["generate", "--config", "bin.toml", "--check"], d.path(), "bin.toml: not UTF-8 text");
    fails_cleanly(&["sim", "bin.toml"], d.path(), "bin.toml: not UTF-8 text");
    fails_cleanly(&["campaign", "--merge", "bin.toml"], d.path(), "bin.toml: not UTF-8 text");
}

#[test]
fn a_closed_stdout_ends_a_command_quietly() {
    let d = scratch();
    let arb = example("arbitration.toml");
    for args in [
        vec!["campaign", "--list"],
        vec!["conformance", "--program", "idle"],
        vec!["sim", arb.as_str(), "--ms", "0.05", "--log", "a.log"],
        vec!["bench", "--cycles", "2000", "--nodes", "2"],
    ] {
        // A pipe whose reader is gone before the command starts.
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let o = Command::new(env!("CARGO_BIN_EXE_canstar"))
            .args(&args)
            .current_dir(d.path())
            .stdout(writer)
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!err.contains("panicked") && !err.contains("Broken pipe"), "{args:?}: {err}");
        assert_eq!(o.status.code(), Some(141), "{args:?}: {err}");
    }
    assert_eq!(canstar_temps(d.path()), Vec::<String>::new());
}

#[test]
fn network_summary_reports_maxima_and_plain_progress_off_a_terminal() {
    let d = scratch();
    let r = run(&["sim", &example("recancentrate.toml"), "--ms", "0.05"], d.path());
    assert!(r.ok, "{}{}", r.out, r.err);
    for s in ["max A", "max B", "blame counters (BIC)", "isolation(s)"] {
        assert!(r.out.contains(s), "missing {s:?} in\n{}", r.out);
    }
    assert!(!r.err.contains('\r') && !r.err.contains('\u{1b}'), "no bar drawn into a pipe: {:?}", r.err);
    assert!(r.code == Some(0));
}

#[test]
fn a_full_disk_during_the_run_is_an_error_not_a_panic() {
    // The kernel used to panic ("VCD write failed") when a VCD write failed mid-run.
    if !Path::new("/dev/full").exists() {
        return;
    }
    let d = scratch();
    let r = run(&["sim", &example("arbitration.toml"), "--ms", "0.05", "--vcd", "/dev/full", "--log", "a.log"], d.path());
    assert!(!r.ok && r.err.contains("No space left"), "{}{}", r.out, r.err);
    assert!(!d.path().join("a.log").exists(), "the other outputs are not kept");
    let r = run(&["sim", &example("recancentrate.toml"), "--ms", "0.01", "--vcd", "/dev/full"], d.path());
    assert!(!r.ok && r.err.contains("No space left"), "{}{}", r.out, r.err);
}

#[test]
fn ctrl_c_during_a_run_removes_every_output() {
    let d = scratch();
    let mut child = Command::new(env!("CARGO_BIN_EXE_canstar"))
        .args(["sim", &example("recancentrate.toml"), "--ms", "5", "--vcd", "n.vcd", "--trace", "n.trace"])
        .current_dir(d.path())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Wait until the run has reserved its outputs, then interrupt it.
    let t0 = std::time::Instant::now();
    while !tree(d.path()).iter().any(|p| p.contains("n.vcd.")) && t0.elapsed().as_secs() < 20 {
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let _ = Command::new("kill").args(["-INT", &child.id().to_string()]).status();
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130));
    assert_eq!(tree(d.path()), ["adir", "afile"]);
}
