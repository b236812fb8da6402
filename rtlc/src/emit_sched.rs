//! The evaluation machinery of a generated model: activity tracking and the clock.
//!
//! Every scheduled group has a dirty bit. A group runs only when one of the stored
//! values it reads has changed since it last ran: storing a group's result, committing
//! a register at the edge, or an input differing from its last seen value sets the
//! dirty bits of the groups that read it. Groups are numbered in dependency order and
//! a group only marks later ones, so one pass over the dirty bits, lowest first,
//! evaluates every group that needs it exactly once. rust-hdl (and Verilator)
//! evaluate everything every clock; a CAN design is idle most clocks (clock enables,
//! one bit per many clocks), so most groups are skipped.
//!
//! Registers work the same way: a register whose input comes from a group, an input
//! or a constant is pending when that value changed since the register last took it,
//! and only pending registers are looked at on the edge. Registers fed from other
//! registers (shift chains) and the memories are handled on every edge, their inputs
//! read before anything commits (two-phase update).
//!
//! Per clock:
//! ```text
//! cycle(): sense()        inputs that changed mark their readers
//!          run(PRE)       dirty input-dependent groups
//!          edge()         registers and memories take their inputs; changes mark readers
//!          run(POST)      dirty state-only groups and output cone (ALL when tracing)
//! ```

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write;

use crate::emit_expr::Ctx;
use crate::ir::{Design, Expr, Role, SigId, Stmt};
use crate::opt::value_of;
use crate::sched::{Class, Group, Schedule};

/// Which groups (and pending-tracked registers) read which stored values.
pub struct Activity {
    /// Readers of each stored signal (group numbers, ascending).
    pub readers: BTreeMap<SigId, Vec<usize>>,
    /// Number of 64-bit dirty words.
    pub words: usize,
    /// Pending-tracked registers: (flip-flop index, source value), numbered in order.
    pub regs: Vec<(usize, Expr)>,
    /// Pending-tracked registers fed by each stored signal.
    pub reg_readers: BTreeMap<SigId, Vec<usize>>,
    /// Number of 64-bit pending words.
    pub reg_words: usize,
    /// Registers taken on every edge (fed from the state): flip-flop indices.
    pub chained: Vec<usize>,
}

/// Does `e` read a register or a memory output?
fn reads_state(d: &Design, e: &Expr) -> bool {
    let mut st = false;
    e.reads(&mut |r| st |= matches!(d.sigs[r].role, Role::Reg(_) | Role::RamRead(_)));
    st
}

fn stmt_reads(stmts: &[Stmt], f: &mut dyn FnMut(SigId)) {
    for s in stmts {
        s.walk(&mut |s| {
            for e in s.exprs() {
                e.reads(f);
            }
        });
    }
}

/// Stored values a group reads (through `self.`): settled reads and the stored
/// values its locals start from.
pub fn field_reads(d: &Design, g: &Group) -> BTreeSet<SigId> {
    let mut out: BTreeSet<SigId> = g.init.clone();
    stmt_reads(&g.stmts, &mut |r| {
        if !g.locals.contains(&r) || d.sigs[r].reads_settled {
            out.insert(r);
        }
    });
    out
}

impl Activity {
    pub fn of(d: &Design, sch: &Schedule) -> Activity {
        let mut readers: BTreeMap<SigId, Vec<usize>> = BTreeMap::new();
        for (k, g) in sch.groups.iter().enumerate() {
            for r in field_reads(d, g) {
                readers.entry(r).or_default().push(k);
            }
        }
        let mut regs = vec![];
        let mut reg_readers: BTreeMap<SigId, Vec<usize>> = BTreeMap::new();
        let mut chained = vec![];
        for (i, f) in d.dffs.iter().enumerate() {
            let v = value_of(d, f.d);
            if !f.clocked || v == Expr::read(f.q, d.sigs[f.q].width) {
                continue;
            }
            if reads_state(d, &v) {
                chained.push(i);
                continue;
            }
            let k = regs.len();
            v.reads(&mut |r| reg_readers.entry(r).or_default().push(k));
            regs.push((i, v));
        }
        Activity { readers, words: sch.groups.len().div_ceil(64).max(1), reg_words: regs.len().div_ceil(64).max(1), regs, reg_readers, chained }
    }

    /// Statements marking the readers of `s` dirty (except group `me`) and the
    /// registers it feeds pending.
    pub fn mark(&self, s: SigId, me: Option<usize>) -> String {
        let mut words: BTreeMap<usize, u64> = BTreeMap::new();
        for &k in self.readers.get(&s).into_iter().flatten() {
            if Some(k) != me {
                *words.entry(k / 64).or_default() |= 1u64 << (k % 64);
            }
        }
        let mut regs: BTreeMap<usize, u64> = BTreeMap::new();
        for &k in self.reg_readers.get(&s).into_iter().flatten() {
            *regs.entry(k / 64).or_default() |= 1u64 << (k % 64);
        }
        let mut out: Vec<String> = words.iter().map(|(w, m)| format!("self.dirty[{w}] |= {m:#x};")).collect();
        out.extend(regs.iter().map(|(w, m)| format!("self.pend[{w}] |= {m:#x};")));
        out.join(" ")
    }

    /// Bit masks (per word) of the groups whose class satisfies `pred`.
    pub fn phase(&self, sch: &Schedule, pred: &dyn Fn(Class) -> bool) -> String {
        let mut m = vec![0u64; self.words];
        for (k, g) in sch.groups.iter().enumerate() {
            if pred(g.class) {
                m[k / 64] |= 1u64 << (k % 64);
            }
        }
        format!("[{}]", m.iter().map(|x| format!("{x:#x}")).collect::<Vec<_>>().join(", "))
    }
}

/// `self.t = t;`, marking the readers when the value changes.
pub fn store(act: &Activity, names: &[String], t: SigId, value: &str, me: Option<usize>) -> String {
    let mark = act.mark(t, me);
    if mark.is_empty() {
        format!("self.{} = {value};", names[t])
    } else {
        format!("if {value} != self.{0} {{ self.{0} = {value}; {mark} }}", names[t])
    }
}

/// Phase masks, `run`, `group`, `sense`, `cycle`, `settle`, `eval_all` and `edge`.
pub fn emit_clock(s: &mut String, d: &Design, sch: &Schedule, act: &Activity, names: &[String], mems: &[String], top: &Ctx) {
    let w = act.words;
    let _ = writeln!(s, "    /// Groups evaluated before the edge: input-dependent.");
    let _ = writeln!(s, "    const PRE: [u64; {w}] = {};", act.phase(sch, &|c| matches!(c, Class::InputDep | Class::InputDepCone)));
    let _ = writeln!(s, "    /// Groups evaluated after the edge: state-only and the output cone.");
    let _ = writeln!(s, "    const POST: [u64; {w}] = {};", act.phase(sch, &|c| matches!(c, Class::StateOnly | Class::InputDepCone)));
    let _ = writeln!(s, "    const ALL: [u64; {w}] = {};\n", act.phase(sch, &|_| true));
    let _ = writeln!(s, "    /// One clock cycle (`canstar_hdl::drive::cycle`): settle, rising edge, settle.");
    let _ = writeln!(
        s,
        "    pub fn cycle(&mut self) {{\n        self.sense();\n        self.run(&Self::PRE);\n        self.edge();\n        self.run(if self.trace {{ &Self::ALL }} else {{ &Self::POST }});\n    }}\n"
    );
    let _ = writeln!(s, "    /// Propagate input changes (no clock edge).");
    let _ = writeln!(s, "    pub fn settle(&mut self) {{\n        self.sense();\n        self.run(if self.trace {{ &Self::ALL }} else {{ &Self::PRE }});\n    }}\n");
    let _ = writeln!(s, "    /// Evaluate every group.");
    let _ = writeln!(
        s,
        "    fn eval_all(&mut self) {{\n        self.dirty = [!0; {w}];\n        self.pend = [!0; {}];\n        self.sense();\n        self.run(&Self::ALL);\n    }}\n",
        act.reg_words
    );
    let _ = writeln!(s, "    /// Run the dirty groups of a phase, in dependency order.");
    let _ = writeln!(
        s,
        "    fn run(&mut self, phase: &[u64; {w}]) {{\n        for w in 0..{w} {{\n            loop {{\n                let m = self.dirty[w] & phase[w];\n                if m == 0 {{\n                    break;\n                }}\n                let k = m.trailing_zeros() as usize;\n                self.dirty[w] &= !(1u64 << k);\n                self.group(w * 64 + k);\n            }}\n        }}\n    }}\n"
    );
    // not inlined into the loop: the optimiser would hoist every arm's loads out of it
    let _ = writeln!(s, "    #[inline(never)]\n    fn group(&mut self, k: usize) {{\n        match k {{");
    for k in 0..sch.groups.len() {
        let _ = writeln!(s, "            {k} => self.g{k}(),");
    }
    let _ = writeln!(s, "            _ => {{}}\n        }}\n    }}\n");
    // inputs
    let _ = writeln!(s, "    /// Inputs that changed since they were last seen mark their readers.");
    let _ = writeln!(s, "    fn sense(&mut self) {{");
    for &x in &d.inputs {
        let mark = act.mark(x, None);
        if !mark.is_empty() {
            let _ = writeln!(s, "        if self.{0} != self.seen_{0} {{ self.seen_{0} = self.{0}; {mark} }}", names[x]);
        }
    }
    let _ = writeln!(s, "    }}\n");
    emit_edge(s, d, act, names, mems, top);
}

/// Inputs with readers keep a copy of the value last seen (`seen_<name>`).
pub fn sensed_inputs(d: &Design, act: &Activity) -> Vec<SigId> {
    d.inputs.iter().copied().filter(|&x| !act.mark(x, None).is_empty()).collect()
}

/// The state update at the rising edge: inputs of the chained registers and memory
/// reads first, then memory writes, then the pending registers, then the chained ones.
fn emit_edge(s: &mut String, d: &Design, act: &Activity, names: &[String], mems: &[String], top: &Ctx) {
    let _ = writeln!(s, "    /// Rising edge: registers and memories take their inputs.");
    let _ = writeln!(s, "    fn edge(&mut self) {{");
    let mut commits = vec![];
    for &i in &act.chained {
        let f = &d.dffs[i];
        let _ = writeln!(s, "        let n{i} = {};", top.ex(&value_of(d, f.d)));
        commits.push(store(act, names, f.q, &format!("n{i}"), None));
    }
    for (r, ram) in d.rams.iter().enumerate() {
        let words = 1usize << ram.aw;
        let idx = |e: &Expr| format!("(({} as usize) & {})", top.ex(e), words - 1);
        if ram.read_clocked {
            let _ = writeln!(s, "        let m{r} = self.{}[{}];", mems[r], idx(&value_of(d, ram.read_address)));
            commits.push(store(act, names, ram.read_data, &format!("m{r}"), None));
        }
        if ram.write_clocked {
            let we = value_of(d, ram.write_enable);
            let _ = writeln!(s, "        if {} {{", top.ex(&we));
            let _ = writeln!(s, "            self.{}[{}] = {};", mems[r], idx(&value_of(d, ram.write_address)), top.ex(&value_of(d, ram.write_data)));
            let _ = writeln!(s, "        }}");
        }
    }
    let w = act.reg_words;
    let _ = writeln!(
        s,
        "        for w in 0..{w} {{\n            loop {{\n                let m = self.pend[w];\n                if m == 0 {{\n                    break;\n                }}\n                let k = m.trailing_zeros() as usize;\n                self.pend[w] &= !(1u64 << k);\n                self.take(w * 64 + k);\n            }}\n        }}"
    );
    for c in commits {
        let _ = writeln!(s, "        {c}");
    }
    let _ = writeln!(s, "    }}\n");
    let _ = writeln!(s, "    /// Pending register `k` takes its input.");
    let _ = writeln!(s, "    #[inline(never)]\n    fn take(&mut self, k: usize) {{\n        match k {{");
    for (k, (i, v)) in act.regs.iter().enumerate() {
        let q = d.dffs[*i].q;
        let _ = writeln!(s, "            {k} => {{\n                let n = {};\n                {}\n            }}", top.ex(v), store(act, names, q, "n", None));
    }
    let _ = writeln!(s, "            _ => {{}}\n        }}\n    }}\n");
}
