//! `canstar report`: logic size and fmax of the generated designs.
//!
//! - iCE40-HX8K (CB132, the Alchitry Cu's package): Yosys `synth_ice40`, then
//!   `nextpnr-ice40` with several seeds ([`seeds`]), each under a watchdog
//!   ([`pnr`]), for the placed logic-cell count and the best and median fmax;
//! - Xilinx Spartan-3 (the XSA-3S1000's family; Yosys `synth_xilinx -family
//!   xc3s -flatten`, marked experimental by Yosys; flattened like `synth_ice40`,
//!   so that constants propagate across module boundaries): LUT and flip-flop
//!   counts, no place and route (there is no open Spartan-3 flow).

#[doc(hidden)]
pub mod fake;
pub mod pnr;
pub mod seeds;

use anyhow::{bail, Context, Result};
use pnr::{Pnr, SeedRun};
use seeds::Seeds;
use std::process::Command;

/// One row of the report.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Row {
    pub design: String,
    /// iCE40: SB_LUT4 cells after synthesis.
    pub ice40_lut4: usize,
    /// iCE40: flip-flops (SB_DFF*) after synthesis.
    pub ice40_dff: usize,
    /// iCE40: block RAMs (SB_RAM40_4K).
    pub ice40_bram: usize,
    /// iCE40: the place-and-route runs, if nextpnr ran: placed logic cells
    /// (ICESTORM_LC, including the measurement wrapper's flip-flops, see
    /// [`pnr_wrapper`]) and fmax per seed.
    pub pnr: Option<Seeds>,
    /// Why nextpnr did not run, if it did not.
    pub pnr_note: Option<String>,
    /// Spartan-3: LUTs (LUT1..LUT4).
    pub xc3s_lut: usize,
    /// Spartan-3: flip-flops (FD*).
    pub xc3s_ff: usize,
}

fn have(tool: &str) -> bool {
    canstar_hdl::flow::have_tool(tool)
}

fn count_cells(stat: &str, pred: impl Fn(&str) -> bool) -> usize {
    // Lines of Yosys `stat` look like "     SB_LUT4                       123". An
    // unflattened design lists every module and then the totals of the hierarchy.
    let stat = stat.split("=== design hierarchy ===").last().unwrap_or(stat);
    stat.lines()
        .filter_map(|l| {
            let mut it = l.split_whitespace();
            let name = it.next()?;
            let n: usize = it.next()?.parse().ok()?;
            if it.next().is_none() && pred(name) { Some(n) } else { None }
        })
        .sum()
}

fn yosys(script: &str) -> Result<String> {
    let out = Command::new("yosys").arg("-q").arg("-p").arg(script).output().context("running yosys")?;
    if !out.status.success() {
        bail!("yosys failed:\n{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// A measurement wrapper for designs with more ports than the package has
/// pins: every input of `top` (but `clock`) comes from one long shift
/// register fed by pin `sin`, every output is registered and XOR-reduced to
/// pin `sout`, so nothing is optimised away and nextpnr can place the design
/// with three I/Os. The wrapper's own flip-flops (one per port bit) are
/// included in the placed figures.
pub fn pnr_wrapper(verilog: &str, top: &str) -> (String, String) {
    let ports = crate::verilog::parse_ports(verilog, top);
    let inb: usize = ports.iter().filter(|p| !p.2 && p.0 != "clock").map(|p| p.1).sum();
    let outb: usize = ports.iter().filter(|p| p.2).map(|p| p.1).sum();
    let name = format!("{top}_pnr");
    let mut w = String::new();
    w += &format!("module {name}(input wire clock, input wire sin, output reg sout);\n");
    w += &format!("  reg [{}:0] chain = 0;\n", inb.max(1) - 1);
    w += &format!("  wire [{}:0] outs;\n", outb.max(1) - 1);
    w += &format!("  reg [{}:0] outs_r = 0;\n", outb.max(1) - 1);
    w += "  always @(posedge clock) begin\n";
    if inb > 1 {
        w += &format!("    chain <= {{chain[{}:0], sin}};\n", inb - 2);
    } else {
        w += "    chain <= sin;\n";
    }
    w += "    outs_r <= outs;\n    sout <= ^outs_r;\n  end\n";
    let mut conns = vec![".clock(clock)".to_string()];
    let (mut ib, mut ob) = (0usize, 0usize);
    for (n, b, out) in &ports {
        if n == "clock" {
            continue;
        }
        let (base, acc) = if *out { ("outs", &mut ob) } else { ("chain", &mut ib) };
        conns.push(format!(".{n}({base}[{}:{}])", *acc + b - 1, *acc));
        *acc += b;
    }
    w += &format!("  {top} dut({});\nendmodule\n", conns.join(", "));
    (format!("{verilog}\n{w}"), name)
}

/// Synthesise one design, and place and route it with seeds 1..=`seeds` if
/// `pnr` is given and its program is present; `on_run` sees each seed's run.
pub fn measure(design: &str, verilog: &str, top: &str, pnr: Option<&Pnr>, seeds: u64, on_run: &mut dyn FnMut(&SeedRun)) -> Result<Row> {
    if !have("yosys") {
        bail!("yosys not found on PATH (scripts/test-all.sh installs it)");
    }
    let wd = canstar_hdl::flow::WorkDir::new("report")?;
    let v = wd.path().join(format!("{top}.v"));
    std::fs::write(&v, verilog)?;
    let json = wd.path().join("ice40.json");
    let ice_stat = wd.path().join("ice40.stat");
    yosys(&format!(
        "read_verilog {v}; synth_ice40 -top {top} -json {json}; tee -q -o {s} stat",
        v = v.display(),
        json = json.display(),
        s = ice_stat.display()
    ))?;
    let ice = std::fs::read_to_string(&ice_stat)?;
    let xil_stat = wd.path().join("xc3s.stat");
    yosys(&format!(
        "read_verilog {v}; synth_xilinx -family xc3s -flatten -top {top}; tee -q -o {s} stat",
        v = v.display(),
        s = xil_stat.display()
    ))?;
    let xil = std::fs::read_to_string(&xil_stat)?;
    let mut row = Row {
        design: design.to_string(),
        ice40_lut4: count_cells(&ice, |n| n == "SB_LUT4"),
        ice40_dff: count_cells(&ice, |n| n.starts_with("SB_DFF")),
        ice40_bram: count_cells(&ice, |n| n.starts_with("SB_RAM40")),
        xc3s_lut: count_cells(&xil, |n| n.starts_with("LUT") && n.len() == 4),
        xc3s_ff: count_cells(&xil, |n| n.starts_with("FD")),
        ..Default::default()
    };
    match pnr {
        None => row.pnr_note = Some("place and route skipped (--pnr-timeout 0)".into()),
        Some(p) if !have(&p.program) => row.pnr_note = Some(format!("{} not installed", p.program)),
        Some(p) => {
            // Place the measurement wrapper, so that designs with wide native
            // interfaces fit the package too.
            let (wrapped, wtop) = pnr_wrapper(verilog, top);
            let wv = wd.path().join("wrapped.v");
            std::fs::write(&wv, wrapped)?;
            let wjson = wd.path().join("wrapped.json");
            yosys(&format!("read_verilog {}; synth_ice40 -top {wtop} -json {}", wv.display(), wjson.display()))?;
            row.pnr = Some(seeds::place(p, &wjson, seeds, on_run).with_context(|| format!("place and route of {design}"))?);
        }
    }
    Ok(row)
}

/// Render rows as a Markdown table, followed by a line for every design or seed
/// without place-and-route figures and a legend for fmax below the requested
/// frequency.
pub fn table(rows: &[Row]) -> String {
    let mut s = String::from(
        "| design | iCE40 LUT4 | iCE40 DFF | iCE40 BRAM | iCE40 LCs placed (seed) | iCE40 fmax median | iCE40 fmax best | seeds placed | Spartan-3 LUT | Spartan-3 FF |\n\
         |---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    let mut below = None;
    for r in rows {
        let (mut lc, mut med, mut best, mut n) = ("-".to_string(), "-".to_string(), "-".to_string(), "-".to_string());
        if let Some(p) = &r.pnr {
            let mut mhz = |f: f64| {
                if f < p.freq_mhz {
                    below = Some(p.freq_mhz);
                    format!("{f:.1} MHz *")
                } else {
                    format!("{f:.1} MHz")
                }
            };
            if let Some(m) = p.median() {
                lc = format!("{} (seed {})", m.lc, m.seed);
                med = mhz(m.fmax_mhz);
            }
            if let Some(b) = p.best() {
                best = format!("{} (seed {})", mhz(b.fmax_mhz), b.seed);
            }
            n = format!("{}/{}", p.placed().len(), p.runs.len());
        }
        s.push_str(&format!(
            "| {} | {} | {} | {} | {lc} | {med} | {best} | {n} | {} | {} |\n",
            r.design, r.ice40_lut4, r.ice40_dff, r.ice40_bram, r.xc3s_lut, r.xc3s_ff
        ));
    }
    if let Some(f) = below {
        s.push_str(&format!("\n\\* below the requested {f} MHz (nextpnr --timing-allow-fail: the achieved fmax)\n"));
    }
    for r in rows {
        if let Some(n) = &r.pnr_note {
            s.push_str(&format!("\n{}: no place-and-route figures ({n})", r.design));
        }
        if let Some(n) = r.pnr.as_ref().and_then(|p| p.note(&r.design)) {
            s.push_str(&format!("\n{n}"));
        }
    }
    s
}

/// Versions of the tools used, for the README.
pub fn tool_versions() -> String {
    let v = |cmd: &str, arg: &str| {
        Command::new(cmd)
            .arg(arg)
            .output()
            .ok()
            .map(|o| {
                let s = String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
                s.lines().next().unwrap_or("").trim().to_string()
            })
            .unwrap_or_else(|| format!("{cmd}: not found"))
    };
    format!("{}; {}", v("yosys", "-V"), v("nextpnr-ice40", "--version"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_use_the_hierarchy_totals() {
        let stat = "=== a ===\n     LUT3   29\n=== a$b ===\n     FDRE  15\n=== design hierarchy ===\n     FDRE  15\n     LUT1  6\n     LUT3  29\n";
        assert_eq!(count_cells(stat, |n| n.starts_with("FD")), 15);
        assert_eq!(count_cells(stat, |n| n.starts_with("LUT") && n.len() == 4), 35);
        let flat = "=== a ===\n   Number of cells: 52\n     SB_LUT4   23\n     SB_DFFESR  15\n";
        assert_eq!(count_cells(flat, |n| n == "SB_LUT4"), 23);
        assert_eq!(count_cells(flat, |n| n.starts_with("SB_DFF")), 15);
    }
}

#[cfg(test)]
mod table_tests {
    use super::pnr::Outcome;
    use super::*;

    fn row(design: &str, runs: Vec<(u64, Outcome)>) -> Row {
        let runs = runs.into_iter().map(|(seed, outcome)| SeedRun { seed, outcome, secs: 2.0 }).collect();
        Row { design: design.into(), ice40_lut4: 9, pnr: Some(Seeds { freq_mhz: 50.0, runs }), ..Default::default() }
    }

    #[test]
    fn table_gives_median_best_and_a_line_for_every_design_without_figures() {
        let placed = |lc, fmax_mhz| Outcome::Placed { lc, fmax_mhz };
        let rows = [
            row("a", vec![(1, placed(49, 235.5)), (2, placed(49, 240.0)), (3, Outcome::Stalled { stall_s: 60.0 })]),
            row("b", vec![(1, placed(2871, 47.39)), (2, placed(2871, 51.5)), (3, placed(2871, 46.21))]),
            row("c", vec![(1, Outcome::Stalled { stall_s: 60.0 }), (2, Outcome::TimedOut)]),
            Row { design: "d".into(), pnr_note: Some("place and route skipped (--pnr-timeout 0)".into()), ..Default::default() },
        ];
        let t = table(&rows);
        assert!(t.contains("| a | 9 | 0 | 0 | 49 (seed 1) | 235.5 MHz | 240.0 MHz (seed 2) | 2/3 |"), "{t}");
        assert!(t.contains("| b | 9 | 0 | 0 | 2871 (seed 1) | 47.4 MHz * | 51.5 MHz (seed 2) | 3/3 |"), "{t}");
        assert!(t.contains("| c | 9 | 0 | 0 | - | - | - | 0/2 |"), "{t}");
        assert!(t.contains("\\* below the requested 50 MHz"), "{t}");
        assert!(t.contains("\na: 2 of 3 seeds placed (seed 3: stalled: no router progress for 60 s, killed after 2 s)"), "{t}");
        assert!(t.contains("\nc: not placed (seed 1: stalled: no router progress for 60 s, killed after 2 s; seed 2: did not finish within 2 s, killed)"), "{t}");
        assert!(t.contains("\nd: no place-and-route figures (place and route skipped"), "{t}");
        assert!(!t.contains("\nb:"), "{t}");
    }
}

#[cfg(test)]
mod wrapper_tests {
    use super::*;

    #[test]
    fn wrapper_connects_every_port_bit() {
        let v = "module top(clock,a,b,y);\n    input wire  clock;\n    input wire  [3:0] a;\n    input wire  b;\n    output reg  [1:0] y;\nendmodule // top\n";
        assert_eq!(crate::verilog::parse_ports(v, "top"), vec![("clock".into(), 1, false), ("a".into(), 4, false), ("b".into(), 1, false), ("y".into(), 2, true)]);
        let (w, name) = pnr_wrapper(v, "top");
        assert_eq!(name, "top_pnr");
        assert!(w.contains("reg [4:0] chain") && w.contains(".a(chain[3:0])") && w.contains(".b(chain[4:4])") && w.contains(".y(outs[1:0])"), "{w}");
    }
}
