//! Shared harness of the hub system tests: the RTL hub(s) with real CAN controllers
//! (`CanNode`) in the kernel, reference timing (hub 14.74 MHz, TQ 2 clocks; nodes
//! 29.48 MHz, BRP 4; 8 TQ per bit: PROP 3, PH1 2, PH2 2, SJW 1; 921.25 kbit/s).
#![allow(dead_code)]

use canstar_controller::frame::Frame;
use canstar_hub::config::HubConfig;
use canstar_sim::Handle;
use canstar_verify::node::{CanNode, NodeConfig};
use canstar_sim::star::{HubPorts, LinkSpec, PortSpec, TwoHubs};
pub use canstar_recan::rtl_hub::RtlHub;
use canstar_sim::{ClockSpec, Sim};
use rand::{Rng, SeedableRng};

/// Hub clock period in ps (14.74 MHz).
pub const HUB_PERIOD: u64 = 67_843;
/// Node clock period in ps (29.48 MHz).
pub const NODE_PERIOD: u64 = 33_921;
/// Nominal bit time in ps (8 TQ of 4 node clocks).
pub const BIT: u64 = 8 * 4 * NODE_PERIOD;
/// Link delay used for every uplink and downlink (about 4 m of cable).
pub const LINK_DELAY: u64 = 20_000;
/// Interlink delay (each direction).
pub const SUBLINK_DELAY: u64 = 20_000;

/// Oscillator tolerance limit of the reference bit timing (ISO 11898-1):
/// df <= min(min(PH1, PH2) / (2 (13 NBT - PH2)), SJW / (20 NBT)) = min(2/204, 1/160).
pub fn tolerance_ppm() -> f64 {
    let (ph1, ph2, sjw, nbt) = (2.0, 2.0, 1.0, 8.0);
    let a: f64 = f64::min(ph1, ph2) / (2.0 * (13.0 * nbt - ph2));
    let b: f64 = sjw / (20.0 * nbt);
    a.min(b) * 1e6
}

pub fn node_cfg(name: &str) -> NodeConfig {
    NodeConfig::named(name).timing(4, 3, 2, 1)
}

pub fn node_clock(ppm: f64, phase: u64) -> ClockSpec {
    ClockSpec::new(NODE_PERIOD).with_ppm(ppm).with_phase(phase)
}

pub fn hub_cfg(ports: usize, sublinks: usize) -> HubConfig {
    HubConfig { ports, sublinks, debug: true, ..HubConfig::default() }
}

pub fn port_spec() -> PortSpec {
    PortSpec { up: LinkSpec::symmetric(LINK_DELAY), down: LinkSpec::symmetric(LINK_DELAY) }
}

/// One hub with one `CanNode` per port.
pub struct Star {
    pub sim: Sim,
    pub ports: HubPorts,
    pub hub: Handle<RtlHub>,
    pub nodes: Vec<Handle<CanNode>>,
}

impl Star {
    /// `ppm[i]`: oscillator offset of node i (the hub runs nominal).
    pub fn new(cfg: &HubConfig, ppm: &[f64], seed: u64) -> Star {
        let mut sim = Sim::new(seed);
        let ports = HubPorts::star(&mut sim, "h", &vec![port_spec(); cfg.ports]);
        let hub = sim.add(RtlHub::with_clock("h", cfg, ClockSpec::new(HUB_PERIOD)), &ports.hub_inputs(), &ports.hub_outputs());
        let mut nodes = Vec::new();
        for i in 0..cfg.ports {
            let phase = sim.rng().gen_range(0..NODE_PERIOD);
            let n = CanNode::new(node_cfg(&format!("n{i}")), node_clock(ppm.get(i).copied().unwrap_or(0.0), phase));
            nodes.push(sim.add(n, &[ports.node_rx(i)], &[ports.node_tx(i)]));
        }
        Star { sim, ports, hub, nodes }
    }
    pub fn node(&self, i: usize) -> &CanNode {
        self.sim.get(self.nodes[i])
    }
    pub fn node_mut(&mut self, i: usize) -> &mut CanNode {
        self.sim.get_mut(self.nodes[i])
    }
    pub fn rtl(&self) -> &RtlHub {
        self.sim.get(self.hub)
    }
    pub fn rtl_mut(&mut self) -> &mut RtlHub {
        self.sim.get_mut(self.hub)
    }
    /// Run until no node has a pending frame (or the deadline in bits passes);
    /// then 30 more bits. Returns whether all queues drained.
    pub fn run_until_drained(&mut self, max_bits: u64) -> bool {
        let deadline = self.sim.now() + max_bits * BIT;
        let nodes = self.nodes.clone();
        let mut k = 0u64;
        let ok = self.sim.run_until_cond(deadline, |s| {
            k += 1;
            k.is_multiple_of(64) && nodes.iter().all(|&h| !s.get(h).pending())
        });
        self.sim.run_for(30 * BIT);
        ok
    }
}

/// Two hubs joined by `m` interlinks; node k has controller `a[k]` on hub 0 port k and
/// controller `b[k]` on hub 1 port k.
pub struct Dual {
    pub sim: Sim,
    pub net: TwoHubs,
    pub hubs: [Handle<RtlHub>; 2],
    pub a: Vec<Handle<CanNode>>,
    pub b: Vec<Handle<CanNode>>,
}

impl Dual {
    pub fn new(cfg: &HubConfig, ppm: &[f64], seed: u64) -> Dual {
        let mut sim = Sim::new(seed);
        let ports = vec![port_spec(); cfg.ports];
        let il = vec![(LinkSpec::symmetric(SUBLINK_DELAY), LinkSpec::symmetric(SUBLINK_DELAY)); cfg.sublinks];
        let net = TwoHubs::build(&mut sim, "r", [&ports, &ports], &il);
        let h0 = sim.add(RtlHub::with_clock("h0", cfg, ClockSpec::new(HUB_PERIOD)), &net.hubs[0].hub_inputs(), &net.hubs[0].hub_outputs());
        // the second hub's oscillator is independent: another phase, a small offset
        let h1 = sim.add(
            RtlHub::with_clock("h1", cfg, ClockSpec::new(HUB_PERIOD).with_phase(HUB_PERIOD / 3).with_ppm(30.0)),
            &net.hubs[1].hub_inputs(),
            &net.hubs[1].hub_outputs(),
        );
        let (mut a, mut b) = (Vec::new(), Vec::new());
        for k in 0..cfg.ports {
            let ppm_k = ppm.get(k).copied().unwrap_or(0.0);
            let phase = sim.rng().gen_range(0..NODE_PERIOD);
            // both controllers of a node share its oscillator
            let ca = CanNode::new(node_cfg(&format!("a{k}")), node_clock(ppm_k, phase));
            a.push(sim.add(ca, &[net.hubs[0].node_rx(k)], &[net.hubs[0].node_tx(k)]));
            let cb = CanNode::new(node_cfg(&format!("b{k}")), node_clock(ppm_k, phase));
            b.push(sim.add(cb, &[net.hubs[1].node_rx(k)], &[net.hubs[1].node_tx(k)]));
        }
        Dual { sim, net, hubs: [h0, h1], a, b }
    }
    pub fn rtl(&self, h: usize) -> &RtlHub {
        self.sim.get(self.hubs[h])
    }
    pub fn rtl_mut(&mut self, h: usize) -> &mut RtlHub {
        self.sim.get_mut(self.hubs[h])
    }
    /// Controller of node `k` on hub `h`.
    pub fn ctrl(&self, h: usize, k: usize) -> &CanNode {
        self.sim.get(if h == 0 { self.a[k] } else { self.b[k] })
    }
    pub fn ctrl_mut(&mut self, h: usize, k: usize) -> &mut CanNode {
        let hd = if h == 0 { self.a[k] } else { self.b[k] };
        self.sim.get_mut(hd)
    }
    pub fn all(&self) -> Vec<Handle<CanNode>> {
        self.a.iter().chain(&self.b).copied().collect()
    }
    pub fn run_until_drained(&mut self, max_bits: u64) -> bool {
        let deadline = self.sim.now() + max_bits * BIT;
        let nodes = self.all();
        let mut k = 0u64;
        let ok = self.sim.run_until_cond(deadline, |s| {
            k += 1;
            k.is_multiple_of(64) && nodes.iter().all(|&h| !s.get(h).pending())
        });
        self.sim.run_for(30 * BIT);
        ok
    }
}

/// A random legal frame of node `node` (identifiers carry the node number in their
/// low bits, so two nodes never send different frames with the same identifier):
/// standard, extended, remote frames, DLC 0..8.
pub fn random_frame(rng: &mut impl Rng, node: u32) -> Frame {
    let ext = rng.gen_bool(0.35);
    let id = if ext { (rng.gen_range(0..1u32 << 26) << 3) | node } else { (rng.gen_range(0..0xfe) << 3) | node };
    if rng.gen_ratio(1, 6) {
        return Frame::remote(ext, id, rng.gen_range(0..=8));
    }
    let len = rng.gen_range(0..=8);
    let data: Vec<u8> = (0..len).map(|_| rng.gen()).collect();
    if ext {
        Frame::ext(id, &data)
    } else {
        Frame::std(id, &data)
    }
}

/// Queue `count` random frames on each of the given nodes (full load: each node
/// requests its next frame as soon as the previous one is done).
pub fn load(sim: &mut Sim, nodes: &[Handle<CanNode>], count: usize, seed: u64) -> Vec<Vec<Frame>> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut out = vec![Vec::new(); nodes.len()];
    for _ in 0..count {
        for (k, &h) in nodes.iter().enumerate() {
            let f = random_frame(&mut rng, k as u32);
            sim.get_mut(h).request(f.clone());
            out[k].push(f);
        }
    }
    out
}

/// Every frame in `sent` was received by `rx` (as a subsequence, in order).
pub fn received_in_order(rx: &CanNode, sent: &[Frame]) -> bool {
    let got = rx.received();
    let mut it = got.iter();
    sent.iter().all(|f| it.any(|g| g == f))
}

/// Assert the hub never blamed or isolated anything.
pub fn assert_never_blamed(h: &RtlHub, what: &str) {
    let s = &h.stats;
    assert_eq!(s.blames, 0, "{what}: blames {s:?}");
    assert!(s.max_bic.iter().chain(&s.max_sub_bic).all(|&b| b == 0), "{what}: bic {s:?}");
    assert!(s.isolated_at.iter().chain(&s.sub_isolated_at).all(|x| x.is_none()), "{what}: isolation {s:?}");
    assert!(s.silent_at.iter().all(|x| x.is_none()), "{what}: silent {s:?}");
}

pub fn max_counters(n: &CanNode) -> (u32, u32) {
    (n.tec(), n.rec())
}

/// Wait (at most `max_bits`) until controller `node` reports FIELD `f` at position `pos`
/// for the bit in progress (that is just after the sample point of the bit before),
/// with `cond` true, then invert `link` around that bit's sample point. Returns
/// whether it found the bit.
pub fn flip_bit_at(
    sim: &mut Sim,
    node: Handle<CanNode>,
    link: canstar_sim::star::Link,
    f: canstar_controller::fsm::Field,
    pos: u32,
    max_bits: u64,
    cond: impl Fn(&CanNode) -> bool,
) -> bool {
    let deadline = sim.now() + max_bits * BIT;
    let found = sim.run_until_cond(deadline, |s| {
        let n = s.get(node);
        n.field() == f && n.pos() == pos && cond(n)
    });
    if found {
        let t = sim.now();
        link.add_flip_window(sim, t + BIT / 2, t + BIT * 6 / 5);
    }
    found
}

/// Run for `dt` ps and return the largest TEC and REC seen (checked every 32 kernel
/// steps) over the given controllers.
pub fn run_tracking(sim: &mut Sim, ctrls: &[Handle<CanNode>], dt: u64) -> (u32, u32) {
    let end = sim.now() + dt;
    let (mut tec, mut rec) = (0, 0);
    let mut k = 0u64;
    sim.run_until_cond(end, |s| {
        k += 1;
        if k.is_multiple_of(32) {
            for &h in ctrls {
                tec = tec.max(s.get(h).tec());
                rec = rec.max(s.get(h).rec());
            }
        }
        false
    });
    sim.run_until(end);
    (tec, rec)
}

/// Arbitration losses reported by the given controllers.
pub fn arb_losses(sim: &Sim, ctrls: &[Handle<CanNode>]) -> usize {
    ctrls.iter().map(|&h| sim.get(h).log().iter().filter(|(_, e)| matches!(e, canstar_verify::node::HostEvent::ArbLost(_))).count()).sum()
}

/// The frames cover extended, standard, remote and data frames.
pub fn assert_frame_mix(sent: &[Vec<Frame>]) {
    let all: Vec<&Frame> = sent.iter().flatten().collect();
    assert!(all.iter().any(|f| f.ide) && all.iter().any(|f| !f.ide), "standard and extended frames");
    assert!(all.iter().any(|f| f.rtr) && all.iter().any(|f| !f.rtr), "remote and data frames");
}
