//! Rust source of a compiled model: one struct with every stored value as a field
//! of the narrowest integer type (named after its rust-hdl path), one method per
//! scheduled group, the clock ([`crate::emit_sched`]), the [`crate::rt::Model`]
//! implementation (ports, atoms, probe walk) and, optionally, functions that drive a
//! rust-hdl instance with the same port vectors.

use std::collections::{BTreeSet, HashSet};
use std::fmt::Write;

use crate::collect::ValueType;
use crate::emit_expr::{lit, ty, Ctx};
use crate::emit_sched::{emit_clock, sensed_inputs, store, Activity};
use crate::ir::{Design, Role, SigId};
use crate::sched::{Class, Schedule};

const KEYWORDS: &[&str] = &[
    "as", "break", "const", "continue", "crate", "else", "enum", "extern", "false", "fn", "for", "if", "impl", "in", "let", "loop", "match", "mod", "move",
    "mut", "pub", "ref", "return", "self", "Self", "static", "struct", "super", "trait", "true", "type", "unsafe", "use", "where", "while", "async", "await",
    "dyn", "abstract", "become", "box", "do", "final", "macro", "override", "priv", "typeof", "unsized", "virtual", "yield", "try", "gen", "rt", "trace",
];

fn sanitize(s: &str) -> String {
    let mut out: String = s.chars().map(|c| if c.is_ascii_alphanumeric() || c == '_' { c } else { '_' }).collect();
    if out.is_empty() || out.starts_with(|c: char| c.is_ascii_digit()) {
        out.insert(0, '_');
    }
    if KEYWORDS.contains(&out.as_str()) {
        out.push('_');
    }
    out
}

/// Field names: top-level ports by their name, registers by their flip-flop's path,
/// everything else by its path (`fsm.l_ev` -> `fsm_l_ev`).
pub fn field_names(d: &Design) -> (Vec<String>, Vec<String>) {
    let mut used: HashSet<String> = KEYWORDS.iter().map(|s| s.to_string()).collect();
    let mut unique = |base: String| {
        let mut n = base.clone();
        let mut k = 2;
        while !used.insert(n.clone()) {
            n = format!("{base}_{k}");
            k += 1;
        }
        n
    };
    let mut names = vec![String::new(); d.sigs.len()];
    // ports first so that they keep their plain names
    for &s in d.inputs.iter().chain(d.outputs.iter()) {
        names[s] = unique(sanitize(&d.hier.atoms[d.sigs[s].atom].name));
    }
    for (s, sig) in d.sigs.iter().enumerate() {
        if !names[s].is_empty() {
            continue;
        }
        let base = match sig.role {
            Role::Reg(_) => d.hier.modules[sig.module].dotted(),
            _ => sig.path.clone(),
        };
        names[s] = unique(sanitize(&base));
    }
    let mems = d.rams.iter().map(|r| unique(sanitize(&format!("{}_mem", d.hier.modules[r.module].dotted())))).collect();
    (names, mems)
}

/// Signals whose value only trace mode keeps current: the targets of probe-only
/// groups, and aliases that read one.
pub fn probe_only(d: &Design, sch: &Schedule) -> Vec<SigId> {
    let mut stale = vec![false; d.sigs.len()];
    for g in sch.groups.iter().filter(|g| g.class == Class::ProbeOnly) {
        for &t in &g.targets {
            stale[t] = true;
        }
    }
    (0..d.sigs.len())
        .filter(|&x| {
            stale[x]
                || match &d.sigs[x].role {
                    Role::Alias(e) => {
                        let mut any = false;
                        e.reads(&mut |r| any |= stale[r]);
                        any
                    }
                    _ => false,
                }
        })
        .collect()
}

/// Does signal `s` have a field?
pub fn stored(d: &Design, s: SigId) -> bool {
    match d.sigs[s].role {
        Role::Input | Role::Const | Role::Reg(_) | Role::RamRead(_) | Role::Comb(_) => true,
        Role::Alias(_) => d.outputs.contains(&s),
        Role::Clock | Role::Undriven => false,
    }
}

fn role_text(d: &Design, s: SigId) -> &'static str {
    match d.sigs[s].role {
        Role::Input => "input",
        Role::Const => "constant",
        Role::Reg(_) => "register",
        Role::RamRead(_) => "memory read register",
        Role::Comb(_) if d.outputs.contains(&s) => "output",
        Role::Comb(_) => "combinational",
        Role::Alias(_) => "output (constant)",
        Role::Clock | Role::Undriven => "",
    }
}

fn class_text(c: Class) -> &'static str {
    match c {
        Class::StateOnly => "state-only",
        Class::InputDep => "input-dependent",
        Class::InputDepCone => "input-dependent, output cone",
        Class::ProbeOnly => "probe-only",
    }
}

/// Code generation options (see [`crate::Options`]).
pub struct EmitOptions<'a> {
    pub name: &'a str,
    pub description: &'a str,
    pub hdl_type: Option<&'a str>,
    pub fingerprint: u64,
}

/// `v: u128` converted to the storage type of width `w`.
fn from_u128(v: &str, w: usize) -> String {
    if w == 1 {
        format!("({v} & 1) != 0")
    } else {
        format!("({v} & {:#x}) as {}", crate::ir::mask(w), ty(w))
    }
}

/// Emit the whole model source.
pub fn emit(d: &Design, sch: &Schedule, o: &EmitOptions) -> String {
    let (names, mems) = field_names(d);
    let none = BTreeSet::new();
    let top = Ctx { d, names: &names, locals: &none };
    let act = Activity::of(d, sch);
    let sensed = sensed_inputs(d, &act);
    let mut s = String::new();
    let name = o.name;
    let _ = writeln!(s, "//! Compiled model: {}", o.description);
    let _ = writeln!(s, "//!");
    let _ = writeln!(s, "//! Generated by canstar-rtlc from the rust-hdl design; do not edit. Shape fingerprint {:#018x}.", o.fingerprint);
    let _ = writeln!(
        s,
        "//! {} signals ({} stored), {} registers, {} memories, {} scheduled groups from {} slices.",
        d.sigs.len(),
        (0..d.sigs.len()).filter(|&x| stored(d, x)).count(),
        d.dffs.len(),
        d.rams.len(),
        sch.groups.len(),
        sch.slices
    );
    let _ = writeln!(s, "#![allow(unused_mut, unused_variables, unused_assignments, unused_parens, unreachable_patterns, non_snake_case, dead_code)]");
    let _ = writeln!(s, "#![allow(clippy::all)]\n");
    let _ = writeln!(s, "use canstar_rtlc::rt;\n");
    // struct
    let _ = writeln!(s, "/// {}\n#[derive(Clone)]\npub struct {name} {{", o.description);
    let order: Vec<SigId> = {
        let rank = |x: SigId| match d.sigs[x].role {
            Role::Input => 0,
            _ if d.outputs.contains(&x) => 1,
            Role::Const => 2,
            Role::Reg(_) | Role::RamRead(_) => 3,
            _ => 4,
        };
        let mut v: Vec<SigId> = (0..d.sigs.len()).filter(|&x| stored(d, x)).collect();
        v.sort_by_key(|&x| (rank(x), x));
        v
    };
    for &x in &order {
        let sig = &d.sigs[x];
        let vis = "pub ";
        let _ = writeln!(s, "    /// `{}` ({}, {} bit{})", sig.path, role_text(d, x), sig.width, if sig.width == 1 { "" } else { "s" });
        let _ = writeln!(s, "    {vis}{}: {},", names[x], ty(sig.width));
    }
    for (r, ram) in d.rams.iter().enumerate() {
        let _ = writeln!(s, "    /// `{}` memory, {} x {} bits", d.module_path(ram.module), 1usize << ram.aw, ram.dw);
        let _ = writeln!(s, "    pub {}: [{}; {}],", mems[r], ty(ram.dw), 1usize << ram.aw);
    }
    for &x in &sensed {
        let _ = writeln!(s, "    seen_{}: {},", names[x], ty(d.sigs[x].width));
    }
    let _ = writeln!(s, "    /// Groups to evaluate (one bit per group, see `run`).\n    dirty: [u64; {}],", act.words);
    let _ = writeln!(s, "    /// Registers whose input changed since they took it (see `edge`).\n    pend: [u64; {}],", act.reg_words);
    let _ = writeln!(s, "    trace: bool,\n}}\n");
    let _ = writeln!(s, "impl Default for {name} {{\n    fn default() -> Self {{\n        Self::new()\n    }}\n}}\n");
    let _ = writeln!(s, "impl {name} {{");
    let _ = writeln!(s, "    /// Shape fingerprint of the design this model was compiled from.");
    let _ = writeln!(s, "    pub const FINGERPRINT: u64 = {:#018x};\n", o.fingerprint);
    // new()
    let _ = writeln!(s, "    /// Power-up state with the constants of the instance it was generated from (settled).");
    let _ = writeln!(s, "    pub fn new() -> Self {{\n        let mut m = {name} {{");
    for &x in &order {
        let sig = &d.sigs[x];
        let init = match &sig.role {
            Role::Reg(i) => d.dffs[*i].init,
            Role::Alias(e) => e.as_lit().unwrap_or(0),
            _ => d.hier.atoms[sig.atom].value,
        };
        let init = match sig.role {
            Role::Comb(_) | Role::RamRead(_) => 0,
            _ => init,
        };
        let _ = writeln!(s, "            {}: {},", names[x], lit(init, sig.width));
    }
    for (r, ram) in d.rams.iter().enumerate() {
        let words = 1usize << ram.aw;
        let mut init = vec![0u128; words];
        for &(a, v) in &ram.init {
            if (a as usize) < words {
                init[a as usize] = v;
            }
        }
        if init.iter().all(|&v| v == 0) {
            let _ = writeln!(s, "            {}: [{}; {words}],", mems[r], lit(0, ram.dw));
        } else {
            let items: Vec<String> = init.iter().map(|&v| lit(v, ram.dw)).collect();
            let _ = writeln!(s, "            {}: [{}],", mems[r], items.join(", "));
        }
    }
    for &x in &sensed {
        let _ = writeln!(s, "            seen_{}: {},", names[x], lit(d.hier.atoms[d.sigs[x].atom].value, d.sigs[x].width));
    }
    let _ = writeln!(s, "            dirty: [!0; {}],", act.words);
    let _ = writeln!(s, "            pend: [!0; {}],", act.reg_words);
    let _ = writeln!(s, "            trace: false,\n        }};\n        m.eval_all();\n        m\n    }}\n");
    let _ = writeln!(s, "    /// A model with the constants, state and inputs of a rust-hdl instance of the same shape.");
    let _ = writeln!(s, "    pub fn from_instance(b: &dyn rt::Block) -> Result<Self, canstar_rtlc::Error> {{");
    let _ = writeln!(s, "        let mut m = Self::new();\n        rt::Model::load(&mut m, b)?;\n        Ok(m)\n    }}\n");
    emit_clock(&mut s, d, sch, &act, &names, &mems, &top);
    for (i, g) in sch.groups.iter().enumerate() {
        let ctx = Ctx { d, names: &names, locals: &g.locals };
        let targets: Vec<&str> = g.targets.iter().map(|&t| d.sigs[t].path.as_str()).collect();
        let shown = if targets.len() > 6 { format!("{}, ... ({} signals)", targets[..6].join(", "), targets.len()) } else { targets.join(", ") };
        let _ = writeln!(s, "    /// `{}` block, depth {}, {}: {shown}", d.module_path(d.blocks[g.block].module), g.depth, class_text(g.class));
        let _ = writeln!(s, "    fn g{i}(&mut self) {{");
        for &l in &g.locals {
            let w = d.sigs[l].width;
            let init = if g.init.contains(&l) { format!("self.{}", names[l]) } else { lit(0, w) };
            let _ = writeln!(s, "        let mut {}: {} = {init};", names[l], ty(w));
        }
        ctx.stmts(&mut s, &g.stmts, 2);
        for &t in &g.targets {
            let _ = writeln!(s, "        {}", store(&act, &names, t, &names[t], Some(i)));
        }
        let _ = writeln!(s, "    }}\n");
    }
    let _ = writeln!(s, "}}\n");
    emit_model_impl(&mut s, d, &names, &mems, &top, o, &act, &probe_only(d, sch));
    if let Some(t) = o.hdl_type {
        emit_hdl_adapters(&mut s, d, t);
    }
    s
}

#[allow(clippy::too_many_arguments)]
fn emit_model_impl(s: &mut String, d: &Design, names: &[String], mems: &[String], top: &Ctx, o: &EmitOptions, act: &Activity, stale: &[SigId]) {
    let (words, reg_words) = (act.words, act.reg_words);
    let act_words = |_: &Design| words;
    let name = o.name;
    let _ = writeln!(s, "impl rt::Model for {name} {{");
    let _ = writeln!(s, "    fn info(&self) -> &'static rt::ModelInfo {{\n        &INFO\n    }}");
    let _ = writeln!(s, "    fn cycle(&mut self) {{\n        {name}::cycle(self)\n    }}");
    let _ = writeln!(s, "    fn settle(&mut self) {{\n        {name}::settle(self)\n    }}");
    let _ = writeln!(s, "    fn settle_all(&mut self) {{\n        self.eval_all()\n    }}");
    let _ = writeln!(s, "    fn set_trace(&mut self, on: bool) {{\n        self.trace = on;\n        if on {{\n            self.eval_all();\n        }}\n    }}");
    let _ = writeln!(s, "    fn set_input(&mut self, i: usize, v: u128) {{\n        match i {{");
    for (i, &x) in d.inputs.iter().enumerate() {
        let _ = writeln!(s, "            {i} => self.{} = {},", names[x], from_u128("v", d.sigs[x].width));
    }
    let _ = writeln!(s, "            _ => panic!(\"no input port {{i}}\"),\n        }}\n    }}");
    let _ = writeln!(s, "    fn set_inputs(&mut self, v: &[u128]) {{\n        let v = &v[..{}];", d.inputs.len());
    for (i, &x) in d.inputs.iter().enumerate() {
        let _ = writeln!(s, "        self.{} = {};", names[x], from_u128(&format!("v[{i}]"), d.sigs[x].width));
    }
    let _ = writeln!(s, "    }}");
    let _ = writeln!(s, "    fn outputs(&self, o: &mut [u128]) {{\n        let o = &mut o[..{}];", d.outputs.len());
    for (i, &x) in d.outputs.iter().enumerate() {
        let _ = writeln!(s, "        o[{i}] = self.{} as u128;", names[x]);
    }
    let _ = writeln!(s, "    }}");
    for (f, ports) in [("input", &d.inputs), ("output", &d.outputs)] {
        let _ = writeln!(s, "    fn {f}(&self, i: usize) -> u128 {{\n        match i {{");
        for (i, &x) in ports.iter().enumerate() {
            let _ = writeln!(s, "            {i} => self.{} as u128,", names[x]);
        }
        let _ = writeln!(s, "            _ => panic!(\"no {f} port {{i}}\"),\n        }}\n    }}");
    }
    let _ = writeln!(s, "    fn atom(&self, a: usize) -> u128 {{\n        match a {{");
    for (x, sig) in d.sigs.iter().enumerate() {
        let v = match &sig.role {
            Role::Clock | Role::Undriven => "0".to_string(),
            _ if stored(d, x) => format!("self.{} as u128", names[x]),
            Role::Alias(e) => format!("{} as u128", top.ex(e)),
            _ => unreachable!(),
        };
        let _ = writeln!(s, "            {x} => {v},");
    }
    let _ = writeln!(s, "            _ => panic!(\"no atom {{a}}\"),\n        }}\n    }}");
    let _ = writeln!(s, "    fn set_atom(&mut self, a: usize, v: u128) -> bool {{\n        match a {{");
    for (x, sig) in d.sigs.iter().enumerate() {
        if matches!(sig.role, Role::Input | Role::Const | Role::Reg(_)) {
            let _ = writeln!(s, "            {x} => self.{} = {},", names[x], from_u128("v", sig.width));
        }
    }
    let _ = writeln!(s, "            _ => return false,\n        }}\n        self.dirty = [!0; {}];\n        self.pend = [!0; {}];\n        true\n    }}", act_words(d), reg_words);
    let _ = writeln!(s, "    fn set_mem(&mut self, r: usize, addr: usize, v: u128) {{\n        match r {{");
    for (r, ram) in d.rams.iter().enumerate() {
        let _ = writeln!(s, "            {r} => self.{}[addr] = {},", mems[r], from_u128("v", ram.dw));
    }
    let _ = writeln!(s, "            _ => panic!(\"no memory {{r}}\"),\n        }}\n    }}");
    let _ = writeln!(s, "    fn mem(&self, r: usize, addr: usize) -> u128 {{\n        match r {{");
    for (r, _) in d.rams.iter().enumerate() {
        let _ = writeln!(s, "            {r} => self.{}[addr] as u128,", mems[r]);
    }
    let _ = writeln!(s, "            _ => panic!(\"no memory {{r}}\"),\n        }}\n    }}");
    let _ = writeln!(s, "}}\n");
    // static description
    let port = |x: SigId| format!("rt::Port {{ name: {:?}, width: {}, atom: {x} }}", d.hier.atoms[d.sigs[x].atom].name, d.sigs[x].width);
    let _ = writeln!(s, "static INFO: rt::ModelInfo = rt::ModelInfo {{");
    let _ = writeln!(s, "    name: {name:?},\n    fingerprint: {:#018x},", o.fingerprint);
    let _ = writeln!(s, "    inputs: &[{}],", d.inputs.iter().map(|&x| port(x)).collect::<Vec<_>>().join(", "));
    let _ = writeln!(s, "    outputs: &[{}],", d.outputs.iter().map(|&x| port(x)).collect::<Vec<_>>().join(", "));
    let _ = writeln!(s, "    atoms: &ATOMS,\n    probe: &PROBE,");
    let rams: Vec<String> = d.rams.iter().map(|r| format!("rt::RamMeta {{ module: {}, words: {}, width: {} }}", r.module, 1usize << r.aw, r.dw)).collect();
    let _ = writeln!(s, "    rams: &[{}],", rams.join(", "));
    let po: Vec<String> = stale.iter().map(|x| x.to_string()).collect();
    let _ = writeln!(s, "    probe_only: &[{}],\n}};\n", po.join(", "));
    let _ = writeln!(s, "static ATOMS: [rt::AtomMeta; {}] = [", d.hier.atoms.len());
    for a in &d.hier.atoms {
        let vt = match &a.ty {
            ValueType::Bool => "rt::Vt::Bool".to_string(),
            ValueType::Clock => "rt::Vt::Clock".to_string(),
            ValueType::Enum(e) => format!("rt::Vt::Enum(&{:?})", d.hier.enums[*e].variants),
            _ => "rt::Vt::Bits".to_string(),
        };
        let _ = writeln!(
            s,
            "    rt::AtomMeta {{ name: {:?}, kind: rt::AtomKind::{:?}, width: {}, type_name: {:?}, vt: {vt} }},",
            a.probe_name, a.kind, a.width, a.type_name
        );
    }
    let _ = writeln!(s, "];\n");
    let _ = writeln!(s, "static PROBE: [rt::Op; {}] = [", d.hier.ops.len());
    for op in &d.hier.ops {
        let t = match op {
            crate::collect::ProbeOp::Scope(n) => format!("rt::Op::Scope({n:?})"),
            crate::collect::ProbeOp::Namespace(n) => format!("rt::Op::Namespace({n:?})"),
            crate::collect::ProbeOp::Atom(a) => format!("rt::Op::Atom({a})"),
            crate::collect::ProbeOp::EndNamespace(n) => format!("rt::Op::EndNamespace({n:?})"),
            crate::collect::ProbeOp::EndScope(n) => format!("rt::Op::EndScope({n:?})"),
        };
        let _ = writeln!(s, "    {t},");
    }
    let _ = writeln!(s, "];");
}

/// Rust access path of a top-level port of the rust-hdl instance (`rx$0` -> `rx[0]`).
fn access(d: &Design, x: SigId) -> String {
    let at = &d.hier.atoms[d.sigs[x].atom];
    let mut p = String::new();
    for n in &at.namespace {
        p.push('.');
        p.push_str(n);
    }
    for (i, seg) in at.probe_name.split('$').enumerate() {
        if i > 0 && seg.chars().all(|c| c.is_ascii_digit()) {
            let _ = write!(p, "[{seg}]");
        } else {
            p.push('.');
            p.push_str(seg);
        }
    }
    p
}

/// Functions that put an input vector on a rust-hdl instance and read its outputs
/// (for running the rust-hdl design next to the model on the same stimulus).
fn emit_hdl_adapters(s: &mut String, d: &Design, t: &str) {
    if d.inputs.iter().chain(d.outputs.iter()).any(|&x| matches!(d.sigs[x].ty, ValueType::Enum(_))) {
        let _ = writeln!(s, "\n// (no rust-hdl adapters: a top-level port has an enum type)");
        return;
    }
    let _ = writeln!(s, "\n/// Set the inputs of a rust-hdl `{t}` from a port vector (the model's input order).");
    let _ = writeln!(s, "pub fn hdl_set_inputs(u: &mut {t}, v: &[u128]) {{");
    for (i, &x) in d.inputs.iter().enumerate() {
        let w = d.sigs[x].width;
        let val = match d.sigs[x].ty {
            ValueType::Bool => format!("v[{i}] != 0"),
            _ => format!("rt::to_bits::<{w}>(v[{i}])"),
        };
        let _ = writeln!(s, "    u{}.next = {val};", access(d, x));
    }
    let _ = writeln!(s, "}}\n");
    let _ = writeln!(s, "/// Read the outputs of a rust-hdl `{t}` into a port vector (the model's output order).");
    let _ = writeln!(s, "pub fn hdl_outputs(u: &{t}, o: &mut [u128]) {{");
    for (i, &x) in d.outputs.iter().enumerate() {
        let val = match d.sigs[x].ty {
            ValueType::Bool => format!("u{}.val() as u128", access(d, x)),
            _ => format!("u{}.val().to_u128()", access(d, x)),
        };
        let _ = writeln!(s, "    o[{i}] = {val};");
    }
    let _ = writeln!(s, "}}");
}
