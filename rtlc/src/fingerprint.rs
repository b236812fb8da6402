//! The shape fingerprint of a design: a stable hash (FNV-1a, 64 bits) of everything
//! the compiled code depends on (hierarchy, atom names, kinds, widths and types, every
//! module's HDL) with the values left out: constant values and memory contents are
//! runtime data of a model, so one model serves every value of them.

use std::hash::Hasher;

use rust_hdl::core::prelude::*;

use crate::collect::{Hierarchy, ProbeOp};
use crate::error::Result;

fn put(h: &mut fnv::FnvHasher, tag: &str, s: &str) {
    h.write(tag.as_bytes());
    h.write(&(s.len() as u64).to_le_bytes());
    h.write(s.as_bytes());
}

/// Fingerprint of a collected hierarchy.
pub fn of(hier: &Hierarchy) -> u64 {
    let mut h = fnv::FnvHasher::default();
    put(&mut h, "canstar-rtlc shape", "1");
    for op in &hier.ops {
        match op {
            ProbeOp::Scope(n) => put(&mut h, "S", n),
            ProbeOp::Namespace(n) => put(&mut h, "N", n),
            ProbeOp::EndNamespace(n) => put(&mut h, "n", n),
            ProbeOp::EndScope(n) => put(&mut h, "s", n),
            ProbeOp::Atom(a) => {
                let at = &hier.atoms[*a];
                put(&mut h, "A", &format!("{}:{:?}:{}:{}:{:?}", at.name, at.kind, at.width, at.type_name, at.ty));
            }
        }
    }
    for e in &hier.enums {
        put(&mut h, "E", &format!("{}={}", e.name, e.variants.join(",")));
    }
    for (i, m) in hier.modules.iter().enumerate() {
        let code = match &m.code {
            Verilog::Empty => "empty".to_string(),
            Verilog::Combinatorial(b) => format!("{b:?}"),
            Verilog::Custom(t) => crate::prims::masked_text(t),
            Verilog::Blackbox(b) => format!("{b:?}"),
            Verilog::Wrapper(w) => format!("{w:?}"),
        };
        put(&mut h, "M", &format!("{i}:{code}"));
    }
    h.finish()
}

/// Fingerprint of a rust-hdl block.
pub fn fingerprint(top: &dyn Block) -> Result<u64> {
    Ok(of(&crate::collect::collect(top)?))
}
