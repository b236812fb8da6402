//! Star topologies: links, one hub with N ports, and two hubs joined by
//! interlinks (ReCANcentrate).
//!
//! A [`Link`] is three nets: `<name>.in` (driven: bind it as the sender's
//! output), `<name>.delayed` (delay line) and `<name>.out` (fault transform
//! with a [`FaultMode`]: bind it as the receiver's input).
//!
//! A hub is an ordinary [`crate::Component`]. Bind it with
//! `sim.add(hub, &ports.hub_inputs(), &ports.hub_outputs())`:
//! inputs are the uplinks' outputs (port order) followed by the incoming
//! sublinks' outputs (interlink order); outputs are the downlinks' inputs
//! followed by the outgoing sublinks' inputs. Node port `i` is bound with
//! `sim.add(node, &[ports.node_rx(i)], &[ports.node_tx(i)])`.
//!
//! Net names: hub `h`, port `i`: `h.p<i>.up.*`, `h.p<i>.down.*`; interlink `j`
//! of a two-hub network `r`: `r.il<j>.h0_to_h1.*` and `r.il<j>.h1_to_h0.*`.

use crate::{ClockSpec, Component, Io, Sim};
use crate::net::{FaultMode, NetId};

/// Delays of a link in ps.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Default)]
pub struct LinkSpec {
    /// Delay of a transition to dominant.
    pub d_dom: u64,
    /// Delay of a transition to recessive.
    pub d_rec: u64,
}

impl LinkSpec {
    pub fn symmetric(d: u64) -> Self {
        LinkSpec { d_dom: d, d_rec: d }
    }
}

/// A point-to-point link with a delay and a fault mode.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Link {
    /// Driven net: the sender's output.
    pub input: NetId,
    /// `input` after the delay.
    pub delayed: NetId,
    /// Fault net: what the receiver sees.
    pub output: NetId,
}

impl Link {
    /// Create the nets of a link named `name`.
    pub fn build(sim: &mut Sim, name: &str, spec: LinkSpec) -> Link {
        let input = sim.driven(&format!("{name}.in"), true);
        let delayed = sim.delay(&format!("{name}.delayed"), input, spec.d_dom, spec.d_rec);
        let output = sim.fault(&format!("{name}.out"), delayed);
        Link { input, delayed, output }
    }
    /// Change the fault mode now.
    pub fn set_fault(&self, sim: &mut Sim, f: FaultMode) {
        sim.set_fault(self.output, f);
    }
    /// Change the fault mode at time `t`.
    pub fn schedule_fault(&self, sim: &mut Sim, t: u64, f: FaultMode) {
        sim.schedule_fault(self.output, t, f);
    }
    /// Invert the link's output during `[start, end)`.
    pub fn add_flip_window(&self, sim: &mut Sim, start: u64, end: u64) {
        sim.add_flip_window(self.output, start, end);
    }
}

/// Link delays of one hub port.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Default)]
pub struct PortSpec {
    /// Node → hub.
    pub up: LinkSpec,
    /// Hub → node.
    pub down: LinkSpec,
}

/// The links around one hub.
#[derive(Clone, Debug)]
pub struct HubPorts {
    pub name: String,
    /// Per port: node TX → hub.
    pub uplinks: Vec<Link>,
    /// Per port: hub → node RX.
    pub downlinks: Vec<Link>,
    /// Per interlink: sublink from the other hub into this one.
    pub sub_in: Vec<Link>,
    /// Per interlink: sublink from this hub to the other one.
    pub sub_out: Vec<Link>,
}

impl HubPorts {
    /// Build a hub named `name` with one port per spec and no interlinks.
    pub fn star(sim: &mut Sim, name: &str, ports: &[PortSpec]) -> HubPorts {
        let mut uplinks = Vec::new();
        let mut downlinks = Vec::new();
        for (i, p) in ports.iter().enumerate() {
            uplinks.push(Link::build(sim, &format!("{name}.p{i}.up"), p.up));
            downlinks.push(Link::build(sim, &format!("{name}.p{i}.down"), p.down));
        }
        HubPorts { name: name.to_string(), uplinks, downlinks, sub_in: Vec::new(), sub_out: Vec::new() }
    }
    /// A star with `n` ports, all with the same link delays.
    pub fn star_uniform(sim: &mut Sim, name: &str, n: usize, up: LinkSpec, down: LinkSpec) -> HubPorts {
        Self::star(sim, name, &vec![PortSpec { up, down }; n])
    }
    pub fn n_ports(&self) -> usize {
        self.uplinks.len()
    }
    /// Net the node on port `i` drives (its TX).
    pub fn node_tx(&self, i: usize) -> NetId {
        self.uplinks[i].input
    }
    /// Net the node on port `i` reads (its RX).
    pub fn node_rx(&self, i: usize) -> NetId {
        self.downlinks[i].output
    }
    /// The hub's input nets: uplink outputs, then incoming sublink outputs.
    pub fn hub_inputs(&self) -> Vec<NetId> {
        self.uplinks.iter().chain(&self.sub_in).map(|l| l.output).collect()
    }
    /// The hub's output nets: downlink inputs, then outgoing sublink inputs.
    pub fn hub_outputs(&self) -> Vec<NetId> {
        self.downlinks.iter().chain(&self.sub_out).map(|l| l.input).collect()
    }
}

/// Two hubs joined by interlinks.
#[derive(Clone, Debug)]
pub struct TwoHubs {
    /// `hubs[0].sub_out[j] == hubs[1].sub_in[j]` and vice versa.
    pub hubs: [HubPorts; 2],
}

impl TwoHubs {
    /// Build hubs `<name>.h0` and `<name>.h1` with the given ports and one
    /// interlink per entry of `interlinks`: (sublink h0 → h1, sublink h1 → h0).
    pub fn build(
        sim: &mut Sim,
        name: &str,
        ports: [&[PortSpec]; 2],
        interlinks: &[(LinkSpec, LinkSpec)],
    ) -> TwoHubs {
        let mut h0 = HubPorts::star(sim, &format!("{name}.h0"), ports[0]);
        let mut h1 = HubPorts::star(sim, &format!("{name}.h1"), ports[1]);
        for (j, (a, b)) in interlinks.iter().enumerate() {
            let l01 = Link::build(sim, &format!("{name}.il{j}.h0_to_h1"), *a);
            let l10 = Link::build(sim, &format!("{name}.il{j}.h1_to_h0"), *b);
            h0.sub_out.push(l01);
            h1.sub_in.push(l01);
            h1.sub_out.push(l10);
            h0.sub_in.push(l10);
        }
        TwoHubs { hubs: [h0, h1] }
    }
    /// `n_ports` per hub and `n_interlinks`, uniform delays.
    pub fn uniform(
        sim: &mut Sim,
        name: &str,
        n_ports: usize,
        n_interlinks: usize,
        port: PortSpec,
        sublink: LinkSpec,
    ) -> TwoHubs {
        let ports = vec![port; n_ports];
        Self::build(sim, name, [&ports, &ports], &vec![(sublink, sublink); n_interlinks])
    }
}

/// Stand-in hub (no RTL): registers all inputs on its clock, drives every
/// downlink with the AND of all uplinks and incoming sublinks, and every
/// outgoing sublink with the AND of the uplinks only (its own contribution).
/// One clock of latency, like the reference hub's input register.
pub struct AndHub {
    name: String,
    clock: ClockSpec,
    n_ports: usize,
    n_sub: usize,
}

impl AndHub {
    pub fn new(name: &str, clock: ClockSpec, n_ports: usize, n_sub: usize) -> Self {
        AndHub { name: name.to_string(), clock, n_ports, n_sub }
    }
}

impl Component for AndHub {
    fn name(&self) -> &str {
        &self.name
    }
    fn clock(&self) -> ClockSpec {
        self.clock
    }
    fn tick(&mut self, io: &mut Io<'_>) {
        let own = (0..self.n_ports).all(|i| io.input(i));
        let all = own && (0..self.n_sub).all(|j| io.input(self.n_ports + j));
        for i in 0..self.n_ports {
            io.set_output(i, all);
        }
        for j in 0..self.n_sub {
            io.set_output(self.n_ports + j, own);
        }
    }
}
