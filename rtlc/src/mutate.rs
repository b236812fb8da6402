//! A debug hook for testing the equivalence checks: swap one operator of the
//! compiled design (after optimisation), so that a deliberately wrong model can be
//! generated and shown to be caught.

use crate::ir::{BinOp, Design, Ek, Expr, Stmt};

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

/// Count down `n` over the swappable operators of `e`; swap the one that reaches 0.
fn visit(e: &mut Expr, n: &mut usize) -> Option<String> {
    if let Ek::Bin(op, _, _) = &mut e.k {
        if let Some(new) = swapped(*op) {
            if *n == 0 {
                let what = format!("{op:?} -> {new:?}");
                *op = new;
                return Some(what);
            }
            *n -= 1;
        }
    }
    match &mut e.k {
        Ek::Lit(_) | Ek::Read(_) => None,
        Ek::Un(_, a) | Ek::Cast(a) => visit(a, n),
        Ek::Bin(_, a, b) | Ek::Index(a, b) | Ek::Slice(a, b) => visit(a, n).or_else(|| visit(b, n)),
        Ek::Replace(a, b, c) => visit(a, n).or_else(|| visit(b, n)).or_else(|| visit(c, n)),
    }
}

fn stmts(ss: &mut [Stmt], n: &mut usize, d: &[String]) -> Option<String> {
    for s in ss.iter_mut() {
        let place = match s {
            Stmt::Assign { s, .. } | Stmt::AssignSlice { s, .. } => format!("assignment to `{}`", d[*s]),
            Stmt::If { .. } => "an if condition".to_string(),
            Stmt::Case { .. } => "a match selector".to_string(),
        };
        for e in s.exprs_mut() {
            if let Some(w) = visit(e, n) {
                return Some(format!("{w} in {place}"));
            }
        }
        for c in s.children_mut() {
            if let Some(w) = stmts(c, n, d) {
                return Some(w);
            }
        }
    }
    None
}

/// Swap the `n`-th swappable binary operator (in block order). Returns what was
/// changed and where, or `None` if the design has fewer operators.
pub fn swap_operator(d: &mut Design, n: usize) -> Option<String> {
    let paths: Vec<String> = d.sigs.iter().map(|s| s.path.clone()).collect();
    let mut left = n;
    for b in 0..d.blocks.len() {
        let module = d.module_path(d.blocks[b].module);
        if let Some(w) = stmts(&mut d.blocks[b].stmts, &mut left, &paths) {
            return Some(format!("module `{module}`: {w}"));
        }
    }
    None
}
