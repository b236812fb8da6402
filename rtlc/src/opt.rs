//! Design-level simplification before scheduling: wires and constants are
//! propagated (a signal assigned once, unconditionally, with a literal or another
//! signal's settled value becomes an alias and gets no storage), literal conditions
//! select their branch, and literal operands fold. rust-hdl designs are mostly wiring
//! between modules (`self.child.x.next = self.y.val()`), so this removes most of the
//! signal copies the rust-hdl engine commits and compares every pass.
//!
//! Top-level outputs keep their storage (they are the model's public fields).

use std::collections::{HashMap, HashSet};

use crate::eval::fold;
use crate::ir::{map_exprs, Design, Ek, Expr, Role, SigId, Stmt, UnOp};

/// Statement-level folding: literal conditions and selectors pick their branch,
/// branches without effect disappear.
pub fn simplify(stmts: Vec<Stmt>) -> Vec<Stmt> {
    let mut out = vec![];
    for s in stmts {
        match s {
            Stmt::If { mut c, t, e } => {
                fold(&mut c);
                let (t, e) = (simplify(t), simplify(e));
                match c.as_lit() {
                    Some(1) => out.extend(t),
                    Some(_) => out.extend(e),
                    None if t.is_empty() && e.is_empty() => {}
                    None if t.is_empty() => {
                        let mut n = Expr { w: 1, k: Ek::Un(UnOp::Not, Box::new(c)) };
                        fold(&mut n);
                        out.push(Stmt::If { c: n, t: e, e: vec![] })
                    }
                    None => out.push(Stmt::If { c, t, e }),
                }
            }
            Stmt::Case { mut sel, arms, default, exhaustive } => {
                fold(&mut sel);
                let arms: Vec<(Vec<u128>, Vec<Stmt>)> = arms.into_iter().map(|(l, b)| (l, simplify(b))).collect();
                let default = simplify(default);
                if let Some(v) = sel.as_lit() {
                    match arms.into_iter().find(|(l, _)| l.contains(&v)) {
                        Some((_, b)) => out.extend(b),
                        None => out.extend(default),
                    }
                } else if arms.iter().all(|a| a.1.is_empty()) && default.is_empty() {
                } else {
                    out.push(Stmt::Case { sel, arms, default, exhaustive });
                }
            }
            Stmt::Assign { s, mut v } => {
                fold(&mut v);
                out.push(Stmt::Assign { s, v });
            }
            Stmt::AssignSlice { s, mut off, w, mut v } => {
                fold(&mut off);
                fold(&mut v);
                out.push(Stmt::AssignSlice { s, off, w, v });
            }
        }
    }
    out
}

/// Remove top-level full assignments that a later top-level full assignment to the
/// same signal overwrites before anything reads it (`dff_setup!`'s `d = q` followed
/// by `d = ...`, defaults overwritten unconditionally).
pub fn dead_stores(stmts: Vec<Stmt>) -> Vec<Stmt> {
    let reads_of = |st: &Stmt, sig: SigId| {
        let mut hit = false;
        st.walk(&mut |x| {
            for e in x.exprs() {
                e.reads(&mut |r| hit |= r == sig);
            }
            if let Stmt::AssignSlice { s, .. } = x {
                hit |= *s == sig;
            }
        });
        hit
    };
    let n = stmts.len();
    let mut dead = vec![false; n];
    for i in 0..n {
        let Stmt::Assign { s, .. } = &stmts[i] else { continue };
        for later in &stmts[i + 1..] {
            if reads_of(later, *s) {
                break;
            }
            if matches!(later, Stmt::Assign { s: t, .. } if t == s) {
                dead[i] = true;
                break;
            }
        }
    }
    stmts.into_iter().zip(dead).filter(|(_, d)| !d).map(|(s, _)| s).collect()
}

/// Per block: how often each signal is assigned, and which are assigned exactly once
/// by a full assignment at the top level of the block.
fn assignment_counts(stmts: &[Stmt]) -> (HashMap<SigId, usize>, HashSet<SigId>) {
    let mut count: HashMap<SigId, usize> = HashMap::new();
    for s in stmts {
        s.walk(&mut |s| {
            if let Stmt::Assign { s, .. } | Stmt::AssignSlice { s, .. } = s {
                *count.entry(*s).or_default() += 1;
            }
        });
    }
    let top: HashSet<SigId> = stmts
        .iter()
        .filter_map(|s| match s {
            Stmt::Assign { s, .. } if count[s] == 1 => Some(*s),
            _ => None,
        })
        .collect();
    (count, top)
}

/// Find new aliases in every block.
fn find_aliases(d: &Design) -> HashMap<SigId, Expr> {
    let outputs: HashSet<SigId> = d.outputs.iter().copied().collect();
    let mut found = HashMap::new();
    for blk in &d.blocks {
        let (count, single) = assignment_counts(&blk.stmts);
        for st in &blk.stmts {
            let Stmt::Assign { s, v } = st else { continue };
            if !single.contains(s) || outputs.contains(s) {
                continue;
            }
            let ok = match &v.k {
                Ek::Lit(_) => true,
                Ek::Read(r) => *r != *s && (!count.contains_key(r) || d.sigs[*r].reads_settled || single.contains(r)),
                _ => false,
            };
            if ok {
                found.insert(*s, v.clone());
            }
        }
    }
    found
}

/// Resolve alias chains; aliases that form a cycle are dropped (the scheduler reports the loop).
fn resolve(found: HashMap<SigId, Expr>) -> HashMap<SigId, Expr> {
    let mut out = HashMap::new();
    for (&s, e) in &found {
        let mut cur = e.clone();
        let mut seen = HashSet::from([s]);
        let mut cyclic = false;
        while let Ek::Read(r) = cur.k {
            match found.get(&r) {
                Some(next) => {
                    if !seen.insert(r) {
                        cyclic = true;
                        break;
                    }
                    cur = next.clone();
                }
                None => break,
            }
        }
        if !cyclic {
            out.insert(s, cur);
        }
    }
    out
}

fn substitute(d: &mut Design, map: &HashMap<SigId, Expr>) {
    let mut f = |s: SigId| map.get(&s).cloned();
    for b in &mut d.blocks {
        map_exprs(&mut b.stmts, &mut |e| e.map_reads(&mut f));
    }
}

fn remove_assignments(stmts: Vec<Stmt>, gone: &HashMap<SigId, Expr>) -> Vec<Stmt> {
    stmts
        .into_iter()
        .filter_map(|s| match s {
            Stmt::Assign { s, .. } if gone.contains_key(&s) => None,
            Stmt::If { c, t, e } => Some(Stmt::If { c, t: remove_assignments(t, gone), e: remove_assignments(e, gone) }),
            Stmt::Case { sel, arms, default, exhaustive } => Some(Stmt::Case {
                sel,
                arms: arms.into_iter().map(|(l, b)| (l, remove_assignments(b, gone))).collect(),
                default: remove_assignments(default, gone),
                exhaustive,
            }),
            other => Some(other),
        })
        .collect()
}

/// Propagate wires and constants to a fixpoint.
pub fn optimize(d: &mut Design) {
    // never-assigned signals are their default value
    let mut undriven = HashMap::new();
    for (i, s) in d.sigs.iter_mut().enumerate() {
        if s.role == Role::Undriven {
            let e = Expr::lit(0, s.width);
            s.role = Role::Alias(e.clone());
            undriven.insert(i, e);
        }
    }
    substitute(d, &undriven);
    for b in &mut d.blocks {
        b.stmts = dead_stores(simplify(std::mem::take(&mut b.stmts)));
    }
    loop {
        let map = resolve(find_aliases(d));
        if map.is_empty() {
            break;
        }
        for (&s, e) in &map {
            d.sigs[s].role = Role::Alias(e.clone());
        }
        for b in &mut d.blocks {
            b.stmts = remove_assignments(std::mem::take(&mut b.stmts), &map);
        }
        substitute(d, &map);
        // earlier aliases that pointed at a signal that has just become an alias
        let sigs_snapshot: Vec<Role> = d.sigs.iter().map(|s| s.role.clone()).collect();
        for s in d.sigs.iter_mut() {
            if let Role::Alias(e) = &mut s.role {
                e.map_reads(&mut |r| match &sigs_snapshot[r] {
                    Role::Alias(x) => Some(x.clone()),
                    _ => None,
                });
            }
        }
        for b in &mut d.blocks {
            b.stmts = dead_stores(simplify(std::mem::take(&mut b.stmts)));
        }
    }
}

/// The expression a signal's value is: itself, or what it aliases.
pub fn value_of(d: &Design, s: SigId) -> Expr {
    match &d.sigs[s].role {
        Role::Alias(e) => e.clone(),
        _ => Expr::read(s, d.sigs[s].width),
    }
}
