//! From the collected hierarchy to the flattened [`Design`]: signals and their roles,
//! every `#[hdl_gen]` block lowered to typed statements over global signal ids
//! (loops unrolled, names resolved the way rust-hdl's Verilog generator resolves them),
//! the primitives, and the clock network (wiring only: every clock must come from the
//! top-level clock input unchanged).

use std::collections::{BTreeSet, HashMap};

use rust_hdl::core::ast::{Verilog, VerilogBlockOrConditional, VerilogExpression, VerilogStatement};
use rust_hdl::core::prelude::AtomKind;

use crate::collect::{Hierarchy, ValueType};
use crate::error::{Error, Result};
use crate::ir::{assigned, CombBlock, Design, Dff, Ram, Role, Sig, SigId, Stmt};
use crate::names::{fixup, parse_int};
use crate::prims::{recognise, Prim};

/// Lowering context of one module's block.
pub(crate) struct Lower<'a> {
    pub(crate) sigs: &'a [Sig],
    pub(crate) hier: &'a Hierarchy,
    pub(crate) module: usize,
    /// Names visible in the module: its own atoms and its children's ports.
    pub(crate) names: HashMap<String, SigId>,
    /// `Type$Variant` -> (enum index, value).
    pub(crate) enum_consts: &'a HashMap<String, (usize, u128)>,
    pub(crate) loops: Vec<(String, usize)>,
    /// Clock wiring found: (target, source).
    pub(crate) clocks: Vec<(SigId, SigId)>,
    pub(crate) warnings: Vec<String>,
    /// Lowering a bit index or slice offset (a `usize` in Rust).
    pub(crate) index_mode: bool,
}

impl Lower<'_> {
    pub(crate) fn module_path(&self) -> String {
        let p = self.hier.modules[self.module].dotted();
        if p.is_empty() {
            "top".into()
        } else {
            p
        }
    }
    pub(crate) fn unsupported(&self, what: &str) -> Error {
        Error::Unsupported(format!("module `{}`: {what}", self.module_path()))
    }
    pub(crate) fn width_err(&self, what: String) -> Error {
        Error::Width { module: self.module_path(), what }
    }
    pub(crate) fn warn(&mut self, what: String) {
        let m = self.module_path();
        self.warnings.push(format!("module `{m}`: {what}"));
    }
    pub(crate) fn enum_width(&self, e: usize) -> usize {
        rust_hdl::core::prelude::clog2(self.hier.enums[e].variants.len())
    }

    fn target(&mut self, e: &VerilogExpression) -> Result<SigId> {
        match e {
            VerilogExpression::Signal(raw) => {
                let name = fixup(raw, &self.loops)?;
                self.names.get(&name).copied().ok_or(Error::UnknownSignal { module: self.module_path(), name })
            }
            _ => Err(self.unsupported("an assignment to something other than a signal")),
        }
    }

    fn block(&mut self, src: &[VerilogStatement], depth: usize) -> Result<Vec<Stmt>> {
        let mut out = vec![];
        for s in src {
            self.statement(s, depth, &mut out)?;
        }
        Ok(out)
    }

    fn statement(&mut self, s: &VerilogStatement, depth: usize, out: &mut Vec<Stmt>) -> Result<()> {
        use VerilogStatement as S;
        match s {
            S::Assignment(t, v) => {
                let t = self.target(t)?;
                let sig = &self.sigs[t];
                let (w, tclock, path) = (sig.width, sig.ty == ValueType::Clock, sig.path.clone());
                let v = self.expr(v)?;
                if tclock {
                    match (&v.e.k, v.clock, depth) {
                        (crate::ir::Ek::Read(src), true, 0) => self.clocks.push((t, *src)),
                        _ => return Err(self.unsupported(&format!("clock `{path}` driven by something other than a clock wire (gated or derived clocks)"))),
                    }
                } else {
                    let v = self.fit(v, w, &format!("assignment to `{path}`"))?;
                    out.push(Stmt::Assign { s: t, v });
                }
            }
            S::SliceAssignment { base, width, offset, replacement } => {
                let t = self.target(base)?;
                let off = self.index_expr(offset, "slice assignment offset")?;
                let v = self.expr(replacement)?;
                let v = self.fit(v, *width, "slice assignment")?;
                out.push(Stmt::AssignSlice { s: t, off, w: *width, v });
            }
            S::If(c) => {
                let test = self.expr(&c.test)?;
                let test = self.fit_bool(test, "if condition")?;
                let t = self.block(&c.then, depth + 1)?;
                let e = match &c.otherwise {
                    VerilogBlockOrConditional::Block(b) => self.block(b, depth + 1)?,
                    VerilogBlockOrConditional::Conditional(s) => self.block(std::slice::from_ref(s), depth + 1)?,
                    VerilogBlockOrConditional::None => vec![],
                };
                out.push(Stmt::If { c: test, t, e });
            }
            S::Match(m) => out.push(self.lower_match(m, depth)?),
            S::Loop(l) => {
                for i in l.from.as_usize()..l.to.as_usize() {
                    self.loops.push((l.index.clone(), i));
                    let b = self.block(&l.block, depth);
                    self.loops.pop();
                    out.extend(b?);
                }
            }
            S::Comment(_) => {}
            S::Macro(b) => out.extend(self.block(b, depth)?),
            S::Link(_) => return Err(self.unsupported("interface links (LogicInterface join/link)")),
        }
        Ok(())
    }

    fn lower_match(&mut self, m: &rust_hdl::core::ast::VerilogMatch, depth: usize) -> Result<Stmt> {
        let sel = self.expr(&m.test)?;
        if sel.flex {
            return Err(self.unsupported("a match on an untyped literal"));
        }
        let w = sel.e.w;
        let domain: u128 = match &sel.e.k {
            crate::ir::Ek::Read(s) => match self.sigs[*s].ty {
                ValueType::Enum(e) => self.hier.enums[e].variants.len() as u128,
                _ => 1u128 << w.min(127),
            },
            _ => 1u128 << w.min(127),
        };
        let mut arms: Vec<(Vec<u128>, Vec<Stmt>)> = vec![];
        let mut seen = BTreeSet::new();
        let mut default = None;
        for case in &m.cases {
            if default.is_some() {
                break; // arms after a wildcard are unreachable in Rust
            }
            let label = fixup(&case.condition, &self.loops)?;
            let block = self.block(&case.block, depth + 1)?;
            if label == "default" {
                default = Some(block);
                continue;
            }
            let v = match label.as_str() {
                "true" => 1,
                "false" => 0,
                _ => match parse_int(&label) {
                    Some(v) => v,
                    None => match self.enum_consts.get(&label) {
                        Some(&(_, v)) => v,
                        None => return Err(self.unsupported(&format!("match pattern `{}`", case.condition))),
                    },
                },
            };
            if v >= domain {
                self.warn(format!("match label {label} outside the {w}-bit domain"));
                continue;
            }
            if seen.insert(v) {
                arms.push((vec![v], block));
            }
        }
        // `exhaustive`: the labels alone cover every value (no path through the default)
        let exhaustive = seen.len() as u128 == domain;
        Ok(Stmt::Case { sel: sel.e, arms, default: if exhaustive { vec![] } else { default.unwrap_or_default() }, exhaustive })
    }
}

fn check_atom(h: &Hierarchy, a: usize) -> Result<()> {
    let at = &h.atoms[a];
    let path = h.atom_path(a);
    match at.ty {
        ValueType::Signed => return Err(Error::Unsupported(format!("`{path}`: Signed values"))),
        ValueType::Composite => return Err(Error::Unsupported(format!("`{path}`: LogicStruct values"))),
        _ => {}
    }
    if at.kind == AtomKind::InOutParameter {
        return Err(Error::Unsupported(format!("`{path}`: InOut (tristate) signals")));
    }
    if at.width == 0 || at.width > 128 {
        return Err(Error::Unsupported(format!("`{path}`: {} bits (1..=128 are supported)", at.width)));
    }
    Ok(())
}

/// Names visible in module `m`: its atoms, and `child$port` for its children's ports.
fn visible_names(h: &Hierarchy, m: usize) -> HashMap<String, SigId> {
    let mut names = HashMap::new();
    for &a in &h.modules[m].atoms {
        names.insert(h.atoms[a].name.clone(), a);
    }
    for &c in &h.modules[m].children {
        for &a in &h.modules[c].atoms {
            if h.atoms[a].kind.is_parameter() {
                names.insert(format!("{}${}", h.modules[c].name, h.atoms[a].name), a);
            }
        }
    }
    names
}

/// Follow clock wiring back to its source.
fn clock_root(src: &HashMap<SigId, SigId>, mut s: SigId) -> SigId {
    let mut n = 0;
    while let Some(&p) = src.get(&s) {
        s = p;
        n += 1;
        if n > src.len() {
            break;
        }
    }
    s
}

/// Build the flattened design from a collected hierarchy.
pub fn lower(h: Hierarchy) -> Result<Design> {
    for a in 0..h.atoms.len() {
        check_atom(&h, a)?;
    }
    let mut sigs: Vec<Sig> = (0..h.atoms.len())
        .map(|a| {
            let at = &h.atoms[a];
            let role = match (at.kind, &at.ty) {
                (_, ValueType::Clock) => Role::Clock,
                (AtomKind::Constant, _) => Role::Const,
                (AtomKind::InputParameter, _) if at.module == 0 => Role::Input,
                _ => Role::Undriven,
            };
            Sig { path: h.atom_path(a), module: at.module, atom: a, width: at.width, ty: at.ty.clone(), role, reads_settled: at.kind == AtomKind::InputParameter }
        })
        .collect();
    let mut enum_consts = HashMap::new();
    for (i, e) in h.enums.iter().enumerate() {
        for (v, name) in e.variants.iter().enumerate() {
            enum_consts.insert(name.replace("::", "$"), (i, v as u128));
        }
    }
    let mut blocks = vec![];
    let mut prims = vec![];
    let mut clocks = vec![];
    let mut warnings = vec![];
    for m in 0..h.modules.len() {
        let path = if m == 0 { "top".to_string() } else { h.modules[m].dotted() };
        match &h.modules[m].code {
            Verilog::Combinatorial(code) => {
                let mut l = Lower { sigs: &sigs, hier: &h, module: m, names: visible_names(&h, m), enum_consts: &enum_consts, loops: vec![], clocks: vec![], warnings: vec![], index_mode: false };
                let stmts = l.block(code, 0)?;
                clocks.extend(l.clocks);
                warnings.extend(l.warnings);
                blocks.push(CombBlock { module: m, stmts });
            }
            Verilog::Custom(text) => match recognise(&h, m, text) {
                Some(p) => prims.push((m, p)),
                None => return Err(Error::Unsupported(format!("module `{path}`: custom Verilog that is neither rust-hdl's DFF nor its RAM"))),
            },
            Verilog::Empty => {
                if !h.modules[m].atoms.is_empty() || !h.modules[m].children.is_empty() {
                    return Err(Error::Unsupported(format!("module `{path}` has no HDL (its update() cannot be compiled)")));
                }
            }
            Verilog::Blackbox(_) | Verilog::Wrapper(_) => {
                return Err(Error::Unsupported(format!("module `{path}`: black-box or wrapped external Verilog")))
            }
        }
    }
    // roles of assigned signals
    for (b, blk) in blocks.iter().enumerate() {
        for s in assigned(&blk.stmts) {
            let sig = &mut sigs[s];
            match sig.role {
                Role::Undriven => {
                    if sig.reads_settled && sig.module == blk.module {
                        return Err(Error::Unsupported(format!("`{}`: a module assigns its own input", sig.path)));
                    }
                    sig.role = Role::Comb(b)
                }
                Role::Comb(_) => return Err(Error::MultipleDrivers(sig.path.clone())),
                _ => return Err(Error::Unsupported(format!("`{}` is assigned but is an input, constant or register output", sig.path))),
            }
        }
    }
    // clocks
    let top_clocks: Vec<SigId> = h.modules[0].atoms.iter().copied().filter(|&a| sigs[a].role == Role::Clock && h.atoms[a].kind == AtomKind::InputParameter).collect();
    if top_clocks.len() > 1 {
        return Err(Error::Unsupported("more than one clock input at the top".into()));
    }
    let clock_src: HashMap<SigId, SigId> = clocks.into_iter().collect();
    let clocked = |c: SigId| top_clocks.first().is_some_and(|&t| clock_root(&clock_src, c) == t);
    let mut dffs = vec![];
    let mut rams = vec![];
    for (m, p) in prims {
        match p {
            Prim::Dff { d, q, clock, init } => {
                let on = clocked(clock);
                if !on {
                    warnings.push(format!("flip-flop `{}` is not clocked by the top clock: it keeps its value", sigs[q].path));
                }
                sigs[q].role = Role::Reg(dffs.len());
                dffs.push(Dff { module: m, d, q, clocked: on, init });
            }
            Prim::Ram { read_address, read_clock, read_data, write_address, write_clock, write_data, write_enable, init } => {
                sigs[read_data].role = Role::RamRead(rams.len());
                rams.push(Ram {
                    module: m,
                    read_address,
                    read_data,
                    write_address,
                    write_data,
                    write_enable,
                    read_clocked: clocked(read_clock),
                    write_clocked: clocked(write_clock),
                    dw: sigs[read_data].width,
                    aw: sigs[read_address].width,
                    init,
                });
            }
        }
    }
    let inputs = h.modules[0].atoms.iter().copied().filter(|&a| sigs[a].role == Role::Input).collect();
    let outputs = h.modules[0].atoms.iter().copied().filter(|&a| h.atoms[a].kind == AtomKind::OutputParameter && sigs[a].role != Role::Clock).collect();
    Ok(Design { hier: h, sigs, blocks, dffs, rams, inputs, outputs, warnings })
}
