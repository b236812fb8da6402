//! The primitives canstar's designs use, recognised by their ports and their exact
//! Verilog text (rust-hdl emits them as `Verilog::Custom`): `DFF<T>` and `RAM<D, N>`
//! (rust-hdl-widgets). Any other custom Verilog is rejected by the caller.

use rust_hdl::core::prelude::AtomKind;

use crate::collect::{parse_literal, Hierarchy, ValueType};

/// A recognised primitive: atom indices of its ports.
#[derive(Clone, Debug, PartialEq)]
pub enum Prim {
    Dff { d: usize, q: usize, clock: usize, init: u128 },
    Ram { read_address: usize, read_clock: usize, read_data: usize, write_address: usize, write_clock: usize, write_data: usize, write_enable: usize, init: Vec<(u128, u128)> },
}

fn norm(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The module's atoms by name, if they are exactly `want` (name, kind, is-clock).
fn ports(h: &Hierarchy, m: usize, want: &[(&str, AtomKind, bool)]) -> Option<Vec<usize>> {
    let atoms = &h.modules[m].atoms;
    if atoms.len() != want.len() || !h.modules[m].children.is_empty() {
        return None;
    }
    let mut out = vec![];
    for (name, kind, clock) in want {
        let a = *atoms.iter().find(|&&a| h.atoms[a].name == *name)?;
        let at = &h.atoms[a];
        if at.kind != *kind || (at.ty == ValueType::Clock) != *clock {
            return None;
        }
        out.push(a);
    }
    Some(out)
}

/// Recognise the custom Verilog `text` of module `m`.
pub fn recognise(h: &Hierarchy, m: usize, text: &str) -> Option<Prim> {
    use AtomKind::{InputParameter as I, OutputParameter as O};
    if let Some(p) = ports(h, m, &[("d", I, false), ("q", O, false), ("clock", I, true)]) {
        let t = norm(text);
        let rest = t.strip_prefix("initial begin q = ")?;
        let (lit, rest) = rest.split_once(';')?;
        if rest.trim() != "end always @(posedge clock) begin q <= d; end" {
            return None;
        }
        let (init, _) = parse_literal(lit.trim()).ok()?;
        return Some(Prim::Dff { d: p[0], q: p[1], clock: p[2], init });
    }
    let want = [
        ("read_address", I, false),
        ("read_clock", I, true),
        ("read_data", O, false),
        ("write_address", I, false),
        ("write_clock", I, true),
        ("write_data", I, false),
        ("write_enable", I, false),
    ];
    if let Some(p) = ports(h, m, &want) {
        let dw = h.atoms[p[2]].width;
        let aw = h.atoms[p[0]].width;
        if h.atoms[p[3]].width != aw || h.atoms[p[5]].width != dw || h.atoms[p[6]].width != 1 || aw >= 24 {
            return None;
        }
        let t = norm(text);
        let head = format!("reg[{}:0] mem[{}:0];", dw - 1, (1u64 << aw) - 1);
        let rest = t.strip_prefix(&head)?.trim_start();
        let tail = "always @(posedge read_clock) begin read_data <= mem[read_address]; end \
                    always @(posedge write_clock) begin if (write_enable) begin mem[write_address] <= write_data; end end";
        let init_text = rest.strip_suffix(tail)?.trim();
        let mut init = vec![];
        if !init_text.is_empty() {
            let body = init_text.strip_prefix("initial begin")?.strip_suffix("end")?;
            for item in body.split(';').map(str::trim).filter(|s| !s.is_empty()) {
                let (lhs, rhs) = item.split_once('=')?;
                let addr = lhs.trim().strip_prefix("mem[")?.strip_suffix(']')?;
                let (a, _) = parse_literal(addr).ok()?;
                let (v, _) = parse_literal(rhs.trim()).ok()?;
                init.push((a, v));
            }
        }
        return Some(Prim::Ram {
            read_address: p[0],
            read_clock: p[1],
            read_data: p[2],
            write_address: p[3],
            write_clock: p[4],
            write_data: p[5],
            write_enable: p[6],
            init,
        });
    }
    None
}

/// The custom text of a module with the memory contents left out (for the shape
/// fingerprint: initial contents are data, not structure).
pub fn masked_text(text: &str) -> String {
    let t = norm(text);
    match (t.find("initial begin mem["), t.find("always @(posedge read_clock)")) {
        (Some(a), Some(b)) if a < b => format!("{}{}", &t[..a], &t[b..]),
        _ => t,
    }
}
