//! Generation-time configuration of a hub ([`HubConfig`], requirement H1 of hub.md):
//! ports, interlinks, clock, frame-monitor bit timing, judging thresholds,
//! reintegration and the optional fault-injection hook (H8).

use crate::coupler;
use crate::judge::JudgeParams;
use canstar_hdl::timing::BtlConfig;
use serde::{Deserialize, Serialize};

/// Where a fault is injected.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum FaultPoint {
    /// Uplink of port i, after the input stage (coupler and judge see it).
    Uplink(usize),
    /// Downlink of port i, after ANDT.
    Downlink(usize),
    /// Outgoing sublink j.
    Sublink(usize),
}

/// Which fault.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum InjectionKind {
    StuckRecessive,
    StuckDominant,
    /// Inversion of the signal while active (every bit flipped once).
    BitFlip,
}

impl InjectionKind {
    pub fn code(self) -> u64 {
        match self {
            InjectionKind::StuckRecessive => coupler::FAULT_STUCK_RECESSIVE,
            InjectionKind::StuckDominant => coupler::FAULT_STUCK_DOMINANT,
            InjectionKind::BitFlip => coupler::FAULT_BIT_FLIP,
        }
    }
}

/// A fault-injection hook (H8).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct FaultInjection {
    pub point: FaultPoint,
    pub kind: InjectionKind,
    /// Field code at which an armed injection starts ([`Field`] code, e.g. 6 = data).
    pub start_field: u8,
}

/// Generation-time parameters of a hub (H1). Defaults = the reference hub.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HubConfig {
    /// Node ports N (>= 1).
    pub ports: usize,
    /// Interlink sublink pairs M (>= 0; 0 = CANcentrate).
    pub sublinks: usize,
    /// Hub clock in Hz (documentation and pin constraints; the RTL counts clocks).
    pub clock_hz: u64,
    /// Bit timing of the frame monitor. Files write it in the controller's register
    /// encoding (every field the value − 1, `[hub.timing]`), converted when read.
    /// The default is the reference hub: TQ = 2 clocks of 14.74 MHz (the reference's
    /// "brp 0" of an SJA1000-style prescaler, which doubles), 8 TQ per bit, sample
    /// point at 6 TQ (75 %), SJW 1.
    #[serde(serialize_with = "canstar_hdl::timing::encoded::serialize", deserialize_with = "reference_timing_over")]
    pub timing: BtlConfig,
    /// Input synchroniser depth, 1 or 2 (default 1: two coupled hubs need it to keep the
    /// arbitration loop inside PROP with the reference timing, see the crate docs).
    pub sync_depth: usize,
    /// BIC threshold (isolation at bic >= 8 * threshold), 1..=31.
    pub bic_threshold: u64,
    /// Lifetime limit of blames per port (non-decaying counter, see [`crate::judge`]),
    /// 1..=127.
    pub life_threshold: u64,
    /// Lifetime limit of blames per sublink, 1..=127.
    pub sub_life_threshold: u64,
    /// NACK threshold, 1..=7.
    pub nack_threshold: u64,
    /// DBC threshold for ports, 1..=31 (reference value 24 is available).
    pub dbc_threshold: u64,
    /// BIC threshold for sublinks (default twice the port threshold), 1..=31.
    pub sub_bic_threshold: u64,
    /// Good frames per count taken off a port's / a sublink's `bic` (§5.3 decay), 1..=7.
    pub bic_decay: u64,
    pub sub_bic_decay: u64,
    /// Blames that one charged dominant bit in an error or overload delimiter counts on a
    /// port / a sublink (hub.md §5.17), 1..=3.
    pub delim_blames: u64,
    pub sub_delim_blames: u64,
    /// Dominant-run threshold for sublinks, 1..=31 (default 29 since hub.md §5.28).
    pub sub_dbc_threshold: u64,
    /// Replica disagreement limit, 1..=7.
    pub replica_limit: u64,
    /// Replica rule (hub.md §5.18): clocks that two replica sublinks must have differed
    /// before a sample for the disagreement to count, 1..=7 (default 4: replicas whose
    /// propagation delays differ by up to 3 hub clocks, about 200 ns or 40 m of cable at the
    /// reference 14.74 MHz, never disagree at a peer edge).
    pub replica_skew: u64,
    /// Glitch rule (hub.md §5.8): a run of equal level of at most this many clocks on an
    /// input is a glitch (None: one bit minus SJW minus 3 clocks, 11 with the reference
    /// timing), 1..=30.
    pub glitch_max: Option<u64>,
    /// Shortest recessive run that counts as a glitch on a sublink (shorter recessive
    /// slivers occur when the peer isolates a port or an error flag starts inside a bit),
    /// 1..=30.
    pub sub_glitch_min: u64,
    /// Shortest dominant run that counts as a glitch on a sublink (hub.md §5.15), 1..=30.
    pub sub_dominant_glitch_min: u64,
    /// Glitches that isolate a port / a sublink (decaying counter), 1..=7 (sublinks: 5 since
    /// hub.md §5.28).
    pub glitch_limit: u64,
    pub sub_glitch_limit: u64,
    /// Frames completed without error that take one glitch off the counter, 1..=31.
    pub glitch_decay: u64,
    /// Peer-hub rule (hub.md §5.11): common glitches (every replica sublink at once)
    /// that isolate every sublink from the peer, 1..=15, and the good frames that take
    /// one off the counter, 1..=7.
    pub peer_glitch_limit: u64,
    pub peer_glitch_decay: u64,
    /// Window rule (hub.md §5.2): clocks after the estimated bit start from which a
    /// dominant level at any clock up to the sample point counts as the bit's value for
    /// the unjustified-dominant rules (ports, sublinks), 0..=31.
    pub window_lag: u64,
    pub sub_window_lag: u64,
    /// First-flagger rule (hub.md §5.12): at an error episode that the frame monitor
    /// alone started in the transmission region of a frame without glitches, charge every
    /// port / sublink that was a dominant contender at that sample (a transmitter flagging
    /// a bit error the hub did not see).
    pub first_flagger: bool,
    pub sub_first_flagger: bool,
    /// Last-EOF-bit rule (hub.md §5.19, ports only): a port dominant in the last EOF bit,
    /// outside an error phase, is blamed (a transmitter takes that bit for a form error).
    pub eof_last_rule: bool,
    /// Peer guard (hub.md §5.20): the hub estimates the peer's sublink counters from its
    /// own ports' charges (the peer charges its sublinks for the same episodes); while the
    /// estimate is at least `8 * peer_guard`, a port charged alone is isolated at once, so
    /// that the peer's sublinks never overtake a second faulty port. 0 = off, else 1..=31
    /// (default 6, hub.md §5.24: two delimiter episodes before the peer's sublink limit
    /// of 9).
    pub peer_guard: u64,
    /// Replica overload rule (hub.md §5.21, sublinks): a sublink that was the dominant
    /// minority of its replicas for `replica_skew` clocks in Intermission bit 1 or 2, up to
    /// the sample (an overload condition it alone raised), gets a replica-rule charge at
    /// that sample.
    pub replica_overload: bool,
    /// Bus-run rule (hub.md §5.22, ports): in an error phase, a port's recessive sample
    /// under a bus that was dominant at every clock since the last sample does not clear
    /// its dominant run (`dbc_threshold`), so that a port that restarts its error flag after
    /// one recessive bit under the other nodes' flags (a node whose downlink loses dominant
    /// bits) is still one run.
    pub dominant_run_bridge: bool,
    /// Intermission-bit-2 lag (hub.md §5.23, sublinks): a sublink's level in Intermission
    /// bit 2 counts as a flag that started in that bit only when BT was still recessive at
    /// this many clocks after the bit-start clock (the peer saw it rise in bit 1 and it
    /// arrives an interlink crossing later), 0..=7; 0 = the clock before the bit start, as
    /// for ports.
    pub sub_intermission_lag: u64,
    /// Stuff-bit pulse rule (hub.md §5.23, ports): a port blamed at a dominant stuff bit,
    /// where §5.10 does not charge it (a healthy node's error flag can start there), is
    /// charged when it is recessive again at the next sample (a pulse, not a flag).
    pub stuff_pulse_rule: bool,
    /// Sublink-follower excuse (hub.md §5.25, ports): a port's dominant level in an error or
    /// overload delimiter that rose while a sublink had been dominant since the last sample
    /// point is the node's reaction to the peer's pulse: blamed, not charged.
    pub sublink_follower_excuse: bool,
    /// Early-SOF excuse (hub.md §5.26): no first-flagger charge in a dominant run that began
    /// at a SOF whose edge came through a sublink alone at least this many clocks before
    /// the SOF's bit start (in Intermission bit 2 after this hub's sample point: nodes that
    /// sample later answer it with overload flags), 0..=3; 0 = off.
    pub early_sof_clocks: u64,
    /// First-flagger replica charge (hub.md §5.27, sublinks): at an error episode that the
    /// frame monitor alone started, a sublink charged as a dominant contender while another
    /// replica was recessive in its window (the dominant minority the monitor reacted to)
    /// also gets a replica-rule charge.
    pub ff_replica_charge: bool,
    /// Reintegration window W in frames (None = isolation latched until reset).
    pub reintegration: Option<u64>,
    /// Fault-injection hook (None = no hooks).
    pub fault_injection: Option<FaultInjection>,
    /// Debug outputs (counters).
    pub debug: bool,
}

impl Default for HubConfig {
    fn default() -> Self {
        Self {
            ports: 3,
            sublinks: 2,
            clock_hz: 14_740_000,
            timing: REFERENCE_TIMING,
            sync_depth: 1,
            bic_threshold: 6,
            life_threshold: 32,
            sub_life_threshold: 64,
            nack_threshold: 7,
            dbc_threshold: 13,
            sub_bic_threshold: 9,
            bic_decay: 2,
            sub_bic_decay: 2,
            delim_blames: 3,
            sub_delim_blames: 2,
            sub_dbc_threshold: 29,
            replica_limit: 2,
            replica_skew: 4,
            glitch_max: None,
            sub_glitch_min: 3,
            sub_dominant_glitch_min: 1,
            glitch_limit: 3,
            sub_glitch_limit: 5,
            glitch_decay: 16,
            peer_glitch_limit: 12,
            peer_glitch_decay: 4,
            window_lag: 7,
            sub_window_lag: 8,
            first_flagger: true,
            sub_first_flagger: true,
            eof_last_rule: true,
            peer_guard: 6,
            replica_overload: true,
            dominant_run_bridge: true,
            sub_intermission_lag: 2,
            stuff_pulse_rule: true,
            sublink_follower_excuse: true,
            early_sof_clocks: 3,
            ff_replica_charge: true,
            reintegration: None,
            fault_injection: None,
            debug: true,
        }
    }
}

/// Most node ports of a hub (more than any CAN network has nodes; rust-hdl's
/// Verilog writer takes time quadratic in the number of signals, about 3 s here).
pub const MAX_PORTS: usize = 128;

/// Most interlinks of a hub.
pub const MAX_SUBLINKS: usize = 8;

/// The reference hub's monitor timing: TQ = 2 clocks, PROP 3, PH1 2, PH2 2, SJW 1 TQ.
pub const REFERENCE_TIMING: BtlConfig = BtlConfig::new(2, 3, 2, 1);

fn reference_timing_over<'de, D: serde::Deserializer<'de>>(d: D) -> Result<BtlConfig, D::Error> {
    canstar_hdl::timing::encoded::deserialize_over(d, REFERENCE_TIMING)
}

impl HubConfig {
    /// Clocks per bit of the frame monitor.
    pub fn bit_clocks(&self) -> u32 {
        self.timing.ntq() * self.timing.brp
    }
    /// Clock edges from an uplink pin to the downlink pins.
    pub fn coupling_latency(&self) -> usize {
        coupler::coupling_latency(self.sync_depth)
    }
    /// Parameters of the port judge units.
    pub fn port_params(&self) -> JudgeParams {
        JudgeParams {
            bic_limit: 8 * self.bic_threshold,
            bic_decay: self.bic_decay,
            life_limit: self.life_threshold,
            dbc_threshold: self.dbc_threshold,
            nack_threshold: self.nack_threshold,
            replica_limit: self.replica_limit,
            replica_skew: self.replica_skew,
            reintegration: self.reintegration,
            glitch_min: 1,
            glitch_min_dominant: 1,
            glitch_max: self.glitch_max_clocks(),
            glitch_limit: self.glitch_limit,
            glitch_decay: self.glitch_decay,
            peer_glitch_limit: self.peer_glitch_limit,
            peer_glitch_decay: self.peer_glitch_decay,
            window_lag: self.window_lag,
            crc_window_end: self.crc_window_end(),
            first_flagger: self.first_flagger,
            eof_last: self.eof_last_rule,
            delim_blames: self.delim_blames,
            replica_overload: false,
            dbc_bridge: self.dominant_run_bridge,
            im2_lag: 0,
            stuff_pulse: self.stuff_pulse_rule,
            sub_follower: self.sublink_follower_excuse,
            ff_replica: false,
        }
    }
    /// Longest glitch in clocks: [`HubConfig::glitch_max`], or one bit minus SJW minus
    /// 3 clocks (the shortest bit a controller sends, less a margin for sampling and for
    /// asymmetric transceiver delays), at least 1.
    pub fn glitch_max_clocks(&self) -> u64 {
        self.glitch_max.unwrap_or_else(|| {
            let t = &self.timing;
            ((t.ntq() - t.sjw) * t.brp).saturating_sub(3).clamp(1, 30) as u64
        })
    }
    /// Early-ACK rule (hub.md §5.2): the last clock after the bit start at which a dominant
    /// level counts in the CRC delimiter, one SJW plus one TQ before the sample point
    /// ((PROP + PH1 - SJW) TQ; 8 clocks with the reference timing). A receiver whose
    /// oscillator is fast against the transmitter's legitimately starts its ACK up to SJW
    /// early, and a hub that lags the other hub's frame by an interlink crossing sees that
    /// ACK earlier still.
    pub fn crc_window_end(&self) -> u64 {
        let t = &self.timing;
        ((t.prop + t.ph1).saturating_sub(t.sjw) * t.brp).min(31) as u64
    }
    /// Parameters of the sublink judge units.
    pub fn sublink_params(&self) -> JudgeParams {
        JudgeParams {
            bic_limit: 8 * self.sub_bic_threshold,
            bic_decay: self.sub_bic_decay,
            life_limit: self.sub_life_threshold,
            dbc_threshold: self.sub_dbc_threshold,
            nack_threshold: self.nack_threshold,
            replica_limit: self.replica_limit,
            replica_skew: self.replica_skew,
            reintegration: self.reintegration,
            glitch_min: self.sub_glitch_min,
            glitch_min_dominant: self.sub_dominant_glitch_min,
            glitch_max: self.glitch_max_clocks(),
            glitch_limit: self.sub_glitch_limit,
            glitch_decay: self.glitch_decay,
            peer_glitch_limit: self.peer_glitch_limit,
            peer_glitch_decay: self.peer_glitch_decay,
            window_lag: self.sub_window_lag,
            crc_window_end: self.crc_window_end(),
            first_flagger: self.sub_first_flagger,
            eof_last: false,
            delim_blames: self.sub_delim_blames,
            replica_overload: self.replica_overload,
            dbc_bridge: false,
            im2_lag: self.sub_intermission_lag,
            stuff_pulse: false,
            sub_follower: false,
            ff_replica: self.ff_replica_charge,
        }
    }
    /// Check the ranges; returns a description of the first problem, starting
    /// with the key.
    pub fn validate(&self) -> Result<(), String> {
        if self.ports == 0 {
            return Err("ports must be >= 1".into());
        }
        if self.ports > MAX_PORTS {
            return Err(format!("ports = {} (at most {MAX_PORTS})", self.ports));
        }
        if self.sublinks > MAX_SUBLINKS {
            return Err(format!("sublinks = {} (at most {MAX_SUBLINKS})", self.sublinks));
        }
        if !(1_000..=1_000_000_000).contains(&self.clock_hz) {
            return Err(format!("clock_hz = {} (must be 1 kHz ..= 1 GHz)", self.clock_hz));
        }
        if !(1..=2).contains(&self.sync_depth) {
            return Err("sync_depth must be 1 or 2".into());
        }
        let t = &self.timing;
        if t.brp > 32 || t.prop > 8 || t.triple {
            return Err("timing: bit timing out of range for the hub's monitor (at most 32 clocks per TQ, PROP <= 8 TQ, no triple sampling)".into());
        }
        t.check().map_err(|e| format!("timing: bit timing: {e}"))?;
        for (n, v, hi) in [
            ("bic_threshold", self.bic_threshold, 31),
            ("sub_bic_threshold", self.sub_bic_threshold, 31),
            ("bic_decay", self.bic_decay, 7),
            ("sub_bic_decay", self.sub_bic_decay, 7),
            ("delim_blames", self.delim_blames, 3),
            ("sub_delim_blames", self.sub_delim_blames, 3),
            ("dbc_threshold", self.dbc_threshold, 31),
            ("sub_dbc_threshold", self.sub_dbc_threshold, 31),
            ("nack_threshold", self.nack_threshold, 7),
            ("replica_limit", self.replica_limit, 7),
            ("replica_skew", self.replica_skew, 7),
            ("life_threshold", self.life_threshold, 127),
            ("sub_life_threshold", self.sub_life_threshold, 127),
            ("glitch_limit", self.glitch_limit, 7),
            ("sub_glitch_limit", self.sub_glitch_limit, 7),
            ("glitch_decay", self.glitch_decay, 31),
            ("peer_glitch_limit", self.peer_glitch_limit, 15),
            ("peer_glitch_decay", self.peer_glitch_decay, 7),
            ("sub_glitch_min", self.sub_glitch_min, 30),
            ("sub_dominant_glitch_min", self.sub_dominant_glitch_min, 30),
            ("glitch_max", self.glitch_max.unwrap_or(1), 30),
        ] {
            if v == 0 || v > hi {
                return Err(format!("{n} must be in 1..={hi}"));
            }
        }
        if self.peer_guard > 31 {
            return Err("peer_guard must be in 0..=31 (0 = off)".into());
        }
        if self.sub_intermission_lag > 7 {
            return Err("sub_intermission_lag must be in 0..=7".into());
        }
        if self.early_sof_clocks > 3 {
            return Err("early_sof_clocks must be in 0..=3 (0 = off)".into());
        }
        if self.window_lag > 31 || self.sub_window_lag > 31 {
            return Err("window_lag and sub_window_lag must be in 0..=31".into());
        }
        for (n, v) in [("sub_glitch_min", self.sub_glitch_min), ("sub_dominant_glitch_min", self.sub_dominant_glitch_min)] {
            if v > self.glitch_max_clocks() {
                return Err(format!("{n} must not exceed the glitch maximum"));
            }
        }
        if let Some(w) = self.reintegration {
            if w == 0 || w > 255 {
                return Err("reintegration window must be in 1..=255".into());
            }
        }
        if let Some(f) = self.fault_injection {
            let ok = match f.point {
                FaultPoint::Uplink(i) | FaultPoint::Downlink(i) => i < self.ports,
                FaultPoint::Sublink(j) => j < self.sublinks,
            };
            if !ok {
                return Err("fault_injection.point: fault-injection point out of range".into());
            }
            if f.start_field > 15 {
                return Err("fault_injection.start_field must be a 4-bit field code".into());
            }
        }
        Ok(())
    }
}


#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc_window_ends_one_sjw_and_one_tq_before_the_sample_point() {
        let c = HubConfig::default();
        // sample point at (1 + PROP + PH1) TQ = 12 clocks; SJW + 1 TQ = 4 clocks earlier
        assert_eq!(c.crc_window_end(), 8);
        assert_eq!(c.port_params().crc_window_end, 8);
        assert_eq!(c.sublink_params().crc_window_end, 8);
        let hub29 = HubConfig { timing: BtlConfig::new(4, 3, 2, 1), ..HubConfig::default() };
        assert_eq!(hub29.crc_window_end(), 16);
    }
}
