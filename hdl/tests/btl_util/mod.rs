//! The bit timing RTL and its clock-exact model side by side, shared by the btl tests.
#![allow(dead_code, unused_imports)]

pub use canstar_hdl::btl::{BitTiming, BtlConfig, BtlCycleModel, BtlInputs, BtlModel, BtlPins, IPT_CLOCKS};
pub use canstar_hdl::{drive, flow};
pub use rand::{Rng, SeedableRng};
pub use rand_chacha::ChaCha8Rng;

pub const R: bool = true;
pub const D: bool = false;

/// What an edge does to the bit it falls in (can-protocol.md §3.3), the expected value of the
/// synchronisation tests (btl_cases.rs, btl_iso.rs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Outcome {
    /// No change of the bit.
    Nothing,
    /// The edge's TQ becomes SYNC_SEG.
    Restart,
    /// PH1 lengthened by this many TQ.
    Ph1Plus(u32),
    /// PH2 shortened by this many TQ.
    Ph2Minus(u32),
}

/// The RTL and the clock-exact model side by side; every step compares all
/// outputs. `rtl = None` runs the model alone.
pub struct Rig {
    pub rtl: Option<BitTiming>,
    pub model: BtlCycleModel,
    pub trace: Vec<BtlPins>,
}

impl Rig {
    pub fn new(with_rtl: bool) -> Self {
        let rtl = with_rtl.then(|| {
            let mut u = BitTiming::default();
            drive::init(&mut u);
            u
        });
        Self { rtl, model: BtlCycleModel::new(), trace: Vec::new() }
    }

    /// One clock; returns the outputs seen on it (before the rising edge).
    pub fn step(&mut self, i: &BtlInputs) -> BtlPins {
        let m = self.model.step(i);
        if let Some(u) = self.rtl.as_mut() {
            u.set_inputs(i);
            drive::settle(u);
            let p = u.pins();
            assert_eq!(p, m, "cycle {}: RTL (left) differs from BtlCycleModel (right), inputs {:?}", self.trace.len(), i);
            drive::rising_edge(u);
            drive::falling_edge(u);
        }
        self.trace.push(m);
        m
    }

    pub fn reset(&mut self, cfg: &BtlConfig) {
        let mut i = BtlInputs::with_config(cfg);
        i.reset = true;
        self.step(&i);
        self.step(&i);
    }

    /// Registered `sample` and `tx` of the current clock, before its inputs
    /// are set (what a bit-stream logic sees). Needs the RTL.
    pub fn registered(&self) -> (bool, bool) {
        let u = self.rtl.as_ref().expect("registered() needs the RTL");
        (u.sample.val(), u.tx.val())
    }
}

