//! The hubs: compiled model against rust-hdl, every output every cycle, every atom
//! at checkpoints.
//!
//! - `Hub` (with its frame monitor) in a ReCANcentrate network: hub A runs in both
//!   engines, hub B (compiled only) is its interlinked replica; three CAN nodes
//!   (compiled `CanCore` models with hosts sending frames) on each hub's ports.
//!   Ports and interlinks get faults now and then (stuck dominant, stuck recessive,
//!   bit flipping), so the judges blame, isolate, count and the error flag fires.
//! - The same for CANcentrate (M = 0) and one interlink (M = 1).
//! - `HubCore` on random stimulus.

mod common;

use canstar_hub::hub::{FaultInjection, FaultKind, FaultPoint, Hub, HubConfig, HubCore};
use canstar_models::generated as g;
use canstar_models::lockstep::{Lockstep, RandomInputs};
use canstar_rtlc::rt::Model;
use common::{Host, Ports};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A CAN node on a hub port: a compiled `CanCore` and its host.
struct CanNode {
    m: g::can_core::CanCore,
    host: Host,
    out: Vec<u128>,
}

/// The reference hub's bit timing (2 clocks per TQ, 8 TQ per bit) in the core's fields.
const HUB_TIMING: (u128, u128, u128, u128) = (1, 2, 1, 0);

impl CanNode {
    fn new(p: &Ports) -> CanNode {
        let m = g::can_core::CanCore::new();
        let out = vec![0; m.info().outputs.len()];
        CanNode { m, host: Host::new(p, HUB_TIMING, false), out }
    }
    fn step(&mut self, p: &Ports, rx: bool, rng: &mut ChaCha8Rng, cycle: u64) -> bool {
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
enum Fault {
    None,
    Dominant(u32),
    Recessive(u32),
    Flip(u32),
}

impl Fault {
    fn apply(&mut self, v: bool, rng: &mut ChaCha8Rng, rate: f64) -> bool {
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
fn replica(m: usize) -> Box<dyn Model> {
    match m {
        0 => Box::new(g::hub_n3_m0::HubN3M0::new()),
        1 => Box::new(g::hub_n3_m1::HubN3M1::new()),
        _ => Box::new(g::hub_n3_m2::HubN3M2::new()),
    }
}

/// Run hub A (rust-hdl and model in lock-step) in a network for `cycles` clocks.
/// Returns (frames received by the nodes, clocks with a port isolated).
fn network<M: Model>(a: &mut Lockstep<Hub, M>, m: usize, cycles: u64, seed: u64) -> (u64, u64) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let n = 3;
    let node_ports = Ports::of(&g::can_core::CanCore::new());
    let mut nodes: Vec<Vec<CanNode>> = (0..2).map(|_| (0..n).map(|_| CanNode::new(&node_ports)).collect()).collect();
    let mut b = replica(m);
    let pa = Ports::of(&a.model);
    let pb = Ports::of(b.as_ref());
    let mut va = vec![0u128; pa.ins.len()];
    let mut vb = vec![0u128; pb.ins.len()];
    let mut port_faults = vec![Fault::None; n];
    let mut link_faults = vec![Fault::None; m];
    let mut node_tx = vec![vec![true; n]; 2];
    let (mut frames, mut isolated) = (0, 0);
    for c in 0..cycles {
        let rst = c < 3 || rng.gen_bool(0.000_001);
        va[pa.i("rst_n")] = !rst as u128;
        vb[pb.i("rst_n")] = (c >= 3) as u128;
        va[pa.i("inject_fault")] = rng.gen_bool(0.0001) as u128;
        for i in 0..n {
            va[pa.i(&format!("rx${i}"))] = port_faults[i].apply(node_tx[0][i], &mut rng, 0.000_02) as u128;
            vb[pb.i(&format!("rx${i}"))] = node_tx[1][i] as u128;
        }
        for j in 0..m {
            let from_b = b.output(pb.o(&format!("hub_tx${j}"))) != 0;
            va[pa.i(&format!("reh_rx${j}"))] = link_faults[j].apply(from_b, &mut rng, 0.000_01) as u128;
            vb[pb.i(&format!("reh_rx${j}"))] = a.outputs()[pa.o(&format!("hub_tx${j}"))];
        }
        a.step(&va).unwrap_or_else(|e| panic!("hub: {e}"));
        for (i, &v) in vb.iter().enumerate() {
            b.set_input(i, v);
        }
        b.cycle();
        for i in 0..n {
            let down = [a.outputs()[pa.o(&format!("tx${i}"))] != 0, b.output(pb.o(&format!("tx${i}"))) != 0];
            for h in 0..2 {
                node_tx[h][i] = nodes[h][i].step(&node_ports, down[h], &mut rng, c);
                frames += nodes[h][i].out[node_ports.o("rx_valid")] as u64;
            }
            isolated += a.outputs()[pa.o(&format!("isolated${i}"))] as u64;
        }
        if c % 100_000 == 99_999 {
            a.compare_all().unwrap_or_else(|e| panic!("hub: {e}"));
        }
    }
    a.compare_all().unwrap_or_else(|e| panic!("hub: {e}"));
    (frames, isolated)
}

fn start<M: Model>(cfg: &HubConfig, make: fn(&dyn canstar_rtlc::rt::Block) -> Result<M, canstar_rtlc::Error>, set: fn(&mut Hub, &[u128]), get: fn(&Hub, &mut [u128])) -> Lockstep<Hub, M> {
    Lockstep::new(Hub::new(cfg), make, set, get).unwrap_or_else(|e| panic!("{e}"))
}

/// The reference ReCANcentrate hub (N = 3, M = 2), 1 M clocks.
#[test]
fn recancentrate_network() {
    let cfg = HubConfig::default();
    let mut a = start(&cfg, g::hub_n3_m2::HubN3M2::from_instance, g::hub_n3_m2::hdl_set_inputs, g::hub_n3_m2::hdl_outputs);
    let (frames, isolated) = network(&mut a, 2, 1_000_000, 31);
    assert!(frames > 500, "{frames} frames");
    assert!(isolated > 1000, "{isolated} clocks with a port isolated");
}

/// CANcentrate (M = 0) with reintegration, synchroniser depth 2 and a fault-injection
/// hook (all runtime constants of the same model shape).
#[test]
fn cancentrate_network_with_runtime_constants() {
    let cfg = HubConfig {
        sublinks: 0,
        sync_depth: 2,
        reintegration: Some(3),
        bic_threshold: 4,
        fault_injection: Some(FaultInjection { point: FaultPoint::Downlink(1), kind: FaultKind::BitFlip, start_field: 6 }),
        ..HubConfig::default()
    };
    let mut a = start(&cfg, g::hub_n3_m0::HubN3M0::from_instance, g::hub_n3_m0::hdl_set_inputs, g::hub_n3_m0::hdl_outputs);
    let (frames, _) = network(&mut a, 0, 300_000, 32);
    assert!(frames > 100, "{frames} frames");
}

/// One interlink (M = 1), 300 000 clocks.
#[test]
fn one_interlink_network() {
    let cfg = HubConfig { sublinks: 1, ..HubConfig::default() };
    let mut a = start(&cfg, g::hub_n3_m1::HubN3M1::from_instance, g::hub_n3_m1::hdl_set_inputs, g::hub_n3_m1::hdl_outputs);
    let (frames, _) = network(&mut a, 1, 300_000, 33);
    assert!(frames > 100, "{frames} frames");
}

/// `HubCore` of every committed shape on random stimulus (the monitor inputs too).
#[test]
fn hub_core_random() {
    fn run<M: Model>(cfg: HubConfig, make: fn(&dyn canstar_rtlc::rt::Block) -> Result<M, canstar_rtlc::Error>, set: fn(&mut HubCore, &[u128]), get: fn(&HubCore, &mut [u128]), cycles: u64, seed: u64) {
        let mut l = Lockstep::new(HubCore::new(&cfg), make, set, get).unwrap_or_else(|e| panic!("{e}"));
        let prob = |n: &str| match n {
            "rst_n" => 0.0005,
            "mon_sample" | "mon_bit_start" => 0.2,
            "inject_fault" => 0.001,
            _ if n.starts_with("rx") || n.starts_with("reh_rx") => 0.05,
            _ => 0.05,
        };
        let mut stim = RandomInputs::new(&l.model, seed, prob);
        for _ in 0..cycles {
            let v = stim.next().to_vec();
            l.step(&v).unwrap_or_else(|e| panic!("{e}"));
        }
        l.compare_all().unwrap_or_else(|e| panic!("{e}"));
    }
    let with_hook = |m| HubConfig {
        sublinks: m,
        fault_injection: Some(FaultInjection { point: FaultPoint::Uplink(0), kind: FaultKind::StuckDominant, start_field: 3 }),
        ..HubConfig::default()
    };
    run(with_hook(2), g::hub_core_n3_m2::HubCoreN3M2::from_instance, g::hub_core_n3_m2::hdl_set_inputs, g::hub_core_n3_m2::hdl_outputs, 300_000, 41);
    run(with_hook(0), g::hub_core_n3_m0::HubCoreN3M0::from_instance, g::hub_core_n3_m0::hdl_set_inputs, g::hub_core_n3_m0::hdl_outputs, 150_000, 42);
    run(HubConfig { sublinks: 1, ..HubConfig::default() }, g::hub_core_n3_m1::HubCoreN3M1::from_instance, g::hub_core_n3_m1::hdl_set_inputs, g::hub_core_n3_m1::hdl_outputs, 150_000, 43);
}
