//! canstar-rtlc: a compiler from canstar's rust-hdl designs to straight-line Rust.
//!
//! The design is read from rust-hdl itself ([`collect`]): the instance hierarchy as the
//! block's `accept` presents it and every module's `hdl()` AST. [`lower`] resolves
//! names and types and unrolls loops into a flat [`ir::Design`]; [`opt`] propagates
//! wires and constants; [`sched`] slices the combinational blocks into groups that are
//! evaluated once per clock in dependency order (combinational loops are reported);
//! [`emit`] writes one Rust struct per design with a `cycle()` that matches
//! `canstar_hdl::drive::cycle` value for value. The generated code depends only on
//! [`rt`].
//!
//! Constant values (`Constant<T>`) and memory contents are runtime data of a model,
//! so one model serves every value of them; everything else is the design's shape,
//! identified by [`fingerprint()`].
//!
//! # Semantics
//! The reference is rust-hdl's simulation of the `update()` code the AST comes from:
//! `Bits<N>` operators wrap at N bits, literals take the width of what they meet,
//! shifts fill with zeros (also by amounts at or beyond the width), `LiteralType <<
//! Bits<M>` is 64 bits wide, `get_bits`/`bit_cast` truncate or zero-extend, enums are
//! their variant index, a `match` takes the first arm. An `In` signal reads its settled
//! value; an `Out` or `Local` signal the block assigns reads the value assigned so
//! far, or its settled value before the first assignment (a dependency on the block's
//! own result, which the scheduler orders or reports as a loop). Registers and
//! memories update on the rising edge of the single top-level clock, all from the
//! values before the edge; a memory reads before it writes.
//!
//! # Limits (refused with a message naming the module or signal)
//! `Signed`, `LogicStruct` and tristate values, values wider than 128 bits, interface
//! links (`LogicInterface`), black-box or wrapper Verilog, custom Verilog other than
//! rust-hdl's `DFF` and `RAM`, modules without HDL, gated or derived clocks, more than
//! one clock input, the clock read as data, and combinational loops (with the signals
//! on the loop). Two readings are approximations, reported as warnings: a bit index or
//! slice offset computed from signals is read as `usize` arithmetic (`x.index() + k`;
//! the AST cannot tell it from `(x + k).index()`), and a signal not assigned on every
//! path of its block (a latch) keeps its value between evaluations (rust-hdl's value
//! there depends on the order of its settle passes; canstar's designs have none).

pub mod collect;
pub mod emit;
pub mod emit_expr;
pub mod emit_sched;
pub mod error;
pub mod eval;
pub mod fingerprint;
pub mod ir;
pub mod lower;
mod lower_expr;
pub mod mutate;
pub mod names;
pub mod opt;
pub mod prims;
pub mod rt;
pub mod sched;

pub use error::{Error, Result};
pub use fingerprint::fingerprint;
use rust_hdl::core::prelude::Block;

/// What to generate.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// Name of the model struct.
    pub name: String,
    /// One-line description (the generated file's header and the struct's doc).
    pub description: String,
    /// Rust path of the rust-hdl type (e.g. `canstar_controller::core::CanCore`): when
    /// given, `hdl_set_inputs`/`hdl_outputs` functions for it are generated too.
    pub hdl_type: Option<String>,
    /// Debug hook: swap the n-th binary operator (see [`mutate`]).
    pub mutate: Option<usize>,
    /// Dotted paths of signals (`core.pj$0.charged`) to evaluate every clock although
    /// nothing but probes needs them: the internal signals a caller reads between
    /// clocks without trace mode (see [`rt::ModelInfo::probe_only`]). A path that
    /// names no signal is an error.
    pub keep: Vec<String>,
}

/// Figures of a compilation.
#[derive(Clone, Debug, Default)]
pub struct Stats {
    pub signals: usize,
    pub stored: usize,
    pub registers: usize,
    pub memories: usize,
    pub slices: usize,
    pub groups: usize,
    pub source_lines: usize,
}

/// A compiled model.
#[derive(Clone, Debug)]
pub struct Compiled {
    pub source: String,
    pub fingerprint: u64,
    pub warnings: Vec<String>,
    pub stats: Stats,
    /// What the mutation hook changed, if used.
    pub mutation: Option<String>,
}

/// Read, lower and optimise a design (the steps before scheduling).
pub fn analyse(top: &dyn Block) -> Result<(ir::Design, u64)> {
    let h = collect::collect(top)?;
    let fp = fingerprint::of(&h);
    let mut d = lower::lower(h)?;
    opt::optimize(&mut d);
    Ok((d, fp))
}

/// Compile a rust-hdl instance (connected or not) into the Rust source of a model.
pub fn compile(top: &dyn Block, opts: &Options) -> Result<Compiled> {
    let (mut d, fp) = analyse(top)?;
    let mutation = match opts.mutate {
        Some(n) => Some(mutate::swap_operator(&mut d, n).ok_or_else(|| Error::Unsupported(format!("no operator number {n} to swap")))?),
        None => None,
    };
    let keep = opts
        .keep
        .iter()
        .map(|k| d.sigs.iter().position(|s| &s.path == k).ok_or_else(|| Error::Unsupported(format!("keep: no signal `{k}` in the design"))))
        .collect::<Result<Vec<_>>>()?;
    let sch = sched::schedule(&d, &keep)?;
    let eo = emit::EmitOptions { name: &opts.name, description: &opts.description, hdl_type: opts.hdl_type.as_deref(), fingerprint: fp };
    let source = emit::emit(&d, &sch, &eo);
    let stats = Stats {
        signals: d.sigs.len(),
        stored: (0..d.sigs.len()).filter(|&s| emit::stored(&d, s)).count(),
        registers: d.dffs.len(),
        memories: d.rams.len(),
        slices: sch.slices,
        groups: sch.groups.len(),
        source_lines: source.lines().count(),
    };
    let mut warnings = d.warnings.clone();
    warnings.extend(sch.warnings);
    Ok(Compiled { source, fingerprint: fp, warnings, stats, mutation })
}

/// Compile and write the model source to `path` (for configurations without a
/// committed model).
pub fn generate(top: &dyn Block, opts: &Options, path: &std::path::Path) -> std::result::Result<Compiled, Box<dyn std::error::Error>> {
    let c = compile(top, opts)?;
    std::fs::write(path, &c.source)?;
    Ok(c)
}
