//! `canstar boards`: the built-in boards with family, clock, pin-file format,
//! the roles `canstar build` makes bitstreams of, and designs; a board file
//! given by path is checked and listed; bad input is a
//! clear error naming the file and the key.
mod common;
use common::canstar;
use std::path::Path;

#[test]
fn boards_lists_every_builtin_board() {
    let d = tempfile::tempdir().unwrap();
    let (ok, out, err) = canstar(&["boards"], d.path());
    assert!(ok, "{out}{err}");
    let row = |name: &str| out.lines().find(|l| l.starts_with(&format!("{name} "))).unwrap_or_else(|| panic!("no row for {name}:\n{out}")).to_string();
    assert!(out.lines().next().unwrap().starts_with("board"), "{out}");
    for (name, family, clock, format, bitstream, designs) in [
        ("xsa-3s1000", "spartan3", "14.74 MHz on H16", "ucf (Xilinx ISE)", "-", "hub, controller"),
        ("ice40-hx8k", "ice40", "100 MHz on P7", "pcf (nextpnr-ice40)", "hub, controller", "hub, controller"),
        ("alchitry-cu", "ice40", "100 MHz on P7", "pcf (nextpnr-ice40)", "hub, controller, slcan", "hub, controller, slcan"),
        ("ulx3s", "ecp5", "25 MHz on G2", "lpf (", "-", "hub, controller"),
        ("arty-a7", "artix7", "100 MHz on E3", "xdc (Vivado)", "-", "hub, controller"),
    ] {
        let r = row(name);
        for want in [family, clock, format] {
            assert!(r.contains(want), "{name}: `{want}` not in `{r}`");
        }
        // Columns are separated by at least two spaces.
        let cells: Vec<&str> = r.split("  ").map(str::trim).filter(|c| !c.is_empty()).collect();
        assert_eq!(cells[5..], [bitstream, designs], "{name}: `{r}`");
    }
    assert!(out.lines().next().unwrap().contains("bitstream"), "{out}");
    assert!(std::fs::read_dir(d.path()).unwrap().next().is_none(), "`boards` writes nothing");
}

#[test]
fn boards_checks_a_board_file() {
    let d = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("boards/ulx3s.toml")).unwrap();
    // A hub-only copy of a board: listed with the hub only.
    let hub_only = text.split("[controller.pins]").next().unwrap().replace("name = \"ulx3s\"", "name = \"mine\"");
    std::fs::write(d.path().join("mine.toml"), &hub_only).unwrap();
    let (ok, out, err) = canstar(&["boards", "mine.toml", "arty-a7"], d.path());
    assert!(ok, "{out}{err}");
    assert!(out.lines().any(|l| l.starts_with("mine ") && l.ends_with(" hub")), "{out}");
    assert!(out.contains("(mine.toml)") && out.contains("arty-a7 "), "{out}");
    // A bad key and an unknown board: the file and key named, non-zero exit, nothing printed.
    std::fs::write(d.path().join("bad.toml"), format!("{hub_only}\n[clock2]\nhz = 1\n")).unwrap();
    let (ok, out, err) = canstar(&["boards", "bad.toml"], d.path());
    assert!(!ok && out.is_empty() && err.contains("bad.toml") && err.contains("clock2"), "{out}{err}");
    let (ok, out, err) = canstar(&["boards", "no-such-board"], d.path());
    assert!(!ok && out.is_empty() && err.contains("unknown board `no-such-board`") && err.contains("ulx3s"), "{out}{err}");
}
