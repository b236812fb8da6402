//! VCD output (timescale 1 ps).
//!
//! Layout: one top scope `sim`; inside it one scope per component that
//! presents signals through [`crate::Component::probe`] (rust-hdl blocks:
//! every atom of the block hierarchy, sub-blocks as sub-scopes), then the
//! nets, placed in scopes by splitting their names at `.` (so the net
//! `bus.node0.rx` is the wire `rx` in scope `bus.node0`).
//!
//! Net wires carry their exact transition times (also those of delayed
//! wires between clock edges); component signals are sampled after each of
//! the component's edges. Only changes are written. Id codes are assigned in a
//! fixed order (components in order of addition, then nets sorted by name), so
//! the output is identical for identical simulations.
//!
//! # Selection
//! A filter is a list of patterns over hierarchical names (`node0.btl.cnt`,
//! `bus.level`; component signals are named `<component>.<sub>...<atom>`).
//! A name matches a pattern `p` if it equals `p`, starts with `p.`, or, when
//! `p` ends in `*`, starts with `p` without the `*`.

use std::cell::RefCell;
use std::io::{self, Write};
use std::rc::Rc;

use rust_hdl::core::prelude::{Atom, Block, Probe, TypeDescriptor, TypeKind, VCDValue};
use vcd::{IdCode, TimescaleUnit, Value, VarType, Writer};

use crate::net::NetId;

/// What the VCD writer reads of a simulation: the components' signals (through
/// rust-hdl's [`Probe`]) and the nets' levels and transition times. The kernel's
/// `Sim` implements it; the writer knows nothing else of the kernel.
pub trait VcdView {
    /// Current time in ps.
    fn now(&self) -> u64;
    /// Number of components, in order of addition.
    fn component_count(&self) -> usize;
    /// Present component `i`'s signals to `probe`.
    fn probe_component(&self, i: usize, probe: &mut dyn Probe);
    /// Every net with its hierarchical name.
    fn net_names(&self) -> Vec<(&str, NetId)>;
    /// Level of a net at instant `t`.
    fn net_at(&self, id: NetId, t: u64) -> bool;
    /// First transition of a net strictly after `after` (None: no later transition known).
    fn next_event(&self, id: NetId, after: i64) -> Option<u64>;
}

/// Does hierarchical `name` match one of the patterns (`None` = everything)?
pub fn matches(filter: Option<&[String]>, name: &str) -> bool {
    let Some(pats) = filter else { return true };
    pats.iter().any(|p| {
        if let Some(pre) = p.strip_suffix('*') {
            name.starts_with(pre)
        } else {
            name == p || (name.starts_with(p.as_str()) && name[p.len()..].starts_with('.'))
        }
    })
}

#[derive(Clone)]
struct Shared(Rc<RefCell<Box<dyn Write>>>);
impl Write for Shared {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.0.borrow_mut().write(buf)
    }
    fn flush(&mut self) -> io::Result<()> {
        self.0.borrow_mut().flush()
    }
}

enum Code {
    One(IdCode),
    Many(Vec<Code>),
}

struct AtomSlot {
    code: Option<Code>,
    last: Option<VCDValue>,
}

struct Wire {
    net: NetId,
    code: IdCode,
    last: bool,
}

pub(crate) struct VcdState {
    w: Writer<Shared>,
    out: Shared,
    comps: Vec<Vec<AtomSlot>>,
    wires: Vec<Wire>,
    last_t: u64,
    ts: Option<u64>,
    err: Option<io::Error>,
}

fn register(w: &mut Writer<Shared>, name: &str, d: &TypeDescriptor) -> io::Result<Code> {
    Ok(match &d.kind {
        TypeKind::Bits(width) | TypeKind::Signed(width) => Code::One(w.add_wire(*width as u32, name)?),
        TypeKind::Enum(_) => Code::One(w.add_var(VarType::String, 1, name, None)?),
        TypeKind::Composite(fields) => {
            let mut v = Vec::new();
            for f in fields {
                v.push(register(w, &format!("{}${}", name, f.fieldname), &f.kind)?);
            }
            Code::Many(v)
        }
    })
}

fn emit(w: &mut Writer<Shared>, code: &Code, v: &VCDValue) -> io::Result<()> {
    match (code, v) {
        (Code::One(c), VCDValue::Single(s)) => w.change_scalar(*c, *s),
        (Code::One(c), VCDValue::Vector(b)) if b.len() == 1 => w.change_scalar(*c, b[0]),
        (Code::One(c), VCDValue::Vector(b)) => w.change_vector(*c, b),
        (Code::One(c), VCDValue::String(s)) => w.change_string(*c, s),
        (Code::Many(cs), VCDValue::Composite(vs)) if cs.len() == vs.len() => {
            for (c, v) in cs.iter().zip(vs) {
                emit(w, c, v)?;
            }
            Ok(())
        }
        _ => Err(io::Error::other("VCD value does not match its declaration")),
    }
}

fn set_time(w: &mut Writer<Shared>, ts: &mut Option<u64>, t: u64) -> io::Result<()> {
    if *ts != Some(t) {
        debug_assert!(ts.is_none_or(|x| x < t));
        w.timestamp(t)?;
        *ts = Some(t);
    }
    Ok(())
}

struct HeaderProbe<'a> {
    w: &'a mut Writer<Shared>,
    filter: Option<&'a [String]>,
    path: Vec<String>,
    opened: usize,
    slots: Vec<AtomSlot>,
    err: Option<io::Error>,
}

impl HeaderProbe<'_> {
    fn start(&mut self, name: &str) {
        self.path.push(name.to_string());
    }
    fn end(&mut self) {
        if self.opened == self.path.len() {
            if let Err(e) = self.w.upscope() {
                self.err.get_or_insert(e);
            }
            self.opened -= 1;
        }
        self.path.pop();
    }
}

impl Probe for HeaderProbe<'_> {
    fn visit_start_scope(&mut self, name: &str, _node: &dyn Block) {
        self.start(name)
    }
    fn visit_start_namespace(&mut self, name: &str, _node: &dyn Block) {
        self.start(name)
    }
    fn visit_end_scope(&mut self, _name: &str, _node: &dyn Block) {
        self.end()
    }
    fn visit_end_namespace(&mut self, _name: &str, _node: &dyn Block) {
        self.end()
    }
    fn visit_atom(&mut self, name: &str, atom: &dyn Atom) {
        let full = if self.path.is_empty() { name.to_string() } else { format!("{}.{}", self.path.join("."), name) };
        if !matches(self.filter, &full) {
            self.slots.push(AtomSlot { code: None, last: None });
            return;
        }
        let r = (|| {
            while self.opened < self.path.len() {
                self.w.add_module(&self.path[self.opened])?;
                self.opened += 1;
            }
            register(self.w, name, &atom.descriptor())
        })();
        match r {
            Ok(code) => self.slots.push(AtomSlot { code: Some(code), last: None }),
            Err(e) => {
                self.err.get_or_insert(e);
                self.slots.push(AtomSlot { code: None, last: None });
            }
        }
    }
}

struct ChangeProbe<'a> {
    w: &'a mut Writer<Shared>,
    ts: &'a mut Option<u64>,
    t: u64,
    slots: &'a mut [AtomSlot],
    k: usize,
    dump: bool,
    err: Option<io::Error>,
}

impl Probe for ChangeProbe<'_> {
    fn visit_atom(&mut self, _name: &str, atom: &dyn Atom) {
        let Some(slot) = self.slots.get_mut(self.k) else {
            self.err.get_or_insert(io::Error::other("block hierarchy changed after VCD start"));
            return;
        };
        self.k += 1;
        let Some(code) = &slot.code else { return };
        let v = atom.vcd();
        if !self.dump && slot.last.as_ref() == Some(&v) {
            return;
        }
        let r = set_time(self.w, self.ts, self.t).and_then(|_| emit(self.w, code, &v));
        if let Err(e) = r {
            self.err.get_or_insert(e);
        }
        slot.last = Some(v);
    }
}

fn bit(v: bool) -> Value {
    if v {
        Value::V1
    } else {
        Value::V0
    }
}

impl VcdState {
    pub(crate) fn start(sim: &dyn VcdView, out: Box<dyn Write>, filter: Option<&[&str]>) -> io::Result<Self> {
        let filter: Option<Vec<String>> = filter.map(|f| f.iter().map(|s| s.to_string()).collect());
        let filter = filter.as_deref();
        let out = Shared(Rc::new(RefCell::new(out)));
        let mut w = Writer::new(out.clone());
        w.timescale(1, TimescaleUnit::PS)?;
        w.add_module("sim")?;
        let mut comps = Vec::new();
        for i in 0..sim.component_count() {
            let mut hp = HeaderProbe { w: &mut w, filter, path: Vec::new(), opened: 0, slots: Vec::new(), err: None };
            sim.probe_component(i, &mut hp);
            if let Some(e) = hp.err {
                return Err(e);
            }
            while hp.opened > 0 {
                hp.w.upscope()?;
                hp.opened -= 1;
            }
            comps.push(hp.slots);
        }
        // nets, sorted by their name segments
        let names = sim.net_names();
        let mut nets: Vec<(Vec<&str>, NetId)> =
            names.iter().filter(|(n, _)| matches(filter, n)).map(|(n, id)| (n.split('.').collect(), *id)).collect();
        nets.sort();
        let mut stack: Vec<&str> = Vec::new();
        let mut wires = Vec::new();
        for (segs, id) in &nets {
            let scopes = &segs[..segs.len() - 1];
            let common = stack.iter().zip(scopes).take_while(|(a, b)| a == b).count();
            while stack.len() > common {
                w.upscope()?;
                stack.pop();
            }
            for s in &scopes[common..] {
                w.add_module(s)?;
                stack.push(s);
            }
            let code = w.add_wire(1, segs[segs.len() - 1])?;
            wires.push(Wire { net: *id, code, last: sim.net_at(*id, sim.now()) });
        }
        for _ in stack {
            w.upscope()?;
        }
        w.upscope()?;
        w.enddefinitions()?;
        let mut st = VcdState { w, out, comps, wires, last_t: sim.now(), ts: None, err: None };
        set_time(&mut st.w, &mut st.ts, sim.now())?;
        st.w.begin(vcd::SimulationCommand::Dumpvars)?;
        for i in 0..sim.component_count() {
            st.visit(sim, i, sim.now(), true)?;
        }
        for wire in &st.wires {
            st.w.change_scalar(wire.code, bit(wire.last))?;
        }
        st.w.end()?;
        Ok(st)
    }

    fn visit(&mut self, sim: &dyn VcdView, i: usize, t: u64, dump: bool) -> io::Result<()> {
        let mut cp =
            ChangeProbe { w: &mut self.w, ts: &mut self.ts, t, slots: &mut self.comps[i], k: 0, dump, err: None };
        sim.probe_component(i, &mut cp);
        match cp.err {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// Write wire changes in `(last_t, t]` and the signals of `ticked` components at `t`.
    pub(crate) fn dump(&mut self, sim: &dyn VcdView, t: u64, ticked: &[usize]) -> io::Result<()> {
        if let Some(e) = self.err.take() {
            return Err(e);
        }
        // changes at last_t made after the last dump (test code setting a fault or driving a net)
        let lt = self.last_t;
        for k in 0..self.wires.len() {
            let v = sim.net_at(self.wires[k].net, lt);
            if v != self.wires[k].last {
                set_time(&mut self.w, &mut self.ts, lt)?;
                self.w.change_scalar(self.wires[k].code, bit(v))?;
                self.wires[k].last = v;
            }
        }
        let mut events: Vec<(u64, usize, bool)> = Vec::new();
        for (k, wire) in self.wires.iter_mut().enumerate() {
            let mut after = lt as i64;
            while let Some(e) = sim.next_event(wire.net, after) {
                if e > t {
                    break;
                }
                let v = sim.net_at(wire.net, e);
                if v != wire.last {
                    events.push((e, k, v));
                    wire.last = v;
                }
                after = e as i64;
            }
        }
        events.sort_unstable();
        for (e, k, v) in events {
            set_time(&mut self.w, &mut self.ts, e)?;
            self.w.change_scalar(self.wires[k].code, bit(v))?;
        }
        for &i in ticked {
            self.visit(sim, i, t, false)?;
        }
        self.last_t = t;
        Ok(())
    }

    pub(crate) fn finish(mut self) -> io::Result<()> {
        self.out.flush()?;
        drop(self.w);
        let r = self.out.0.borrow_mut().flush();
        r
    }
}
