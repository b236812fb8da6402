//! The simulation engine of an RTL component: the compiled model (default) or the
//! rust-hdl design driven with `canstar_hdl::drive` (the reference).
//!
//! Components that simulate canstar's RTL ([`crate::core_sim::CoreSim`] for the
//! controller core, [`crate::hub_sim::HubSim`] for the hub) take an [`Engine`]; when
//! the configuration has no committed model they fall back to rust-hdl with a
//! one-line warning on stderr (see [`fallback_warning`]).

use std::collections::HashSet;
use std::sync::Mutex;

/// Which engine simulates an RTL design.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Engine {
    /// The committed compiled model (`canstar-models`), loaded from the rust-hdl instance.
    #[default]
    Compiled,
    /// The rust-hdl design itself, driven with `canstar_hdl::drive` (reference path).
    RustHdl,
}

impl Engine {
    pub const ALL: [Engine; 2] = [Engine::Compiled, Engine::RustHdl];
    pub fn name(self) -> &'static str {
        match self {
            Engine::Compiled => "compiled",
            Engine::RustHdl => "rust-hdl",
        }
    }
}

impl std::fmt::Display for Engine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Engine {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "compiled" => Ok(Engine::Compiled),
            "rust-hdl" | "rusthdl" | "hdl" => Ok(Engine::RustHdl),
            _ => Err(format!("unknown engine `{s}` (compiled or rust-hdl)")),
        }
    }
}

static WARNED: Mutex<Option<HashSet<String>>> = Mutex::new(None);

/// Print, once per process and design, that `design` runs on rust-hdl because no
/// committed model fits (`why`).
pub fn fallback_warning(design: &str, why: &str) {
    let mut w = WARNED.lock().unwrap_or_else(|e| e.into_inner());
    if w.get_or_insert_with(HashSet::new).insert(design.to_string()) {
        eprintln!("warning: no compiled model for {design} ({why}); simulating it with rust-hdl (regenerate with `canstar generate models` or add the shape to canstar_models::registry)");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for e in Engine::ALL {
            assert_eq!(e.name().parse::<Engine>().unwrap(), e);
        }
        assert!("verilator".parse::<Engine>().is_err());
        assert_eq!(Engine::default(), Engine::Compiled);
    }
}
