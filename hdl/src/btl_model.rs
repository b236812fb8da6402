//! Reference models of the bit timing logic: [`BtlModel`], a pure-Rust
//! transcription of the normative counter model of can-protocol.md §2.3 (one call
//! per time quantum), and [`BtlCycleModel`], which adds the prescaler, the
//! configuration latch and the register timing of the RTL so that it predicts every
//! output of [`crate::btl::BitTiming`] on every clock. The tests compare the RTL
//! against it; the lock-step checker uses it as the golden bit timing.

use crate::timing::{BtlConfig, IPT};

/// What happened on one TQ tick of [`BtlModel`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BtlEvents {
    /// A sample point (step 5); `busmon` holds the sampled level.
    pub sample: bool,
    /// A transmit point took effect: `tx` took `drive` on this tick.
    pub bit_start: bool,
    /// A synchronisation condition held with `hs_en` set.
    pub hard_sync: bool,
    /// A synchronisation condition held with `hs_en` clear.
    pub resync: bool,
    /// The synchronisation restarted the bit (`cnt := 1`).
    pub restart: bool,
    /// Phase error of the synchronising edge, if any.
    pub phase_error: Option<i32>,
    /// The bit ended (step 4) on this tick.
    pub bit_end: bool,
    /// A transmit point was postponed on this tick (§2.5).
    pub postponed: bool,
    /// Level of `busmon` after the tick.
    pub busmon: bool,
    /// Level of `tx` after the tick.
    pub tx: bool,
}

/// The normative counter model of can-protocol.md §2.3, one call per TQ.
///
/// Levels are `true` = recessive. A new model is in the state right after
/// reset: at the start of a bit, `busmon` and `tx` recessive,
/// synchronisation enabled, no sample point within the last IPT.
#[derive(Debug, Clone)]
pub struct BtlModel {
    cfg: BtlConfig,
    /// TQ counter inside the bit.
    pub cnt: u32,
    /// Working sample index.
    pub sp: u32,
    /// Working bit length.
    pub nb: u32,
    /// Last sampled level.
    pub busmon: bool,
    /// Synchronisation enabled.
    pub sync_en: bool,
    /// The TX pin.
    pub tx: bool,
    /// TQ ticks since the latest sample point (saturating).
    since_sample: u32,
    /// A transmit point waits for sample point + IPT (`cfg.ipt()`).
    pending_tx: bool,
    /// `rx` on the previous two ticks (most recent first), for triple sampling.
    hist: [bool; 2],
}

impl BtlModel {
    /// Model in its reset state. The configuration should be valid.
    pub fn new(cfg: BtlConfig) -> Self {
        Self {
            cfg,
            cnt: 0,
            sp: cfg.sp(),
            nb: cfg.ntq(),
            busmon: true,
            sync_en: true,
            tx: true,
            since_sample: IPT,
            pending_tx: false,
            hist: [true, true],
        }
    }

    pub fn config(&self) -> &BtlConfig {
        &self.cfg
    }

    fn reload(&mut self) {
        self.sp = self.cfg.sp();
        self.nb = self.cfg.ntq();
    }

    /// One TQ tick with `rx` = the synchronised RX level at this tick.
    pub fn tq_tick(&mut self, rx: bool, drive: bool, hs_en: bool) -> BtlEvents {
        let mut ev = BtlEvents::default();
        let sjw = self.cfg.sjw;
        self.since_sample = (self.since_sample + 1).min(IPT);
        let mut transmit_point = false;

        // Step 1: the edge, if any, lies in TQ j of the bit.
        self.cnt += 1;
        let j = self.cnt as i32 - 1;
        // Step 2: phase error.
        let e = if self.cnt <= self.sp { j } else { j - self.nb as i32 };
        // Step 3: synchronisation.
        if !rx && self.busmon && self.sync_en {
            self.sync_en = false;
            ev.phase_error = Some(e);
            let mut restart = false;
            if hs_en {
                // §3.3
                ev.hard_sync = true;
                restart = drive || self.cnt > self.sp;
            } else {
                // §3.4 (drive R) and §3.5 (drive D)
                ev.resync = true;
                if e > 0 {
                    if drive {
                        let d = (e as u32).min(sjw);
                        self.sp += d;
                        self.nb += d;
                    }
                } else if e < 0 {
                    if e.unsigned_abs() <= sjw {
                        restart = true;
                    } else {
                        self.nb -= sjw;
                    }
                }
            }
            if restart {
                self.cnt = 1;
                self.reload();
                ev.restart = true;
                transmit_point = true;
            }
        }
        // Step 4: end of bit.
        if self.cnt == self.nb {
            self.cnt = 0;
            self.reload();
            ev.bit_end = true;
            transmit_point = true;
        }
        // Step 5: sample point.
        if self.cnt == self.sp {
            self.busmon = if self.cfg.triple {
                let n = rx as u32 + self.hist[0] as u32 + self.hist[1] as u32;
                n >= 2
            } else {
                rx
            };
            self.sync_en = true;
            self.since_sample = 0;
            ev.sample = true;
        }
        // §2.5: transmit points, postponed to sample point + IPT.
        if transmit_point || self.pending_tx {
            if self.since_sample >= self.cfg.ipt() {
                self.tx = drive;
                self.pending_tx = false;
                ev.bit_start = true;
            } else {
                ev.postponed = transmit_point;
                self.pending_tx = true;
            }
        }
        self.hist = [rx, self.hist[0]];
        ev.busmon = self.busmon;
        ev.tx = self.tx;
        ev
    }
}

/// Inputs of [`BitTiming`] for one clock, as plain values (fields in the
/// value − 1 encoding of the ports).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BtlInputs {
    pub reset: bool,
    pub brp: u32,
    pub prop: u32,
    pub ph1: u32,
    pub ph2: u32,
    pub sjw: u32,
    pub triple: bool,
    pub rx: bool,
    pub drive: bool,
    pub hs_en: bool,
}

impl BtlInputs {
    /// Inputs holding `cfg` (recessive rx and drive, no reset, no hard sync).
    pub fn with_config(cfg: &BtlConfig) -> Self {
        let (brp, prop, ph1, ph2, sjw) = cfg.fields();
        Self { reset: false, brp, prop, ph1, ph2, sjw, triple: cfg.triple, rx: true, drive: true, hs_en: false }
    }
}

/// Outputs of [`BitTiming`] on one clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BtlPins {
    pub tq: bool,
    pub sample: bool,
    pub busmon: bool,
    pub bit_start: bool,
    pub tx: bool,
    pub hard_sync: bool,
    pub resync: bool,
    pub cfg_err: bool,
}

/// Clock-exact model of [`BitTiming`]: [`BtlModel`] plus the prescaler, the
/// configuration latch and the output registers.
#[derive(Debug, Clone)]
pub struct BtlCycleModel {
    /// Latched configuration when valid (None: inert).
    active: Option<BtlModel>,
    bad: bool,
    pre: u32,
    sample_r: bool,
    hard_r: bool,
    resync_r: bool,
    last: Option<BtlEvents>,
}

impl Default for BtlCycleModel {
    fn default() -> Self {
        Self::new()
    }
}

impl BtlCycleModel {
    /// The power-up state (inert until the first reset).
    pub fn new() -> Self {
        Self { active: None, bad: false, pre: 0, sample_r: false, hard_r: false, resync_r: false, last: None }
    }

    /// The events of the TQ step taken on the last [`step`](Self::step), if
    /// that clock was a tick.
    pub fn last_events(&self) -> Option<BtlEvents> {
        self.last
    }

    /// The counter model, when a valid configuration is latched.
    pub fn model(&self) -> Option<&BtlModel> {
        self.active.as_ref()
    }

    /// The outputs on a clock with inputs `i`, then the rising edge.
    pub fn step(&mut self, i: &BtlInputs) -> BtlPins {
        let (busmon, tx) = self.active.as_ref().map(|m| (m.busmon, m.tx)).unwrap_or((true, true));
        let mut pins = BtlPins {
            tq: false,
            sample: self.sample_r,
            busmon,
            bit_start: false,
            tx,
            hard_sync: self.hard_r,
            resync: self.resync_r,
            cfg_err: self.bad,
        };
        self.last = None;
        if i.reset {
            let cfg = BtlConfig::from_fields(i.brp, i.prop, i.ph1, i.ph2, i.sjw, i.triple);
            self.bad = !cfg.is_valid();
            self.active = if self.bad { None } else { Some(BtlModel::new(cfg)) };
            self.pre = 0;
            self.sample_r = false;
            self.hard_r = false;
            self.resync_r = false;
            return pins;
        }
        let Some(m) = self.active.as_mut() else {
            self.sample_r = false;
            self.hard_r = false;
            self.resync_r = false;
            return pins;
        };
        let tick = self.pre + 1 == m.config().brp;
        self.pre = if tick { 0 } else { self.pre + 1 };
        if tick {
            let ev = m.tq_tick(i.rx, i.drive, i.hs_en);
            pins.tq = true;
            pins.bit_start = ev.bit_start;
            self.last = Some(ev);
            self.sample_r = ev.sample;
            self.hard_r = ev.hard_sync;
            self.resync_r = ev.resync;
        } else {
            self.sample_r = false;
            self.hard_r = false;
            self.resync_r = false;
        }
        pins
    }
}

