//! The builder: a [`NetworkSpec`] instantiated in a kernel [`Sim`] (hubs,
//! links, controllers).

use crate::ctrl::Ctrl;
use crate::rtl_hub::RtlHub;
use crate::spec::NetworkSpec;
use canstar_models::Engine;
use canstar_sim::star::{LinkSpec, PortSpec, TwoHubs};
use canstar_sim::{ClockSpec, Handle, Sim};

/// A network instantiated in a [`Sim`].
pub struct Network {
    pub spec: NetworkSpec,
    pub links: TwoHubs,
    pub hubs: [Handle<RtlHub>; 2],
    /// `ctrls[node][c]`, c = 0 (A, hub 0) or 1 (B, hub 1).
    pub ctrls: Vec<[Handle<Ctrl>; 2]>,
}

impl Network {
    /// Build the network in `sim` (validates first). Clock phases left `None`
    /// in the spec are drawn from `sim.rng()`.
    pub fn build(sim: &mut Sim, spec: &NetworkSpec) -> Result<Network, String> {
        Self::build_with(sim, spec, Engine::default())
    }

    /// [`Network::build`] with the hubs and controllers on `engine`.
    pub fn build_with(sim: &mut Sim, spec: &NetworkSpec, engine: Engine) -> Result<Network, String> {
        spec.validate()?;
        let n = spec.hub.ports;
        let mut ports: [Vec<PortSpec>; 2] = [vec![PortSpec::default(); n], vec![PortSpec::default(); n]];
        for (k, node) in spec.nodes.iter().enumerate() {
            for (c, p) in ports.iter_mut().enumerate() {
                let cs = node.ctrl(c);
                p[k] = PortSpec { up: LinkSpec::symmetric(cs.up_ps), down: LinkSpec::symmetric(cs.down_ps) };
            }
        }
        let il: Vec<(LinkSpec, LinkSpec)> = spec
            .interlinks
            .iter()
            .map(|l| (LinkSpec::symmetric(l.h0_to_h1_ps), LinkSpec::symmetric(l.h1_to_h0_ps)))
            .collect();
        let links = TwoHubs::build(sim, "r", [&ports[0], &ports[1]], &il);
        let hp = spec.hub_period_ps();
        let mut hub_handles = Vec::new();
        for (h, hc) in spec.hubs.iter().enumerate() {
            let phase = match hc.phase_ps {
                Some(p) => p,
                None => rand::Rng::gen_range(sim.rng(), 0..hp),
            };
            let clock = ClockSpec::new(hp).with_ppm(hc.ppm).with_phase(phase);
            let hub = RtlHub::with_engine(&format!("hub{h}"), &spec.hub, clock, engine);
            hub_handles.push(sim.add(hub, &links.hubs[h].hub_inputs(), &links.hubs[h].hub_outputs()));
        }
        let mut ctrls = Vec::new();
        for (k, node) in spec.nodes.iter().enumerate() {
            let mut pair = Vec::new();
            for c in 0..2 {
                let cs = node.ctrl(c);
                let p = cs.period_ps();
                let phase = match cs.phase_ps {
                    Some(x) => x,
                    None => rand::Rng::gen_range(sim.rng(), 0..p),
                };
                let clock = ClockSpec::new(p).with_ppm(cs.ppm).with_phase(phase);
                let name = format!("{}.{}", node.name, ["a", "b"][c]);
                let ctrl = Ctrl::with_engine(&name, cs, clock, engine);
                let hp = &links.hubs[c];
                pair.push(sim.add(ctrl, &[hp.node_rx(k)], &[hp.node_tx(k)]));
            }
            ctrls.push([pair[0], pair[1]]);
        }
        Ok(Network { spec: spec.clone(), links, hubs: [hub_handles[0], hub_handles[1]], ctrls })
    }
}
