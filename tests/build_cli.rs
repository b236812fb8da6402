//! `canstar build` end to end: bitstreams of the hub and the controller for the
//! Alchitry Cu (Yosys, nextpnr-ice40, icepack), a timing failure (a fake
//! nextpnr-ice40 on PATH), and bad input (unknown board or role, a family without
//! a bitstream flow, a PLL out of tolerance, missing tools): an error naming the
//! file and key, a non-zero exit and nothing written.
use std::path::Path;
use std::process::Command;

/// Run `canstar build ARGS` in `dir` with TMPDIR = `dir/tmp` and `path` (if any)
/// as PATH: (success, stdout, stderr).
fn build(args: &[&str], dir: &Path, path: Option<String>) -> (bool, String, String) {
    let tmp = dir.join("tmp");
    std::fs::create_dir_all(&tmp).unwrap();
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_canstar"));
    cmd.arg("build").args(args).current_dir(dir).env("TMPDIR", &tmp).env_remove("CANSTAR_KEEP_FLOW");
    if let Some(p) = path {
        cmd.env("PATH", p);
    }
    let out = cmd.output().unwrap();
    (out.status.success(), String::from_utf8_lossy(&out.stdout).into_owned(), String::from_utf8_lossy(&out.stderr).into_owned())
}

fn entries(p: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(p).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    v.sort();
    v
}

/// The folder holds only `tmp`, and `tmp` is empty.
fn wrote_nothing(d: &Path, what: &str) {
    assert_eq!(entries(d), ["tmp"], "{what}");
    assert!(entries(&d.join("tmp")).is_empty(), "{what}: {:?}", entries(&d.join("tmp")));
}

#[test]
fn bad_input_is_an_error_naming_the_file_and_key_and_writes_nothing() {
    let d = tempfile::tempdir().unwrap();
    let cu = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("boards/alchitry-cu.toml")).unwrap();
    std::fs::write(d.path().join("xc.toml"), cu.replace("part = \"hx8k\"", "part = \"xc7a35t\"")).unwrap();
    std::fs::write(d.path().join("slow.toml"), cu.replace("hz = 100_000_000", "hz = 5_000_000")).unwrap();
    std::fs::write(d.path().join("hubonly.toml"), cu.split("[controller.pins]").next().unwrap()).unwrap();
    let cases: &[(&[&str], &str)] = &[
        (&["--board", "no-such-board", "hub"], "unknown board `no-such-board`"),
        (&["--board", "alchitry-cu", "router"], "unknown role `router` (known roles: hub, controller, slcan)"),
        (&["--board", "arty-a7", "hub"], "board arty-a7: family: bitstream not supported for family artix7"),
        (&["--board", "xsa-3s1000", "controller"], "bitstream not supported for family spartan3"),
        (&["--board", "xc.toml", "hub"], "xc.toml: board alchitry-cu: part: \"xc7a35t\" is not an iCE40 device"),
        (&["--board", "slow.toml", "hub"], "slow.toml: board alchitry-cu: clock.hz: 5000000 Hz is outside the iCE40 PLL's reference range"),
        (&["--board", "hubonly.toml", "controller"], "hubonly.toml: board alchitry-cu has no controller pinout ([controller.pins])"),
        (&["--board", "alchitry-cu", "hub", "--pll-tolerance-ppm", "100"], "board alchitry-cu: clock.hz: the iCE40 PLL's closest setting to 14.740000 MHz"),
        (&["--board", "alchitry-cu", "hub", "--seeds", "0"], "--seeds 0: must be 1 to 100"),
        (&["--board", "alchitry-cu", "hub", "--config", "none.toml"], "none.toml"),
    ];
    for (args, expect) in cases {
        let (ok, out, err) = build(args, d.path(), None);
        assert!(!ok && out.is_empty() && err.contains(expect), "{args:?}: {out}{err}");
        let mut left = entries(d.path());
        left.retain(|n| !n.ends_with(".toml"));
        assert_eq!(left, ["tmp"], "{args:?}");
        assert!(entries(&d.path().join("tmp")).is_empty(), "{args:?}");
    }
    // No tools on PATH: the missing tool and its Debian package, nothing written.
    let empty = tempfile::tempdir().unwrap();
    let e = tempfile::tempdir().unwrap();
    let (ok, out, err) = build(&["--board", "alchitry-cu", "hub"], e.path(), Some(empty.path().display().to_string()));
    assert!(!ok && out.is_empty() && err.contains("yosys not found on PATH: install the Debian package `yosys`"), "{out}{err}");
    wrote_nothing(e.path(), "no tools");
}

/// The synchronisation word after icepack's comment block `FF 00 ... 00 FF`.
fn preamble(bin: &[u8]) -> &[u8] {
    assert_eq!(&bin[..2], [0xFF, 0x00], "icepack's comment block");
    let end = bin.windows(2).position(|w| w == [0x00, 0xFF]).expect("end of the comment block");
    &bin[end + 2..end + 6]
}

/// Build `role` for the Alchitry Cu in a fresh folder and check the bitstream,
/// the pin file, the PLL clock and the timing check at that clock.
fn bitstream(role: &str, top: &str, clock_mhz: &str, ppm: &str, pins: &[(&str, &str)]) {
    let d = tempfile::tempdir().unwrap();
    let board = canstar::boards::Board::lookup("alchitry-cu").unwrap();
    let (ok, out, err) = build(&["--board", "alchitry-cu", role, "--seeds", "2"], d.path(), None);
    assert!(ok, "{role}: {out}{err}");
    let dir = d.path().join("build/alchitry-cu").join(role);
    assert_eq!(entries(&dir), [format!("{top}.bin"), format!("{top}.pcf"), format!("{top}.v"), "nextpnr.log".to_string()], "{role}");
    let bin = std::fs::read(dir.join(format!("{top}.bin"))).unwrap();
    assert_eq!(preamble(&bin), [0x7E, 0xAA, 0x99, 0x7E], "{role}");
    assert!(bin.len() > 100_000, "{role}: {} bytes", bin.len());
    let pcf = std::fs::read_to_string(dir.join(format!("{top}.pcf"))).unwrap();
    assert!(pcf.contains(&format!("set_io {} {}\n", board.clock.port, board.clock.pin)), "{pcf}");
    for (port, pin) in pins {
        assert!(pcf.contains(&format!("set_io {port} {pin}\n")), "{role}: `{port} {pin}` not in\n{pcf}");
    }
    // Timing checked at the PLL's clock, and passed.
    assert!(out.contains(&format!("PLL:       {clock_mhz} MHz from 100 MHz, {ppm}")), "{out}");
    let timing = out.lines().find(|l| l.starts_with("timing:")).unwrap_or_else(|| panic!("{out}"));
    let fmax: f64 = timing.split_whitespace().nth(2).unwrap().parse().unwrap();
    assert!(timing.ends_with(&format!("at the {clock_mhz} MHz design clock: PASS")) && fmax >= clock_mhz.parse::<f64>().unwrap(), "{timing}");
    let log = std::fs::read_to_string(dir.join("nextpnr.log")).unwrap();
    assert!(log.contains(&format!("(PASS at {:.2} MHz)", clock_mhz.parse::<f64>().unwrap())), "{role}: no PASS line in the log");
    assert!(log.contains("ICESTORM_PLL:     1/    2"), "{role}: the PLL is not in the placed design");
    let lc: usize = out.lines().find_map(|l| l.strip_prefix("logic:")).unwrap().split_whitespace().next().unwrap().parse().unwrap();
    assert!(lc > 500, "{role}: {lc} LC");
    assert!(out.contains(&format!("flash:     iceprog build/alchitry-cu/{role}/{top}.bin")), "{out}");
    assert!(entries(&d.path().join("tmp")).is_empty(), "{:?}", entries(&d.path().join("tmp")));
}

#[test]
#[ignore = "needs yosys, nextpnr-ice40 and icepack: run scripts/test-all.sh"]
fn hub_and_controller_bitstreams_for_the_alchitry_cu() {
    bitstream("hub", "canstar_hub", "14.732143", "-533 ppm", &[("rst_n", "P8"), ("rx[0]", "M1"), ("tx[0]", "L1"), ("reh_rx[1]", "A5"), ("hub_tx[1]", "C5"), ("isolated[0]", "J11")]);
    bitstream("controller", "canstar_sja1000_board", "16.015625", "+977 ppm", &[("rst_n", "P8"), ("rx", "M1"), ("tx", "L1"), ("int_n", "J1"), ("wb_dat_r[0]", "A7")]);
}

#[test]
#[ignore = "needs yosys, nextpnr-ice40 and icepack: run scripts/test-all.sh"]
fn slcan_bitstream_for_the_alchitry_cu() {
    bitstream("slcan", "canstar_slcan_board", "16.015625", "+977 ppm", &[("rst_n", "P8"), ("uart_rx", "P14"), ("uart_tx", "M9"), ("rx", "M1"), ("tx", "L1")]);
}

#[test]
#[ignore = "needs yosys and icepack: run scripts/test-all.sh"]
fn fmax_below_the_design_clock_is_an_error_unless_allowed() {
    use std::os::unix::fs::PermissionsExt;
    let d = tempfile::tempdir().unwrap();
    let bin = tempfile::tempdir().unwrap();
    // A nextpnr-ice40 that "routes" every seed to 5 MHz (and writes no .asc).
    let fake = bin.path().join("nextpnr-ice40");
    std::fs::write(
        &fake,
        "#!/bin/sh\necho 'Info: \t         ICESTORM_LC:   100/ 7680     1%' >&2\n\
         echo \"Warning: Max frequency for clock 'canstar_pll_clock': 5.00 MHz (FAIL at 14.73 MHz)\" >&2\n",
    )
    .unwrap();
    std::fs::set_permissions(&fake, std::fs::Permissions::from_mode(0o755)).unwrap();
    let path = format!("{}:{}", bin.path().display(), std::env::var("PATH").unwrap_or_default());
    let (ok, out, err) = build(&["--board", "alchitry-cu", "hub", "--seeds", "2"], d.path(), Some(path.clone()));
    assert!(!ok && out.is_empty(), "{out}{err}");
    assert!(err.contains("timing: fmax 5.00 MHz (best of 2 seed(s), seed 1) is below the 14.732143 MHz design clock"), "{err}");
    assert!(err.contains("seed 1: 5.0 MHz, 100 LC") && err.contains("seed 2: 5.0 MHz"), "{err}");
    wrote_nothing(d.path(), "timing failure");
    // Allowed: the run gets as far as icepack, which finds no .asc from the fake.
    let (ok, _, err) = build(&["--board", "alchitry-cu", "hub", "--seeds", "1", "--timing-allow-fail"], d.path(), Some(path));
    assert!(!ok && err.contains("icepack failed"), "{err}");
    wrote_nothing(d.path(), "icepack failure");
}
