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

/// (hs_en, drive) of a situation of the Bosch btl program: 'a' hard sync
/// driving R, 'b' (and 'e') resync driving R (receiver), 'd' (and 'c') resync
/// driving D (transmitter), 'f' hard sync driving D (own SOF).
pub fn situation(case: char) -> (bool, bool) {
    match case {
        'a' => (true, R),
        'b' | 'e' => (false, R),
        'c' | 'd' => (false, D),
        'f' => (true, D),
        _ => panic!("case {case}"),
    }
}

/// Expected ticks, counted from the bit start (transmit point) of the bit
/// that holds the edge.
#[derive(Debug)]
pub struct Expect {
    pub samples: Vec<u32>,
    pub bit_starts: Vec<u32>,
    /// Tick of the transmit point that takes the new drive level.
    pub tx_tick: u32,
    pub horizon: u32,
}

/// The ticks `outcome` gives for an edge in TQ j (can-protocol.md §3.3-§3.6):
/// a transmit point is never less than IPT = `cfg.ipt()` TQ after the latest
/// sample point (§2.5).
pub fn expect(cfg: &BtlConfig, outcome: Outcome, j: u32) -> Expect {
    let (sp, ntq, ipt) = (cfg.sp(), cfg.ntq(), cfg.ipt());
    // (samples inside the edge bit, first transmit point, origin (cnt = 0) of the next bit)
    let (mut samples, tx_tick, origin) = match outcome {
        Outcome::Nothing => (vec![sp], ntq, ntq),
        Outcome::Ph1Plus(d) => (vec![sp + d], ntq + d, ntq + d),
        Outcome::Ph2Minus(s) => (vec![sp], (ntq - s).max(sp + ipt), ntq - s),
        // the edge's TQ (index j) becomes SYNC_SEG: cnt = 0 at tick j
        Outcome::Restart if j >= sp => (vec![sp], (j + 1).max(sp + ipt), j),
        Outcome::Restart => (vec![], j + 1, j),
    };
    let horizon = origin + 2 * ntq;
    let mut bit_starts = vec![0, tx_tick];
    for k in 0..=2 {
        if k > 0 {
            bit_starts.push(origin + k * ntq);
        }
        if origin + k * ntq + sp <= horizon {
            samples.push(origin + k * ntq + sp);
        }
    }
    samples.sort();
    samples.dedup();
    Expect { samples, bit_starts, tx_tick, horizon }
}

/// One edge in TQ j (at a random clock inside it) after two recessive bits,
/// in situation `case`, on the rig (the RTL when `with_rtl`, and the model,
/// compared on every clock): the sample points, transmit points, the one
/// synchronisation strobe and TX must be those of [`expect`] for `outcome`.
/// Returns the expectation (for checks of its own by the caller).
pub fn check_edge(cfg: &BtlConfig, case: char, j: u32, outcome: Outcome, with_rtl: bool, rng: &mut ChaCha8Rng, tag: &str) -> Expect {
    let exp = expect(cfg, outcome, j);
    let (hs_en, level) = situation(case);
    let (ntq, b) = (cfg.ntq(), cfg.brp as usize);
    let mut rig = Rig::new(with_rtl);
    rig.reset(cfg);
    // Two bits with a recessive bus: the last sample is R, sync enabled.
    // TX carries the opposite of `level` in the edge bit, so that the
    // transmit point that takes `level` is visible on TX.
    let mut i = BtlInputs::with_config(cfg);
    i.hs_en = hs_en;
    i.drive = !level;
    let mut starts = 0;
    let c0 = loop {
        let p = rig.step(&i);
        if p.bit_start {
            starts += 1;
            if starts == 2 {
                break rig.trace.len() - 1;
            }
        }
        assert!(rig.trace.len() < 3 * ntq as usize * b + 10, "{tag}: no bit start");
    };
    let c_edge = c0 + j as usize * b + rng.gen_range(1..=b);
    let end = c0 + exp.horizon as usize * b + 2;
    i.drive = level;
    while rig.trace.len() < end {
        i.rx = rig.trace.len() < c_edge;
        rig.step(&i);
    }
    let tr = &rig.trace;
    let tick_of = |c: usize, what: &str| -> u32 {
        assert_eq!((c - c0) % b, 0, "{tag}: {what} at cycle {c} is not on the TQ grid (bit start at {c0})");
        ((c - c0) / b) as u32
    };
    let (mut samples, mut starts, mut syncs) = (vec![], vec![], vec![]);
    for (c, p) in tr.iter().enumerate().skip(c0) {
        if p.bit_start {
            starts.push(tick_of(c, "bit_start"));
            assert!(p.tq, "{tag}: bit_start without tq at cycle {c}");
        }
        if c > c0 && p.sample {
            let k = tick_of(c - 1, "sample");
            samples.push(k);
            let want = if k > j { D } else { R };
            assert_eq!(p.busmon, want, "{tag}: sampled level at tick {k}");
        }
        if c > c0 && (p.hard_sync || p.resync) {
            syncs.push((tick_of(c - 1, "sync"), p.hard_sync, p.resync));
        }
    }
    samples.retain(|&k| k <= exp.horizon);
    starts.retain(|&k| k <= exp.horizon);
    assert_eq!(samples, exp.samples, "{tag}: sample points (ticks from the bit start)");
    assert_eq!(starts, exp.bit_starts, "{tag}: transmit points (ticks from the bit start)");
    assert_eq!(syncs, vec![(j + 1, hs_en, !hs_en)], "{tag}: synchronisation strobes (tick, hard, resync)");
    // TX: the old level up to the transmit point, the new one from the next clock.
    let tx_change = c0 + exp.tx_tick as usize * b + 1;
    for (c, p) in tr.iter().enumerate().skip(c0 + 1) {
        let want = if c >= tx_change { level } else { !level };
        assert_eq!(p.tx, want, "{tag}: TX at cycle {c} (tick {}); expected change at tick {}", (c - c0) / b, exp.tx_tick);
    }
    exp
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

