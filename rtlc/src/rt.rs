//! Runtime support of the generated models: the [`Model`] trait every model
//! implements, the static description of its ports and atoms, loading a model from a
//! rust-hdl instance (shape check, constants, state), presenting its signals to a
//! rust-hdl [`Probe`] with the instance's hierarchy and names, and the few operator
//! helpers the generated code calls.

pub use rust_hdl::core::prelude::{AtomKind, Block, Probe};
use rust_hdl::core::prelude::*;

use crate::error::{Error, Result};

/// The value type of an atom, for probes.
#[derive(Clone, Copy, Debug)]
pub enum Vt {
    Bool,
    Bits,
    Clock,
    /// A `LogicState` enum: its variants as rust-hdl's descriptor lists them.
    Enum(&'static [&'static str]),
}

/// One atom (signal or constant) of the design, in probe order.
#[derive(Clone, Copy, Debug)]
pub struct AtomMeta {
    /// Name as passed to `visit_atom`.
    pub name: &'static str,
    pub kind: AtomKind,
    pub width: usize,
    /// rust-hdl's type name (`Bits::<8>`, `Bit`, `clock`, the enum's name).
    pub type_name: &'static str,
    pub vt: Vt,
}

/// One event of the probe walk (the top scope takes the caller's name).
#[derive(Clone, Copy, Debug)]
pub enum Op {
    Scope(&'static str),
    Namespace(&'static str),
    Atom(usize),
    EndNamespace(&'static str),
    EndScope(&'static str),
}

/// A top-level port: its name, width and atom index.
#[derive(Clone, Copy, Debug)]
pub struct Port {
    pub name: &'static str,
    pub width: usize,
    pub atom: usize,
}

/// A memory: the module index of its `RAM` instance, word count and width.
#[derive(Clone, Copy, Debug)]
pub struct RamMeta {
    pub module: usize,
    pub words: usize,
    pub width: usize,
}

/// Static description of a generated model.
#[derive(Debug)]
pub struct ModelInfo {
    pub name: &'static str,
    /// Shape fingerprint ([`crate::fingerprint()`]).
    pub fingerprint: u64,
    pub inputs: &'static [Port],
    pub outputs: &'static [Port],
    pub atoms: &'static [AtomMeta],
    pub probe: &'static [Op],
    pub rams: &'static [RamMeta],
    /// Atoms ([`Model::atom`] indices) that nothing but probes needs: the model
    /// evaluates them only in trace mode or in [`Model::settle_all`], so a reader
    /// of one sees a stale value otherwise (compile with `Options::keep` to have
    /// them evaluated every clock).
    pub probe_only: &'static [usize],
}

/// The interface of every compiled model.
///
/// The simulation contract is `canstar_hdl::drive::cycle`: set inputs, then
/// [`Model::cycle`] settles them, applies the rising edge and settles again; the
/// outputs then show the state after the edge with the same inputs.
pub trait Model {
    fn info(&self) -> &'static ModelInfo;
    /// One clock cycle.
    fn cycle(&mut self);
    /// Propagate input changes without a clock edge (outputs become valid).
    fn settle(&mut self);
    /// Evaluate every signal, also those only probes show.
    fn settle_all(&mut self);
    /// Trace mode: every cycle evaluates every signal (for VCD); off by default,
    /// when signals no output or register needs are left stale.
    fn set_trace(&mut self, on: bool);
    /// Set input port `i` (value masked to the port width).
    fn set_input(&mut self, i: usize, v: u128);
    fn input(&self, i: usize) -> u128;
    fn output(&self, i: usize) -> u128;
    /// Set every input from a vector (input order; values masked to the widths).
    fn set_inputs(&mut self, v: &[u128]) {
        for (i, &x) in v.iter().enumerate() {
            self.set_input(i, x);
        }
    }
    /// Read every output into a vector (output order).
    fn outputs(&self, o: &mut [u128]) {
        for (i, x) in o.iter_mut().enumerate() {
            *x = self.output(i);
        }
    }
    /// The current value of atom `a` (probe order), as its canonical integer.
    fn atom(&self, a: usize) -> u128;
    /// Set a constant, register or input atom; `false` for other atoms.
    fn set_atom(&mut self, a: usize, v: u128) -> bool;
    /// Write word `addr` of memory `r`.
    fn set_mem(&mut self, r: usize, addr: usize, v: u128);
    fn mem(&self, r: usize, addr: usize) -> u128;

    /// Take constants, register state, memory contents and input values from a
    /// rust-hdl instance of the same shape, then settle.
    fn load(&mut self, b: &dyn Block) -> Result<()> {
        let info = self.info();
        let h = crate::collect::collect(b)?;
        let fp = crate::fingerprint::of(&h);
        if fp != info.fingerprint {
            return Err(Error::ShapeMismatch { model: info.name.into(), expected: info.fingerprint, found: fp });
        }
        for (a, at) in h.atoms.iter().enumerate() {
            self.set_atom(a, at.value);
        }
        for (r, meta) in info.rams.iter().enumerate() {
            for addr in 0..meta.words {
                self.set_mem(r, addr, 0);
            }
            if let Verilog::Custom(text) = &h.modules[meta.module].code {
                if let Some(crate::prims::Prim::Ram { init, .. }) = crate::prims::recognise(&h, meta.module, text) {
                    for (addr, v) in init {
                        self.set_mem(r, addr as usize, v);
                    }
                }
            }
        }
        self.settle_all();
        Ok(())
    }

    /// Present the signals to `probe` exactly as the rust-hdl instance's
    /// `accept(name, probe)` does (same scopes, names, order, types). Values are
    /// current as of the last evaluation: call [`Model::settle_all`] or run in
    /// trace mode to have the probe-only signals up to date.
    fn accept(&self, name: &str, probe: &mut dyn Probe) {
        let info = self.info();
        let node = ScopeNode;
        let mut depth = 0usize;
        for op in info.probe {
            match *op {
                Op::Scope(n) => {
                    probe.visit_start_scope(if depth == 0 { name } else { n }, &node);
                    depth += 1;
                }
                Op::Namespace(n) => probe.visit_start_namespace(n, &node),
                Op::Atom(a) => {
                    let meta = &info.atoms[a];
                    probe.visit_atom(meta.name, &AtomView { meta, value: self.atom(a), id: a });
                }
                Op::EndNamespace(n) => probe.visit_end_namespace(n, &node),
                Op::EndScope(n) => {
                    depth = depth.saturating_sub(1);
                    probe.visit_end_scope(if depth == 0 { name } else { n }, &node)
                }
            }
        }
    }

    /// Input port index by name.
    fn input_index(&self, name: &str) -> Option<usize> {
        self.info().inputs.iter().position(|p| p.name == name)
    }
    /// Output port index by name.
    fn output_index(&self, name: &str) -> Option<usize> {
        self.info().outputs.iter().position(|p| p.name == name)
    }
}

/// A model as a rust-hdl [`Block`], for code that walks blocks with a probe (VCD
/// writers): `accept` presents the model's signals, the simulation methods do nothing.
pub struct AsBlock<'a>(pub &'a dyn Model);

impl Logic for AsBlock<'_> {
    fn update(&mut self) {}
}

impl Block for AsBlock<'_> {
    fn connect_all(&mut self) {}
    fn update_all(&mut self) {}
    fn has_changed(&self) -> bool {
        false
    }
    fn accept(&self, name: &str, probe: &mut dyn Probe) {
        self.0.accept(name, probe)
    }
}

/// The node handed to `visit_start_scope` (probes that need a real block, such as
/// rust-hdl's Verilog generator, do not work on a compiled model).
struct ScopeNode;

impl Logic for ScopeNode {
    fn update(&mut self) {}
}

impl Block for ScopeNode {
    fn connect_all(&mut self) {}
    fn update_all(&mut self) {}
    fn has_changed(&self) -> bool {
        false
    }
    fn accept(&self, _name: &str, _probe: &mut dyn Probe) {}
}

/// An atom of a compiled model as rust-hdl's [`Atom`].
pub struct AtomView {
    meta: &'static AtomMeta,
    value: u128,
    id: usize,
}

/// rust-hdl's literal of a `width`-bit value.
pub fn literal(width: usize, value: u128) -> VerilogLiteral {
    seq_macro::seq!(N in 1..=128 {
        match width {
            #( N => VerilogLiteral::from(value.to_bits::<N>()), )*
            _ => VerilogLiteral::from(value),
        }
    })
}

impl Atom for AtomView {
    fn bits(&self) -> usize {
        self.meta.width
    }
    fn connected(&self) -> bool {
        true
    }
    fn changed(&self) -> bool {
        false
    }
    fn kind(&self) -> AtomKind {
        self.meta.kind
    }
    fn descriptor(&self) -> TypeDescriptor {
        let kind = match self.meta.vt {
            Vt::Enum(v) => TypeKind::Enum(v.iter().map(|s| s.to_string()).collect()),
            _ => TypeKind::Bits(self.meta.width),
        };
        TypeDescriptor { name: self.meta.type_name.to_string(), kind }
    }
    fn vcd(&self) -> VCDValue {
        match self.meta.vt {
            Vt::Enum(v) => {
                let full = v.get(self.value as usize).copied().unwrap_or("");
                VCDValue::String(full.rsplit("::").next().unwrap_or(full).to_string())
            }
            _ if self.meta.width == 1 => (self.value != 0).into(),
            _ => VCDValue::Vector((0..self.meta.width).rev().map(|i| if (self.value >> i) & 1 == 1 { vcd::Value::V1 } else { vcd::Value::V0 }).collect()),
        }
    }
    fn id(&self) -> usize {
        self.id
    }
    fn verilog(&self) -> VerilogLiteral {
        match self.meta.vt {
            Vt::Bool | Vt::Clock => VerilogLiteral::from(self.value != 0),
            Vt::Enum(_) => VerilogLiteral::from(self.value as usize),
            Vt::Bits => literal(self.meta.width, self.value),
        }
    }
    fn constraints(&self) -> Vec<rust_hdl::core::constraint::PinConstraint> {
        vec![]
    }
}

/// A `Bits<N>` from a canonical value (fast for N <= 64).
#[inline]
pub fn to_bits<const N: usize>(v: u128) -> Bits<N> {
    if N <= 64 {
        Bits::from(v as u64)
    } else {
        v.to_bits::<N>()
    }
}

macro_rules! helpers {
    ($($t:ident: $shl:ident $shr:ident $rep:ident $set:ident),*) => {$(
        /// `a << s` (0 when `s` reaches the type width; the caller masks to the value width).
        #[inline(always)]
        pub fn $shl(a: $t, s: u128) -> $t {
            if s >= <$t>::BITS as u128 { 0 } else { a << s }
        }
        /// `a >> s` (0 when `s` reaches the type width).
        #[inline(always)]
        pub fn $shr(a: $t, s: u128) -> $t {
            if s >= <$t>::BITS as u128 { 0 } else { a >> s }
        }
        /// `a` with bit `i` replaced by `v` (unchanged when `i` is out of range).
        #[inline(always)]
        pub fn $rep(a: $t, i: u128, v: bool) -> $t {
            if i >= <$t>::BITS as u128 { a } else { (a & !(1 << i)) | ((v as $t) << i) }
        }
        /// `a` with `w` bits at `off` replaced by `v` (the caller masks to the value width).
        #[inline(always)]
        pub fn $set(a: $t, off: u128, w: usize, v: $t) -> $t {
            if off >= <$t>::BITS as u128 { return a; }
            let m: $t = if w >= <$t>::BITS as usize { !0 } else { (1 << w) - 1 };
            (a & !(m << off)) | ((v & m) << off)
        }
    )*};
}

helpers!(
    u8: shl_u8 shr_u8 replace_u8 set_bits_u8,
    u16: shl_u16 shr_u16 replace_u16 set_bits_u16,
    u32: shl_u32 shr_u32 replace_u32 set_bits_u32,
    u64: shl_u64 shr_u64 replace_u64 set_bits_u64,
    u128: shl_u128 shr_u128 replace_u128 set_bits_u128
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn helpers_saturate() {
        assert_eq!(shl_u8(0x81, 1), 0x02);
        assert_eq!(shl_u8(0x81, 8), 0);
        assert_eq!(shr_u16(0x8000, 15), 1);
        assert_eq!(shr_u16(0x8000, 300), 0);
        assert_eq!(replace_u8(0xff, 3, false), 0xf7);
        assert_eq!(set_bits_u32(0xffff_ffff, 4, 8, 0), 0xffff_f00f);
    }

    #[test]
    fn literals_have_the_width() {
        assert_eq!(literal(12, 0xabc).to_string(), "12'habc");
        assert_eq!(literal(104, 5).to_string(), VerilogLiteral::from(5u128.to_bits::<104>()).to_string());
    }
}
