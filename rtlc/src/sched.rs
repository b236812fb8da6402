//! Scheduling: the combinational blocks cut into pieces that can be evaluated once
//! each, in dependency order, per clock.
//!
//! rust-hdl evaluates every block again and again until nothing changes; a parent's
//! block typically writes a child's inputs, reads the child's outputs and writes other
//! children's inputs, so no whole-block order exists. Each block is therefore sliced
//! per assigned signal (the slice keeps the block's control flow and the assignments
//! of every block-local value the target's assignments read), the slices form a
//! dependency graph (a cycle is a combinational loop: reported with its signals), and
//! slices of the same block at the same depth and of the same evaluation class are
//! merged back into one group of straight-line code.
//!
//! Reads follow rust-hdl: an `In` signal's `val()` is its settled value; an `Out` or
//! `Local` signal the block itself assigns reads the value assigned so far in the
//! block, or, before the first assignment on the path, the settled value.
//!
//! Classes: a group is needed (it feeds a register, a memory or an output) or only
//! shown to probes; a needed group depends on the inputs or only on the state; an
//! input-dependent group may be in the output cone. Per clock the model evaluates the
//! input-dependent groups before the edge and the state-only groups plus the output
//! cone after it (see [`crate::emit`]).

use std::collections::{BTreeMap, BTreeSet, HashMap};

use petgraph::graph::{DiGraph, NodeIndex};

use crate::error::{Error, Result};
use crate::ir::{Design, Expr, Role, SigId, Stmt};


#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Class {
    /// Reads only registers, memories and constants: valid from the edge to the next.
    StateOnly,
    /// Depends on the inputs, not needed for an output.
    InputDep,
    /// Depends on the inputs and an output needs it.
    InputDepCone,
    /// Nothing but probes needs it (evaluated only when tracing).
    ProbeOnly,
}

#[derive(Clone, Debug)]
pub struct Group {
    pub block: usize,
    pub depth: usize,
    pub class: Class,
    /// Signals whose value this group stores.
    pub targets: BTreeSet<SigId>,
    /// Block-local values computed in the group (targets and helpers).
    pub locals: BTreeSet<SigId>,
    /// Locals that start from their stored value (read before assigned, or latches).
    pub init: BTreeSet<SigId>,
    pub stmts: Vec<Stmt>,
}

#[derive(Clone, Debug, Default)]
pub struct Schedule {
    /// In evaluation order.
    pub groups: Vec<Group>,
    pub slices: usize,
    pub warnings: Vec<String>,
}

/// Marker for "the value before the block assigns it" in reaching-definition sets.
const INIT: usize = usize::MAX;

/// Signals read at one point: the block-local definitions that reach the reads,
/// the locals whose settled value reaches them, and the settled reads of others.
#[derive(Clone, Debug, Default)]
struct Reads {
    defs: BTreeSet<usize>,
    inits: BTreeSet<SigId>,
    settled: BTreeSet<SigId>,
}

impl Reads {
    fn extend(&mut self, o: &Reads) {
        self.defs.extend(o.defs.iter().copied());
        self.inits.extend(o.inits.iter().copied());
        self.settled.extend(o.settled.iter().copied());
    }
}

/// One assignment of a block (numbered in pre-order) and what its value and the
/// conditions around it read.
#[derive(Clone, Debug)]
struct Def {
    target: SigId,
    reads: Reads,
}

/// Reaching definitions per block-local signal (absent: only `INIT`).
type State = HashMap<SigId, BTreeSet<usize>>;

fn merge(states: Vec<State>) -> State {
    let mut keys: BTreeSet<SigId> = BTreeSet::new();
    for st in &states {
        keys.extend(st.keys().copied());
    }
    let mut out = State::new();
    for k in keys {
        let mut set = BTreeSet::new();
        for st in &states {
            match st.get(&k) {
                Some(s) => set.extend(s.iter().copied()),
                None => {
                    set.insert(INIT);
                }
            }
        }
        out.insert(k, set);
    }
    out
}

/// Reaching-definition analysis of one block (structured control flow).
struct Rd<'a> {
    is_local: &'a dyn Fn(SigId) -> bool,
    defs: Vec<Def>,
}

impl Rd<'_> {
    fn reads(&self, e: &Expr, st: &State, out: &mut Reads) {
        e.reads(&mut |r| self.read(r, st, out));
    }
    fn read(&self, r: SigId, st: &State, out: &mut Reads) {
        if !(self.is_local)(r) {
            out.settled.insert(r);
            return;
        }
        match st.get(&r) {
            None => {
                out.inits.insert(r);
            }
            Some(set) => {
                for &d in set {
                    if d == INIT {
                        out.inits.insert(r);
                    } else {
                        out.defs.insert(d);
                    }
                }
            }
        }
    }
    fn walk(&mut self, stmts: &[Stmt], st: &mut State, conds: &mut Vec<Reads>) {
        for s in stmts {
            match s {
                Stmt::Assign { s: t, v } => {
                    let mut r = Reads::default();
                    self.reads(v, st, &mut r);
                    conds.iter().for_each(|c| r.extend(c));
                    st.insert(*t, BTreeSet::from([self.defs.len()]));
                    self.defs.push(Def { target: *t, reads: r });
                }
                Stmt::AssignSlice { s: t, off, v, .. } => {
                    let mut r = Reads::default();
                    self.reads(off, st, &mut r);
                    self.reads(v, st, &mut r);
                    // read-modify-write of the target's current value
                    match st.get(t) {
                        None => {
                            r.inits.insert(*t);
                        }
                        Some(set) => {
                            for &d in set {
                                if d == INIT {
                                    r.inits.insert(*t);
                                } else {
                                    r.defs.insert(d);
                                }
                            }
                        }
                    }
                    conds.iter().for_each(|c| r.extend(c));
                    st.insert(*t, BTreeSet::from([self.defs.len()]));
                    self.defs.push(Def { target: *t, reads: r });
                }
                Stmt::If { c, t, e } => {
                    let mut rc = Reads::default();
                    self.reads(c, st, &mut rc);
                    conds.push(rc);
                    let mut a = st.clone();
                    self.walk(t, &mut a, conds);
                    let mut b = st.clone();
                    self.walk(e, &mut b, conds);
                    conds.pop();
                    *st = merge(vec![a, b]);
                }
                Stmt::Case { sel, arms, default, exhaustive } => {
                    let mut rc = Reads::default();
                    self.reads(sel, st, &mut rc);
                    conds.push(rc);
                    let mut outs = vec![];
                    for (_, b) in arms {
                        let mut x = st.clone();
                        self.walk(b, &mut x, conds);
                        outs.push(x);
                    }
                    let mut x = st.clone();
                    self.walk(default, &mut x, conds);
                    if !exhaustive {
                        outs.push(x);
                    }
                    conds.pop();
                    *st = merge(outs);
                }
            }
        }
    }
}

/// Keep only the assignments whose pre-order number is in `keep` (and the control
/// flow around them).
pub fn filter(stmts: &[Stmt], keep: &BTreeSet<usize>) -> Vec<Stmt> {
    let mut n = 0;
    filter_ids(stmts, keep, &mut n)
}

fn filter_ids(stmts: &[Stmt], keep: &BTreeSet<usize>, n: &mut usize) -> Vec<Stmt> {
    let mut out = vec![];
    for s in stmts {
        match s {
            Stmt::Assign { .. } | Stmt::AssignSlice { .. } => {
                if keep.contains(n) {
                    out.push(s.clone())
                }
                *n += 1;
            }
            Stmt::If { c, t, e } => {
                let t = filter_ids(t, keep, n);
                let e = filter_ids(e, keep, n);
                if !t.is_empty() || !e.is_empty() {
                    out.push(Stmt::If { c: c.clone(), t, e });
                }
            }
            Stmt::Case { sel, arms, default, exhaustive } => {
                let arms: Vec<(Vec<u128>, Vec<Stmt>)> = arms.iter().map(|(l, b)| (l.clone(), filter_ids(b, keep, n))).collect();
                let default = filter_ids(default, keep, n);
                if arms.iter().any(|a| !a.1.is_empty()) || !default.is_empty() {
                    out.push(Stmt::Case { sel: sel.clone(), arms, default, exhaustive: *exhaustive });
                }
            }
        }
    }
    out
}

struct Slice {
    block: usize,
    target: SigId,
    /// Assignments (pre-order numbers) the target's value needs.
    keep: BTreeSet<usize>,
    reads: Reads,
    latch: bool,
}

/// Cut, order and group the design's combinational logic.
/// `keep`: signals to evaluate every clock even when nothing but probes needs them.
pub fn schedule(d: &Design, keep: &[SigId]) -> Result<Schedule> {
    let mut slices: Vec<Slice> = vec![];
    let mut owner: HashMap<SigId, usize> = HashMap::new();
    let mut block_defs: Vec<Vec<Def>> = vec![];
    for (b, blk) in d.blocks.iter().enumerate() {
        let w = d.writes(b);
        let is_local = |s: SigId| w.contains(&s) && !d.sigs[s].reads_settled;
        let mut rd = Rd { is_local: &is_local, defs: vec![] };
        let mut st = State::new();
        rd.walk(&blk.stmts, &mut st, &mut vec![]);
        for &t in &w {
            let fin = st.get(&t).cloned().unwrap_or_else(|| BTreeSet::from([INIT]));
            let latch = fin.contains(&INIT);
            let mut keep = BTreeSet::new();
            let mut todo: Vec<usize> = fin.into_iter().filter(|&x| x != INIT).collect();
            let mut reads = Reads::default();
            while let Some(k) = todo.pop() {
                if !keep.insert(k) {
                    continue;
                }
                reads.extend(&rd.defs[k].reads);
                todo.extend(rd.defs[k].reads.defs.iter().copied());
            }
            owner.insert(t, slices.len());
            slices.push(Slice { block: b, target: t, keep, reads, latch });
        }
        block_defs.push(rd.defs);
    }
    let mut warnings = vec![];
    let mut g: DiGraph<usize, ()> = DiGraph::new();
    let nodes: Vec<NodeIndex> = (0..slices.len()).map(|i| g.add_node(i)).collect();
    let mut reads_input = vec![false; slices.len()];
    let path = |s: SigId| d.sigs[s].path.clone();
    for (i, sl) in slices.iter().enumerate() {
        let mut deps = BTreeSet::new();
        for &r in &sl.reads.settled {
            match d.sigs[r].role {
                Role::Comb(_) => {
                    let o = owner[&r];
                    if o == i {
                        return Err(Error::CombLoop(vec![path(r)]));
                    }
                    deps.insert(o);
                }
                Role::Input => reads_input[i] = true,
                _ => {}
            }
        }
        for &r in &sl.reads.inits {
            if r == sl.target {
                return Err(Error::CombLoop(vec![format!("{} (read before it is assigned in its own block)", path(r))]));
            }
            deps.insert(owner[&r]);
        }
        if sl.latch {
            warnings.push(format!("`{}` is not assigned on every path (a latch: it keeps its value)", path(sl.target)));
        }
        for o in deps {
            g.add_edge(nodes[o], nodes[i], ());
        }
    }
    for scc in petgraph::algo::tarjan_scc(&g) {
        if scc.len() > 1 {
            let mut names: Vec<String> = scc.iter().map(|n| path(slices[g[*n]].target)).collect();
            names.sort();
            return Err(Error::CombLoop(names));
        }
    }
    let order = petgraph::algo::toposort(&g, None).map_err(|c| Error::CombLoop(vec![path(slices[g[c.node_id()]].target)]))?;
    let n = slices.len();
    let mut depth = vec![0usize; n];
    let mut input_dep = reads_input.clone();
    for &v in &order {
        let i = g[v];
        for p in g.neighbors_directed(v, petgraph::Direction::Incoming) {
            let j = g[p];
            depth[i] = depth[i].max(depth[j] + 1);
            input_dep[i] |= input_dep[j];
        }
    }
    // needed / output cone: reverse reachability from the sinks
    let sink_slices = |sigs: Vec<SigId>| -> Vec<usize> {
        let mut out = vec![];
        for s in sigs {
            crate::opt::value_of(d, s).reads(&mut |r| {
                if let Some(&o) = owner.get(&r) {
                    out.push(o)
                }
            });
        }
        out
    };
    let reach = |start: Vec<usize>| -> Vec<bool> {
        let mut seen = vec![false; n];
        let mut todo = start;
        while let Some(i) = todo.pop() {
            if std::mem::replace(&mut seen[i], true) {
                continue;
            }
            for p in g.neighbors_directed(nodes[i], petgraph::Direction::Incoming) {
                todo.push(g[p]);
            }
        }
        seen
    };
    let mut sinks: Vec<SigId> = d.outputs.clone();
    for f in d.dffs.iter().filter(|f| f.clocked) {
        sinks.push(f.d);
    }
    for r in &d.rams {
        if r.read_clocked {
            sinks.push(r.read_address);
        }
        if r.write_clocked {
            sinks.extend([r.write_address, r.write_data, r.write_enable]);
        }
    }
    sinks.extend(keep.iter().copied());
    let latches: Vec<usize> = (0..n).filter(|&i| slices[i].latch).collect();
    let mut sinks = sink_slices(sinks);
    sinks.extend(latches.iter().copied());
    let needed = reach(sinks);
    let mut cone_start = sink_slices(d.outputs.clone());
    cone_start.extend(latches.iter().copied());
    let cone = reach(cone_start);
    let class = |i: usize| {
        if slices[i].latch {
            Class::InputDepCone
        } else if !needed[i] {
            Class::ProbeOnly
        } else if !input_dep[i] {
            Class::StateOnly
        } else if cone[i] {
            Class::InputDepCone
        } else {
            Class::InputDep
        }
    };
    let mut groups: BTreeMap<(usize, usize, Class), Vec<usize>> = BTreeMap::new();
    for (i, sl) in slices.iter().enumerate() {
        groups.entry((depth[i], sl.block, class(i))).or_default().push(i);
    }
    let mut out = vec![];
    for ((depth, block, class), members) in groups {
        let mut keep = BTreeSet::new();
        let mut targets = BTreeSet::new();
        let mut init = BTreeSet::new();
        for &i in &members {
            keep.extend(slices[i].keep.iter().copied());
            targets.insert(slices[i].target);
            init.extend(slices[i].reads.inits.iter().copied());
            if slices[i].latch {
                init.insert(slices[i].target);
            }
        }
        let mut locals: BTreeSet<SigId> = keep.iter().map(|&k| block_defs[block][k].target).collect();
        locals.extend(targets.iter().copied());
        let init = init.intersection(&locals).copied().collect();
        let stmts = filter(&d.blocks[block].stmts, &keep);
        out.push(Group { block, depth, class, targets, locals, init, stmts });
    }
    Ok(Schedule { groups: out, slices: n, warnings })
}
