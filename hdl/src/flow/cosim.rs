//! Co-simulation: the emitted Verilog against the Rust model, every output on
//! every cycle. The Rust model records its input and output vectors; a generated
//! testbench replays the inputs and compares the outputs. Icarus Verilog (4-state:
//! an X, an uninitialised register or a race shows there) simulates the first
//! [`iverilog_cycles`] cycles; a run too long for Icarus is then simulated in full by Verilator
//! (`--binary`, 2-state, about a hundred times faster than Icarus on canstar's
//! designs), so long stimuli cost seconds instead of minutes.

use super::{emit, require, run, FlowError, WorkDir};
use crate::drive::{self, Clocked};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rust_hdl::prelude::*;
use std::fmt::Write as _;
use std::process::Command;

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
    /// Cycles compared (by Verilator when more than `iverilog_cycles`).
    pub cycles: usize,
    /// Cycles Icarus Verilog simulated (the first ones).
    pub iverilog_cycles: usize,
    /// Cycles Verilator simulated (all of them, or 0 when Icarus did).
    pub verilator_cycles: usize,
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
/// input vectors drive the Verilog in Icarus Verilog (the first
/// [`iverilog_cycles`] cycles) and, for long runs of large designs, in
/// Verilator (every cycle); the testbench checks every output at the same
/// point of every cycle. The first mismatches are
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
    let ivl = iverilog_cycles(cycles, verilog.len());
    cosim_split(uut, verilog, top, cycles, seed, stimulus, ivl)
}

/// As [`cosim_with_verilog`], with Icarus simulating the first `ivl_cycles`
/// cycles and Verilator all of them when `ivl_cycles < cycles`.
pub fn cosim_split<B, F>(
    uut: &mut B,
    verilog: &str,
    top: &str,
    cycles: usize,
    seed: u64,
    stimulus: &mut F,
    ivl_cycles: usize,
) -> Result<CosimReport, FlowError>
where
    B: Clocked,
    F: FnMut(&mut B, &mut ChaCha8Rng, usize),
{
    require("iverilog")?;
    require("vvp")?;
    let ivl_cycles = ivl_cycles.min(cycles);
    if ivl_cycles < cycles {
        require("verilator")?;
    }
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
    let (ok, log) = run(Command::new("vvp").current_dir(wd.path()).args(["-n", "sim.vvp"]).arg(format!("+cycles={ivl_cycles}")))?;
    check_log(top, "Icarus Verilog", ok, &log, ivl_cycles)?;
    let mut verilator_cycles = 0;
    if ivl_cycles < cycles {
        // `--binary` builds the testbench with its delays (`--timing`); the C++ is
        // compiled at -O1, which here costs less compile time than -O3 saves
        let (ok, log) = run(Command::new("verilator")
            .current_dir(wd.path())
            .args(["--binary", "-j", "1", "-Wno-fatal", "-Wno-lint", "-Wno-style", "--top-module", "tb", "-o", "simv"])
            .args(["-MAKEFLAGS", "OPT_FAST=-O1 OPT_SLOW=-O1 OPT_GLOBAL=-O1", "tb.v", "dut.v"]))?;
        if !ok {
            return Err(FlowError::Cosim { top: top.into(), detail: format!("verilator failed:\n{log}") });
        }
        let (ok, log) = run(Command::new(wd.path().join("obj_dir/simv")).current_dir(wd.path()).arg(format!("+cycles={cycles}")))?;
        check_log(top, "Verilator", ok, &log, cycles)?;
        verilator_cycles = cycles;
    }
    Ok(CosimReport { cycles, iverilog_cycles: ivl_cycles, verilator_cycles, outputs_compared: outputs.len() })
}

/// Cycles of a co-simulation that Icarus Verilog simulates, for a run of
/// `cycles` cycles of a Verilog source of `verilog_bytes` bytes:
/// `CANSTAR_COSIM_IVERILOG_CYCLES` when set (a large number runs every cycle in
/// Icarus), otherwise every cycle while Icarus needs about as long as building
/// the Verilator testbench (cycles x bytes up to 4e9, about 8 s of Icarus on
/// the build machine), and a prefix of that budget (at least 2 000 cycles)
/// otherwise. The rest is Verilator's.
pub fn iverilog_cycles(cycles: usize, verilog_bytes: usize) -> usize {
    const BUDGET: usize = 4_000_000_000;
    if let Some(n) = std::env::var("CANSTAR_COSIM_IVERILOG_CYCLES").ok().and_then(|v| v.trim().parse().ok()) {
        return cycles.min(n);
    }
    cycles.min((BUDGET / verilog_bytes.max(1)).max(2_000))
}

fn check_log(top: &str, simulator: &str, ok: bool, log: &str, cycles: usize) -> Result<(), FlowError> {
    if ok && log.lines().any(|l| l.trim() == format!("COSIM PASS {cycles}")) {
        return Ok(());
    }
    let excerpt: String = log.lines().filter(|l| !l.starts_with("VCD")).take(40).collect::<Vec<_>>().join("\n");
    Err(FlowError::Cosim { top: top.into(), detail: format!("{simulator}:\n{excerpt}") })
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
    writeln!(s, "  integer i; integer errors; integer n;").unwrap();
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
    writeln!(s, "    if (!$value$plusargs(\"cycles=%d\", n) || n > {cycles}) n = {cycles};").unwrap();
    writeln!(s, "    for (i = 0; i < n; i = i + 1) begin").unwrap();
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
    writeln!(s, "    if (errors == 0) $display(\"COSIM PASS %0d\", n); else $display(\"COSIM FAIL\");").unwrap();
    writeln!(s, "    $finish;\n  end\nendmodule").unwrap();
    s
}

#[cfg(test)]
mod tests {
    use super::iverilog_cycles;

    #[test]
    fn icarus_takes_small_runs_whole_and_a_prefix_of_large_ones() {
        if std::env::var_os("CANSTAR_COSIM_IVERILOG_CYCLES").is_some() {
            return; // the override decides
        }
        assert_eq!(iverilog_cycles(30_000, 2_000), 30_000, "a block's 30 000 cycles stay in Icarus");
        assert_eq!(iverilog_cycles(100_000, 315_000), 12_698, "the hub gets a prefix of the budget");
        assert_eq!(iverilog_cycles(100_000, 40_000_000), 2_000, "at least 2 000 cycles in Icarus");
        assert_eq!(iverilog_cycles(500, 40_000_000), 500);
    }
}
