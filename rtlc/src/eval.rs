//! Reference evaluation of IR expressions (rust-hdl `Bits` semantics), used for
//! constant folding and as the specification the generated code is checked against.

use crate::ir::{mask, BinOp, Ek, Expr, SigId, UnOp};

fn shl(a: u128, s: u128, w: usize) -> u128 {
    if s >= w as u128 {
        0
    } else {
        (a << s) & mask(w)
    }
}

fn shr(a: u128, s: u128, w: usize) -> u128 {
    if s >= w as u128 {
        0
    } else {
        a >> s
    }
}

/// Apply a binary operator to canonical operands of widths `wa`, `wb`; result width `w`.
pub fn bin(op: BinOp, a: u128, wa: usize, b: u128, w: usize) -> u128 {
    let m = mask(w);
    match op {
        BinOp::Add => a.wrapping_add(b) & m,
        BinOp::Sub => a.wrapping_sub(b) & m,
        BinOp::Mul => a.wrapping_mul(b) & m,
        BinOp::And => a & b,
        BinOp::Or => a | b,
        BinOp::Xor => a ^ b,
        BinOp::Shl => shl(a, b, wa),
        BinOp::Shr => shr(a, b, wa),
        BinOp::Eq => (a == b) as u128,
        BinOp::Ne => (a != b) as u128,
        BinOp::Lt => (a < b) as u128,
        BinOp::Le => (a <= b) as u128,
        BinOp::Gt => (a > b) as u128,
        BinOp::Ge => (a >= b) as u128,
    }
}

pub fn un(op: UnOp, a: u128, wa: usize) -> u128 {
    match op {
        UnOp::Not => !a & mask(wa),
        UnOp::All => (a == mask(wa)) as u128,
        UnOp::Any => (a != 0) as u128,
        UnOp::Parity => (a.count_ones() & 1) as u128,
    }
}

/// Evaluate with `read` giving signal values.
pub fn eval(e: &Expr, read: &dyn Fn(SigId) -> u128) -> u128 {
    match &e.k {
        Ek::Lit(v) => *v,
        Ek::Read(s) => read(*s),
        Ek::Un(op, a) => un(*op, eval(a, read), a.w),
        Ek::Bin(op, a, b) => bin(*op, eval(a, read), a.w, eval(b, read), e.w),
        Ek::Index(a, i) => {
            let i = eval(i, read);
            if i >= 128 {
                0
            } else {
                (eval(a, read) >> i) & 1
            }
        }
        Ek::Slice(a, off) => shr(eval(a, read), eval(off, read), a.w) & mask(e.w),
        Ek::Replace(a, i, v) => {
            let (a, i, v) = (eval(a, read), eval(i, read), eval(v, read));
            if i >= e.w as u128 {
                a
            } else {
                (a & !(1u128 << i)) | (v << i)
            }
        }
        Ek::Cast(a) => eval(a, read) & mask(e.w),
    }
}

/// Fold an expression whose operands are all literals (bottom-up), plus the algebraic
/// identities that constant inputs make common (`x & 0`, `x | 0`, `!!x`...).
pub fn fold(e: &mut Expr) {
    match &mut e.k {
        Ek::Lit(_) | Ek::Read(_) => return,
        Ek::Un(_, a) | Ek::Cast(a) => fold(a),
        Ek::Bin(_, a, b) | Ek::Index(a, b) | Ek::Slice(a, b) => {
            fold(a);
            fold(b);
        }
        Ek::Replace(a, b, c) => {
            fold(a);
            fold(b);
            fold(c);
        }
    }
    if e.children().iter().all(|c| c.as_lit().is_some()) {
        let v = eval(e, &|_| 0);
        *e = Expr::lit(v, e.w);
        return;
    }
    let w = e.w;
    let replacement = match &e.k {
        Ek::Bin(op, a, b) => {
            let (la, lb) = (a.as_lit(), b.as_lit());
            let full = mask(w);
            match op {
                BinOp::And if la == Some(0) || lb == Some(0) => Some(Expr::lit(0, w)),
                BinOp::And if la == Some(full) && a.w == w && b.w == w => Some((**b).clone()),
                BinOp::And if lb == Some(full) && a.w == w && b.w == w => Some((**a).clone()),
                BinOp::Or if la == Some(full) || lb == Some(full) => Some(Expr::lit(full, w)),
                BinOp::Or | BinOp::Xor if la == Some(0) && b.w == w => Some((**b).clone()),
                BinOp::Or | BinOp::Xor | BinOp::Add | BinOp::Sub if lb == Some(0) && a.w == w => Some((**a).clone()),
                BinOp::Add if la == Some(0) && b.w == w => Some((**b).clone()),
                BinOp::Shl | BinOp::Shr if lb == Some(0) => Some((**a).clone()),
                BinOp::Eq if a.w == 1 && lb == Some(1) => Some((**a).clone()),
                BinOp::Eq if a.w == 1 && la == Some(1) => Some((**b).clone()),
                BinOp::Ne if a.w == 1 && lb == Some(0) => Some((**a).clone()),
                BinOp::Ne if a.w == 1 && la == Some(0) => Some((**b).clone()),
                _ => None,
            }
        }
        Ek::Un(UnOp::Not, a) => match &a.k {
            Ek::Un(UnOp::Not, inner) => Some((**inner).clone()),
            _ => None,
        },
        Ek::Un(UnOp::All | UnOp::Any | UnOp::Parity, a) if a.w == 1 => Some((**a).clone()),
        Ek::Cast(a) if a.w == w => Some((**a).clone()),
        _ => None,
    };
    if let Some(r) = replacement {
        *e = r;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rust_hdl::core::prelude::*;

    fn lit(v: u128, w: usize) -> Expr {
        Expr::lit(v, w)
    }
    fn b(op: BinOp, a: Expr, c: Expr, w: usize) -> Expr {
        Expr { w, k: Ek::Bin(op, Box::new(a), Box::new(c)) }
    }

    #[test]
    fn matches_rust_hdl_bits_semantics() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        for _ in 0..2000 {
            let x: u64 = rng.gen::<u64>() & 0x1fff;
            let y: u64 = rng.gen::<u64>() & 0x1fff;
            let s: u64 = rng.gen_range(0..20);
            let (bx, by): (Bits<13>, Bits<13>) = (x.into(), y.into());
            let ev = |op, a: u64, c: u64, w| eval(&b(op, lit(a as u128, 13), lit(c as u128, 13), w), &|_| 0) as u64;
            assert_eq!(ev(BinOp::Add, x, y, 13), (bx + by).to_u64());
            assert_eq!(ev(BinOp::Sub, x, y, 13), (bx - by).to_u64());
            assert_eq!(ev(BinOp::And, x, y, 13), (bx & by).to_u64());
            assert_eq!(ev(BinOp::Xor, x, y, 13), (bx ^ by).to_u64());
            assert_eq!(ev(BinOp::Lt, x, y, 1) == 1, bx < by);
            let sh = |op, a: u64| eval(&b(op, lit(a as u128, 13), lit(s as u128, 5), 13), &|_| 0) as u64;
            assert_eq!(sh(BinOp::Shl, x), (bx << s).to_u64());
            assert_eq!(sh(BinOp::Shr, x), (bx >> s).to_u64());
            let not = eval(&Expr { w: 13, k: Ek::Un(UnOp::Not, Box::new(lit(x as u128, 13))) }, &|_| 0) as u64;
            assert_eq!(not, (!bx).to_u64());
            let off = rng.gen_range(0..=13usize);
            let sl = eval(&Expr { w: 5, k: Ek::Slice(Box::new(lit(x as u128, 13)), Box::new(lit(off as u128, 4))) }, &|_| 0) as u64;
            assert_eq!(sl, bx.get_bits::<5>(off).to_u64());
            let i = rng.gen_range(0..13usize);
            let rep = eval(&Expr { w: 13, k: Ek::Replace(Box::new(lit(x as u128, 13)), Box::new(lit(i as u128, 4)), Box::new(lit(1, 1))) }, &|_| 0) as u64;
            assert_eq!(rep, bx.replace_bit(i, true).to_u64());
        }
    }

    #[test]
    fn folding_and_identities() {
        let mut e = b(BinOp::Add, lit(250, 8), lit(10, 8), 8);
        fold(&mut e);
        assert_eq!(e, lit(4, 8));
        let x = Expr::read(3, 8);
        let mut e = b(BinOp::And, x.clone(), lit(0, 8), 8);
        fold(&mut e);
        assert_eq!(e, lit(0, 8));
        let mut e = b(BinOp::Or, lit(0, 8), x.clone(), 8);
        fold(&mut e);
        assert_eq!(e, x);
        let y = Expr::read(4, 1);
        let mut e = Expr { w: 1, k: Ek::Un(UnOp::Not, Box::new(Expr { w: 1, k: Ek::Un(UnOp::Not, Box::new(y.clone())) })) };
        fold(&mut e);
        assert_eq!(e, y);
    }
}
