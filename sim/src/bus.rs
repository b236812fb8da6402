//! CAN bus model: wired-AND of every node's TX with per-node delays and
//! per-node receive-path interference.
//!
//! For node `i` named `n` on a bus with prefix `p`, the builder creates
//! these nets:
//!
//! | net              | kind        | meaning |
//! |------------------|-------------|---------|
//! | `p.n.tx`         | driven      | the node's TX (bind it as a component output) |
//! | `p.n.tx_at_bus`  | delay       | TX as it reaches the bus (`tx_dom`, `tx_rec` ps) |
//! | `p.level`        | wired-AND   | the bus level |
//! | `p.n.rx_path`    | delay       | bus level at the node's receiver (`rx_dom`, `rx_rec` ps) |
//! | `p.n.rx`         | fault       | what the node receives, after [`FaultMode`] (bind as input) |

use crate::kernel::Sim;
use crate::net::{FaultMode, NetId};

/// Delays of one node's bus interface in ps.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Default)]
pub struct NodeDelays {
    /// TX → bus for a transition to dominant.
    pub tx_dom: u64,
    /// TX → bus for a transition to recessive.
    pub tx_rec: u64,
    /// Bus → RX for a transition to dominant.
    pub rx_dom: u64,
    /// Bus → RX for a transition to recessive.
    pub rx_rec: u64,
}

impl NodeDelays {
    /// Symmetric delays: `tx` ps from TX to the bus, `rx` ps from the bus to RX.
    pub fn symmetric(tx: u64, rx: u64) -> Self {
        NodeDelays { tx_dom: tx, tx_rec: tx, rx_dom: rx, rx_rec: rx }
    }
}

/// Nets of one node on a [`Bus`].
#[derive(Clone, Debug)]
pub struct BusNode {
    pub name: String,
    /// Driven net: bind as the node's TX output.
    pub tx: NetId,
    /// The node's TX as it reaches the bus.
    pub tx_at_bus: NetId,
    /// Fault net: what the node receives; bind as the node's RX input and
    /// change its [`FaultMode`] with [`Bus::set_interference`].
    pub rx: NetId,
}

/// A built bus.
#[derive(Clone, Debug)]
pub struct Bus {
    /// The bus level (wired-AND).
    pub level: NetId,
    pub nodes: Vec<BusNode>,
}

impl Bus {
    /// Build a bus named `prefix` with one node per `(name, delays)`.
    pub fn build(sim: &mut Sim, prefix: &str, nodes: &[(&str, NodeDelays)]) -> Bus {
        assert!(!nodes.is_empty(), "a bus needs at least one node");
        let mut tx = Vec::new();
        let mut at_bus = Vec::new();
        for (n, d) in nodes {
            let t = sim.driven(&format!("{prefix}.{n}.tx"), true);
            tx.push(t);
            at_bus.push(sim.delay(&format!("{prefix}.{n}.tx_at_bus"), t, d.tx_dom, d.tx_rec));
        }
        let level = sim.wired_and(&format!("{prefix}.level"), &at_bus);
        let mut out = Vec::new();
        for (i, (n, d)) in nodes.iter().enumerate() {
            let path = sim.delay(&format!("{prefix}.{n}.rx_path"), level, d.rx_dom, d.rx_rec);
            let rx = sim.fault(&format!("{prefix}.{n}.rx"), path);
            out.push(BusNode { name: n.to_string(), tx: tx[i], tx_at_bus: at_bus[i], rx });
        }
        Bus { level, nodes: out }
    }

    /// Build a bus with nodes `node0..nodeN-1`, all with the same delays.
    pub fn uniform(sim: &mut Sim, prefix: &str, n: usize, delays: NodeDelays) -> Bus {
        let names: Vec<String> = (0..n).map(|i| format!("node{i}")).collect();
        let spec: Vec<(&str, NodeDelays)> = names.iter().map(|s| (s.as_str(), delays)).collect();
        Self::build(sim, prefix, &spec)
    }

    /// Change node `i`'s receive-path interference now.
    pub fn set_interference(&self, sim: &mut Sim, i: usize, mode: FaultMode) {
        sim.set_fault(self.nodes[i].rx, mode);
    }

    /// Schedule a change of node `i`'s interference at time `t`.
    pub fn schedule_interference(&self, sim: &mut Sim, i: usize, t: u64, mode: FaultMode) {
        sim.schedule_fault(self.nodes[i].rx, t, mode);
    }
}
