//! `canstar report` end to end: bad options, a nextpnr that stalls (a fake on
//! PATH), and the real Yosys + nextpnr-ice40 flow on a small block.
use std::path::Path;
use std::process::Command;
use canstar::report::fake::alive;

/// Run `canstar report ARGS` in `dir` with TMPDIR = `dir/tmp` and `path_first`
/// (if any) ahead of PATH: (success, stdout, stderr).
fn report(args: &[&str], dir: &Path, path_first: Option<&Path>) -> (bool, String, String) {
    let tmp = dir.join("tmp");
    std::fs::create_dir_all(&tmp).unwrap();
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_canstar"));
    cmd.arg("report").args(args).current_dir(dir).env("TMPDIR", &tmp).env_remove("CANSTAR_KEEP_FLOW");
    if let Some(p) = path_first {
        cmd.env("PATH", format!("{}:{}", p.display(), std::env::var("PATH").unwrap_or_default()));
    }
    let out = cmd.output().unwrap();
    (out.status.success(), String::from_utf8_lossy(&out.stdout).into_owned(), String::from_utf8_lossy(&out.stderr).into_owned())
}

fn entries(p: &Path) -> Vec<String> {
    std::fs::read_dir(p).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect()
}

#[test]
fn report_rejects_bad_options_and_writes_nothing() {
    let d = tempfile::tempdir().unwrap();
    for (args, expect) in [
        (&["--seeds", "0"][..], "--seeds 0: must be 1 to 100"),
        (&["--seeds", "101"][..], "--seeds 101: must be 1 to 100"),
        (&["--stall", "0"][..], "--stall 0: must be 1 to 86400 seconds"),
        (&["--freq", "0"][..], "--freq 0.0: must be a frequency"),
        (&["--seeds", "three"][..], "invalid value 'three' for '--seeds <SEEDS>'"),
        (&["--design", "canstar_nothing"][..], "unknown design \"canstar_nothing\""),
    ] {
        let (ok, out, err) = report(args, d.path(), None);
        assert!(!ok && out.is_empty() && err.contains(expect), "{args:?}: {out}{err}");
        assert_eq!(entries(d.path()), vec!["tmp"], "{args:?}");
        assert!(entries(&d.path().join("tmp")).is_empty(), "{args:?}");
    }
}

#[test]
#[ignore = "needs yosys: run scripts/test-all.sh"]
fn report_kills_a_stalled_nextpnr_and_says_the_design_was_not_placed() {
    use std::os::unix::fs::PermissionsExt;
    let d = tempfile::tempdir().unwrap();
    let bin = d.path().join("bin");
    std::fs::create_dir(&bin).unwrap();
    let pids = bin.join("pids");
    // Prints the start of a router table, then waits for a child that sleeps
    // (`--version`, for the tools line, answers at once).
    let fake = bin.join("nextpnr-ice40");
    std::fs::write(
        &fake,
        format!(
            "#!/bin/sh\n[ \"$1\" = --version ] && {{ echo 'fake nextpnr-ice40'; exit 0; }}\n\
             echo $$ >> {p}\necho 'Info: Routing..' >&2\n\
             echo 'Info:       1000 |       86        913 |   86   913 |      4053|       0.45       0.45|' >&2\n\
             sleep 3600 &\necho $! >> {p}\nwait\n",
            p = pids.display()
        ),
    )
    .unwrap();
    std::fs::set_permissions(&fake, std::fs::Permissions::from_mode(0o755)).unwrap();
    let t = std::time::Instant::now();
    let (ok, out, err) = report(&["--design", "canstar_synchroniser", "--seeds", "2", "--stall", "2"], d.path(), Some(&bin));
    let secs = t.elapsed().as_secs_f64();
    assert!(ok, "{out}{err}");
    assert!(
        out.contains("\ncanstar_synchroniser: not placed (seed 1: stalled: no router progress for 2 s, killed after 2 s; seed 2: stalled: no router progress for 2 s, killed after 2 s)"),
        "{out}{err}"
    );
    assert!(out.contains("| canstar_synchroniser | 2 | 2 | 0 | - | - | - | 0/2 |"), "{out}");
    assert!(err.contains("canstar_synchroniser seed 1: stalled") && err.contains("canstar_synchroniser seed 2: stalled"), "{err}");
    assert!(secs < 60.0, "{secs} s");
    // Two seeds, two processes each, none left running, no temporary files left.
    assert_eq!(std::fs::read_to_string(&pids).unwrap().lines().count(), 4);
    assert!(alive(&bin).is_empty(), "left running: {:?}", alive(&bin));
    assert!(entries(&d.path().join("tmp")).is_empty(), "{:?}", entries(&d.path().join("tmp")));
}

#[test]
#[ignore = "needs yosys and nextpnr-ice40: run scripts/test-all.sh"]
fn report_places_a_small_block_with_two_seeds() {
    let d = tempfile::tempdir().unwrap();
    let (ok, out, err) = report(&["--design", "canstar_crc15", "--seeds", "2", "--stall", "60", "--pnr-timeout", "300"], d.path(), None);
    assert!(ok, "{out}{err}");
    let row = out.lines().find(|l| l.starts_with("| canstar_crc15 |")).unwrap_or_else(|| panic!("{out}"));
    let cells: Vec<&str> = row.split('|').map(str::trim).collect();
    // | design | LUT4 | DFF | BRAM | LCs placed (seed) | fmax median | fmax best | seeds placed | ...
    let lc: usize = cells[5].split(' ').next().unwrap().parse().unwrap_or_else(|_| panic!("{row}"));
    let median: f64 = cells[6].split(' ').next().unwrap().parse().unwrap_or_else(|_| panic!("{row}"));
    let best: f64 = cells[7].split(' ').next().unwrap().parse().unwrap_or_else(|_| panic!("{row}"));
    assert!(lc > 0 && median > 0.0 && best >= median, "{row}");
    assert_eq!(cells[8], "2/2", "{row}");
    assert!(err.contains("canstar_crc15 seed 1: ") && err.contains("canstar_crc15 seed 2: "), "{err}");
    assert!(entries(&d.path().join("tmp")).is_empty());
}
