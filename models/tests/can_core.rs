//! `CanCore`: compiled model against rust-hdl, every output every cycle, every atom
//! at checkpoints: nodes exchanging frames on a wired-AND bus (with disturbances,
//! mode changes, counter loads, aborts), and a node on random stimulus.

use canstar_controller::core::CanCore;
use canstar_models::generated::can_core as g;
use canstar_models::lockstep::{Lockstep, RandomInputs};
mod common;

use common::{Host, Ports};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

type Node = Lockstep<CanCore, g::CanCore>;

fn node(depth: usize) -> Node {
    Lockstep::new(CanCore::with_sync_depth(depth), g::CanCore::from_instance, g::hdl_set_inputs, g::hdl_outputs).unwrap_or_else(|m| panic!("{m}"))
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
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn bus_traffic_three_nodes() {
    let (frames, errors) = bus(&[2, 2, 1], (0, 0, 3, 3), false, 350_000, 11);
    assert!(frames > 200, "only {frames} frames received");
    assert!(errors > 10, "only {errors} errors");
}

/// Two nodes with another timing (2 clocks per TQ, triple sampling).
#[test]
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn bus_traffic_triple_sampling() {
    let (frames, errors) = bus(&[2, 1], (1, 2, 2, 1), true, 150_000, 12);
    assert!(frames > 20, "only {frames} frames received");
    assert!(errors > 0);
}

/// One node on random stimulus (timing and modes change rarely, RX often).
#[test]
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn random_stimulus() {
    let mut n = node(2);
    let prob = |name: &str| match name {
        "rx" => 0.1,
        "reset" => 0.0005,
        "brp" | "prop" | "ph1" | "ph2" | "sjw" | "triple" | "listen_only" => 0.0001,
        "cnt_load" | "recover" | "tx_abort" => 0.002,
        _ => 0.01,
    };
    let mut stim = RandomInputs::new(&n.model, 13, prob);
    for _ in 0..200_000 {
        let v = stim.draw().to_vec();
        n.step(&v).unwrap_or_else(|m| panic!("{m}"));
    }
    n.compare_all().unwrap_or_else(|m| panic!("{m}"));
}
