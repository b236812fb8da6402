//! The Verilog verification flow every canstar RTL block goes through:
//!
//! 1. emit Verilog with rust-hdl ([`emit`]),
//! 2. `verilator --lint-only -Wall` with the documented waivers of
//!    `verilator/waivers.vlt` ([`lint`]),
//! 3. Yosys synthesis with no latch, no undriven wire and no adder whose two
//!    operands are the same signal ([`synth_check`]; `x + x` becomes an iCE40
//!    carry chain with one net on two interchangeable inputs, on which
//!    nextpnr-ice40 0.4's router can livelock: write a shift),
//! 4. co-simulation: the emitted Verilog runs on the same random stimulus as
//!    the Rust model and every output is compared on every cycle ([`cosim`]):
//!    Icarus Verilog (4-state) on the first cycles, Verilator on all of them
//!    when the run is long for the design's size ([`iverilog_cycles`]).
//!
//! rust-hdl prints binary operators without parentheses, so Verilog operator
//! precedence can silently change the meaning of an expression; step 4 is what
//! keeps the Verilog honest.
//!
//! The external tools are looked up on `PATH`. Tests that need them are marked
//! `#[ignore]` so that plain `cargo test` runs only the Rust checks and lists
//! the skipped ones; `scripts/test-all.sh` installs the tools and runs them.

use crate::drive::{self, Clocked};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rust_hdl::prelude::*;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The documented Verilator waivers (see the file for the reason of each).
pub const VERILATOR_WAIVERS: &str = include_str!("../verilator/waivers.vlt");

#[derive(Debug, thiserror::Error)]
pub enum FlowError {
    #[error("tool `{0}` not found on PATH (install it, or run scripts/test-all.sh which does)")]
    MissingTool(&'static str),
    #[error("io error: {0}")]
    Io(#[from] std::io::Error),
    #[error("verilator lint of `{top}` failed:\n{log}")]
    Lint { top: String, log: String },
    #[error("yosys synthesis of `{top}` failed:\n{log}")]
    Synth { top: String, log: String },
    #[error("co-simulation of `{top}` failed: {detail}")]
    Cosim { top: String, detail: String },
}

/// Is `tool` on PATH?
pub fn have_tool(tool: &str) -> bool {
    Command::new("sh")
        .arg("-c")
        .arg(format!("command -v {tool} >/dev/null 2>&1"))
        .status()
        .map(|s| s.success())
        .unwrap_or(false)
}

fn require(tool: &'static str) -> Result<(), FlowError> {
    if have_tool(tool) {
        Ok(())
    } else {
        Err(FlowError::MissingTool(tool))
    }
}

/// Emit the Verilog of a block (top module `top`). The block must be connected.
pub fn emit<B: Block>(uut: &B) -> String {
    generate_verilog(uut)
}

/// Rename the top module of rust-hdl output (`top`, and its submodules
/// `top$x`) so that several designs can live side by side.
pub fn rename_top(verilog: &str, name: &str) -> String {
    verilog
        .replace("module top(", &format!("module {name}("))
        .replace("module top$", &format!("module {name}$"))
        .replace("\ntop$", &format!("\n{name}$"))
        .replace("    top$", &format!("    {name}$"))
        .replace("endmodule // top", &format!("endmodule // {name}"))
}

/// A scratch directory for tool runs; kept when `CANSTAR_KEEP_FLOW` is set.
pub struct WorkDir {
    dir: Option<tempfile::TempDir>,
    path: PathBuf,
}

impl WorkDir {
    pub fn new(prefix: &str) -> std::io::Result<Self> {
        let dir = tempfile::Builder::new().prefix(&format!("canstar-{prefix}-")).tempdir()?;
        let path = dir.path().to_path_buf();
        if std::env::var_os("CANSTAR_KEEP_FLOW").is_some() {
            eprintln!("flow artefacts kept in {}", path.display());
            #[allow(deprecated)]
            let _ = dir.into_path();
            return Ok(Self { dir: None, path });
        }
        Ok(Self { dir: Some(dir), path })
    }
    pub fn path(&self) -> &Path {
        &self.path
    }
}

impl Drop for WorkDir {
    fn drop(&mut self) {
        let _ = self.dir.take();
    }
}

fn run(cmd: &mut Command) -> std::io::Result<(bool, String)> {
    let out = cmd.output()?;
    let mut log = String::from_utf8_lossy(&out.stdout).into_owned();
    log.push_str(&String::from_utf8_lossy(&out.stderr));
    Ok((out.status.success(), log))
}

/// `verilator --lint-only -Wall` on a Verilog source with top module `top`.
pub fn lint(verilog: &str, top: &str) -> Result<(), FlowError> {
    require("verilator")?;
    let wd = WorkDir::new("lint")?;
    let vfile = wd.path().join(format!("{top}.v"));
    std::fs::write(&vfile, verilog)?;
    let waivers = wd.path().join("waivers.vlt");
    std::fs::write(&waivers, VERILATOR_WAIVERS)?;
    let (ok, log) = run(Command::new("verilator")
        .arg("--lint-only")
        .arg("-Wall")
        .arg("--top-module")
        .arg(top)
        .arg(&waivers)
        .arg(&vfile))?;
    if ok && !log.contains("%Warning") && !log.contains("%Error") {
        Ok(())
    } else {
        Err(FlowError::Lint { top: top.into(), log })
    }
}

/// Result of a Yosys run.
#[derive(Debug, Clone, Default)]
pub struct SynthReport {
    /// Yosys' `stat` output for the flattened top level.
    pub stat: String,
    /// Total number of cells.
    pub cells: usize,
}

/// Which Yosys synthesis script to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SynthTarget {
    /// Generic `synth`.
    Generic,
    /// `synth_ice40` (LUT4 + DFF counts).
    Ice40,
    /// `synth_ecp5` (Lattice ECP5: LUT4, TRELLIS_FF, CCU2C carry cells).
    Ecp5,
    /// `synth_xilinx -family xc7` (7-series: LUT1..6, FDRE/FDSE, CARRY4, I/O buffers).
    Xilinx7,
}

/// Synthesise with Yosys; fail on any latch, on undriven wires and on any
/// other problem `check -assert` reports.
pub fn synth_check(verilog: &str, top: &str, target: SynthTarget) -> Result<SynthReport, FlowError> {
    require("yosys")?;
    let wd = WorkDir::new("synth")?;
    let vfile = wd.path().join(format!("{top}.v"));
    std::fs::write(&vfile, verilog)?;
    let synth = match target {
        SynthTarget::Generic => format!("synth -flatten -top {top}"),
        SynthTarget::Ice40 => format!("synth_ice40 -top {top}"),
        SynthTarget::Ecp5 => format!("synth_ecp5 -top {top}"),
        SynthTarget::Xilinx7 => format!("synth_xilinx -flatten -family xc7 -top {top}"),
    };
    // Latches are looked for right after `proc`, before technology mapping
    // renames them, and again at the end.
    let json = wd.path().join("rtl.json");
    let script = format!(
        "read_verilog {v}; hierarchy -check -top {top}; proc; flatten; \
         select -assert-none t:$dlatch t:$adlatch t:$dlatchsr t:$sr; \
         opt_clean; write_json {json}; \
         {synth}; \
         select -assert-none t:$_DLATCH_* t:$_SR_* t:SB_DFF*_LATCH* t:LDCE t:LDPE; \
         check -assert; tee -o {stat} stat",
        v = vfile.display(),
        json = json.display(),
        stat = wd.path().join("stat.txt").display(),
    );
    let (ok, log) = run(Command::new("yosys").arg("-q").arg("-p").arg(&script))?;
    if !ok {
        return Err(FlowError::Synth { top: top.into(), log });
    }
    let same = same_operand_adders(&std::fs::read_to_string(&json)?)
        .map_err(|e| FlowError::Synth { top: top.into(), log: format!("reading Yosys JSON netlist: {e}") })?;
    if !same.is_empty() {
        return Err(FlowError::Synth {
            top: top.into(),
            log: format!(
                "adder(s) with the same signal on both operands (write `x << 1`, not `x + x`: \
                 nextpnr-ice40 can livelock routing such a carry chain): {}",
                same.join(", ")
            ),
        });
    }
    let stat = std::fs::read_to_string(wd.path().join("stat.txt")).unwrap_or_default();
    let cells = stat
        .lines()
        .find_map(|l| l.trim().strip_prefix("Number of cells:").map(|n| n.trim().parse().unwrap_or(0)))
        .unwrap_or(0);
    Ok(SynthReport { stat, cells })
}

/// The `$add` cells of a Yosys JSON netlist (after `proc; flatten; opt_clean`)
/// whose A and B inputs are the same nets, named by their `src` attribute.
pub fn same_operand_adders(json: &str) -> Result<Vec<String>, serde_json::Error> {
    let v: serde_json::Value = serde_json::from_str(json)?;
    let mut found = Vec::new();
    let modules = v.get("modules").and_then(|m| m.as_object());
    for (mname, m) in modules.into_iter().flatten() {
        let cells = m.get("cells").and_then(|c| c.as_object());
        for (cname, c) in cells.into_iter().flatten() {
            if c.get("type").and_then(|t| t.as_str()) != Some("$add") {
                continue;
            }
            let conn = |k: &str| c.get("connections").and_then(|x| x.get(k)).cloned();
            let (Some(a), Some(b)) = (conn("A"), conn("B")) else { continue };
            // Constant bits are strings ("0", "1"); only a net shared by both
            // operands makes the router's two inputs interchangeable.
            let has_net = a.as_array().map_or(false, |bits| bits.iter().any(|x| x.is_number()));
            if a == b && has_net {
                let src = c.get("attributes").and_then(|x| x.get("src")).and_then(|s| s.as_str()).unwrap_or(cname);
                found.push(format!("{mname}: {src}"));
            }
        }
    }
    Ok(found)
}

mod cosim;
pub use cosim::{cosim, cosim_split, cosim_with_verilog, iverilog_cycles, ports, CosimReport, Port};

/// Run the whole flow (lint, synthesis, co-simulation) on one block.
pub fn full_check<B, F>(uut: &mut B, top: &str, cycles: usize, seed: u64, stimulus: F) -> Result<(SynthReport, CosimReport), FlowError>
where
    B: Clocked,
    F: FnMut(&mut B, &mut ChaCha8Rng, usize),
{
    drive::init(uut);
    let verilog = emit(uut);
    lint(&verilog, "top")?;
    let synth = synth_check(&verilog, "top", SynthTarget::Generic)?;
    let cs = cosim_with_verilog(uut, &verilog, top, cycles, seed, &mut { stimulus })?;
    Ok((synth, cs))
}

/// Seeded RNG used by the stimulus generators.
pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}
