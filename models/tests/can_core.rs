//! `CanCore`: compiled model against rust-hdl, every output every cycle, every atom
//! at checkpoints: nodes exchanging frames on a wired-AND bus (with disturbances,
//! mode changes, counter loads, aborts), and a node on random stimulus.

use canstar_controller::core::CanCore;
use canstar_models::generated::can_core as g;
use canstar_models::lockstep::{Lockstep, RandomInputs};
use canstar_rtlc::rt::Model;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

type Node = Lockstep<CanCore, g::CanCore>;

fn node(depth: usize) -> Node {
    Lockstep::new(CanCore::with_sync_depth(depth), g::CanCore::from_instance, g::hdl_set_inputs, g::hdl_outputs).unwrap_or_else(|m| panic!("{m}"))
}

/// Port indices by name.
struct Ports {
    ins: Vec<&'static str>,
    outs: Vec<&'static str>,
}

impl Ports {
    fn of(m: &dyn Model) -> Ports {
        let i = m.info();
        Ports { ins: i.inputs.iter().map(|p| p.name).collect(), outs: i.outputs.iter().map(|p| p.name).collect() }
    }
    fn i(&self, n: &str) -> usize {
        self.ins.iter().position(|x| *x == n).unwrap_or_else(|| panic!("no input {n}"))
    }
    fn o(&self, n: &str) -> usize {
        self.outs.iter().position(|x| *x == n).unwrap_or_else(|| panic!("no output {n}"))
    }
}

/// The host side of one node: requests, aborts, mode changes, counter loads.
struct Host {
    v: Vec<u128>,
    busy: bool,
    low: u32,
}

impl Host {
    fn new(p: &Ports, timing: (u128, u128, u128, u128), triple: bool) -> Host {
        let mut v = vec![0u128; p.ins.len()];
        v[p.i("brp")] = timing.0;
        v[p.i("prop")] = timing.1;
        v[p.i("ph1")] = timing.2;
        v[p.i("sjw")] = timing.3;
        v[p.i("triple")] = triple as u128;
        v[p.i("reset")] = 1;
        v[p.i("rx")] = 1;
        Host { v, busy: false, low: 0 }
    }

    fn tick(&mut self, p: &Ports, out: &[u128], rng: &mut ChaCha8Rng, cycle: u64) {
        let v = &mut self.v;
        v[p.i("reset")] = (cycle < 3 || rng.gen_bool(0.000_01)) as u128;
        v[p.i("recover")] = 0;
        v[p.i("tx_abort")] = 0;
        v[p.i("cnt_load")] = 0;
        let done = out[p.o("tx_done")] != 0;
        let single = v[p.i("single_shot")] != 0;
        let failed = single && (out[p.o("arb_lost")] != 0 || (out[p.o("error")] != 0 && out[p.o("err_tx")] != 0));
        if self.busy && (done || failed || rng.gen_bool(0.000_02)) {
            self.busy = false;
            v[p.i("tx_req")] = 0;
            self.low = rng.gen_range(1..400);
        } else if !self.busy {
            if self.low > 0 {
                self.low -= 1;
            } else if rng.gen_bool(0.002) {
                self.busy = true;
                v[p.i("tx_req")] = 1;
                v[p.i("tx_ide")] = rng.gen_bool(0.4) as u128;
                v[p.i("tx_rtr")] = rng.gen_bool(0.1) as u128;
                v[p.i("tx_id")] = rng.gen::<u32>() as u128 & 0x1fff_ffff;
                v[p.i("tx_dlc")] = rng.gen_range(0..16);
                v[p.i("tx_data")] = rng.gen::<u64>() as u128;
            }
        }
        if self.busy && rng.gen_bool(0.000_05) {
            v[p.i("tx_abort")] = 1;
        }
        if rng.gen_bool(0.000_02) {
            // a mode change
            let k = rng.gen_range(0..4);
            let name = ["listen_only", "self_test", "single_shot", "host_recovery"][k];
            v[p.i(name)] = rng.gen_bool(if k == 0 { 0.2 } else { 0.5 }) as u128;
        }
        if out[p.o("state")] == 2 && rng.gen_bool(0.001) {
            v[p.i("recover")] = 1;
        }
        if rng.gen_bool(0.000_01) {
            v[p.i("cnt_load")] = 1;
            v[p.i("tec_in")] = rng.gen_range(0..300);
            v[p.i("rec_in")] = rng.gen_range(0..256);
        }
    }
}

/// `n` nodes on a wired-AND bus for `cycles` clocks. Each node's RX is disturbed now
/// and then (a few clocks of the inverted level), so errors, error frames,
/// confinement and bus-off happen too.
fn bus(depths: &[usize], timing: (u128, u128, u128, u128), triple: bool, cycles: u64, seed: u64) -> (u64, u64) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut nodes: Vec<Node> = depths.iter().map(|&d| node(d)).collect();
    let p = Ports::of(&nodes[0].model);
    let mut hosts: Vec<Host> = nodes.iter().map(|_| Host::new(&p, timing, triple)).collect();
    let mut flip = vec![0u32; nodes.len()];
    let (tx, rxv) = (p.o("tx"), p.o("rx_valid"));
    let (mut frames, mut errors) = (0, 0);
    for c in 0..cycles {
        let bus = nodes.iter().all(|n| n.outputs()[tx] != 0) || c == 0;
        for (i, n) in nodes.iter_mut().enumerate() {
            hosts[i].tick(&p, n.outputs(), &mut rng, c);
            if flip[i] == 0 && rng.gen_bool(0.000_05) {
                flip[i] = rng.gen_range(1..25);
            }
            let lvl = if flip[i] > 0 {
                flip[i] -= 1;
                !bus
            } else {
                bus
            };
            hosts[i].v[p.i("rx")] = lvl as u128;
            n.step(&hosts[i].v).unwrap_or_else(|m| panic!("node {i}: {m}"));
            frames += n.outputs()[rxv] as u64;
            errors += n.outputs()[p.o("error")] as u64;
        }
        if c % 50_000 == 49_999 {
            for (i, n) in nodes.iter_mut().enumerate() {
                n.compare_all().unwrap_or_else(|m| panic!("node {i}: {m}"));
            }
        }
    }
    for (i, n) in nodes.iter_mut().enumerate() {
        n.compare_all().unwrap_or_else(|m| panic!("node {i}: {m}"));
    }
    (frames, errors)
}

/// 3 nodes (synchroniser depths 2, 2, 1), 10 clocks per bit, 350 000 clocks each
/// (1.05 M node-cycles).
#[test]
fn bus_traffic_three_nodes() {
    let (frames, errors) = bus(&[2, 2, 1], (0, 0, 3, 3), false, 350_000, 11);
    assert!(frames > 200, "only {frames} frames received");
    assert!(errors > 10, "only {errors} errors");
}

/// Two nodes with another timing (2 clocks per TQ, triple sampling).
#[test]
fn bus_traffic_triple_sampling() {
    let (frames, errors) = bus(&[2, 1], (1, 2, 2, 1), true, 150_000, 12);
    assert!(frames > 20, "only {frames} frames received");
    assert!(errors > 0);
}

/// One node on random stimulus (timing and modes change rarely, RX often).
#[test]
fn random_stimulus() {
    let mut n = node(2);
    let prob = |name: &str| match name {
        "rx" => 0.1,
        "reset" => 0.0005,
        "brp" | "prop" | "ph1" | "sjw" | "triple" | "listen_only" => 0.0001,
        "cnt_load" | "recover" | "tx_abort" => 0.002,
        _ => 0.01,
    };
    let mut stim = RandomInputs::new(&n.model, 13, prob);
    for _ in 0..200_000 {
        let v = stim.next().to_vec();
        n.step(&v).unwrap_or_else(|m| panic!("{m}"));
    }
    n.compare_all().unwrap_or_else(|m| panic!("{m}"));
}
