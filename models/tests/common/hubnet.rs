//! The environment of a hub under test ("hub A") in a ReCANcentrate network: its
//! interlinked replica hub B (compiled model), three CAN nodes (compiled `CanCore`
//! models with hosts sending frames) on each hub's ports, and faults now and then on
//! A's ports and interlinks (stuck dominant, stuck recessive, bit flipping), so that
//! the judges blame, isolate and count and the error flag fires.
//!
//! Per clock: `inputs(a_out)` gives hub A's inputs from its last outputs, then hub A
//! steps (in whichever engine), then `advance(a_out)` moves the rest of the network.

use canstar_models::generated as g;
use canstar_rtlc::rt::Model;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::{Host, Ports};

/// A CAN node on a hub port: a compiled `CanCore` and its host.
pub struct CanNode {
    pub m: g::can_core::CanCore,
    pub host: Host,
    pub out: Vec<u128>,
}

/// The reference hub's bit timing (2 clocks per TQ, 8 TQ per bit) in the core's fields.
pub const HUB_TIMING: (u128, u128, u128, u128) = (1, 2, 1, 0);

impl CanNode {
    pub fn new(p: &Ports) -> CanNode {
        let m = g::can_core::CanCore::new();
        let out = vec![0; m.info().outputs.len()];
        CanNode { m, host: Host::new(p, HUB_TIMING, false), out }
    }
    pub fn step(&mut self, p: &Ports, rx: bool, rng: &mut ChaCha8Rng, cycle: u64) -> bool {
        self.host.tick(p, &self.out, rng, cycle);
        self.host.v[p.i("rx")] = rx as u128;
        for (i, &v) in self.host.v.iter().enumerate() {
            self.m.set_input(i, v);
        }
        self.m.cycle();
        for (i, o) in self.out.iter_mut().enumerate() {
            *o = self.m.output(i);
        }
        self.out[p.o("tx")] != 0
    }
}

/// A fault on a link: none, stuck dominant, stuck recessive, inverting.
#[derive(Clone, Copy)]
pub enum Fault {
    None,
    Dominant(u32),
    Recessive(u32),
    Flip(u32),
}

impl Fault {
    pub fn apply(&mut self, v: bool, rng: &mut ChaCha8Rng, rate: f64) -> bool {
        let out = match *self {
            Fault::None => v,
            Fault::Dominant(_) => false,
            Fault::Recessive(_) => true,
            Fault::Flip(_) => !v,
        };
        *self = match *self {
            Fault::None if rng.gen_bool(rate) => match rng.gen_range(0..3) {
                0 => Fault::Dominant(rng.gen_range(100..3000)),
                1 => Fault::Recessive(rng.gen_range(100..20_000)),
                _ => Fault::Flip(rng.gen_range(5..300)),
            },
            Fault::Dominant(0) | Fault::Recessive(0) | Fault::Flip(0) => Fault::None,
            Fault::Dominant(n) => Fault::Dominant(n - 1),
            Fault::Recessive(n) => Fault::Recessive(n - 1),
            Fault::Flip(n) => Fault::Flip(n - 1),
            f => f,
        };
        out
    }
}

/// Generic view of the two compiled hub shapes used as replica.
pub fn replica(m: usize) -> Box<dyn Model> {
    match m {
        0 => Box::new(g::hub_n3_m0::HubN3M0::new()),
        1 => Box::new(g::hub_n3_m1::HubN3M1::new()),
        _ => Box::new(g::hub_n3_m2::HubN3M2::new()),
    }
}

pub struct HubNet {
    pub m: usize,
    rng: ChaCha8Rng,
    node_ports: Ports,
    nodes: Vec<Vec<CanNode>>,
    b: Box<dyn Model>,
    pa: Ports,
    pb: Ports,
    va: Vec<u128>,
    vb: Vec<u128>,
    port_faults: Vec<Fault>,
    link_faults: Vec<Fault>,
    node_tx: Vec<Vec<bool>>,
    cycle: u64,
    /// Frames the nodes received.
    pub frames: u64,
    /// Clocks x ports with a port of hub A isolated.
    pub isolated: u64,
}

impl HubNet {
    /// The network around a hub A with `m` interlinks whose ports are `pa`.
    pub fn new(pa: Ports, m: usize, seed: u64) -> HubNet {
        let n = 3;
        let node_ports = Ports::of(&g::can_core::CanCore::new());
        let nodes: Vec<Vec<CanNode>> = (0..2).map(|_| (0..n).map(|_| CanNode::new(&node_ports)).collect()).collect();
        let b = replica(m);
        let pb = Ports::of(b.as_ref());
        let va = vec![0u128; pa.ins.len()];
        let vb = vec![0u128; pb.ins.len()];
        HubNet {
            m,
            rng: ChaCha8Rng::seed_from_u64(seed),
            node_ports,
            nodes,
            b,
            pa,
            pb,
            va,
            vb,
            port_faults: vec![Fault::None; n],
            link_faults: vec![Fault::None; m],
            node_tx: vec![vec![true; n]; 2],
            cycle: 0,
            frames: 0,
            isolated: 0,
        }
    }

    /// Hub A's inputs for this clock.
    pub fn inputs(&mut self, a_out: &[u128]) -> &[u128] {
        let (pa, pb, rng) = (&self.pa, &self.pb, &mut self.rng);
        let c = self.cycle;
        let rst = c < 3 || rng.gen_bool(0.000_001);
        self.va[pa.i("rst_n")] = !rst as u128;
        self.vb[pb.i("rst_n")] = (c >= 3) as u128;
        self.va[pa.i("inject_fault")] = rng.gen_bool(0.0001) as u128;
        for i in 0..3 {
            self.va[pa.i(&format!("rx${i}"))] = self.port_faults[i].apply(self.node_tx[0][i], rng, 0.000_02) as u128;
            self.vb[pb.i(&format!("rx${i}"))] = self.node_tx[1][i] as u128;
        }
        for j in 0..self.m {
            let from_b = self.b.output(pb.o(&format!("hub_tx${j}"))) != 0;
            self.va[pa.i(&format!("reh_rx${j}"))] = self.link_faults[j].apply(from_b, rng, 0.000_01) as u128;
            self.vb[pb.i(&format!("reh_rx${j}"))] = a_out[pa.o(&format!("hub_tx${j}"))];
        }
        &self.va
    }

    #[allow(clippy::needless_range_loop)]
    /// The rest of the network after hub A's clock (`a_out`: A's new outputs).
    pub fn advance(&mut self, a_out: &[u128]) {
        self.b.set_inputs(&self.vb);
        self.b.cycle();
        for i in 0..3 {
            let down = [a_out[self.pa.o(&format!("tx${i}"))] != 0, self.b.output(self.pb.o(&format!("tx${i}"))) != 0];
            for h in 0..2 {
                self.node_tx[h][i] = self.nodes[h][i].step(&self.node_ports, down[h], &mut self.rng, self.cycle);
                self.frames += self.nodes[h][i].out[self.node_ports.o("rx_valid")] as u64;
            }
            self.isolated += a_out[self.pa.o(&format!("isolated${i}"))] as u64;
        }
        self.cycle += 1;
    }
}
