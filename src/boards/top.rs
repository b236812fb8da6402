//! A board top for the constraint writers of `rust-hdl-fpga-support`: a
//! rust-hdl [`Block`] whose only contents are the design's top-level ports,
//! each an [`Atom`] that carries its pin constraints (location, I/O standard,
//! clock period) exactly as a rust-hdl `Signal` does after `add_location` /
//! `add_signal_type` / `add_constraint`.
//!
//! The designs' Verilog tops are written as text (vector ports around the
//! rust-hdl core, board tops with an active-low reset), and their port widths
//! depend on the configuration, so the ports here have run-time widths instead
//! of a `Signal<D, Bits<N>>` per port. The writers only ask a port for its
//! name, width, id and constraints.

use rust_hdl::core::prelude::*;

/// One top-level port and its pin constraints.
#[derive(Debug, Clone)]
pub struct Port {
    pub name: String,
    /// Width as the writers see it: 1 for a scalar port (`rst_n`), at least 2
    /// for a vector port (`rx[0]`), so that bit 0 of a vector is written `rx[0]`
    /// / `rx<0>` and not `rx`.
    pub bits: usize,
    pub constraints: Vec<PinConstraint>,
    id: usize,
}

impl Port {
    fn new(name: &str, vector: bool) -> Self {
        Port { name: name.to_string(), bits: if vector { 2 } else { 1 }, constraints: vec![], id: rust_hdl::core::signal::get_signal_id() }
    }

    fn add(&mut self, index: usize, constraint: Constraint) {
        self.constraints.push(PinConstraint { index, constraint });
    }
}

impl Atom for Port {
    fn bits(&self) -> usize {
        self.bits
    }
    fn connected(&self) -> bool {
        true
    }
    fn changed(&self) -> bool {
        false
    }
    fn kind(&self) -> AtomKind {
        AtomKind::InOutParameter
    }
    fn descriptor(&self) -> TypeDescriptor {
        TypeDescriptor { name: format!("Bits::<{}>", self.bits), kind: TypeKind::Bits(self.bits) }
    }
    fn vcd(&self) -> VCDValue {
        VCDValue::String(String::new())
    }
    fn id(&self) -> usize {
        self.id
    }
    fn verilog(&self) -> VerilogLiteral {
        VerilogLiteral::from(0u64)
    }
    fn constraints(&self) -> Vec<PinConstraint> {
        self.constraints.clone()
    }
}

/// The ports of a design's board top, in the order they were first named.
#[derive(Debug, Clone, Default)]
pub struct ConstrainedTop {
    pub ports: Vec<Port>,
}

/// `rx[3]` -> (`rx`, Some(3)); `rst_n` -> (`rst_n`, None). Roles are checked
/// when a board is read ([`super::Board::validate`]).
pub fn split_role(role: &str) -> (&str, Option<usize>) {
    let (base, idx) = super::role_parts(role);
    (base, idx.and_then(|i| i.parse().ok()))
}

impl ConstrainedTop {
    /// The port a role belongs to (created on first use).
    fn port(&mut self, role: &str) -> (&mut Port, usize) {
        let (base, idx) = split_role(role);
        let at = match self.ports.iter().position(|p| p.name == base) {
            Some(i) => i,
            None => {
                self.ports.push(Port::new(base, idx.is_some()));
                self.ports.len() - 1
            }
        };
        let p = &mut self.ports[at];
        let i = idx.unwrap_or(0);
        if idx.is_some() {
            p.bits = p.bits.max(i + 1);
        }
        (p, i)
    }

    /// `role` (a port bit) on `pin`, with an I/O standard if the board has one.
    pub fn place(&mut self, role: &str, pin: &str, io: Option<&SignalType>) {
        let (p, i) = self.port(role);
        p.add(i, Constraint::Location(pin.to_string()));
        if let Some(k) = io {
            p.add(i, Constraint::Kind(k.clone()));
        }
    }

    /// A periodic clock on `role` (50 % duty cycle), named after the port.
    pub fn clock(&mut self, role: &str, period_ns: f64) {
        let (p, i) = self.port(role);
        let net = p.name.clone();
        p.add(i, Constraint::Timing(Timing::Periodic(PeriodicTiming { net, period_nanoseconds: period_ns, duty_cycle: 50.0 })));
    }
}

impl Logic for ConstrainedTop {
    fn update(&mut self) {}
}

impl Block for ConstrainedTop {
    fn connect_all(&mut self) {}
    fn update_all(&mut self) {}
    fn has_changed(&self) -> bool {
        false
    }
    fn accept(&self, name: &str, probe: &mut dyn Probe) {
        probe.visit_start_scope(name, self);
        for p in &self.ports {
            probe.visit_atom(&p.name, p);
        }
        probe.visit_end_scope(name, self);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ports_collect_their_bits_in_first_use_order() {
        let mut t = ConstrainedTop::default();
        t.place("rst_n", "E11", None);
        t.place("rx[0]", "H15", Some(&SignalType::LowVoltageCMOS_3v3));
        t.place("rx[2]", "G12", None);
        t.clock("clock", 10.0);
        let names: Vec<_> = t.ports.iter().map(|p| (p.name.as_str(), p.bits, p.constraints.len())).collect();
        assert_eq!(names, [("rst_n", 1, 1), ("rx", 3, 3), ("clock", 1, 1)]);
        assert_eq!(split_role("hub_tx[11]"), ("hub_tx", Some(11)));
    }
}
