//! The catalogue of scenario classes (recancentrate.md §4–6).
//!
//! | names | what |
//! |---|---|
//! | `pub01`..`pub21` | the 21 published single-fault scenarios, pass criteria = the recorded outcome |
//! | `flip-{blinker,receiver}-{tx,nontx}-{up,down}-r{1,10,100}` | bit-flipping on one link from a random instant on, each bit inverted with probability r/1000 |
//! | `sublink-{sad,sar,flip}` | one sublink (random interlink and direction) stuck or flipping |
//! | `interlink-{sad,sar,flip}` | both sublinks of one interlink |
//! | `hub-{sad,sar,flip}` | a whole hub's output (its ANDC) stuck or flipping on every downlink and sublink it drives |
//! | `crash-{counter,blinker,receiver}-{tx,nontx}` | a controller stops at a random instant (its uplink goes recessive) |
//! | `double-*` | two faults, the second `--double-delay-bits` after the first |
//! | `eof-{last,penult}-*` | a one-bit disturbance at the last / penultimate EOF bit seen by a subset of controllers |
//! | `sweep-{up,down,sublink,interlink,hub}-{flip,d2r,r2d,g2,g6,g10,burst}-e{2,10,100,1000,10000}` | one disturbance every N bit times at one injection point: flips of 0.3-1.2 bits, recessive-to-dominant or dominant-to-recessive only, glitches of 2/6/10 hub clocks, or bursts of 8 random flips within 20 bits (N >= 100) ([`super::sweep`]) |
//!
//! Every class except the published ones is judged by the generic criteria of §5/§6:
//! no frame of a node that keeps a fault-free controller path is lost at the
//! Receiver, no healthy controller reaches 96, the faulty path is isolated where a hub
//! can see it (stuck-dominant uplinks and sublinks), no healthy path is isolated (in
//! particular the hubs never isolate each other's fault-free sublinks), and no healthy
//! controller is quarantined. The faulty path itself may always be isolated.

use crate::fault::Dir;
use serde::{Deserialize, Serialize};

/// Default delay between the two faults of the `double-*` classes, in bit times.
pub const DEFAULT_DOUBLE_DELAY_BITS: u32 = 400;

/// A node of the reference system.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Node {
    /// 3BitCounter (node 0): transmits, never faulty in the published scenarios.
    Counter,
    /// Blinker (node 1): transmits.
    Blinker,
    /// Receiver (node 2): receives both streams and checks their sequence.
    Receiver,
}

impl Node {
    pub const ALL: [Node; 3] = [Node::Counter, Node::Blinker, Node::Receiver];
    pub fn index(self) -> usize {
        self as usize
    }
    pub fn name(self) -> &'static str {
        ["counter", "blinker", "receiver"][self as usize]
    }
}

/// The node's controller by role at the start of the run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Role {
    Tx,
    NonTx,
}

impl Role {
    pub fn name(self) -> &'static str {
        match self {
            Role::Tx => "tx",
            Role::NonTx => "nontx",
        }
    }
}

/// Permanent fault kinds of links and hubs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Fault {
    /// Stuck at dominant.
    Sad,
    /// Stuck at recessive.
    Sar,
    /// Every bit inverted with probability `FLIP_RATE_PERMILLE`/1000.
    Flip,
}

impl Fault {
    pub const ALL: [Fault; 3] = [Fault::Sad, Fault::Sar, Fault::Flip];
    pub fn name(self) -> &'static str {
        match self {
            Fault::Sad => "sad",
            Fault::Sar => "sar",
            Fault::Flip => "flip",
        }
    }
}

/// Flip rate of the `flip` link / hub faults, per 1000 bits.
pub const FLIP_RATE_PERMILLE: u32 = 20;

/// Which EOF bit a disturbance hits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum EofBit {
    /// Bit 7 of EOF: a receiver has accepted the frame, the transmitter has not.
    Last,
    /// Bit 6 of EOF: receivers that see it reject the frame; their error flag reaches
    /// the others at the last bit.
    Penultimate,
}

/// Which controllers see the one-bit disturbance (on their downlinks).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum EofSubset {
    /// The Receiver's tx controller only.
    ReceiverOne,
    /// Both Receiver controllers.
    ReceiverBoth,
    /// The transmitting node's (Blinker's) tx controller only.
    TransmitterTx,
    /// The transmitting node's non-tx controller only.
    TransmitterNonTx,
    /// Every controller except the transmitting node's tx controller.
    AllButTransmitter,
    /// The transmitting node's tx controller, which then crashes before it can
    /// retransmit (the classic inconsistent omission).
    TransmitterTxThenCrash,
    /// Both Receiver controllers, and the transmitting node's tx controller crashes
    /// before it can retransmit (omission at the Receiver unless the node model
    /// re-sends on the other controller).
    ReceiverBothThenCrash,
}

impl EofSubset {
    pub const ALL: [EofSubset; 7] = [
        EofSubset::ReceiverOne,
        EofSubset::ReceiverBoth,
        EofSubset::TransmitterTx,
        EofSubset::TransmitterNonTx,
        EofSubset::AllButTransmitter,
        EofSubset::TransmitterTxThenCrash,
        EofSubset::ReceiverBothThenCrash,
    ];
    pub fn name(self) -> &'static str {
        match self {
            EofSubset::ReceiverOne => "rx1",
            EofSubset::ReceiverBoth => "rx2",
            EofSubset::TransmitterTx => "tx",
            EofSubset::TransmitterNonTx => "nontx",
            EofSubset::AllButTransmitter => "others",
            EofSubset::TransmitterTxThenCrash => "tx-crash",
            EofSubset::ReceiverBothThenCrash => "rx2-crash",
        }
    }
}

/// The double-fault combinations.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Double {
    /// Blinker tx uplink SAD, then Receiver non-tx downlink SAR (two nodes, one
    /// controller each: fully tolerated).
    TwoNodes,
    /// Blinker tx uplink SAD, then Blinker non-tx uplink SAD: Blinker loses both paths
    /// (its frames may be lost; the others' must not be).
    BlinkerBoth,
    /// Blinker tx downlink SAR, then its non-tx downlink SAR.
    BlinkerDeaf,
    /// Interlink 0 SAD, then interlink 1 SAD (the hubs end up disconnected).
    Interlinks,
    /// Two random single-point faults (node, controller, direction, kind drawn from the seed).
    Random,
}

impl Double {
    pub const ALL: [Double; 5] = [Double::TwoNodes, Double::BlinkerBoth, Double::BlinkerDeaf, Double::Interlinks, Double::Random];
    pub fn name(self) -> &'static str {
        match self {
            Double::TwoNodes => "two-nodes",
            Double::BlinkerBoth => "blinker-both",
            Double::BlinkerDeaf => "blinker-deaf",
            Double::Interlinks => "interlinks",
            Double::Random => "random",
        }
    }
}

/// What a class injects.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum ClassKind {
    /// Published scenario 1..=21.
    Published(u8),
    /// Bit flipping on one node link at `rate` flips per 1000 bits.
    BitFlip { node: Node, role: Role, dir: Dir, rate: u32 },
    Sublink(Fault),
    Interlink(Fault),
    Hub(Fault),
    Crash { node: Node, role: Role },
    Double(Double),
    Eof { bit: EofBit, subset: EofSubset },
    /// One disturbance of `shape` every `every` bit times at `point`.
    Sweep { point: Point, shape: Shape, every: u32 },
}

/// Injection points of the sweep classes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Point {
    /// A random node's (Blinker or Receiver) random controller's uplink.
    Up,
    /// Its downlink.
    Down,
    /// One sublink (random interlink and direction).
    Sublink,
    /// Both sublinks of one interlink.
    Interlink,
    /// A whole hub's output.
    Hub,
}

impl Point {
    pub const ALL: [Point; 5] = [Point::Up, Point::Down, Point::Sublink, Point::Interlink, Point::Hub];
    pub fn name(self) -> &'static str {
        ["up", "down", "sublink", "interlink", "hub"][self as usize]
    }
}

/// Disturbance shapes of the sweep classes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Shape {
    /// Inversion of 0.3 to 1.2 bit times.
    Flip,
    /// Forced recessive for 0.3 to 1.2 bit times (dominant-to-recessive flips only).
    D2r,
    /// Forced dominant (recessive-to-dominant flips only).
    R2d,
    /// Inversion of this many hub clocks (a sub-bit glitch).
    Glitch(u32),
    /// 8 inversions of 0.1 to 1 bit time within 20 bit times.
    Burst,
}

impl Shape {
    pub const ALL: [Shape; 7] = [Shape::Flip, Shape::D2r, Shape::R2d, Shape::Glitch(2), Shape::Glitch(6), Shape::Glitch(10), Shape::Burst];
    pub fn name(self) -> String {
        match self {
            Shape::Flip => "flip".into(),
            Shape::D2r => "d2r".into(),
            Shape::R2d => "r2d".into(),
            Shape::Glitch(w) => format!("g{w}"),
            Shape::Burst => "burst".into(),
        }
    }
}

/// Disturbance intervals of the sweep classes, in bit times.
pub const SWEEP_EVERY: [u32; 5] = [2, 10, 100, 1000, 10000];

/// A named scenario class.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Class {
    pub name: String,
    pub kind: ClassKind,
}

/// Flip rates of the `flip-*` classes, per 1000 bits.
pub const FLIP_RATES: [u32; 3] = [1, 10, 100];

/// Every class, in report order.
pub fn catalogue() -> Vec<Class> {
    let mut v = vec![];
    let mut add = |name: String, kind| v.push(Class { name, kind });
    for n in 1..=21u8 {
        add(format!("pub{n:02}"), ClassKind::Published(n));
    }
    for node in [Node::Blinker, Node::Receiver] {
        for role in [Role::Tx, Role::NonTx] {
            for dir in [Dir::Up, Dir::Down] {
                for rate in FLIP_RATES {
                    add(
                        format!("flip-{}-{}-{}-r{rate}", node.name(), role.name(), dir.name()),
                        ClassKind::BitFlip { node, role, dir, rate },
                    );
                }
            }
        }
    }
    for f in Fault::ALL {
        add(format!("sublink-{}", f.name()), ClassKind::Sublink(f));
    }
    for f in Fault::ALL {
        add(format!("interlink-{}", f.name()), ClassKind::Interlink(f));
    }
    for f in Fault::ALL {
        add(format!("hub-{}", f.name()), ClassKind::Hub(f));
    }
    for node in Node::ALL {
        for role in [Role::Tx, Role::NonTx] {
            add(format!("crash-{}-{}", node.name(), role.name()), ClassKind::Crash { node, role });
        }
    }
    for d in Double::ALL {
        add(format!("double-{}", d.name()), ClassKind::Double(d));
    }
    for (bit, bn) in [(EofBit::Last, "last"), (EofBit::Penultimate, "penult")] {
        for subset in EofSubset::ALL {
            add(format!("eof-{bn}-{}", subset.name()), ClassKind::Eof { bit, subset });
        }
    }
    for point in Point::ALL {
        for shape in Shape::ALL {
            for every in SWEEP_EVERY {
                // a burst lasts 20 bit times: only at intervals of 100 and more
                if shape != Shape::Burst || every >= 100 {
                    add(format!("sweep-{}-{}-e{every}", point.name(), shape.name()), ClassKind::Sweep { point, shape, every });
                }
            }
        }
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique() {
        let c = catalogue();
        let mut n: Vec<&str> = c.iter().map(|c| c.name.as_str()).collect();
        n.sort();
        n.dedup();
        assert_eq!(n.len(), c.len());
        assert_eq!(c.iter().filter(|c| c.name.starts_with("pub")).count(), 21);
    }
}
