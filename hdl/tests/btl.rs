//! Tests of the bit timing logic (`canstar_hdl::btl`, can-protocol.md §2 and §3) beyond the conformance
//! tables (those are `btl_cases.rs`):
//!
//! - Properties (one synchronisation per sample interval, none after a `D`
//!   sample), triple sampling, reset and configuration errors.
//! - Randomised cycle-by-cycle comparison of the RTL with `BtlCycleModel`.
//! - `btl_verilog_flow`: lint, synthesis and co-simulation of the Verilog.

mod btl_util;
use btl_util::*;

/// Drives the BTL the way the bit-stream logic and a bus would: another
/// node's bit stream with random edge jitter and short spikes, the own TX
/// looped back (wired-AND), `drive` changed on the clock after `sample`,
/// `hs_en` switched at sample points, and random configuration changes under
/// reset (including invalid ones).
struct Stim {
    cfg: BtlConfig,
    reset_left: u32,
    reset_rate: f64,
    bus: bool,
    bus_left: i64,
    other_silent: bool,
    spike_left: u32,
    drive: bool,
    new_drive: Option<bool>,
    hs_en: bool,
    transmitter: bool,
}

impl Stim {
    fn new(cfg: BtlConfig, reset_rate: f64) -> Self {
        Self {
            cfg,
            reset_left: 3,
            reset_rate,
            bus: R,
            bus_left: 0,
            other_silent: false,
            spike_left: 0,
            drive: R,
            new_drive: None,
            hs_en: true,
            transmitter: false,
        }
    }

    fn random_config(rng: &mut ChaCha8Rng) -> BtlConfig {
        let brp = [1, 1, 1, 1, 2, 2, 3, 4, 5, 8, 32, 33, 128][rng.gen_range(0..13)];
        let mut cfg = match rng.gen_range(0..10) {
            0 => BtlConfig::T10_6_4,
            1 => BtlConfig::T25_17_1,
            2 => BtlConfig::T10_8_1,
            3 => BtlConfig::T10_6_2,
            // Anything, valid or not (PH2 from the field, so also PH2 = 1 and
            // PH2 != PH1; PH2 = 1 is refused with BRP 1).
            4 => BtlConfig::from_fields(
                0,
                rng.gen_range(0..16),
                rng.gen_range(0..8),
                rng.gen_range(0..8),
                rng.gen_range(0..4),
                false,
            ),
            _ => loop {
                let c = BtlConfig::from_fields(
                    0,
                    rng.gen_range(0..16),
                    rng.gen_range(0..8),
                    rng.gen_range(0..8),
                    rng.gen_range(0..4),
                    false,
                )
                .with_brp(brp);
                if c.is_valid() {
                    break c;
                }
            },
        }
        .with_brp(brp);
        cfg.triple = rng.gen_bool(0.2);
        cfg
    }

    /// Inputs for the next clock, given the registered `sample` and `tx` of this clock.
    fn next(&mut self, rng: &mut ChaCha8Rng, sample: bool, tx: bool) -> BtlInputs {
        let mut i = BtlInputs::with_config(&self.cfg);
        if self.reset_left == 0 && rng.gen_bool(self.reset_rate) {
            self.reset_left = rng.gen_range(1..5);
            self.cfg = Self::random_config(rng);
        }
        if self.reset_left > 0 {
            self.reset_left -= 1;
            i = BtlInputs::with_config(&self.cfg);
            if self.reset_left > 0 {
                // Fields may wander while reset is held; the last value counts.
                i.brp = rng.gen_range(0..32);
                i.prop = rng.gen_range(0..8);
                i.ph1 = rng.gen_range(0..8);
                i.ph2 = rng.gen_range(0..8);
                i.sjw = rng.gen_range(0..4);
            }
            i.reset = true;
            self.drive = R;
            self.new_drive = None;
            i.rx = rng.gen_bool(0.8);
            return i;
        }
        // The other node: bits of nominal length with jitter.
        let bit = (self.cfg.ntq() * self.cfg.brp) as i64;
        self.bus_left -= 1;
        if self.bus_left <= 0 {
            if rng.gen_bool(0.02) {
                self.other_silent = !self.other_silent;
            }
            self.bus = if self.other_silent { R } else if rng.gen_bool(0.5) { self.bus } else { !self.bus };
            let jitter = match rng.gen_range(0..10) {
                0..=5 => 0,
                6..=7 => rng.gen_range(-2..=2) * self.cfg.brp as i64,
                _ => rng.gen_range(-bit / 3..=bit / 3),
            };
            self.bus_left = (bit + jitter).max(1);
        }
        if self.spike_left > 0 {
            self.spike_left -= 1;
        } else if rng.gen_bool(0.002) {
            self.spike_left = rng.gen_range(1..=2 * self.cfg.brp);
        }
        i.rx = self.bus & tx & (self.spike_left == 0);
        // The bit-stream logic: latch on `sample`, new drive on the next clock.
        if let Some(d) = self.new_drive.take() {
            self.drive = d;
        }
        if sample {
            if rng.gen_bool(0.05) {
                self.transmitter = !self.transmitter;
            }
            if rng.gen_bool(0.08) {
                self.hs_en = !self.hs_en;
            }
            let d = if self.transmitter { rng.gen_bool(0.5) } else { !rng.gen_bool(0.1) };
            self.new_drive = Some(d);
        }
        i.drive = self.drive;
        i.hs_en = self.hs_en;
        i
    }
}

/// Which situations of §2–3 a random run reached.
#[derive(Default, Debug)]
struct Coverage {
    restart_hard: usize,
    hard_no_restart: usize,
    lengthen: usize,
    shorten: usize,
    shorten_ends_bit: usize,
    restart_resync: usize,
    postponed: usize,
    e_zero: usize,
    triple_samples: usize,
}

impl Coverage {
    fn add(&mut self, cm: &BtlCycleModel) {
        let (Some(ev), Some(m)) = (cm.last_events(), cm.model()) else { return };
        if ev.sample && m.config().triple {
            self.triple_samples += 1;
        }
        if ev.postponed {
            self.postponed += 1;
        }
        let Some(e) = ev.phase_error else { return };
        if ev.hard_sync {
            if ev.restart {
                self.restart_hard += 1;
            } else {
                self.hard_no_restart += 1;
            }
        } else if ev.restart {
            self.restart_resync += 1;
        } else if e == 0 {
            self.e_zero += 1;
        } else if e > 0 && m.sp != m.config().sp() {
            self.lengthen += 1;
        } else if e < 0 {
            self.shorten += 1;
            if ev.bit_end {
                self.shorten_ends_bit += 1;
            }
        }
    }

    fn assert_reached(&self, seed: u64) {
        let c = self;
        for (name, n) in [
            ("hard restart", c.restart_hard),
            ("PH2 shortened to the current tick", c.shorten_ends_bit),
            ("hard sync without restart", c.hard_no_restart),
            ("PH1 lengthened", c.lengthen),
            ("PH2 shortened", c.shorten),
            ("resync restart", c.restart_resync),
            ("postponed transmit point", c.postponed),
            ("edge in SYNC_SEG", c.e_zero),
        ] {
            assert!(n > 0, "seed {seed}: random stimulus never reached: {name} ({c:?})");
        }
    }
}

fn run_random(rig: &mut Rig, stim: &mut Stim, rng: &mut ChaCha8Rng, cycles: usize) {
    for _ in 0..cycles {
        let (sample, tx) = rig.registered();
        let i = stim.next(rng, sample, tx);
        rig.step(&i);
    }
}

/// The RTL equals the clock-exact model on every output of every clock.
#[test]
fn btl_rtl_matches_model_random() {
    for (seed, cfg) in [
        (1, BtlConfig::T10_6_4),
        (2, BtlConfig::T25_17_1),
        (3, BtlConfig::T10_8_1),
        (4, BtlConfig::T10_6_2.with_brp(3)),
        (5, BtlConfig { triple: true, ..BtlConfig::T10_6_4.with_brp(2) }),
        // PH2 = 1 (IPT 1 TQ) at the shortest TQ that allows it, and PH2 != PH1
        (6, BtlConfig::new(2, 5, 3, 2).with_ph2(1)),
        (7, BtlConfig::new(3, 2, 2, 2).with_ph2(5)),
    ] {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut rig = Rig::new(true);
        let mut stim = Stim::new(cfg, 1.0 / 8000.0);
        let mut cov = Coverage::default();
        let mut last_sample: Option<usize> = None;
        for c in 0..200_000 {
            let (sample, tx) = rig.registered();
            let i = stim.next(&mut rng, sample, tx);
            let p = rig.step(&i);
            cov.add(&rig.model);
            // IPT contract: drive presented on the clock after `sample` is in
            // place at the transmit point, which is >= IPT TQ and >= 2 clocks
            // after the sample point's tick (the strobe is 1 clock later).
            if i.reset {
                last_sample = None;
            }
            if p.bit_start {
                let cfg = rig.model.model().unwrap().config();
                let ipt = (cfg.ipt() * cfg.brp) as usize;
                if let Some(s) = last_sample {
                    assert!(
                        c + 1 >= s + ipt,
                        "seed {seed} cycle {c}: transmit point {} clocks after the sample strobe",
                        c - s
                    );
                    assert!(c + 1 >= s + IPT_CLOCKS as usize, "seed {seed} cycle {c}: IPT under {IPT_CLOCKS} clocks");
                }
            }
            if p.sample {
                last_sample = Some(c);
            }
        }
        eprintln!("seed {seed}: {cov:?}");
        cov.assert_reached(seed);
        let syncs = rig.trace.iter().filter(|p| p.hard_sync || p.resync).count();
        let samples = rig.trace.iter().filter(|p| p.sample).count();
        assert!(syncs > 100 && samples > 1000, "seed {seed}: stimulus too quiet ({syncs} syncs, {samples} samples)");
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 24, ..Default::default() })]

    /// Random valid settings, PH2 = 1 and PH2 != PH1 included (the whole
    /// range of the fields): the RTL equals the clock-exact model on every
    /// output of every clock, and no transmit point comes less than IPT
    /// (and 2 clocks) after a sample point.
    #[test]
    fn btl_rtl_matches_model_any_setting(
        brp in proptest::sample::select(vec![1u32, 2, 3, 4, 7, 64]),
        prop in 1u32..=16, ph1 in 1u32..=8, ph2 in 1u32..=8, sjw in 1u32..=4,
        triple in proptest::bool::weighted(0.2), seed in 0u64..1000,
    ) {
        let cfg = BtlConfig { triple, ..BtlConfig::new(brp, prop, ph1, sjw).with_ph2(ph2) };
        proptest::prop_assume!(cfg.is_valid());
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut rig = Rig::new(true);
        let mut stim = Stim::new(cfg, 0.0);
        let mut last_sample: Option<usize> = None;
        let cycles = (60 * cfg.ntq() * brp).max(6000) as usize;
        for c in 0..cycles {
            let (sample, tx) = rig.registered();
            let i = stim.next(&mut rng, sample, tx);
            let p = rig.step(&i);
            if p.bit_start {
                if let Some(s) = last_sample {
                    proptest::prop_assert!(c + 1 >= s + (cfg.ipt() * brp).max(IPT_CLOCKS) as usize, "cycle {c}");
                }
            }
            if p.sample {
                last_sample = Some(c);
            }
        }
        proptest::prop_assert!(rig.trace.iter().filter(|p| p.sample).count() > 40);
    }
}

/// The clock-exact model against the TQ-level model with BRP 1 and pure
/// noise: the wrapper adds exactly one clock of latency to busmon and TX.
#[test]
fn cycle_model_wraps_tq_model() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for cfg in [BtlConfig::T10_6_4, BtlConfig::T25_17_1, BtlConfig::T10_8_1] {
        let mut cm = BtlCycleModel::new();
        let mut i = BtlInputs::with_config(&cfg);
        i.reset = true;
        cm.step(&i);
        i.reset = false;
        let mut m = BtlModel::new(cfg);
        let mut prev = (true, true, false);
        for _ in 0..20_000 {
            i.rx = rng.gen_bool(0.7);
            i.drive = rng.gen_bool(0.5);
            i.hs_en = rng.gen_bool(0.2);
            let p = cm.step(&i);
            assert!(p.tq);
            assert_eq!((p.busmon, p.tx, p.sample), prev);
            let ev = m.tq_tick(i.rx, i.drive, i.hs_en);
            assert_eq!(p.bit_start, ev.bit_start);
            prev = (ev.busmon, ev.tx, ev.sample);
        }
    }
}

/// §3.1: at most one synchronisation between two sample points, none while
/// the last sampled level is D.
#[test]
fn btl_sync_rules_random() {
    let mut rng = ChaCha8Rng::seed_from_u64(21);
    let mut rig = Rig::new(true);
    let mut stim = Stim::new(BtlConfig::T10_6_4, 1.0 / 5000.0);
    run_random(&mut rig, &mut stim, &mut rng, 80_000);
    let mut since_sample = 0;
    let mut checked = 0;
    for c in 1..rig.trace.len() {
        let p = rig.trace[c];
        if p.hard_sync || p.resync {
            // busmon on the tick clock (c - 1) is the level before the tick.
            assert_eq!(rig.trace[c - 1].busmon, R, "cycle {c}: synchronisation after a D sample");
            since_sample += 1;
            assert!(since_sample <= 1, "cycle {c}: second synchronisation without a sample point in between");
            checked += 1;
        }
        if p.sample || rig.trace[c - 1].cfg_err {
            since_sample = 0;
        }
        if p.sample || p.hard_sync || p.resync {
            assert!(rig.trace[c - 1].tq, "cycle {c}: strobe not after a tick");
        }
    }
    assert!(checked > 200, "only {checked} synchronisations");
}

/// Deterministic: a second edge before the sample point does not
/// synchronise, and an edge after a D sample does not either.
#[test]
fn btl_one_sync_per_sample_and_none_after_d() {
    let cfg = BtlConfig::T10_6_4;
    let mut rig = Rig::new(true);
    rig.reset(&cfg);
    let mut i = BtlInputs::with_config(&cfg);
    // Bit 0 (from reset): recessive, ends at tick 10.
    let mut ticks = 0;
    let mut run = |rig: &mut Rig, i: &BtlInputs, n: u32| {
        for _ in 0..n {
            rig.step(i);
            ticks += 1;
        }
    };
    run(&mut rig, &i, 10);
    // Bit 1: edge in TQ 1 (resync, PH1 + 1), back to R, edge in TQ 3.
    run(&mut rig, &i, 1);
    i.rx = D;
    run(&mut rig, &i, 1);
    i.rx = R;
    run(&mut rig, &i, 1);
    i.rx = D;
    run(&mut rig, &i, 2);
    i.rx = R;
    run(&mut rig, &i, 30);
    let n = rig.trace.len();
    let syncs: Vec<usize> = (0..n).filter(|&c| rig.trace[c].resync).collect();
    // Reset took 2 clocks; the tick that sees TQ 1's edge is clock 2 + 11.
    assert_eq!(syncs, vec![2 + 11 + 1], "only the first edge synchronises");
    // PH1 + 1: the sample of bit 1 is at tick 10 + 7.
    let samples: Vec<usize> = (0..n).filter(|&c| rig.trace[c].sample).map(|c| c - 2).collect();
    // Tick t is on clock t + 1 (reset took clocks 0 and 1); strobes one clock later.
    assert_eq!(&samples[..2], &[6, 17]);
    // Now sample D: hold D through a sample point, then R, then an edge.
    let mut rig = Rig::new(true);
    rig.reset(&cfg);
    let mut i = BtlInputs::with_config(&cfg);
    i.rx = R;
    for _ in 0..12 {
        rig.step(&i);
    }
    i.rx = D; // tick 13: edge in TQ 2 of bit 1 → PH1 + 2; the sample at tick 18 is D
    for _ in 0..8 {
        rig.step(&i);
    }
    i.rx = R;
    for _ in 0..3 {
        rig.step(&i);
    }
    i.rx = D; // an R→D edge while busmon = D
    for _ in 0..20 {
        rig.step(&i);
    }
    let syncs = rig.trace.iter().filter(|p| p.resync || p.hard_sync).count();
    assert_eq!(syncs, 1, "no synchronisation while the last sample is D");
    assert!(rig.trace.iter().any(|p| p.sample && !p.busmon));
}

/// Triple sampling: a one-TQ spike at the sample point is voted out, two
/// dominant TQ out of three are not.
#[test]
fn btl_triple_sampling() {
    for (triple, spike_tq, want) in [(false, 1, D), (true, 1, R), (true, 2, D), (false, 2, D)] {
        let cfg = BtlConfig { triple, ..BtlConfig::T10_6_4 };
        let mut rig = Rig::new(true);
        rig.reset(&cfg);
        let mut i = BtlInputs::with_config(&cfg);
        i.drive = D; // driving D: a late edge (e > 0) does not move the sample point
        for _ in 0..10 {
            rig.step(&i);
        }
        // Bit 1 starts at tick 10; its sample point is tick 16.
        for t in 11..=22u32 {
            i.rx = !(t > 16 - spike_tq && t <= 16);
            rig.step(&i);
        }
        let s: Vec<bool> = rig.trace.iter().filter(|p| p.sample).map(|p| p.busmon).collect();
        assert_eq!(s, vec![R, want], "triple {triple}, spike {spike_tq} TQ");
    }
}

/// Reset: TX recessive on the clock after reset, no strobes under reset,
/// the first tick on the BRP-th clock after the release, bit start at NTQ.
#[test]
fn btl_reset_and_prescaler() {
    for brp in [1u32, 2, 7, 32] {
        let cfg = BtlConfig::T10_6_4.with_brp(brp);
        let mut rig = Rig::new(true);
        rig.reset(&cfg);
        let mut i = BtlInputs::with_config(&cfg);
        i.drive = D;
        for _ in 0..(25 * brp) {
            rig.step(&i);
        }
        let ticks: Vec<usize> = (0..rig.trace.len()).filter(|&c| rig.trace[c].tq).collect();
        assert_eq!(ticks[0], 2 + brp as usize - 1, "BRP {brp}: first tick");
        assert!(ticks.windows(2).all(|w| w[1] - w[0] == brp as usize), "BRP {brp}: tick spacing");
        let starts: Vec<usize> = (0..rig.trace.len()).filter(|&c| rig.trace[c].bit_start).collect();
        assert_eq!(starts[0], ticks[9], "BRP {brp}: first bit start after NTQ ticks");
        assert!(rig.trace[starts[0]].tx && !rig.trace[starts[0] + 1].tx, "BRP {brp}: TX after bit_start");
        // Reset in the middle: TX back to R on the next clock, no strobes.
        let mut r = i;
        r.reset = true;
        for _ in 0..(3 * brp) {
            rig.step(&r);
        }
        let n = rig.trace.len();
        let under = &rig.trace[n - 3 * brp as usize + 1..];
        assert!(under.iter().all(|p| p.tx && !p.tq && !p.bit_start && !p.sample && !p.cfg_err), "BRP {brp}: under reset");
    }
}

/// Invalid configurations raise cfg_err and keep the block inert; a valid
/// one clears it.
#[test]
fn btl_cfg_err() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for (cfg, bad) in [
        (BtlConfig::new(1, 1, 1, 1), true),  // NTQ 5
        (BtlConfig::new(1, 2, 1, 1), true),  // NTQ 6
        (BtlConfig::new(1, 3, 1, 1), true),  // NTQ 7
        (BtlConfig::new(1, 4, 1, 1), false), // NTQ 8
        (BtlConfig::new(1, 8, 2, 3), true),  // SJW > PH1
        (BtlConfig::new(1, 8, 3, 3), false),
        (BtlConfig::new(4, 8, 8, 4), false),             // NTQ 25
        (BtlConfig::new(1, 5, 3, 1).with_ph2(1), true),  // PH2 1 with BRP 1: IPT 1 clock
        (BtlConfig::new(2, 5, 3, 1).with_ph2(1), false), // PH2 1 with BRP 2
        (BtlConfig::new(2, 5, 3, 3).with_ph2(1), false), // SJW > PH2 is legal (C22)
        (BtlConfig::new(1, 9, 8, 1).with_ph2(8), true),  // NTQ 26
        (BtlConfig::new(1, 1, 1, 1).with_ph2(5), false), // PH2 > PH1: NTQ 8
    ] {
        assert_eq!(cfg.is_valid(), !bad);
        let mut rig = Rig::new(true);
        rig.reset(&cfg);
        let start = rig.trace.len();
        let mut i = BtlInputs::with_config(&cfg);
        for _ in 0..400 {
            i.rx = rng.gen_bool(0.5);
            i.drive = rng.gen_bool(0.5);
            i.hs_en = rng.gen_bool(0.5);
            rig.step(&i);
        }
        let t = &rig.trace[start..];
        assert!(t.iter().all(|p| p.cfg_err == bad), "{cfg:?}: cfg_err");
        let active = t.iter().any(|p| p.tq || p.sample || p.bit_start || !p.tx || p.hard_sync || p.resync);
        assert_eq!(active, !bad, "{cfg:?}: activity");
        if bad {
            rig.reset(&BtlConfig::T10_6_4);
            let p = rig.step(&BtlInputs::with_config(&BtlConfig::T10_6_4));
            assert!(!p.cfg_err && p.tq);
        }
    }
    // Inert from power-up until the first reset, without cfg_err.
    let mut rig = Rig::new(true);
    for _ in 0..50 {
        let p = rig.step(&BtlInputs { rx: D, drive: D, ..BtlInputs::with_config(&BtlConfig::T10_6_4) });
        assert!(p.tx && !p.tq && !p.cfg_err);
    }
}

/// Lint, synthesis and co-simulation of the emitted Verilog with realistic
/// stimulus, starting from two different configurations.
#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn btl_verilog_flow() {
    for (seed, cfg) in [(101, BtlConfig::T10_6_4), (202, BtlConfig::T25_17_1.with_brp(2)), (303, BtlConfig::T10_8_1)] {
        let mut uut = BitTiming::default();
        let mut stim = Stim::new(cfg, 1.0 / 12_000.0);
        let (synth, cs) = flow::full_check(&mut uut, "btl", 100_000, seed, move |u: &mut BitTiming, rng, _| {
            let i = stim.next(rng, u.sample.val(), u.tx.val());
            u.set_inputs(&i);
        })
        .unwrap_or_else(|e| panic!("flow for {cfg:?}: {e}"));
        assert_eq!(cs.cycles, 100_000);
        assert_eq!(cs.outputs_compared, 8);
        assert!(synth.cells > 50, "{}", synth.stat);
    }
}

/// Size of the synthesised block (printed; asserts only that it synthesises for iCE40).
#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn btl_synth_ice40() {
    let mut uut = BitTiming::default();
    drive::init(&mut uut);
    let v = flow::emit(&uut);
    let r = flow::synth_check(&v, "top", flow::SynthTarget::Ice40).expect("synth_ice40");
    eprintln!("{}", r.stat);
    assert!(r.cells > 0);
}
