//! `canstar boards`: the built-in boards (or the board files given), with FPGA
//! family, part, clock, pin-file format, the roles `canstar build` makes a
//! bitstream of on it and the designs it has a pinout for.

use anyhow::Result;
use canstar::boards::{Board, BUILTIN};

#[derive(clap::Args)]
pub struct Args {
    /// Board names or board .toml files to check and list (default: every built-in board).
    boards: Vec<String>,
}

/// `14740000` -> `14.74 MHz`.
fn mhz(hz: u64) -> String {
    format!("{} MHz", hz as f64 / 1e6)
}

/// The roles `canstar build` can make a bitstream of on a board: those of its
/// pinouts that are registered roles, on an iCE40 board with a PCF; `-` for
/// other families (`canstar build` says "bitstream not supported for family X").
fn bitstream(b: &Board) -> String {
    if b.family != "ice40" || b.format != canstar::boards::Format::Pcf {
        return "-".into();
    }
    let roles: Vec<&str> = b.designs().into_iter().filter(|d| canstar::build::roles::lookup(d).is_ok()).collect();
    if roles.is_empty() { "-".into() } else { roles.join(", ") }
}

pub fn run(a: Args) -> Result<()> {
    let names: Vec<String> = if a.boards.is_empty() { BUILTIN.iter().map(|(n, _)| n.to_string()).collect() } else { a.boards };
    // Every board is read (and checked) before anything is printed.
    let boards = names.iter().map(|n| Board::lookup(n)).collect::<Result<Vec<_>>>()?;
    let rows: Vec<[String; 7]> = boards
        .iter()
        .map(|b| {
            [
                b.name.clone(),
                b.family.clone(),
                b.part.clone(),
                format!("{} on {}", mhz(b.clock.hz), b.clock.pin),
                format!("{} ({})", b.format.ext(), b.format.tool()),
                bitstream(b),
                b.designs().join(", "),
            ]
        })
        .collect();
    let head = ["board", "family", "part", "clock", "pin file", "bitstream", "designs"];
    let mut width = head.map(str::len);
    for r in &rows {
        for (w, c) in width.iter_mut().zip(r) {
            *w = (*w).max(c.len());
        }
    }
    let line = |cells: &[&str]| {
        let mut s = String::new();
        for (i, c) in cells.iter().enumerate() {
            if i + 1 == cells.len() {
                s.push_str(c);
            } else {
                s.push_str(&format!("{c:<w$}  ", w = width[i]));
            }
        }
        s
    };
    outln!("{}", line(&head));
    for r in &rows {
        outln!("{}", line(&r.each_ref().map(String::as_str)));
    }
    outln!();
    for b in &boards {
        outln!("{}: {}{}", b.name, b.description, b.source.as_ref().map(|s| format!(" ({s})")).unwrap_or_default());
    }
    Ok(())
}
