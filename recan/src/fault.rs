//! Fault descriptions ([`FaultSpec`]): where (a controller's uplink or
//! downlink, a sublink, a whole interlink, a whole hub, a controller crash),
//! what (stuck-at-dominant, stuck-at-recessive, bit flips) and when (a time,
//! or a field of a frame on the bus, after some frames).
//!
//! Controller roles (`Tx`, `NonTx`) are resolved when the fault starts, from
//! the node's driver state at that instant.

use serde::{Deserialize, Serialize};

/// Which controller of a node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CtrlRef {
    /// Controller A (on hub 0).
    A,
    /// Controller B (on hub 1).
    B,
    /// The node's tx controller when the fault starts.
    Tx,
    /// The node's non-tx controller when the fault starts.
    NonTx,
}

/// Direction of a controller's link.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Dir {
    /// Controller TX → hub.
    Up,
    /// Hub → controller RX.
    Down,
}

impl Dir {
    /// The name used in class names and files (`up`, `down`).
    pub fn name(self) -> &'static str {
        match self {
            Dir::Up => "up",
            Dir::Down => "down",
        }
    }
}

/// Where a fault is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum FaultTarget {
    /// The uplink or downlink of one controller of node `node`.
    Link { node: usize, ctrl: CtrlRef, dir: Dir },
    /// One sublink of interlink `interlink`, the one leaving hub `from_hub`.
    Sublink { interlink: usize, from_hub: usize },
    /// Both sublinks of interlink `interlink`.
    Interlink { interlink: usize },
    /// A whole hub: its coupled output (every downlink and outgoing sublink).
    Hub { hub: usize },
    /// A controller crash: it stops, reports nothing, its uplink is recessive
    /// (the fault kind is ignored).
    Crash { node: usize, ctrl: CtrlRef },
}

/// What a fault does.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum FaultKind {
    /// Stuck at dominant.
    Sad,
    /// Stuck at recessive.
    Sar,
    /// The signal is inverted while the fault lasts.
    Invert,
    /// One inversion window of `width_ns` every `every_bits` bit times,
    /// starting `offset_ns` after the fault start (a flipped bit every so often).
    BitFlip { every_bits: f64, width_ns: f64, offset_ns: f64 },
    /// The signal forced to one level for `width_ns` every `every_bits` bit times,
    /// starting `offset_ns` after the fault start: `dominant` flips recessive bits to
    /// dominant only, otherwise dominant bits to recessive only.
    Force { every_bits: f64, width_ns: f64, offset_ns: f64, dominant: bool },
    /// Bursts: every `every_bits` bit times, `flips` inversion windows of random width
    /// (0.1 to 1 bit time) at random instants within `len_bits` bit times, drawn from
    /// `seed`.
    Burst { every_bits: f64, len_bits: f64, flips: u32, seed: u64 },
}

/// Schedule the windows of a pattern fault (`BitFlip`, `Force`, `Burst`) on `id` from
/// `start` to `stop` (ps; `bit` = one bit time in ps). Returns false for the other
/// kinds (a level held from the start), which the caller schedules itself.
pub(crate) fn schedule_pattern(sim: &mut canstar_sim::Sim, id: canstar_sim::NetId, kind: FaultKind, start: u64, stop: u64, bit: u64) -> bool {
    use rand::{Rng, SeedableRng};
    let ps = |ns: f64| (ns * 1000.0).round() as u64;
    match kind {
        FaultKind::BitFlip { every_bits, width_ns, offset_ns } => {
            let every = ((every_bits * bit as f64).round() as u64).max(1);
            let s = start + ps(offset_ns);
            let count = ((stop.max(s) - s) / every + 1) as usize;
            sim.add_flip_pattern(id, s, ps(width_ns).max(1), every, count);
        }
        FaultKind::Force { every_bits, width_ns, offset_ns, dominant } => {
            let every = ((every_bits * bit as f64).round() as u64).max(1);
            let width = ps(width_ns).clamp(1, every.saturating_sub(1).max(1));
            let mode = if dominant { canstar_sim::FaultMode::StuckDominant } else { canstar_sim::FaultMode::StuckRecessive };
            let mut t = start + ps(offset_ns);
            while t <= stop {
                sim.schedule_fault(id, t, mode);
                sim.schedule_fault(id, t + width, canstar_sim::FaultMode::None);
                t += every;
            }
        }
        FaultKind::Burst { every_bits, len_bits, flips, seed } => {
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
            let every = ((every_bits * bit as f64).round() as u64).max(1);
            let len = ((len_bits * bit as f64).round() as u64).max(1);
            let mut t = start;
            while t <= stop {
                for _ in 0..flips {
                    let at = t + rng.gen_range(0..len);
                    let w = rng.gen_range(bit / 10..=bit).max(1);
                    sim.add_flip_window(id, at, at + w);
                }
                t += every;
            }
        }
        _ => return false,
    }
    true
}

/// A frame field at which a fault may start (observed on the bus through
/// the controller that transmits the frame).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StartField {
    Sof,
    Ident,
    Dlc,
    /// The first data bit.
    Data,
    Crc,
    AckSlot,
    /// The first EOF bit.
    Eof,
    /// The first intermission bit.
    Inter,
}

/// When a fault starts.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum FaultStart {
    /// At an absolute time (ps).
    At { t_ps: u64 },
    /// At the start of bit `bit` (0-based) of field `field` of a frame sent by
    /// node `of_node` (any node if None), once at least `after_frames` frames
    /// were delivered (successful transmissions of any node), plus `delay_ns`.
    Field { field: StartField, bit: u32, of_node: Option<usize>, after_frames: u32, delay_ns: f64 },
}

/// One fault.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FaultSpec {
    pub target: FaultTarget,
    pub kind: FaultKind,
    pub start: FaultStart,
    /// How long it lasts in ps (None = permanent).
    #[serde(default)]
    pub duration_ps: Option<u64>,
}

impl FaultSpec {
    /// A permanent fault.
    pub fn new(target: FaultTarget, kind: FaultKind, start: FaultStart) -> Self {
        FaultSpec { target, kind, start, duration_ps: None }
    }
    /// Start at the first bit of `field` of any frame after `after_frames` frames.
    pub fn at_field(field: StartField, after_frames: u32) -> FaultStart {
        FaultStart::Field { field, bit: 0, of_node: None, after_frames, delay_ns: 0.0 }
    }
    /// Does this fault affect the node's own links (makes its controller unhealthy)?
    pub fn faulty_ctrl(&self) -> Option<(usize, CtrlRef)> {
        match self.target {
            FaultTarget::Link { node, ctrl, .. } | FaultTarget::Crash { node, ctrl } => Some((node, ctrl)),
            _ => None,
        }
    }
}
