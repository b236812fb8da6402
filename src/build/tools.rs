//! The open iCE40 tools `canstar build` runs: which must be installed (and the
//! Debian package that has each), the device arguments of nextpnr-ice40 for a
//! board, Yosys synthesis and icepack.

use crate::boards::Board;
use anyhow::{bail, Context, Result};
use std::path::Path;
use std::process::Command;

/// (program, Debian package) of every tool a bitstream needs.
pub const TOOLS: &[(&str, &str)] = &[("yosys", "yosys"), ("nextpnr-ice40", "nextpnr-ice40"), ("icepack", "fpga-icestorm")];

/// Every tool on PATH, or an error naming the first missing one and its package.
pub fn require() -> Result<()> {
    for (tool, package) in TOOLS {
        if !canstar_hdl::flow::have_tool(tool) {
            bail!("{tool} not found on PATH: install the Debian package `{package}` (sudo apt-get install {package}; scripts/test-all.sh installs it)");
        }
    }
    Ok(())
}

/// The iCE40 devices nextpnr-ice40 knows (its `--<device>` options).
const DEVICES: &[&str] = &["lp384", "lp1k", "lp4k", "lp8k", "hx1k", "hx4k", "hx8k", "up3k", "up5k", "u1k", "u2k", "u4k"];

/// nextpnr-ice40's device and package arguments for a board (`--hx8k --package
/// cb132`), or an error naming the board file's key.
pub fn device_args(board: &Board) -> Result<Vec<String>> {
    let part = board.part.to_ascii_lowercase();
    let part = part.strip_prefix("ice40").unwrap_or(&part).trim_start_matches('-');
    if !DEVICES.contains(&part) {
        bail!("{}: part: {:?} is not an iCE40 device nextpnr-ice40 knows ({})", board.label(), board.part, DEVICES.join(", "));
    }
    let Some(package) = &board.package else {
        bail!("{}: package: missing; nextpnr-ice40 needs the package (e.g. package = \"cb132\")", board.label());
    };
    Ok(vec![format!("--{part}"), "--package".into(), package.to_ascii_lowercase()])
}

fn run(cmd: &mut Command, what: &str) -> Result<String> {
    let out = cmd.output().with_context(|| format!("running {what}"))?;
    let log = String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    if !out.status.success() {
        let tail: Vec<&str> = log.lines().rev().take(20).collect();
        bail!("{what} failed ({}):\n{}", out.status, tail.into_iter().rev().collect::<Vec<_>>().join("\n"));
    }
    Ok(log)
}

/// Yosys `synth_ice40` of `top` in `verilog`, writing the netlist `json`; returns Yosys' log.
pub fn synth(verilog: &Path, top: &str, json: &Path) -> Result<String> {
    let script = format!("read_verilog {}; synth_ice40 -top {top} -json {}", verilog.display(), json.display());
    run(Command::new("yosys").arg("-q").arg("-p").arg(script), "yosys synth_ice40")
}

/// icepack: the routed `asc` into the bitstream `bin`.
pub fn icepack(asc: &Path, bin: &Path) -> Result<()> {
    run(Command::new("icepack").arg(asc).arg(bin), "icepack").map(|_| ())
}

/// Does `bin` hold an iCE40 bitstream: the optional comment block `FF 00 ... 00 FF`
/// icepack writes first, then the synchronisation word `7E AA 99 7E`?
pub fn is_ice40_bitstream(bin: &[u8]) -> bool {
    const SYNC: [u8; 4] = [0x7E, 0xAA, 0x99, 0x7E];
    let body = match bin {
        [0xFF, 0x00, rest @ ..] => match rest.windows(2).position(|w| w == [0x00, 0xFF]) {
            Some(i) => &rest[i + 2..],
            None => return false,
        },
        _ => bin,
    };
    body.starts_with(&SYNC)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn device_arguments_from_the_board() {
        let b = Board::lookup("alchitry-cu").unwrap();
        assert_eq!(device_args(&b).unwrap(), ["--hx8k", "--package", "cb132"]);
        let mut b2 = b.clone();
        b2.part = "iCE40HX1K".into();
        assert_eq!(device_args(&b2).unwrap()[0], "--hx1k");
        b2.part = "xc7a35t".into();
        let e = device_args(&b2).unwrap_err().to_string();
        assert!(e.contains("board alchitry-cu: part: \"xc7a35t\" is not an iCE40 device"), "{e}");
        b2.part = "hx8k".into();
        b2.package = None;
        assert!(device_args(&b2).unwrap_err().to_string().contains("package: missing"));
    }

    #[test]
    fn the_bitstream_check_wants_the_sync_word() {
        assert!(is_ice40_bitstream(&[0xFF, 0x00, b'x', 0x00, 0xFF, 0x7E, 0xAA, 0x99, 0x7E, 0x51]));
        assert!(is_ice40_bitstream(&[0x7E, 0xAA, 0x99, 0x7E]));
        assert!(!is_ice40_bitstream(&[0xFF, 0x00, 0x00, 0xFF, 0x7E, 0xAA, 0x99]));
        assert!(!is_ice40_bitstream(b"not a bitstream"));
        assert!(!is_ice40_bitstream(&[]));
    }
}
