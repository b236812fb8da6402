//! The top module of a bitstream (`<design>_pll`): the board oscillator into an
//! iCE40 `SB_PLL40_CORE`, the design's board top clocked by the PLL's global
//! output, its active-low reset held low until the PLL has locked (and
//! released through two flip-flops on the design clock), and those of the
//! design's ports that have a pin. A debug output is exposed in part when the
//! board's debug pins run out inside it (`bic[5:0]` of `bic[23:0]`); the rest is
//! left unconnected and Yosys removes the logic that only drives it.

use super::pll::PllSettings;
use anyhow::{bail, Result};

/// One port of the design's board top as the bitstream top exposes it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Exposed {
    pub name: String,
    /// Width of the design's port.
    pub bits: usize,
    /// Bits exposed (0: none, the port stays inside).
    pub exposed: usize,
    pub output: bool,
}

/// Prefix of the top's own nets (no design port starts with it).
const NET: &str = "canstar_pll_";

/// The Verilog of the top `name` around `design_top`, whose clock input is
/// `clock` and active-low reset `rst_n`; `board_clock` is the oscillator port.
pub fn pll_top(name: &str, design_top: &str, ports: &[Exposed], board_clock: &str, pll: &PllSettings) -> Result<String> {
    for p in ports {
        if p.name.starts_with(NET) || (p.name == board_clock && p.name != "clock") {
            bail!("design {design_top}: port {} clashes with a net of the bitstream top", p.name);
        }
        if !p.output && p.name != "clock" && p.exposed != p.bits {
            bail!("design {design_top}: input {} has {} of its {} bits on pins", p.name, p.exposed, p.bits);
        }
    }
    for need in ["clock", "rst_n"] {
        if !ports.iter().any(|p| p.name == need && !p.output && p.bits == 1) {
            bail!("design {design_top} has no 1-bit input `{need}` for the bitstream top to drive");
        }
    }
    let range = |bits: usize| if bits > 1 { format!("[{}:0] ", bits - 1) } else { String::new() };
    let shown: Vec<&Exposed> = ports.iter().filter(|p| p.name != "clock" && p.exposed > 0).collect();
    let mut names = vec![board_clock.to_string()];
    names.extend(shown.iter().map(|p| p.name.clone()));
    let mut v = format!("module {name}({});\n", names.join(", "));
    v += &format!("    input wire {board_clock};\n");
    for p in &shown {
        v += &format!("    {} wire {}{};\n", if p.output { "output" } else { "input" }, range(p.exposed), p.name);
    }
    v += &format!("    wire {NET}clock;\n    wire {NET}lock;\n");
    v += &format!("    reg [1:0] {NET}reset = 2'b00;\n");
    v += &format!(
        "    SB_PLL40_CORE #({}) {NET}core (\n        .REFERENCECLK({board_clock}),\n        .PLLOUTGLOBAL({NET}clock),\n        .LOCK({NET}lock),\n        .RESETB(1'b1),\n        .BYPASS(1'b0)\n    );\n",
        pll.parameters()
    );
    v += &format!("    always @(posedge {NET}clock) {NET}reset <= {{{NET}reset[0], rst_n & {NET}lock}};\n");
    let mut conns = vec![];
    for p in ports {
        let c = match p.name.as_str() {
            "clock" => format!("{NET}clock"),
            "rst_n" => format!("{NET}reset[1]"),
            n if p.exposed == p.bits => n.to_string(),
            _ if p.exposed == 0 => String::new(),
            n => {
                v += &format!("    wire {}{NET}{n};\n", range(p.bits));
                v += &format!("    assign {n} = {NET}{n}[{}:0];\n", p.exposed - 1);
                format!("{NET}{n}")
            }
        };
        conns.push(format!("        .{}({c})", p.name));
    }
    v += &format!("    {design_top} {NET}design (\n{}\n    );\nendmodule // {name}\n", conns.join(",\n"));
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn port(name: &str, bits: usize, exposed: usize, output: bool) -> Exposed {
        Exposed { name: name.into(), bits, exposed, output }
    }

    #[test]
    fn the_top_clocks_the_design_from_the_pll_and_exposes_what_has_pins() {
        let pll = super::super::pll::closest(100_000_000, 14_740_000).unwrap();
        let ports = [
            port("clock", 1, 1, false),
            port("rst_n", 1, 1, false),
            port("rx", 3, 3, false),
            port("tx", 3, 3, true),
            port("bic", 24, 6, true),
            port("nack", 9, 0, true),
        ];
        let v = pll_top("d_pll", "d", &ports, "clock", &pll).unwrap();
        for s in [
            "module d_pll(clock, rst_n, rx, tx, bic);",
            "input wire clock;",
            "input wire [2:0] rx;",
            "output wire [5:0] bic;",
            "SB_PLL40_CORE #(.FEEDBACK_PATH(\"SIMPLE\"), .PLLOUT_SELECT(\"GENCLK_HALF\"), .DIVR(4'd6), .DIVF(7'd65), .DIVQ(3'd5), .FILTER_RANGE(3'd1))",
            ".REFERENCECLK(clock)",
            ".PLLOUTGLOBAL(canstar_pll_clock)",
            "canstar_pll_reset <= {canstar_pll_reset[0], rst_n & canstar_pll_lock};",
            ".clock(canstar_pll_clock)",
            ".rst_n(canstar_pll_reset[1])",
            ".rx(rx)",
            "wire [23:0] canstar_pll_bic;",
            "assign bic = canstar_pll_bic[5:0];",
            ".bic(canstar_pll_bic)",
            ".nack()",
        ] {
            assert!(v.contains(s), "missing `{s}` in\n{v}");
        }
        assert!(!v.contains("output wire [8:0] nack"), "{v}");
    }

    #[test]
    fn an_input_without_all_its_pins_or_without_a_reset_is_refused() {
        let pll = super::super::pll::closest(100_000_000, 16_000_000).unwrap();
        let e = pll_top("t", "d", &[port("clock", 1, 1, false), port("rst_n", 1, 1, false), port("rx", 3, 2, false)], "clock", &pll).unwrap_err();
        assert!(e.to_string().contains("input rx has 2 of its 3 bits"), "{e}");
        let e = pll_top("t", "d", &[port("clock", 1, 1, false)], "clock", &pll).unwrap_err();
        assert!(e.to_string().contains("no 1-bit input `rst_n`"), "{e}");
    }
}
