//! Legal events of healthy nodes ([`NodeEvent`]), for the fault-free soak (hub.md A1):
//! nothing here is a fault of a node, link or hub, and the hubs must blame nobody.
//!
//! - [`NodeEvent::ErrorPassive`]: the host loads a controller's TEC (>= 128: the
//!   controller is error-passive: passive error flags, suspend transmission).
//! - [`NodeEvent::Overload`]: one controller sees the last EOF bit of a frame dominant
//!   (a one-bit disturbance on its downlink, the only way a controller of this design
//!   starts an overload frame) and sends an overload flag; everybody follows with
//!   overload frames.
//! - [`NodeEvent::PowerCycle`]: a sender node (both controllers and its driver) is
//!   switched off at an arbitrary instant (its uplinks go recessive at once, even in the
//!   middle of a dominant bit or of its own frame) and on again later: the controllers
//!   reset, integrate into the bus (11 recessive bits) and the application sends its
//!   unconfirmed frame again. A late joiner is a node off from the start.

use crate::fault::{CtrlRef, Dir, FaultKind, FaultSpec, FaultStart, FaultTarget, StartField};
use crate::spec::{AppKind, NetworkSpec};
use rand::Rng;
use serde::{Deserialize, Serialize};

/// Delay of an overload event's disturbance after the start of the sender's last EOF bit,
/// in eighths of a bit. A receiver's bit starts lag the sender's by its propagation: about
/// 160 ns behind the same hub and 300 ns behind the other on the reference network, plus
/// its synchroniser. Started with the sender's bit (delay 0, before session 23), the
/// disturbance reached a receiver behind the other hub before the sample point of its
/// *second-to-last* EOF bit (2 TQ before its end), and that receiver sent an error flag in
/// the last EOF bit instead of an overload flag after it: a transient downlink error, not
/// the overload this event stands for (hub.md §5.19). 3/8 of a bit (407 ns) is later than
/// that sample point and earlier than the last bit's sample point by about 300 ns on either
/// side, for every receiver of the reference network.
pub const OVERLOAD_DELAY_EIGHTHS: u64 = 3;

/// One legal event (times in bit times of the network from the start of the run).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum NodeEvent {
    /// Load TEC `tec` (and REC 0) into controller `ctrl` (0 = A, 1 = B) of `node`.
    ErrorPassive { node: usize, ctrl: usize, at_bits: u64, tec: u32 },
    /// Controller `ctrl` of `node` sees the last EOF bit of a frame of node `sender`
    /// (another node: for the transmitter a dominant last EOF bit is a form error)
    /// dominant, once `after_frames` frames were delivered.
    Overload { node: usize, ctrl: usize, sender: usize, after_frames: u32 },
    /// Node `node` is off from `off_bits` to `on_bits` (`off_bits` 0: a late joiner).
    PowerCycle { node: usize, off_bits: u64, on_bits: u64 },
}

impl NodeEvent {
    pub fn describe(&self) -> String {
        match *self {
            NodeEvent::ErrorPassive { node, ctrl, at_bits, tec } => {
                format!("node {node} ctrl {} error-passive (TEC {tec}) at bit {at_bits}", "AB".as_bytes()[ctrl] as char)
            }
            NodeEvent::Overload { node, ctrl, sender, after_frames } => {
                format!("node {node} ctrl {} overload frame (last EOF bit of node {sender}) after {after_frames} frames", "AB".as_bytes()[ctrl] as char)
            }
            NodeEvent::PowerCycle { node, off_bits: 0, on_bits } => format!("node {node} joins late at bit {on_bits}"),
            NodeEvent::PowerCycle { node, off_bits, on_bits } => format!("node {node} off at bit {off_bits}, on at bit {on_bits}"),
        }
    }

    /// The overload event as the one-bit downlink disturbance that causes it: dominant
    /// for one bit from 3/8 of a bit after the sender's last EOF bit starts
    /// ([`OVERLOAD_DELAY_EIGHTHS`]), so that it covers the victim's sample point of its last EOF bit and
    /// not that of the bit before, wherever the victim hangs.
    pub fn as_fault(&self, bit_ps: u64) -> Option<FaultSpec> {
        match *self {
            NodeEvent::Overload { node, ctrl, sender, after_frames } => {
                let delay_ns = (bit_ps * OVERLOAD_DELAY_EIGHTHS / 8) as f64 / 1000.0;
                let start = FaultStart::Field { field: StartField::Eof, bit: 6, of_node: Some(sender), after_frames, delay_ns };
                let c = if ctrl == 0 { CtrlRef::A } else { CtrlRef::B };
                let mut f = FaultSpec::new(FaultTarget::Link { node, ctrl: c, dir: Dir::Down }, FaultKind::Sad, start);
                f.duration_ps = Some(bit_ps);
                Some(f)
            }
            _ => None,
        }
    }
}

/// A random mix of every event kind over a run of about `frames` frames: one
/// error-passive controller, a few overload frames, a late joiner or a power cycle of
/// a sender node.
pub fn random_events(rng: &mut impl Rng, net: &NetworkSpec, frames: u32) -> Vec<NodeEvent> {
    let bits_per_frame = 60u64;
    let span = frames as u64 * bits_per_frame;
    let start = net.driver.start_bits as u64;
    let senders: Vec<usize> =
        net.nodes.iter().enumerate().filter(|(_, n)| matches!(n.app, AppKind::Counter | AppKind::Blinker)).map(|(k, _)| k).collect();
    let nn = net.nodes.len();
    let mut v = vec![NodeEvent::ErrorPassive {
        node: rng.gen_range(0..nn),
        ctrl: rng.gen_range(0..2),
        at_bits: start + rng.gen_range(0..span / 4 + 1),
        tec: rng.gen_range(128..200),
    }];
    for _ in 0..3 {
        let node = rng.gen_range(0..nn);
        let others: Vec<usize> = senders.iter().copied().filter(|&k| k != node).collect();
        if let Some(&sender) = others.get(rng.gen_range(0..others.len().max(1))) {
            v.push(NodeEvent::Overload { node, ctrl: rng.gen_range(0..2), sender, after_frames: rng.gen_range(2..frames.max(3)) });
        }
    }
    if let Some(&k) = senders.get(rng.gen_range(0..senders.len().max(1))) {
        if rng.gen_bool(0.5) {
            v.push(NodeEvent::PowerCycle { node: k, off_bits: 0, on_bits: start + rng.gen_range(50..500) });
        } else {
            let off = start + rng.gen_range(span / 4..span / 2 + 1);
            v.push(NodeEvent::PowerCycle { node: k, off_bits: off, on_bits: off + rng.gen_range(20..400) });
        }
    }
    v
}

/// What [`EventRunner::step`] asks the run to do with a node's driver and application.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PowerChange {
    /// The node went off: freeze its driver, stop its application.
    Off(usize),
    /// The node came on again: a fresh driver, the application sends again.
    On(usize),
}

/// Applies the time-triggered events of a run (error-passive loads, power cycles);
/// overload events run as one-bit faults ([`NodeEvent::as_fault`]).
pub struct EventRunner {
    events: Vec<NodeEvent>,
    done: Vec<(bool, bool)>,
    /// Descriptions of the events applied so far.
    pub applied: Vec<String>,
}

impl EventRunner {
    pub fn new(events: &[NodeEvent]) -> Self {
        EventRunner { events: events.to_vec(), done: vec![(false, false); events.len()], applied: vec![] }
    }

    /// Is node `k` switched off now?
    pub fn is_off(&self, k: usize) -> bool {
        self.events.iter().zip(&self.done).any(|(e, d)| matches!(*e, NodeEvent::PowerCycle { node, .. } if node == k) && d.0 && !d.1)
    }

    /// Apply every event due at `now` (ps) to the controllers of `net`.
    pub fn step(&mut self, now: u64, bit: u64, sim: &mut canstar_sim::Sim, net: &crate::network::Network) -> Vec<PowerChange> {
        let mut out = vec![];
        for (e, d) in self.events.iter().zip(self.done.iter_mut()) {
            match *e {
                NodeEvent::ErrorPassive { node, ctrl, at_bits, tec } if !d.0 && now >= at_bits * bit => {
                    sim.get_mut(net.ctrls[node][ctrl]).load_counters(tec, 0);
                    d.0 = true;
                    self.applied.push(e.describe());
                }
                NodeEvent::PowerCycle { node, off_bits, on_bits } => {
                    if !d.0 && now >= off_bits * bit {
                        for c in 0..2 {
                            sim.get_mut(net.ctrls[node][c]).crash();
                        }
                        d.0 = true;
                        out.push(PowerChange::Off(node));
                    }
                    if d.0 && !d.1 && now >= on_bits * bit {
                        for c in 0..2 {
                            sim.get_mut(net.ctrls[node][c]).power_on();
                        }
                        d.1 = true;
                        out.push(PowerChange::On(node));
                        self.applied.push(e.describe());
                    }
                }
                _ => {}
            }
        }
        out
    }
}
