//! The SJA1000 top (Wishbone register block, RX FIFO memory, acceptance filters,
//! CAN core): compiled model against rust-hdl, every output every cycle, every atom
//! at checkpoints. Two controllers on a wired-AND bus, each with a host running a
//! driver-like register program at random (see `common/sjanet.rs`).

mod common;

use canstar_controller::sja1000::Sja1000;
use canstar_models::generated::sja1000 as g;
use canstar_models::lockstep::Lockstep;
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
