//! [`GoldenBus`]: ideal bit-level bus of golden nodes (no timing; can-protocol.md).

use super::{trace, BitLabel, Field, GoldenNode, Role, StepOut};

/// Per-node receive-path override (§1.2, the reference BUS_INTERFERENCE modes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RxOverride {
    #[default]
    None,
    Invert,
    StuckRecessive,
    StuckDominant,
}

impl RxOverride {
    /// The level a node reads for bus level `bus`.
    pub fn apply(self, bus: bool) -> bool {
        match self {
            RxOverride::None => bus,
            RxOverride::Invert => !bus,
            RxOverride::StuckRecessive => true,
            RxOverride::StuckDominant => false,
        }
    }
}

/// Wired-AND bus of [`GoldenNode`]s, one step per bit. Every node samples the AND of all
/// drives, through its [`RxOverride`] (which a test may change before any bit). Keeps every
/// node's [`StepOut`] history and, optionally, §18 trace lines.
#[derive(Clone, Debug)]
pub struct GoldenBus {
    pub nodes: Vec<GoldenNode>,
    pub overrides: Vec<RxOverride>,
    /// Number of bits run so far.
    pub bit: u64,
    /// Nominal bit time and sample-point offset for trace time stamps (ns).
    pub bit_ns: u64,
    pub sp_ns: u64,
    /// `history[n][b]`: node n's result of bit b.
    pub history: Vec<Vec<StepOut>>,
    /// Trace lines, if enabled with [`GoldenBus::enable_trace`].
    pub trace: Option<Vec<String>>,
}

impl GoldenBus {
    /// `n` default-configured nodes, just out of reset. Bit time 1 µs, sample point at 600 ns.
    pub fn new(n: usize) -> Self {
        Self::with_nodes((0..n).map(|_| GoldenNode::default()).collect())
    }
    pub fn with_nodes(nodes: Vec<GoldenNode>) -> Self {
        let n = nodes.len();
        GoldenBus {
            nodes,
            overrides: vec![RxOverride::None; n],
            bit: 0,
            bit_ns: 1000,
            sp_ns: 600,
            history: vec![Vec::new(); n],
            trace: None,
        }
    }
    pub fn enable_trace(&mut self) {
        self.trace = Some(vec![trace::HEADER.to_string()]);
    }
    /// Wired-AND of the current drives.
    pub fn bus_level(&self) -> bool {
        self.nodes.iter().all(|n| n.drive())
    }
    /// Run one bit; returns each node's result.
    pub fn step(&mut self) -> Vec<StepOut> {
        let bus = self.bus_level();
        let t = self.bit * self.bit_ns + self.sp_ns;
        let mut outs = Vec::with_capacity(self.nodes.len());
        for (i, node) in self.nodes.iter_mut().enumerate() {
            let o = node.step(self.overrides[i].apply(bus));
            if let Some(tr) = &mut self.trace {
                tr.extend(trace::step_lines(t, &format!("G{}", i + 1), &o));
            }
            self.history[i].push(o.clone());
            outs.push(o);
        }
        self.bit += 1;
        outs
    }
    /// Run `n` bits.
    pub fn run(&mut self, n: u64) {
        for _ in 0..n {
            self.step();
        }
    }
    /// Step until `pred` holds for the results of a bit; returns that bit's results, or
    /// `None` after `max` bits.
    pub fn run_until(&mut self, max: u64, mut pred: impl FnMut(&[StepOut]) -> bool) -> Option<Vec<StepOut>> {
        for _ in 0..max {
            let o = self.step();
            if pred(&o) {
                return Some(o);
            }
        }
        None
    }
    /// Step until node `n`'s *current* bit (the next one to be processed) has the given
    /// label (role `None` matches any role, `pos` 0 matches any position; stuff bits only
    /// match when `stuff` is set). Returns false after `max` bits.
    pub fn run_to(&mut self, n: usize, role: Role, field: Field, pos: u32, stuff: bool, max: u64) -> bool {
        for _ in 0..max {
            let l: BitLabel = self.nodes[n].label();
            if (role == Role::None || l.role == role) && l.field == field && (pos == 0 || l.pos == pos) && l.stuff == stuff {
                return true;
            }
            self.step();
        }
        false
    }
    /// Run until every node has integrated and all are in Bus_Idle with nothing to do.
    pub fn run_to_idle(&mut self, max: u64) -> bool {
        for _ in 0..max {
            if self.nodes.iter().all(|n| n.label().field == Field::BusIdle) {
                return true;
            }
            self.step();
        }
        false
    }
    /// Apply `o` to node `n` for the next `bits` bits, then restore `None`; returns the results.
    pub fn force(&mut self, n: usize, o: RxOverride, bits: u64) -> Vec<Vec<StepOut>> {
        self.overrides[n] = o;
        let r = (0..bits).map(|_| self.step()).collect();
        self.overrides[n] = RxOverride::None;
        r
    }
    /// Node `n`'s results from bit `from` on.
    pub fn since(&self, n: usize, from: u64) -> &[StepOut] {
        &self.history[n][from as usize..]
    }
}
