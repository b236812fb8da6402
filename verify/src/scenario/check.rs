//! The one check of a scenario file: every number finite and in range (no
//! overflow when converted to picoseconds), every name usable as a VCD scope,
//! every reference resolved. Each message starts with the key
//! (`node[1].ppm: ...`, `frame[0].at_us: ...`); the caller adds the file.

use super::{Scenario, FIELD_NAMES};

/// Longest simulated run, in us (one hour: far beyond any use, and its
/// picoseconds fit 64 bits with room for the offsets added to them).
pub const MAX_DURATION_US: u64 = 3_600_000_000;

/// Longest TX or RX delay of a node, in ns (a bit time at 1 kbit/s).
pub const MAX_DELAY_NS: u64 = 1_000_000;

/// Longest interference, in bit times.
pub const MAX_INTERFERENCE_BITS: u32 = 1_000_000;

/// A node name becomes a VCD scope and a component name.
pub fn check_name(key: &str, name: &str) -> Result<(), String> {
    if name.is_empty() || name.len() > 64 || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(format!("{key}: name `{name}` must be 1 to 64 letters, digits or _"));
    }
    Ok(())
}

pub(super) fn validate(s: &Scenario) -> Result<(), String> {
    if s.nodes.is_empty() {
        return Err("node: a scenario needs at least one [[node]]".into());
    }
    if s.duration_us == 0 || s.duration_us > MAX_DURATION_US {
        return Err(format!("duration_us: {} (must be 1..={MAX_DURATION_US})", s.duration_us));
    }
    s.defaults.bit_timing.check().map_err(|e| format!("defaults.bit_timing: invalid bit timing: {e}"))?;
    let mhz = s.defaults.clock_mhz;
    if !(mhz > 0.1 && mhz <= 1000.0) {
        return Err(format!("defaults.clock_mhz: {mhz:?} (must be in (0.1, 1000])"));
    }
    for (i, n) in s.nodes.iter().enumerate() {
        let key = format!("node[{i}]");
        check_name(&format!("{key}.name"), &n.name)?;
        if s.nodes[..i].iter().any(|m| m.name == n.name) {
            return Err(format!("{key}.name: node name `{}` is used twice", n.name));
        }
        let mhz = s.clock_mhz(i);
        if !(mhz > 0.1 && mhz <= 1000.0) {
            return Err(format!("{key}.clock_mhz: {mhz:?} (node {}; must be in (0.1, 1000])", n.name));
        }
        if !(n.ppm.is_finite() && n.ppm.abs() <= 10_000.0) {
            return Err(format!("{key}.ppm: {:?} (node {}) is not an oscillator offset (finite, |ppm| <= 10000)", n.ppm, n.name));
        }
        for (k, v) in [("tx_delay_ns", n.tx_delay_ns), ("rx_delay_ns", n.rx_delay_ns)] {
            if v > MAX_DELAY_NS {
                return Err(format!("{key}.{k}: {v} (node {}; at most {MAX_DELAY_NS})", n.name));
            }
        }
        s.bit_timing(i).check().map_err(|e| format!("{key}.bit_timing: node {}: invalid bit timing: {e}", n.name))?;
    }
    for (k, f) in s.frames.iter().enumerate() {
        let key = format!("frame[{k}]");
        if s.node_index(&f.node).is_none() {
            return Err(format!("{key}.node: unknown node `{}`", f.node));
        }
        if f.at_us >= s.duration_us {
            return Err(format!("{key}.at_us: {} is not before the end of the run (duration_us = {})", f.at_us, s.duration_us));
        }
        let max = if f.ext { 0x1FFF_FFFF } else { 0x7FF };
        if f.id > max {
            return Err(format!(
                "{key}.id: identifier {:#x} does not fit a {} frame (max {max:#x})",
                f.id,
                if f.ext { "29-bit" } else { "11-bit" }
            ));
        }
        if f.dlc() > 15 {
            return Err(format!("{key}.dlc: {} (must be 0..=15)", f.dlc()));
        }
        let n = if f.rtr { 0 } else { f.dlc().min(8) as usize };
        if f.data.len() != n {
            return Err(format!(
                "{key}.data: {} data byte(s) given, a {} frame with dlc {} carries {n}",
                f.data.len(),
                if f.rtr { "remote" } else { "data" },
                f.dlc()
            ));
        }
    }
    for (k, x) in s.interference.iter().enumerate() {
        let key = format!("interference[{k}]");
        if s.node_index(&x.node).is_none() {
            return Err(format!("{key}.node: unknown node `{}`", x.node));
        }
        match (&x.at_us, &x.at) {
            (Some(_), Some(_)) => return Err(format!("{key}.at_us: give either at_us or at, not both")),
            (None, None) => return Err(format!("{key}.at_us: give at_us or at = {{ field = ..., pos = ... }}")),
            (Some(t), None) => {
                if !(t.is_finite() && *t >= 0.0 && *t < s.duration_us as f64) {
                    return Err(format!("{key}.at_us: {t:?} (must be a time from 0 to before the end, duration_us = {})", s.duration_us));
                }
            }
            (None, Some(p)) => {
                if !FIELD_NAMES.contains(&p.field.as_str()) {
                    return Err(format!("{key}.at.field: unknown field `{}` (one of: {})", p.field, FIELD_NAMES.join(", ")));
                }
                if p.pos == 0 || p.occurrence == 0 {
                    return Err(format!("{key}.at: pos and occurrence count from 1"));
                }
            }
        }
        if let Some(b) = x.bits {
            if b == 0 || b > MAX_INTERFERENCE_BITS {
                return Err(format!("{key}.bits: {b} (must be 1..={MAX_INTERFERENCE_BITS})"));
            }
        }
    }
    Ok(())
}
