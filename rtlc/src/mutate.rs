//! A debug hook for testing the equivalence checks: swap one operator of the
//! compiled design (after optimisation), so that a deliberately wrong model can be
//! generated and shown to be caught.

use crate::ir::{map_exprs, BinOp, Design, Ek, Expr};

fn swapped(op: BinOp) -> Option<BinOp> {
    Some(match op {
        BinOp::Add => BinOp::Sub,
        BinOp::Sub => BinOp::Add,
        BinOp::And => BinOp::Or,
        BinOp::Or => BinOp::And,
        BinOp::Xor => BinOp::Or,
        BinOp::Eq => BinOp::Ne,
        BinOp::Ne => BinOp::Eq,
        BinOp::Lt => BinOp::Le,
        BinOp::Le => BinOp::Lt,
        BinOp::Gt => BinOp::Ge,
        BinOp::Ge => BinOp::Gt,
        BinOp::Shl => BinOp::Shr,
        BinOp::Shr => BinOp::Shl,
        BinOp::Mul => return None,
    })
}

fn visit(e: &mut Expr, n: &mut usize, done: &mut Option<String>) {
    if done.is_some() {
        return;
    }
    if let Ek::Bin(op, _, _) = &mut e.k {
        if let Some(new) = swapped(*op) {
            if *n == 0 {
                *done = Some(format!("{op:?} -> {new:?}"));
                *op = new;
                return;
            }
            *n -= 1;
        }
    }
    match &mut e.k {
        Ek::Lit(_) | Ek::Read(_) => {}
        Ek::Un(_, a) | Ek::Cast(a) => visit(a, n, done),
        Ek::Bin(_, a, b) | Ek::Index(a, b) | Ek::Slice(a, b) => {
            visit(a, n, done);
            visit(b, n, done);
        }
        Ek::Replace(a, b, c) => {
            visit(a, n, done);
            visit(b, n, done);
            visit(c, n, done);
        }
    }
}

/// Swap the `n`-th swappable binary operator (in block order). Returns what was
/// changed and in which module, or `None` if the design has fewer operators.
pub fn swap_operator(d: &mut Design, n: usize) -> Option<String> {
    let mut left = n;
    for b in 0..d.blocks.len() {
        let mut done = None;
        map_exprs(&mut d.blocks[b].stmts, &mut |e| visit(e, &mut left, &mut done));
        if let Some(what) = done {
            return Some(format!("module `{}`: {what}", d.module_path(d.blocks[b].module)));
        }
    }
    None
}
