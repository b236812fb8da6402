//! Rust source for IR expressions and statements.
//!
//! Storage: one bit is `bool`, wider values the narrowest of `u8`..`u128`, always
//! canonical (bits above the width zero), so masks appear only after operators that
//! can carry bits out of the width (`+`, `-`, `<<`, `!`, narrowing casts).

use std::collections::BTreeSet;
use std::fmt::Write;

use crate::ir::{mask, BinOp, Design, Ek, Expr, SigId, Stmt, UnOp};

/// Rust storage type of a `w`-bit value.
pub fn ty(w: usize) -> &'static str {
    match w {
        1 => "bool",
        2..=8 => "u8",
        9..=16 => "u16",
        17..=32 => "u32",
        33..=64 => "u64",
        _ => "u128",
    }
}

/// Bits of the storage type (bool: 1).
pub fn storage_bits(w: usize) -> usize {
    match w {
        1 => 1,
        2..=8 => 8,
        9..=16 => 16,
        17..=32 => 32,
        33..=64 => 64,
        _ => 128,
    }
}

/// A literal of width `w`.
pub fn lit(v: u128, w: usize) -> String {
    let v = v & mask(w);
    if w == 1 {
        return if v != 0 { "true".into() } else { "false".into() };
    }
    if v < 10 {
        format!("{v}{}", ty(w))
    } else {
        format!("{v:#x}_{}", ty(w))
    }
}

/// `s` masked to `w` bits if its storage type is wider.
fn mask_if(s: String, w: usize) -> String {
    if w == storage_bits(w) {
        s
    } else {
        format!("({s} & {})", lit(mask(w), w))
    }
}

/// Convert a value `s` of width `from` to width `to` (truncate or zero-extend).
pub fn convert(s: String, from: usize, to: usize) -> String {
    if from == to {
        return s;
    }
    if to == 1 {
        return format!("(({s} & 1) != 0)");
    }
    if from == 1 {
        return format!("({s} as {})", ty(to));
    }
    let cast = if ty(from) == ty(to) { s } else { format!("({s} as {})", ty(to)) };
    if to < from {
        mask_if(cast, to)
    } else {
        cast
    }
}

/// Emission context: field names and the locals of the group being emitted.
pub struct Ctx<'a> {
    pub d: &'a Design,
    pub names: &'a [String],
    pub locals: &'a BTreeSet<SigId>,
}

impl Ctx<'_> {
    fn read(&self, s: SigId) -> String {
        if self.locals.contains(&s) && !self.d.sigs[s].reads_settled {
            self.names[s].clone()
        } else {
            format!("self.{}", self.names[s])
        }
    }

    /// `true` iff the amount `a` is zero.
    fn is_zero(&self, a: &Expr) -> String {
        if a.w == 1 {
            format!("(!{})", self.ex(a))
        } else {
            format!("({} == 0)", self.ex(a))
        }
    }

    /// An amount as `u128` for the runtime helpers.
    fn amount(&self, a: &Expr) -> String {
        format!("({} as u128)", self.ex(a))
    }

    /// `a >> amount` within `a`'s width (0 when the amount reaches the width).
    fn shr(&self, a: &Expr, s: &Expr) -> String {
        let t = ty(a.w);
        match s.as_lit() {
            Some(0) => self.ex(a),
            Some(k) if k >= a.w as u128 => lit(0, a.w),
            Some(k) => format!("({} >> {k})", self.ex(a)),
            None => format!("rt::shr_{t}({}, {})", self.ex(a), self.amount(s)),
        }
    }

    /// The value of `e`, of type `ty(e.w)`.
    pub fn ex(&self, e: &Expr) -> String {
        let w = e.w;
        match &e.k {
            Ek::Lit(v) => lit(*v, w),
            Ek::Read(s) => self.read(*s),
            Ek::Un(op, a) => match op {
                UnOp::Not if w == 1 => format!("(!{})", self.ex(a)),
                UnOp::Not if w == storage_bits(w) => format!("(!{})", self.ex(a)),
                UnOp::Not => mask_if(format!("!{}", self.ex(a)), w),
                _ if a.w == 1 => self.ex(a),
                UnOp::All => format!("({} == {})", self.ex(a), lit(mask(a.w), a.w)),
                UnOp::Any => format!("({} != 0)", self.ex(a)),
                UnOp::Parity => format!("(({}.count_ones() & 1) != 0)", self.ex(a)),
            },
            Ek::Bin(op, a, b) => self.bin(*op, a, b, w),
            Ek::Index(a, i) => {
                if a.w == 1 {
                    return format!("({} & {})", self.ex(a), self.is_zero(i));
                }
                match i.as_lit() {
                    Some(k) if k >= storage_bits(a.w) as u128 => "false".into(),
                    Some(0) => format!("(({} & 1) != 0)", self.ex(a)),
                    Some(k) => format!("((({} >> {k}) & 1) != 0)", self.ex(a)),
                    None => format!("(({}.wrapping_shr({} as u32) & 1) != 0)", self.ex(a), self.ex(i)),
                }
            }
            Ek::Slice(a, off) => {
                if a.w == 1 {
                    let v = format!("({} & {})", self.ex(a), self.is_zero(off));
                    return convert(v, 1, w);
                }
                convert(self.shr(a, off), a.w, w)
            }
            Ek::Replace(a, i, v) => {
                if w == 1 {
                    return format!("(if {} {{ {} }} else {{ {} }})", self.is_zero(i), self.ex(v), self.ex(a));
                }
                let t = ty(w);
                match i.as_lit() {
                    Some(k) if k >= w as u128 => self.ex(a),
                    Some(k) => format!("(({} & {}) | (({} as {t}) << {k}))", self.ex(a), lit(mask(w) & !(1u128 << k), w), self.ex(v)),
                    None => format!("rt::replace_{t}({}, {}, {})", self.ex(a), self.amount(i), self.ex(v)),
                }
            }
            Ek::Cast(a) => convert(self.ex(a), a.w, w),
        }
    }

    fn bin(&self, op: BinOp, a: &Expr, b: &Expr, w: usize) -> String {
        let sym = match op {
            BinOp::Eq => "==",
            BinOp::Ne => "!=",
            BinOp::Lt => "<",
            BinOp::Le => "<=",
            BinOp::Gt => ">",
            BinOp::Ge => ">=",
            BinOp::And => "&",
            BinOp::Or => "|",
            BinOp::Xor => "^",
            _ => "",
        };
        match op {
            BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge | BinOp::And | BinOp::Or | BinOp::Xor => {
                format!("({} {sym} {})", self.ex(a), self.ex(b))
            }
            BinOp::Add | BinOp::Sub if w == 1 => format!("({} ^ {})", self.ex(a), self.ex(b)),
            BinOp::Add | BinOp::Sub => {
                let f = if op == BinOp::Add { "wrapping_add" } else { "wrapping_sub" };
                let rhs = if b.w != w { convert(self.ex(b), b.w, w) } else { self.ex(b) };
                mask_if(format!("{}.{f}({rhs})", self.ex(a)), w)
            }
            BinOp::Mul => format!("(({} as u32) * ({} as u32))", self.ex(a), self.ex(b)),
            BinOp::Shl | BinOp::Shr if w == 1 => format!("({} & {})", self.ex(a), self.is_zero(b)),
            BinOp::Shr => self.shr(a, b),
            BinOp::Shl => match b.as_lit() {
                Some(0) => self.ex(a),
                Some(k) if k >= w as u128 => lit(0, w),
                Some(k) => mask_if(format!("({} << {k})", self.ex(a)), w),
                None => mask_if(format!("rt::shl_{}({}, {})", ty(w), self.ex(a), self.amount(b)), w),
            },
        }
    }

    /// Statements, indented by `ind` levels.
    pub fn stmts(&self, out: &mut String, stmts: &[Stmt], ind: usize) {
        let pad = "    ".repeat(ind);
        for s in stmts {
            match s {
                Stmt::Assign { s, v } => {
                    let _ = writeln!(out, "{pad}{} = {};", self.names[*s], self.ex(v));
                }
                Stmt::AssignSlice { s, off, w, v } => {
                    let name = &self.names[*s];
                    let tw = self.d.sigs[*s].width;
                    let value = if tw == 1 {
                        let v = convert(self.ex(v), *w, 1);
                        match off.as_lit() {
                            Some(0) => v,
                            Some(_) => name.clone(),
                            None => format!("if {} {{ {v} }} else {{ {name} }}", self.is_zero(off)),
                        }
                    } else {
                        let t = ty(tw);
                        let v = convert(self.ex(v), *w, tw);
                        match off.as_lit() {
                            Some(k) if k >= tw as u128 => name.clone(),
                            Some(k) => {
                                let keep = mask(tw) & !(mask(*w) << k);
                                mask_if(format!("(({name} & {}) | ({v} << {k}))", lit(keep, tw)), tw)
                            }
                            None => mask_if(format!("rt::set_bits_{t}({name}, {}, {w}, {v})", self.amount(off)), tw),
                        }
                    };
                    let _ = writeln!(out, "{pad}{name} = {value};");
                }
                Stmt::If { c, t, e } => {
                    if t.is_empty() {
                        let _ = writeln!(out, "{pad}if !{} {{", self.ex(c));
                        self.stmts(out, e, ind + 1);
                        let _ = writeln!(out, "{pad}}}");
                        continue;
                    }
                    let _ = writeln!(out, "{pad}if {} {{", self.ex(c));
                    self.stmts(out, t, ind + 1);
                    let mut rest = e;
                    loop {
                        match rest.as_slice() {
                            [] => break,
                            [Stmt::If { c, t, e }] if !t.is_empty() => {
                                let _ = writeln!(out, "{pad}}} else if {} {{", self.ex(c));
                                self.stmts(out, t, ind + 1);
                                rest = e;
                            }
                            _ => {
                                let _ = writeln!(out, "{pad}}} else {{");
                                self.stmts(out, rest, ind + 1);
                                break;
                            }
                        }
                    }
                    let _ = writeln!(out, "{pad}}}");
                }
                Stmt::Case { sel, arms, default, .. } => {
                    let _ = writeln!(out, "{pad}match {} {{", self.ex(sel));
                    for (labels, b) in arms {
                        let l: Vec<String> = labels
                            .iter()
                            .map(|v| if sel.w == 1 { (if *v != 0 { "true" } else { "false" }).to_string() } else { v.to_string() })
                            .collect();
                        let _ = writeln!(out, "{pad}    {} => {{", l.join(" | "));
                        self.stmts(out, b, ind + 2);
                        let _ = writeln!(out, "{pad}    }}");
                    }
                    let _ = writeln!(out, "{pad}    _ => {{");
                    self.stmts(out, default, ind + 2);
                    let _ = writeln!(out, "{pad}    }}");
                    let _ = writeln!(out, "{pad}}}");
                }
            }
        }
    }
}
