//! The SJA1000 top (Wishbone register block, RX FIFO memory, acceptance filters,
//! CAN core): compiled model against rust-hdl, every output every cycle, every atom
//! at checkpoints. Two controllers on a wired-AND bus, each with a host running a
//! driver-like register program at random (see `common/sjanet.rs`).

mod common;

use canstar_controller::sja1000::Sja1000;
use canstar_models::generated::sja1000 as g;
use canstar_models::lockstep::Lockstep;
use canstar_rtlc::rt::Model;
use common::sjanet::SjaNet;

type Node = Lockstep<Sja1000, g::Sja1000>;

fn net(nodes_n: usize, cycles: u64, seed: u64) -> u64 {
    let mut nodes: Vec<Node> = (0..nodes_n)
        .map(|i| {
            // power-up bit timing is a runtime constant of the model
            let b = if i == 0 { Sja1000::new() } else { Sja1000::with_reset_timing(0x40, 0x25) };
            Lockstep::new(b, g::Sja1000::from_instance, g::hdl_set_inputs, g::hdl_outputs).unwrap_or_else(|m| panic!("{m}"))
        })
        .collect();
    let mut env = SjaNet::new(&nodes[0].model, nodes_n, seed);
    let (tx, int_n) = (env.ix.tx, env.ix.int_n);
    let mut ints = 0;
    for c in 0..cycles {
        for (i, n) in nodes.iter_mut().enumerate() {
            let v = env.inputs(i, n.outputs()).to_vec();
            n.step(&v).unwrap_or_else(|m| panic!("node {i}: {m}"));
            ints += (n.outputs()[int_n] == 0) as u64;
        }
        env.advance(nodes.iter().map(|n| n.outputs()[tx] != 0));
        if c % 100_000 == 99_999 {
            for (i, n) in nodes.iter_mut().enumerate() {
                n.compare_all().unwrap_or_else(|m| panic!("node {i}: {m}"));
            }
        }
    }
    for (i, n) in nodes.iter_mut().enumerate() {
        n.compare_all().unwrap_or_else(|m| panic!("node {i}: {m}"));
        let h = &env.hosts[i];
        eprintln!("node {i}: {} accesses, IR bits read set (RI TI EI DOI WUI EPI ALI BEI): {:?}", h.reads, h.irq);
        assert!(h.reads > 1000, "node {i}: only {} bus accesses", h.reads);
        for (b, what) in [(0, "receive"), (1, "transmit"), (2, "error warning"), (7, "bus error")] {
            assert!(h.irq[b] > 3, "node {i}: {what} interrupt seen {} times", h.irq[b]);
        }
    }
    ints
}

/// Two controllers, 500 000 clocks each (1 M controller-cycles).
#[test]
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn two_controllers_with_hosts() {
    let ints = net(2, 500_000, 21);
    assert!(ints > 1000, "interrupt line active for only {ints} clocks");
}

/// A model built from a running instance takes over its state (registers, FIFO memory
/// contents, inputs) and continues in lock-step: what switching engines mid-run or
/// starting from a checkpoint needs. Controller 0 runs in both engines, controller 1
/// (compiled only) is its partner on the bus.
#[test]
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn state_transfers_from_a_running_instance() {
    let mut l: Node = Lockstep::new(Sja1000::new(), g::Sja1000::from_instance, g::hdl_set_inputs, g::hdl_outputs).unwrap();
    let mut other = g::Sja1000::new();
    let mut out1 = vec![0u128; other.info().outputs.len()];
    let mut env = SjaNet::new(&l.model, 2, 22);
    let tx = env.ix.tx;
    let mut run = |l: &mut Node, cycles: u64| {
        for _ in 0..cycles {
            let v = env.inputs(0, l.outputs()).to_vec();
            l.step(&v).unwrap_or_else(|m| panic!("{m}"));
            let v = env.inputs(1, &out1).to_vec();
            other.set_inputs(&v);
            other.cycle();
            other.outputs(&mut out1);
            env.advance([l.outputs()[tx] != 0, out1[tx] != 0].into_iter());
        }
    };
    run(&mut l, 150_000);
    let fifo: Vec<u128> = (0..64).map(|a| l.model.mem(0, a)).collect();
    assert!(fifo.iter().any(|&b| b != 0), "the FIFO memory holds received bytes");
    // a fresh model from the running rust-hdl instance
    let mut l2: Node = Lockstep::new(l.hdl, g::Sja1000::from_instance, g::hdl_set_inputs, g::hdl_outputs).unwrap();
    assert_eq!((0..64).map(|a| l2.model.mem(0, a)).collect::<Vec<_>>(), fifo);
    run(&mut l2, 50_000);
    l2.compare_all().unwrap_or_else(|m| panic!("{m}"));
}
