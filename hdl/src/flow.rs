//! The Verilog verification flow every canstar RTL block goes through:
//!
//! 1. emit Verilog with rust-hdl ([`emit`]),
//! 2. `verilator --lint-only -Wall` with the documented waivers of
//!    `verilator/waivers.vlt` ([`lint`]),
//! 3. Yosys synthesis with no latch, no undriven wire and no adder whose two
//!    operands are the same signal ([`synth_check`]; `x + x` becomes an iCE40
//!    carry chain with one net on two interchangeable inputs, on which
//!    nextpnr-ice40 0.4's router can livelock: write a shift),
//! 4. co-simulation: the emitted Verilog runs in Icarus Verilog on the same
//!    random stimulus as the Rust model and every output is compared on every
//!    cycle ([`cosim`]).
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
use std::fmt::Write as _;
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
    };
    // Latches are looked for right after `proc`, before technology mapping
    // renames them, and again at the end.
    let json = wd.path().join("rtl.json");
    let script = format!(
        "read_verilog {v}; hierarchy -check -top {top}; proc; flatten; \
         select -assert-none t:$dlatch t:$adlatch t:$dlatchsr t:$sr; \
         opt_clean; write_json {json}; \
         {synth}; \
         select -assert-none t:$_DLATCH_* t:$_SR_* t:SB_DFF*_LATCH*; \
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

/// One top-level port of a block, as seen by the co-simulation.
#[derive(Debug, Clone)]
pub struct Port {
    pub name: String,
    pub bits: usize,
    pub output: bool,
}

struct PortCollector {
    depth: usize,
    ports: Vec<Port>,
    values: Vec<String>,
    collect_values: bool,
}

fn vcd_to_bits(v: &VCDValue, bits: usize) -> String {
    let ch = |x: &vcd::Value| match x {
        vcd::Value::V0 => '0',
        vcd::Value::V1 => '1',
        vcd::Value::X => 'x',
        vcd::Value::Z => 'z',
    };
    match v {
        VCDValue::Single(x) => ch(x).to_string(),
        VCDValue::Vector(xs) => xs.iter().map(ch).collect(),
        _ => "0".repeat(bits),
    }
}

impl Probe for PortCollector {
    fn visit_start_scope(&mut self, _name: &str, _node: &dyn Block) {
        self.depth += 1;
    }
    fn visit_end_scope(&mut self, _name: &str, _node: &dyn Block) {
        self.depth -= 1;
    }
    fn visit_atom(&mut self, name: &str, signal: &dyn Atom) {
        if self.depth != 1 {
            return;
        }
        let kind = signal.kind();
        let is_clock = signal.descriptor().name == "clock";
        let output = match kind {
            AtomKind::InputParameter => false,
            AtomKind::OutputParameter => true,
            _ => return,
        };
        if is_clock {
            return;
        }
        if self.collect_values {
            self.values.push(vcd_to_bits(&signal.vcd(), signal.bits()));
        } else {
            self.ports.push(Port { name: name.to_string(), bits: signal.bits(), output });
        }
    }
}

/// The non-clock top-level ports of a block, in declaration order.
pub fn ports<B: Block>(uut: &B) -> Vec<Port> {
    let mut c = PortCollector { depth: 0, ports: vec![], values: vec![], collect_values: false };
    uut.accept("top", &mut c);
    c.ports
}

fn port_values<B: Block>(uut: &B) -> Vec<String> {
    let mut c = PortCollector { depth: 0, ports: vec![], values: vec![], collect_values: true };
    uut.accept("top", &mut c);
    c.values
}

/// Summary of a passing co-simulation.
#[derive(Debug, Clone)]
pub struct CosimReport {
    pub cycles: usize,
    pub outputs_compared: usize,
}

fn bits_to_hex(bits: &str) -> String {
    // Pad to a multiple of 4 and convert.
    let pad = (4 - bits.len() % 4) % 4;
    let padded: String = "0".repeat(pad) + bits;
    padded
        .as_bytes()
        .chunks(4)
        .map(|c| {
            let v = c.iter().fold(0u8, |a, b| (a << 1) | (*b == b'1') as u8);
            char::from_digit(v as u32, 16).unwrap()
        })
        .collect()
}

/// Co-simulate a block against its own emitted Verilog.
///
/// The block is initialised, then for `cycles` cycles `stimulus` sets its
/// inputs (through `.next`) from the seeded random generator; the Rust model
/// settles and its outputs are recorded before the rising edge. The same
/// input vectors drive the Verilog in Icarus Verilog, which checks every
/// output at the same point of every cycle. The first mismatches are
/// reported with cycle number, port and both values.
pub fn cosim<B, F>(uut: &mut B, top: &str, cycles: usize, seed: u64, mut stimulus: F) -> Result<CosimReport, FlowError>
where
    B: Clocked,
    F: FnMut(&mut B, &mut ChaCha8Rng, usize),
{
    drive::init(uut);
    let verilog = emit(uut);
    cosim_with_verilog(uut, &verilog, top, cycles, seed, &mut stimulus)
}

/// As [`cosim`], with the Verilog under test given explicitly (it must have
/// a module `top` with the block's ports). Used by the test that shows the
/// flow catches a Verilog that differs from the model.
pub fn cosim_with_verilog<B, F>(
    uut: &mut B,
    verilog: &str,
    top: &str,
    cycles: usize,
    seed: u64,
    stimulus: &mut F,
) -> Result<CosimReport, FlowError>
where
    B: Clocked,
    F: FnMut(&mut B, &mut ChaCha8Rng, usize),
{
    require("iverilog")?;
    require("vvp")?;
    let ports = ports(uut);
    let inputs: Vec<&Port> = ports.iter().filter(|p| !p.output).collect();
    let outputs: Vec<&Port> = ports.iter().filter(|p| p.output).collect();
    let in_bits: usize = inputs.iter().map(|p| p.bits).sum();
    let out_bits: usize = outputs.iter().map(|p| p.bits).sum();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut in_mem = String::with_capacity(cycles * (in_bits / 4 + 2));
    let mut out_mem = String::with_capacity(cycles * (out_bits / 4 + 2));
    for i in 0..cycles {
        stimulus(uut, &mut rng, i);
        drive::settle(uut);
        let vals = port_values(uut);
        let (mut ib, mut ob) = (String::new(), String::new());
        for (p, v) in ports.iter().zip(vals.iter()) {
            if p.output {
                ob.push_str(v);
            } else {
                ib.push_str(v);
            }
        }
        if in_bits > 0 {
            in_mem.push_str(&bits_to_hex(&ib));
            in_mem.push('\n');
        }
        out_mem.push_str(&bits_to_hex(&ob));
        out_mem.push('\n');
        drive::rising_edge(uut);
        drive::falling_edge(uut);
    }
    let wd = WorkDir::new("cosim")?;
    std::fs::write(wd.path().join("dut.v"), verilog)?;
    std::fs::write(wd.path().join("in.hex"), &in_mem)?;
    std::fs::write(wd.path().join("out.hex"), &out_mem)?;
    let tb = testbench(&inputs, &outputs, in_bits, out_bits, cycles);
    std::fs::write(wd.path().join("tb.v"), &tb)?;
    let (ok, log) = run(Command::new("iverilog")
        .current_dir(wd.path())
        .args(["-g2012", "-o", "sim.vvp", "-s", "tb", "tb.v", "dut.v"]))?;
    if !ok {
        return Err(FlowError::Cosim { top: top.into(), detail: format!("iverilog failed:\n{log}") });
    }
    let (ok, log) = run(Command::new("vvp").current_dir(wd.path()).args(["-n", "sim.vvp"]))?;
    let passed = log.lines().any(|l| l.trim() == format!("COSIM PASS {cycles}"));
    if !ok || !passed {
        let excerpt: String = log.lines().filter(|l| !l.starts_with("VCD")).take(40).collect::<Vec<_>>().join("\n");
        return Err(FlowError::Cosim { top: top.into(), detail: excerpt });
    }
    Ok(CosimReport { cycles, outputs_compared: outputs.len() })
}

fn testbench(inputs: &[&Port], outputs: &[&Port], in_bits: usize, out_bits: usize, cycles: usize) -> String {
    let mut s = String::new();
    let w = |n: usize| if n > 1 { format!("[{}:0] ", n - 1) } else { String::new() };
    writeln!(s, "`timescale 1ns/1ps\nmodule tb;").unwrap();
    writeln!(s, "  reg clock = 1'b0;").unwrap();
    for p in inputs {
        writeln!(s, "  reg {}{} ;", w(p.bits), p.name).unwrap();
    }
    for p in outputs {
        writeln!(s, "  wire {}{} ;", w(p.bits), p.name).unwrap();
    }
    if in_bits > 0 {
        writeln!(s, "  reg [{}:0] in_mem [0:{}];", in_bits - 1, cycles - 1).unwrap();
    }
    writeln!(s, "  reg [{}:0] out_mem [0:{}];", out_bits.max(1) - 1, cycles - 1).unwrap();
    writeln!(s, "  reg [{}:0] exp;", out_bits.max(1) - 1).unwrap();
    writeln!(s, "  integer i; integer errors;").unwrap();
    let conns: Vec<String> = std::iter::once(".clock(clock)".to_string())
        .chain(inputs.iter().chain(outputs.iter()).map(|p| format!(".{0}({0})", p.name)))
        .collect();
    writeln!(s, "  top dut({});", conns.join(", ")).unwrap();
    writeln!(s, "  initial begin").unwrap();
    if in_bits > 0 {
        writeln!(s, "    $readmemh(\"in.hex\", in_mem);").unwrap();
    }
    writeln!(s, "    $readmemh(\"out.hex\", out_mem);").unwrap();
    writeln!(s, "    errors = 0;").unwrap();
    writeln!(s, "    for (i = 0; i < {cycles}; i = i + 1) begin").unwrap();
    if in_bits > 0 {
        let names: Vec<&str> = inputs.iter().map(|p| p.name.as_str()).collect();
        writeln!(s, "      {{{}}} = in_mem[i];", names.join(", ")).unwrap();
    }
    writeln!(s, "      #5;").unwrap();
    writeln!(s, "      exp = out_mem[i];").unwrap();
    let mut hi = out_bits;
    for p in outputs {
        let lo = hi - p.bits;
        let slice = if p.bits == 1 { format!("exp[{lo}]") } else { format!("exp[{}:{}]", hi - 1, lo) };
        writeln!(
            s,
            "      if ({n} !== {slice}) begin errors = errors + 1; $display(\"MISMATCH cycle %0d port {n}: verilog %h rust %h\", i, {n}, {slice}); end",
            n = p.name
        )
        .unwrap();
        hi = lo;
    }
    writeln!(s, "      if (errors > 10) begin $display(\"COSIM FAIL\"); $finish; end").unwrap();
    writeln!(s, "      #5 clock = 1'b1;\n      #5 clock = 1'b0;").unwrap();
    writeln!(s, "    end").unwrap();
    writeln!(s, "    if (errors == 0) $display(\"COSIM PASS {cycles}\"); else $display(\"COSIM FAIL\");").unwrap();
    writeln!(s, "    $finish;\n  end\nendmodule").unwrap();
    s
}

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
