//! Expressions of rust-hdl's AST to typed IR expressions.
//!
//! The AST has lost Rust's types, so they are inferred back the way Rust's type check
//! would have resolved the original `update()` code: a signal has its declared width;
//! an integer literal is rust-hdl's `LiteralType` (u64) converted into the `Bits<N>` it
//! meets (`x + 1`, `x == 3`); `Bits<N>` operators keep N and wrap; `LiteralType <<
//! Bits<M>` is `Bits<64>`; comparisons and reductions are `bool`; `get_bits::<W>`,
//! `bit_cast::<W, _>` are W wide. Operand widths that Rust would have rejected are
//! reported (they mean the compiler misread something).

use rust_hdl::core::ast::{VerilogExpression, VerilogOp, VerilogOpUnary};

use crate::collect::{parse_literal, ValueType};
use crate::error::{Error, Result};
use crate::ir::{mask, BinOp, Ek, Expr, SigId, UnOp};
use crate::lower::Lower;
use crate::names::fixup;

/// Width of a literal that has not met a typed operand yet.
const FLEX: usize = 128;

/// A typed expression: `flex` literals take the width of what they meet.
#[derive(Clone, Debug)]
pub struct Te {
    pub e: Expr,
    pub flex: bool,
    pub clock: bool,
}

impl Te {
    fn fixed(e: Expr) -> Te {
        Te { e, flex: false, clock: false }
    }
    fn flex(v: u128) -> Te {
        Te { e: Expr { w: FLEX, k: Ek::Lit(v) }, flex: true, clock: false }
    }
    fn w(&self) -> usize {
        self.e.w
    }
}

fn bin(op: BinOp, a: Expr, b: Expr, w: usize) -> Expr {
    Expr { w, k: Ek::Bin(op, Box::new(a), Box::new(b)) }
}

/// Constant arithmetic on two unconverted literals (Rust integer arithmetic).
fn fold_flex(op: BinOp, a: u128, b: u128) -> u128 {
    match op {
        BinOp::Add => a.wrapping_add(b),
        BinOp::Sub => a.wrapping_sub(b),
        BinOp::Mul => a.wrapping_mul(b),
        BinOp::And => a & b,
        BinOp::Or => a | b,
        BinOp::Xor => a ^ b,
        BinOp::Shl => a.checked_shl(b as u32).unwrap_or(0),
        BinOp::Shr => a.checked_shr(b as u32).unwrap_or(0),
        BinOp::Eq => (a == b) as u128,
        BinOp::Ne => (a != b) as u128,
        BinOp::Lt => (a < b) as u128,
        BinOp::Le => (a <= b) as u128,
        BinOp::Gt => (a > b) as u128,
        BinOp::Ge => (a >= b) as u128,
    }
}

impl Lower<'_> {
    /// Convert to width `w` (literals are converted, others must already have it).
    pub(crate) fn fit(&mut self, t: Te, w: usize, what: &str) -> Result<Expr> {
        if t.clock {
            return Err(self.unsupported(&format!("the clock used as data ({what})")));
        }
        if t.flex {
            let v = t.e.as_lit().unwrap();
            if v > mask(w) {
                self.warn(format!("literal {v} does not fit in {w} bits ({what}); rust-hdl would panic here"));
            }
            return Ok(Expr::lit(v, w));
        }
        if t.w() != w {
            return Err(self.width_err(format!("{what}: a {}-bit value where {w} bits are expected", t.w())));
        }
        Ok(t.e)
    }

    pub(crate) fn fit_bool(&mut self, t: Te, what: &str) -> Result<Expr> {
        self.fit(t, 1, what)
    }

    /// A bit index or slice offset: a `usize` in Rust, so the AST's `x.index()` has
    /// lost its conversion. The expression is evaluated as Rust evaluates
    /// `leaf.index()` arithmetic: signals zero-extended to 64 bits, 64-bit operators
    /// (the reading rust-hdl's Verilog generator gives it too). `(x + 1).index()`,
    /// which would wrap at x's width first, reads the same in the AST: a warning says
    /// so when an index computes with signals.
    pub(crate) fn index_expr(&mut self, e: &VerilogExpression, what: &str) -> Result<Expr> {
        let saved = std::mem::replace(&mut self.index_mode, true);
        let t = self.expr(e);
        self.index_mode = saved;
        let t = self.amount(t?, what)?;
        let computes = matches!(t.k, Ek::Bin(..)) && {
            let mut reads = false;
            t.reads(&mut |_| reads = true);
            reads
        };
        if computes {
            self.warn(format!("{what} computed from signals: evaluated as usize arithmetic (as `x.index() + k`, not `(x + k).index()`)"));
        }
        Ok(t)
    }

    /// A receiver of `get_bit`/`get_bits`/`replace_bit`: a `Bits` value even inside an index.
    fn receiver(&mut self, e: &VerilogExpression) -> Result<Te> {
        let saved = std::mem::replace(&mut self.index_mode, false);
        let t = self.expr(e);
        self.index_mode = saved;
        t
    }

    /// An index or shift amount: any width (a literal gets the bits it needs).
    fn amount(&mut self, t: Te, what: &str) -> Result<Expr> {
        if t.clock {
            return Err(self.unsupported(&format!("the clock used as data ({what})")));
        }
        if t.flex {
            let v = t.e.as_lit().unwrap();
            let w = (128 - v.leading_zeros() as usize).max(1);
            return Ok(Expr::lit(v, w));
        }
        Ok(t.e)
    }

    fn operand(&mut self, t: Te, what: &str) -> Result<Te> {
        if t.clock {
            return Err(self.unsupported(&format!("the clock used as data ({what})")));
        }
        Ok(t)
    }

    pub(crate) fn expr(&mut self, e: &VerilogExpression) -> Result<Te> {
        use VerilogExpression as V;
        Ok(match e {
            V::Signal(raw) => self.signal(raw)?,
            V::Literal(l) => {
                let (v, _) = parse_literal(&l.to_string())?;
                Te::flex(v)
            }
            V::Paren(a) => self.expr(a)?,
            V::Cast(a, w) => {
                let a = self.expr(a)?;
                let a = self.operand(a, "bit_cast")?;
                if a.flex {
                    Te::fixed(self.fit(a, *w, "bits()")?)
                } else if a.w() == *w {
                    a
                } else {
                    Te::fixed(Expr { w: *w, k: Ek::Cast(Box::new(a.e)) })
                }
            }
            V::Signed(_) | V::Unsigned(_) => return Err(self.unsupported("Signed values")),
            V::Binary(a, op, b) => {
                let a = self.expr(a)?;
                let b = self.expr(b)?;
                self.binary(op, a, b)?
            }
            V::Unary(op, a) => {
                let a = self.expr(a)?;
                let a = self.operand(a, "unary operator")?;
                if a.flex {
                    return Err(self.unsupported("a unary operator on an untyped literal"));
                }
                let (op, w) = match op {
                    VerilogOpUnary::Not => (UnOp::Not, a.w()),
                    VerilogOpUnary::All => (UnOp::All, 1),
                    VerilogOpUnary::Any => (UnOp::Any, 1),
                    VerilogOpUnary::Xor => (UnOp::Parity, 1),
                    VerilogOpUnary::Neg => return Err(self.unsupported("negation (only Signed has it)")),
                };
                Te::fixed(Expr { w, k: Ek::Un(op, Box::new(a.e)) })
            }
            V::Index(a, i) => {
                let a = self.receiver(a)?;
                let a = self.operand(a, "get_bit")?;
                if a.flex {
                    return Err(self.unsupported("get_bit on an untyped literal"));
                }
                let i = self.index_expr(i, "bit index")?;
                if let Some(iv) = i.as_lit() {
                    if iv >= a.w() as u128 {
                        self.warn(format!("get_bit({iv}) of a {}-bit value; rust-hdl would panic here", a.w()));
                    }
                }
                Te::fixed(Expr { w: 1, k: Ek::Index(Box::new(a.e), Box::new(i)) })
            }
            V::Slice(a, w, off) => {
                let a = self.receiver(a)?;
                let a = self.operand(a, "get_bits")?;
                if a.flex {
                    return Err(self.unsupported("get_bits on an untyped literal"));
                }
                let off = self.index_expr(off, "slice offset")?;
                Te::fixed(Expr { w: *w, k: Ek::Slice(Box::new(a.e), Box::new(off)) })
            }
            V::IndexReplace(a, i, v) => {
                let a = self.receiver(a)?;
                let a = self.operand(a, "replace_bit")?;
                if a.flex {
                    return Err(self.unsupported("replace_bit on an untyped literal"));
                }
                let i = self.index_expr(i, "bit index")?;
                let saved = std::mem::replace(&mut self.index_mode, false);
                let v = self.expr(v);
                self.index_mode = saved;
                let v = v?;
                let v = self.fit_bool(v, "replace_bit value")?;
                let w = a.w();
                Te::fixed(Expr { w, k: Ek::Replace(Box::new(a.e), Box::new(i), Box::new(v)) })
            }
        })
    }

    fn signal(&mut self, raw: &str) -> Result<Te> {
        let name = fixup(raw, &self.loops)?;
        if let Some(v) = crate::names::parse_int(&name) {
            return Ok(Te::flex(v));
        }
        if let Some(&s) = self.names.get(&name) {
            return Ok(self.read(s));
        }
        if let Some(&(e, v)) = self.enum_consts.get(&name) {
            let w = self.enum_width(e);
            return Ok(Te::fixed(Expr::lit(v, w)));
        }
        Err(Error::UnknownSignal { module: self.module_path(), name })
    }

    fn read(&mut self, s: SigId) -> Te {
        let sig = &self.sigs[s];
        let clock = sig.ty == ValueType::Clock;
        let e = Expr::read(s, sig.width);
        if self.index_mode && !clock && sig.width < 64 {
            // `x.index()`: the value as a usize
            return Te { e: Expr { w: 64, k: Ek::Cast(Box::new(e)) }, flex: false, clock };
        }
        Te { e, flex: false, clock }
    }

    fn binary(&mut self, op: &VerilogOp, a: Te, b: Te) -> Result<Te> {
        use VerilogOp as O;
        let a = self.operand(a, "binary operator")?;
        let b = self.operand(b, "binary operator")?;
        let bop = match op {
            O::Add => BinOp::Add,
            O::Sub => BinOp::Sub,
            O::Mul => BinOp::Mul,
            O::LogicalAnd | O::BitAnd => BinOp::And,
            O::LogicalOr | O::BitOr => BinOp::Or,
            O::BitXor => BinOp::Xor,
            O::Shl => BinOp::Shl,
            O::Shr => BinOp::Shr,
            O::Eq => BinOp::Eq,
            O::Ne => BinOp::Ne,
            O::Lt => BinOp::Lt,
            O::Le => BinOp::Le,
            O::Gt => BinOp::Gt,
            O::Ge => BinOp::Ge,
        };
        if matches!(op, O::LogicalAnd | O::LogicalOr) {
            let a = self.fit_bool(a, "&& / || operand")?;
            let b = self.fit_bool(b, "&& / || operand")?;
            return Ok(Te::fixed(bin(bop, a, b, 1)));
        }
        if a.flex && b.flex {
            let v = fold_flex(bop, a.e.as_lit().unwrap(), b.e.as_lit().unwrap());
            return Ok(if bop.is_compare() { Te::fixed(Expr::lit(v, 1)) } else { Te::flex(v) });
        }
        match bop {
            BinOp::Shl | BinOp::Shr => {
                let a = if a.flex { Expr::lit(a.e.as_lit().unwrap(), 64) } else { a.e };
                let b = self.amount(b, "shift amount")?;
                let w = a.w;
                Ok(Te::fixed(bin(bop, a, b, w)))
            }
            BinOp::Mul => {
                if a.flex || b.flex || a.w() != 16 || b.w() != 16 {
                    return Err(self.unsupported("multiplication other than Bits<16> * Bits<16>"));
                }
                Ok(Te::fixed(bin(bop, a.e, b.e, 32)))
            }
            _ => {
                // `Bits<N> + bool` is the one mixed-width operator rust-hdl has.
                if bop == BinOp::Add && !a.flex && !b.flex && b.w() == 1 && a.w() > 1 {
                    let w = a.w();
                    return Ok(Te::fixed(bin(bop, a.e, b.e, w)));
                }
                let w = if a.flex { b.w() } else { a.w() };
                let a = self.fit(a, w, "operand")?;
                let b = self.fit(b, w, "operand")?;
                let rw = if bop.is_compare() { 1 } else { w };
                Ok(Te::fixed(bin(bop, a, b, rw)))
            }
        }
    }
}
