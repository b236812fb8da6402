//! The flattened design: signals with their roles, the combinational blocks as
//! typed statements over global signal ids, the registers and the memories.
//!
//! Every expression carries its result width (1..=128). Values are unsigned and
//! canonical (bits above the width are zero); the operators have rust-hdl's
//! semantics (wrapping arithmetic within the width, shifts that fill with zeros).

use std::collections::BTreeSet;

use crate::collect::{Hierarchy, ValueType};

pub type SigId = usize;

/// Where a signal's value comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum Role {
    /// A top-level input (set by the user of the model).
    Input,
    /// A `Constant<T>`: a runtime field of the model, filled from the instance.
    Const,
    /// A clock wire (never read as data).
    Clock,
    /// The output `q` of the flip-flop with this index in [`Design::dffs`] (state).
    Reg(usize),
    /// The registered `read_data` of the memory with this index in [`Design::rams`] (state).
    RamRead(usize),
    /// Assigned by the combinational block with this index.
    Comb(usize),
    /// Equal to this expression (a literal or another signal) everywhere.
    Alias(Expr),
    /// Never assigned: keeps its default value (0, `false`, the first enum variant).
    Undriven,
}

/// One atom of the hierarchy as the compiler sees it.
#[derive(Clone, Debug)]
pub struct Sig {
    /// Dotted path from the top (`fsm.tecr.q`).
    pub path: String,
    pub module: usize,
    pub atom: usize,
    pub width: usize,
    pub ty: ValueType,
    pub role: Role,
    /// rust-hdl reads it as `In::val()`: the committed (settled) value, never the
    /// value just assigned in the same block.
    pub reads_settled: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    And,
    Or,
    Xor,
    Shl,
    Shr,
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
}

impl BinOp {
    pub fn is_compare(self) -> bool {
        matches!(self, BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum UnOp {
    /// Bitwise (logical for one bit) inversion within the width.
    Not,
    /// AND reduction.
    All,
    /// OR reduction.
    Any,
    /// XOR reduction (parity).
    Parity,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Ek {
    Lit(u128),
    Read(SigId),
    Un(UnOp, Box<Expr>),
    /// Result width is the node's; comparison operands have equal widths; `Add` may
    /// add a one-bit operand to a wider one (rust-hdl's `Bits<N> + bool`); shift
    /// amounts have any width.
    Bin(BinOp, Box<Expr>, Box<Expr>),
    /// `get_bit(index)`.
    Index(Box<Expr>, Box<Expr>),
    /// `get_bits::<W>(offset)` (W = node width).
    Slice(Box<Expr>, Box<Expr>),
    /// `replace_bit(index, value)`.
    Replace(Box<Expr>, Box<Expr>, Box<Expr>),
    /// `bit_cast`: truncation or zero extension to the node width.
    Cast(Box<Expr>),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    pub w: usize,
    pub k: Ek,
}

pub fn mask(w: usize) -> u128 {
    if w >= 128 {
        u128::MAX
    } else {
        (1u128 << w) - 1
    }
}

impl Expr {
    pub fn lit(v: u128, w: usize) -> Expr {
        Expr { w, k: Ek::Lit(v & mask(w)) }
    }
    pub fn read(s: SigId, w: usize) -> Expr {
        Expr { w, k: Ek::Read(s) }
    }
    pub fn as_lit(&self) -> Option<u128> {
        match self.k {
            Ek::Lit(v) => Some(v),
            _ => None,
        }
    }
    pub fn children(&self) -> Vec<&Expr> {
        match &self.k {
            Ek::Lit(_) | Ek::Read(_) => vec![],
            Ek::Un(_, a) | Ek::Cast(a) => vec![a],
            Ek::Bin(_, a, b) | Ek::Index(a, b) | Ek::Slice(a, b) => vec![a, b],
            Ek::Replace(a, b, c) => vec![a, b, c],
        }
    }
    /// Visit every signal read.
    pub fn reads(&self, f: &mut dyn FnMut(SigId)) {
        match &self.k {
            Ek::Read(s) => f(*s),
            _ => {
                for c in self.children() {
                    c.reads(f)
                }
            }
        }
    }
    /// Replace reads through `f` (returns the replacement or `None` to keep the read).
    pub fn map_reads(&mut self, f: &mut dyn FnMut(SigId) -> Option<Expr>) {
        match &mut self.k {
            Ek::Read(s) => {
                if let Some(e) = f(*s) {
                    *self = e;
                }
            }
            Ek::Lit(_) => {}
            Ek::Un(_, a) | Ek::Cast(a) => a.map_reads(f),
            Ek::Bin(_, a, b) | Ek::Index(a, b) | Ek::Slice(a, b) => {
                a.map_reads(f);
                b.map_reads(f);
            }
            Ek::Replace(a, b, c) => {
                a.map_reads(f);
                b.map_reads(f);
                c.map_reads(f);
            }
        }
    }
    /// Number of nodes (a size measure).
    pub fn size(&self) -> usize {
        1 + self.children().iter().map(|c| c.size()).sum::<usize>()
    }
}

/// A statement of a combinational block.
#[derive(Clone, Debug, PartialEq)]
pub enum Stmt {
    Assign { s: SigId, v: Expr },
    /// `s[off +: w] = v` (rust-hdl `SliceAssignment`).
    AssignSlice { s: SigId, off: Expr, w: usize, v: Expr },
    If { c: Expr, t: Vec<Stmt>, e: Vec<Stmt> },
    /// A `match`: first arm whose label equals `sel`, else `default` (empty if the
    /// source had no wildcard arm). `exhaustive`: the labels cover every value of
    /// `sel`, there is no path through `default`.
    Case { sel: Expr, arms: Vec<(Vec<u128>, Vec<Stmt>)>, default: Vec<Stmt>, exhaustive: bool },
}

impl Stmt {
    /// Visit the statement tree (pre-order).
    pub fn walk<'a>(&'a self, f: &mut dyn FnMut(&'a Stmt)) {
        f(self);
        match self {
            Stmt::If { t, e, .. } => {
                for s in t.iter().chain(e.iter()) {
                    s.walk(f)
                }
            }
            Stmt::Case { arms, default, .. } => {
                for s in arms.iter().flat_map(|a| a.1.iter()).chain(default.iter()) {
                    s.walk(f)
                }
            }
            _ => {}
        }
    }
    /// Every expression directly in this statement (not in nested statements).
    pub fn exprs(&self) -> Vec<&Expr> {
        match self {
            Stmt::Assign { v, .. } => vec![v],
            Stmt::AssignSlice { off, v, .. } => vec![off, v],
            Stmt::If { c, .. } => vec![c],
            Stmt::Case { sel, .. } => vec![sel],
        }
    }
    pub fn exprs_mut(&mut self) -> Vec<&mut Expr> {
        match self {
            Stmt::Assign { v, .. } => vec![v],
            Stmt::AssignSlice { off, v, .. } => vec![off, v],
            Stmt::If { c, .. } => vec![c],
            Stmt::Case { sel, .. } => vec![sel],
        }
    }
    pub fn children_mut(&mut self) -> Vec<&mut Vec<Stmt>> {
        match self {
            Stmt::If { t, e, .. } => vec![t, e],
            Stmt::Case { arms, default, .. } => {
                let mut v: Vec<&mut Vec<Stmt>> = arms.iter_mut().map(|a| &mut a.1).collect();
                v.push(default);
                v
            }
            _ => vec![],
        }
    }
}

/// Apply `f` to every expression of a statement list (recursively).
pub fn map_exprs(stmts: &mut [Stmt], f: &mut dyn FnMut(&mut Expr)) {
    for s in stmts.iter_mut() {
        for e in s.exprs_mut() {
            f(e);
        }
        for c in s.children_mut() {
            map_exprs(c, f);
        }
    }
}

/// Signals assigned anywhere in a statement list.
pub fn assigned(stmts: &[Stmt]) -> BTreeSet<SigId> {
    let mut out = BTreeSet::new();
    for s in stmts {
        s.walk(&mut |s| match s {
            Stmt::Assign { s, .. } | Stmt::AssignSlice { s, .. } => {
                out.insert(*s);
            }
            _ => {}
        });
    }
    out
}

/// A combinational block: one module's `#[hdl_gen]` update.
#[derive(Clone, Debug)]
pub struct CombBlock {
    pub module: usize,
    pub stmts: Vec<Stmt>,
}

/// A `DFF`: `q` takes `d` at every rising edge of the clock.
#[derive(Clone, Debug)]
pub struct Dff {
    pub module: usize,
    pub d: SigId,
    pub q: SigId,
    /// Its clock is driven by the top clock (otherwise `q` never changes).
    pub clocked: bool,
    pub init: u128,
}

/// rust-hdl's `RAM<D, N>`: registered read, synchronous write, read before write.
#[derive(Clone, Debug)]
pub struct Ram {
    pub module: usize,
    pub read_address: SigId,
    pub read_data: SigId,
    pub write_address: SigId,
    pub write_data: SigId,
    pub write_enable: SigId,
    pub read_clocked: bool,
    pub write_clocked: bool,
    /// Data width.
    pub dw: usize,
    /// Address width (2^aw words).
    pub aw: usize,
    /// Initial contents (address, value) from the instance.
    pub init: Vec<(u128, u128)>,
}

/// The flattened design.
#[derive(Clone, Debug)]
pub struct Design {
    pub hier: Hierarchy,
    /// One per atom of the hierarchy, same index.
    pub sigs: Vec<Sig>,
    pub blocks: Vec<CombBlock>,
    pub dffs: Vec<Dff>,
    pub rams: Vec<Ram>,
    /// Top-level data inputs and outputs, in probe order.
    pub inputs: Vec<SigId>,
    pub outputs: Vec<SigId>,
    /// Non-fatal findings (latches, literals that do not fit).
    pub warnings: Vec<String>,
}

impl Design {
    /// Signals assigned by each block.
    pub fn writes(&self, b: usize) -> BTreeSet<SigId> {
        assigned(&self.blocks[b].stmts)
    }
    pub fn module_path(&self, m: usize) -> String {
        let p = self.hier.modules[m].dotted();
        if p.is_empty() {
            "top".into()
        } else {
            p
        }
    }
}
