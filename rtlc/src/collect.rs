//! Reading a design out of rust-hdl: the instance hierarchy as the block's own
//! `accept(name, probe)` presents it (the visitor rust-hdl's Verilog generator uses,
//! see rust-hdl-core's `module_defines.rs`), every atom (signal or constant) with its
//! kind, width, type and current value, and every module's `hdl()`.
//!
//! The probe-event sequence is kept verbatim ([`ProbeOp`]) so that a compiled model can
//! replay it and present exactly the same hierarchy and names to any [`Probe`] (the VCD
//! writer in particular).

use rust_hdl::core::prelude::*;

use crate::error::{Error, Result};

/// One event of a block's `accept` walk, in order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ProbeOp {
    /// `visit_start_scope(name)`: a module instance begins.
    Scope(String),
    /// `visit_start_namespace(name)`: an interface bundle begins.
    Namespace(String),
    /// `visit_atom(name)`: the atom with this index in [`Hierarchy::atoms`].
    Atom(usize),
    /// `visit_end_namespace(name)`.
    EndNamespace(String),
    /// `visit_end_scope(name)`.
    EndScope(String),
}

/// The value type of an atom.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ValueType {
    /// `bool` (rust-hdl `Bit`).
    Bool,
    /// `Bits<N>`.
    Bits,
    /// The clock.
    Clock,
    /// A `LogicState` enum: index into [`Hierarchy::enums`].
    Enum(usize),
    /// `Signed<N>` (recorded; the compiler rejects it).
    Signed,
    /// A `LogicStruct` (recorded; the compiler rejects it).
    Composite,
}

/// A `LogicState` enum type: its name and variants in declaration order
/// (the encoding is the variant's index).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EnumType {
    /// Type name as rust-hdl reports it (`Field`).
    pub name: String,
    /// Variants as rust-hdl's descriptor lists them (`Field::Idle`).
    pub variants: Vec<String>,
}

/// One signal or constant of the hierarchy.
#[derive(Clone, Debug)]
pub struct AtomInfo {
    /// Index of the module that owns it.
    pub module: usize,
    /// Name inside its module as rust-hdl's Verilog names it (namespaces joined by `$`).
    pub name: String,
    /// Name as passed to `visit_atom` (without the namespace).
    pub probe_name: String,
    /// Namespaces (interface fields) around the atom, outermost first.
    pub namespace: Vec<String>,
    pub kind: AtomKind,
    pub width: usize,
    pub ty: ValueType,
    /// rust-hdl's type descriptor name (`Bits::<8>`, `Bit`, `clock`, `Field`).
    pub type_name: String,
    /// Current value (constants: their value; signals: the committed value).
    pub value: u128,
}

/// One module instance.
#[derive(Clone, Debug)]
pub struct ModuleInfo {
    /// Scope name as passed to `visit_start_scope` (`fsm`, `up_sync$0`).
    pub name: String,
    /// Scope names from the top (the top itself excluded).
    pub path: Vec<String>,
    pub parent: Option<usize>,
    pub children: Vec<usize>,
    pub atoms: Vec<usize>,
    /// What the module's `hdl()` returns.
    pub code: Verilog,
}

impl ModuleInfo {
    /// Dotted path from the top (`fsm.tecr`), empty for the top.
    pub fn dotted(&self) -> String {
        self.path.join(".")
    }
}

/// The whole design as rust-hdl presents it.
#[derive(Clone, Debug, Default)]
pub struct Hierarchy {
    pub modules: Vec<ModuleInfo>,
    pub atoms: Vec<AtomInfo>,
    pub enums: Vec<EnumType>,
    pub ops: Vec<ProbeOp>,
}

impl Hierarchy {
    /// Dotted path of an atom from the top (`fsm.tecr.q`).
    pub fn atom_path(&self, a: usize) -> String {
        let at = &self.atoms[a];
        let m = &self.modules[at.module];
        let mut parts = m.path.clone();
        parts.extend(at.namespace.iter().cloned());
        parts.push(at.probe_name.clone());
        parts.join(".")
    }
}

#[derive(Default)]
struct Collector {
    h: Hierarchy,
    stack: Vec<usize>,
    namespace: Vec<String>,
    err: Option<Error>,
}

/// Parse rust-hdl's `Display` of a `VerilogLiteral` (`8'h2a`, `3'b101`).
pub fn parse_literal(text: &str) -> Result<(u128, usize)> {
    let bad = || Error::Unsupported(format!("cannot read the literal `{text}`"));
    let (bits, rest) = text.split_once('\'').ok_or_else(bad)?;
    let bits: usize = bits.parse().map_err(|_| bad())?;
    let (radix, digits) = match rest.as_bytes().first() {
        Some(b'h') => (16, &rest[1..]),
        Some(b'b') => (2, &rest[1..]),
        _ => return Err(bad()),
    };
    if digits.starts_with('-') {
        return Err(Error::Unsupported(format!("negative literal `{text}` (Signed is not supported)")));
    }
    let v = u128::from_str_radix(digits, radix).map_err(|_| {
        Error::Unsupported(format!("literal `{text}` is wider than 128 bits"))
    })?;
    Ok((v, bits))
}

impl Collector {
    fn enum_index(&mut self, d: &TypeDescriptor) -> usize {
        let TypeKind::Enum(vars) = &d.kind else { unreachable!() };
        if let Some(i) = self.h.enums.iter().position(|e| e.name == d.name && &e.variants == vars) {
            return i;
        }
        self.h.enums.push(EnumType { name: d.name.clone(), variants: vars.clone() });
        self.h.enums.len() - 1
    }
}

impl Probe for Collector {
    fn visit_start_scope(&mut self, name: &str, node: &dyn Block) {
        let parent = self.stack.last().copied();
        let path = match parent {
            None => vec![],
            Some(p) => {
                let mut v = self.h.modules[p].path.clone();
                v.push(name.to_string());
                v
            }
        };
        let id = self.h.modules.len();
        self.h.modules.push(ModuleInfo { name: name.to_string(), path, parent, children: vec![], atoms: vec![], code: node.hdl() });
        if let Some(p) = parent {
            self.h.modules[p].children.push(id);
        }
        self.stack.push(id);
        self.namespace.clear();
        self.h.ops.push(ProbeOp::Scope(name.to_string()));
    }

    fn visit_start_namespace(&mut self, name: &str, _node: &dyn Block) {
        self.namespace.push(name.to_string());
        self.h.ops.push(ProbeOp::Namespace(name.to_string()));
    }

    fn visit_atom(&mut self, name: &str, atom: &dyn Atom) {
        let Some(&module) = self.stack.last() else {
            self.err.get_or_insert(Error::Unsupported("an atom outside any module".into()));
            return;
        };
        let d = atom.descriptor();
        let ty = match &d.kind {
            TypeKind::Bits(1) if d.name == "clock" => ValueType::Clock,
            TypeKind::Bits(1) if d.name == "Bit" => ValueType::Bool,
            TypeKind::Bits(_) => ValueType::Bits,
            TypeKind::Signed(_) => ValueType::Signed,
            TypeKind::Enum(_) => ValueType::Enum(self.enum_index(&d)),
            TypeKind::Composite(_) => ValueType::Composite,
        };
        let value = match parse_literal(&atom.verilog().to_string()) {
            Ok((v, _)) => v,
            Err(e) => {
                self.err.get_or_insert(e);
                0
            }
        };
        let full = if self.namespace.is_empty() { name.to_string() } else { format!("{}${}", self.namespace.join("$"), name) };
        let id = self.h.atoms.len();
        self.h.atoms.push(AtomInfo {
            module,
            name: full,
            probe_name: name.to_string(),
            namespace: self.namespace.clone(),
            kind: atom.kind(),
            width: atom.bits(),
            ty,
            type_name: d.name.clone(),
            value,
        });
        self.h.modules[module].atoms.push(id);
        self.h.ops.push(ProbeOp::Atom(id));
    }

    fn visit_end_namespace(&mut self, name: &str, _node: &dyn Block) {
        self.namespace.pop();
        self.h.ops.push(ProbeOp::EndNamespace(name.to_string()));
    }

    fn visit_end_scope(&mut self, name: &str, _node: &dyn Block) {
        self.stack.pop();
        self.h.ops.push(ProbeOp::EndScope(name.to_string()));
    }
}

/// Walk a block (connected or not) and record its hierarchy. The top scope is named `top`.
pub fn collect(top: &dyn Block) -> Result<Hierarchy> {
    let mut c = Collector::default();
    top.accept("top", &mut c);
    if let Some(e) = c.err {
        return Err(e);
    }
    if c.h.modules.is_empty() {
        return Err(Error::Unsupported("the block presents no module scope (is it a bare signal?)".into()));
    }
    Ok(c.h)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literals_parse() {
        assert_eq!(parse_literal("8'h2a").unwrap(), (42, 8));
        assert_eq!(parse_literal("3'b101").unwrap(), (5, 3));
        assert_eq!(parse_literal("1'b1").unwrap(), (1, 1));
        assert_eq!(parse_literal("104'hffffffffffffffffffffffffff").unwrap(), ((1u128 << 104) - 1, 104));
        assert!(parse_literal("8'd3").is_err());
    }

    #[test]
    fn literals_from_rust_hdl_values() {
        use rust_hdl::core::prelude::*;
        let x: Bits<12> = 0xabc.into();
        assert_eq!(parse_literal(&VerilogLiteral::from(x).to_string()).unwrap(), (0xabc, 12));
        let y: Bits<5> = 19.into();
        assert_eq!(parse_literal(&VerilogLiteral::from(y).to_string()).unwrap(), (19, 5));
        assert_eq!(parse_literal(&VerilogLiteral::from(true).to_string()).unwrap(), (1, 1));
    }
}
