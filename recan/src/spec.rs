//! [`NetworkSpec`]: the description of a ReCANcentrate network (TOML), its
//! validation and the builder that instantiates it in a [`Sim`].
//!
//! Node `k` has controller A on port `k` of hub 0 and controller B on port `k`
//! of hub 1. Unused hub ports stay recessive.

use canstar_hub::config::HubConfig;
use canstar_hdl::timing::BtlConfig;
use serde::{Deserialize, Serialize};


/// Name of the network (the top-level `[network]` table marks a network file).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct NetworkMeta {
    pub name: String,
}

impl Default for NetworkMeta {
    fn default() -> Self {
        NetworkMeta { name: "recancentrate".into() }
    }
}

/// Per-hub clock (both hubs share the generation-time [`HubConfig`]).
#[derive(Clone, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HubClock {
    /// Oscillator offset in ppm (positive = slower).
    pub ppm: f64,
    /// Time of the first clock edge in ps (None = random from the run seed).
    pub phase_ps: Option<u64>,
}

/// One interlink: a pair of sublinks with their propagation delays.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct InterlinkSpec {
    /// Delay of the sublink hub 0 → hub 1 in ps.
    pub h0_to_h1_ps: u64,
    /// Delay of the sublink hub 1 → hub 0 in ps.
    pub h1_to_h0_ps: u64,
}

impl Default for InterlinkSpec {
    fn default() -> Self {
        InterlinkSpec { h0_to_h1_ps: 10_000, h1_to_h0_ps: 10_000 }
    }
}

/// One CAN controller of a node: clock, bit timing (real values; the file has no
/// `ph2` key, so PH2 = max(PH1, 2)),
/// and its link delays. In a network file the timing keys (`brp`, `prop`, `ph1`,
/// `sjw`) sit beside the others (see [`CtrlSpecFile`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(from = "CtrlSpecFile", into = "CtrlSpecFile")]
pub struct CtrlSpec {
    pub clock_hz: u64,
    /// Oscillator offset in ppm (positive = slower).
    pub ppm: f64,
    /// Time of the first clock edge in ps (None = random from the run seed).
    pub phase_ps: Option<u64>,
    /// Bit timing: clocks per TQ 1..=128, PROP 1..=16, PH1 1..=8, SJW 1..=4 TQ.
    pub timing: BtlConfig,
    /// RX synchroniser depth (1 or 2).
    pub sync_depth: usize,
    /// Uplink (controller TX → hub) propagation delay in ps.
    pub up_ps: u64,
    /// Downlink (hub → controller RX) propagation delay in ps.
    pub down_ps: u64,
}

/// The reference node controller's timing: TQ = 4 clocks, SYNC 1, PROP 3, PH1 2,
/// PH2 2, SJW 1 (the same sample point as the prototype's PROP 2 / PH1 3 / PH2 2,
/// which this controller cannot express since its PH2 >= PH1).
pub const REFERENCE_CTRL_TIMING: BtlConfig = BtlConfig::new(4, 3, 2, 1);

impl Default for CtrlSpec {
    /// The reference node controller: 29.48 MHz, TQ = 4 clocks (135.7 ns),
    /// 8 TQ per bit with the sample point after 6 TQ ([`REFERENCE_CTRL_TIMING`]),
    /// 10 ns links.
    fn default() -> Self {
        CtrlSpec {
            clock_hz: 29_480_000,
            ppm: 0.0,
            phase_ps: None,
            timing: REFERENCE_CTRL_TIMING,
            sync_depth: 1,
            up_ps: 10_000,
            down_ps: 10_000,
        }
    }
}

/// A controller as a network file writes it: every key optional (default: the
/// reference controller), the bit timing keys inline.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CtrlSpecFile {
    clock_hz: u64,
    ppm: f64,
    phase_ps: Option<u64>,
    brp: u32,
    prop: u32,
    ph1: u32,
    sjw: u32,
    sync_depth: usize,
    up_ps: u64,
    down_ps: u64,
}

impl Default for CtrlSpecFile {
    fn default() -> Self {
        CtrlSpec::default().into()
    }
}

impl From<CtrlSpecFile> for CtrlSpec {
    fn from(f: CtrlSpecFile) -> Self {
        CtrlSpec {
            clock_hz: f.clock_hz,
            ppm: f.ppm,
            phase_ps: f.phase_ps,
            timing: BtlConfig::new(f.brp, f.prop, f.ph1, f.sjw),
            sync_depth: f.sync_depth,
            up_ps: f.up_ps,
            down_ps: f.down_ps,
        }
    }
}

impl From<CtrlSpec> for CtrlSpecFile {
    fn from(c: CtrlSpec) -> Self {
        let t = c.timing;
        CtrlSpecFile {
            clock_hz: c.clock_hz,
            ppm: c.ppm,
            phase_ps: c.phase_ps,
            brp: t.brp,
            prop: t.prop,
            ph1: t.ph1,
            sjw: t.sjw,
            sync_depth: c.sync_depth,
            up_ps: c.up_ps,
            down_ps: c.down_ps,
        }
    }
}

impl CtrlSpec {
    pub fn period_ps(&self) -> u64 {
        (1e12 / self.clock_hz as f64).round() as u64
    }
    /// Nominal bit time in ps.
    pub fn bit_time_ps(&self) -> u64 {
        self.period_ps() * self.timing.brp as u64 * self.timing.ntq() as u64
    }
}

/// The test application a node runs (recancentrate.md §3).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AppKind {
    /// 3BitCounter: sends an incrementing 1-byte counter as fast as it can.
    Counter,
    /// Blinker: the same with its own identifier.
    Blinker,
    /// Receiver: sends nothing; classifies the counters it receives.
    Receiver,
    /// Nothing (the node's driver still receives and acknowledges).
    None,
}

/// One node: its application and its two controllers.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NodeSpec {
    pub name: String,
    pub app: AppKind,
    /// 11-bit identifier of the node's frames (senders only).
    #[serde(default)]
    pub id: u32,
    /// The tx controller at start: 0 = A, 1 = B.
    #[serde(default)]
    pub initial_tx: usize,
    /// Controller A (on hub 0).
    #[serde(default)]
    pub a: CtrlSpec,
    /// Controller B (on hub 1).
    #[serde(default)]
    pub b: CtrlSpec,
}

impl NodeSpec {
    pub fn ctrl(&self, c: usize) -> &CtrlSpec {
        if c == 0 {
            &self.a
        } else {
            &self.b
        }
    }
    pub fn ctrl_mut(&mut self, c: usize) -> &mut CtrlSpec {
        if c == 0 {
            &mut self.a
        } else {
            &mut self.b
        }
    }
}

/// Parameters of the media-management driver (recancentrate.md §2).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DriverSpec {
    /// K: how long a routine waits for the other controller's report, in bit times.
    pub k_bits: f64,
    /// Transmission timeout in ticks of `timer_clock_hz` (prototype: 0xFFFF).
    pub tx_timeout_ticks: u64,
    pub timer_clock_hz: u64,
    /// Omission discrepancies tolerated before the non-tx path is taken as deaf.
    pub max_inconsists: u32,
    /// TEC or REC at which a controller is quarantined.
    pub warning_limit: u32,
    /// Copy to the other star (beyond the published driver, hub.md §5.29): at the omission
    /// discrepancy that ends the retransmissions (`MsgTxOmi` at `max_inconsists`), when the
    /// tx controller's TEC is at least this and the non-tx controller's TEC below it (the tx
    /// controller has had transmit errors lately, the other has not), the frame is also
    /// requested on the non-tx controller and reported sent when that copy is. A split star
    /// (the controllers on different stars, the tx controller's one faulty) then still
    /// delivers the frame to the nodes on the other star. The copy is given up when the
    /// non-tx controller's TEC reaches this. 0: never (as published).
    pub copy_tec: u32,
    /// Send again (beyond the published driver, hub.md §5.30): when the tx controller is
    /// quarantined and its last frame was reported sent on the omission rule alone (the
    /// other controller never saw it), that frame is sent on the new tx controller before
    /// the pending one. The nodes on the new tx controller's star then get the frame the
    /// old star alone carried; the others get it twice. false: as published.
    pub resend_unconfirmed: bool,
    /// Host reaction time from a reported success to the application's next
    /// request, in bit times. It must exceed the 3-bit intermission so that two
    /// nodes sending at maximal rate alternate (otherwise the higher identifier
    /// priority starves the other node).
    pub app_delay_bits: f64,
    /// Bit times after power-up before the applications start.
    pub start_bits: u32,
    /// Interrupt latency of the host in ns: a controller's report (or its
    /// error-warning condition) reaches the driver this long after it happens.
    /// A microcontroller reading its controllers' status over a bus takes
    /// microseconds; with 0 the driver would quarantine a controller whose
    /// counter jumps to 96 inside one error flag before the hub can judge it.
    pub irq_latency_ns: f64,
}

impl Default for DriverSpec {
    fn default() -> Self {
        DriverSpec {
            k_bits: 4.0,
            tx_timeout_ticks: 0xFFFF,
            timer_clock_hz: 29_480_000,
            max_inconsists: 3,
            warning_limit: 96,
            copy_tec: 8,
            resend_unconfirmed: true,
            app_delay_bits: 4.0,
            start_bits: 20,
            irq_latency_ns: 10_000.0,
        }
    }
}

impl DriverSpec {
    /// Transmission timeout in ps.
    pub fn tx_timeout_ps(&self) -> u64 {
        (self.tx_timeout_ticks as f64 * 1e12 / self.timer_clock_hz as f64).round() as u64
    }
}

/// A ReCANcentrate network: two hubs, interlinks, nodes with two controllers.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NetworkSpec {
    #[serde(default)]
    pub network: NetworkMeta,
    /// Generation-time configuration shared by both hubs.
    #[serde(default = "reference_hub")]
    pub hub: HubConfig,
    /// Exactly two entries: the clocks of hub 0 and hub 1.
    #[serde(default = "two_hubs")]
    pub hubs: Vec<HubClock>,
    /// One entry per interlink (as many as `hub.sublinks`).
    #[serde(default = "two_interlinks")]
    pub interlinks: Vec<InterlinkSpec>,
    #[serde(default)]
    pub driver: DriverSpec,
    pub nodes: Vec<NodeSpec>,
}

fn reference_hub() -> HubConfig {
    HubConfig { ports: 3, sublinks: 2, sync_depth: 1, ..HubConfig::default() }
}
fn two_hubs() -> Vec<HubClock> {
    vec![HubClock::default(), HubClock::default()]
}
fn two_interlinks() -> Vec<InterlinkSpec> {
    vec![InterlinkSpec::default(), InterlinkSpec::default()]
}

impl Default for NetworkSpec {
    /// The reference system of recancentrate.md §1: two hubs (N = 3, M = 2,
    /// 14.74 MHz, TQ 2 clocks, one input flip-flop as the prototype), three
    /// nodes (3BitCounter id 0x0A0, Blinker id 0x0B0, Receiver) at 921.25 kbit/s.
    fn default() -> Self {
        let node = |name: &str, app, id| NodeSpec { name: name.into(), app, id, initial_tx: 0, a: CtrlSpec::default(), b: CtrlSpec::default() };
        NetworkSpec {
            network: NetworkMeta::default(),
            hub: reference_hub(),
            hubs: two_hubs(),
            interlinks: two_interlinks(),
            driver: DriverSpec::default(),
            nodes: vec![
                node("counter", AppKind::Counter, 0x0A0),
                node("blinker", AppKind::Blinker, 0x0B0),
                node("receiver", AppKind::Receiver, 0),
            ],
        }
    }
}

impl NetworkSpec {
    /// The reference system with the node controllers clocked at 14.74 MHz
    /// (TQ = 2 clocks: the same 135.7 ns quantum and bit timing) instead of
    /// 29.48 MHz: half the controller clock cycles per simulated second,
    /// used by the published scenarios and the campaign.
    pub fn fast() -> Self {
        let mut s = Self::default();
        s.network.name = "recancentrate-fast".into();
        for n in &mut s.nodes {
            for c in 0..2 {
                let cs = n.ctrl_mut(c);
                cs.clock_hz = 14_740_000;
                cs.timing.brp = 2;
            }
        }
        s.driver.timer_clock_hz = 29_480_000;
        s
    }

    /// Parse a network file (TOML) and validate it.
    pub fn from_toml(text: &str) -> Result<NetworkSpec, String> {
        let s: NetworkSpec = toml::from_str(text).map_err(|e| e.to_string())?;
        s.validate()?;
        Ok(s)
    }

    /// The spec as TOML text.
    pub fn to_toml(&self) -> String {
        toml::to_string_pretty(self).expect("network spec serialises")
    }

    /// Does this TOML text look like a network file (a top-level `[network]`
    /// table or `[[nodes]]` with two controllers and `hubs`)?
    pub fn is_network_file(text: &str) -> bool {
        match text.parse::<toml::Table>() {
            Ok(t) => t.contains_key("network") || t.contains_key("hubs") || t.contains_key("interlinks"),
            Err(_) => false,
        }
    }

    /// Hub clock period in ps.
    pub fn hub_period_ps(&self) -> u64 {
        (1e12 / self.hub.clock_hz as f64).round() as u64
    }

    /// Nominal bit time of the hubs in ps (the reference bit time of the network).
    pub fn bit_time_ps(&self) -> u64 {
        self.hub_period_ps() * self.hub.bit_clocks() as u64
    }

    /// Check the spec (the one check of this format): every number finite
    /// and in range (no zero clock period, no overflow in picoseconds), every
    /// name usable as a VCD scope. The error starts with the key
    /// (`nodes[2].a.ppm: ...`); the caller adds the file.
    pub fn validate(&self) -> Result<(), String> {
        self.hub.validate().map_err(|e| format!("hub: {e}"))?;
        check_name("network.name", &self.network.name, true)?;
        if self.hubs.len() != 2 {
            return Err(format!("hubs: exactly 2 entries expected, found {}", self.hubs.len()));
        }
        if self.interlinks.len() != self.hub.sublinks {
            return Err(format!(
                "interlinks: {} entries but hub.sublinks = {}",
                self.interlinks.len(),
                self.hub.sublinks
            ));
        }
        if self.nodes.is_empty() {
            return Err("nodes: at least one node expected".into());
        }
        if self.nodes.len() > self.hub.ports {
            return Err(format!("nodes: {} nodes but hub.ports = {}", self.nodes.len(), self.hub.ports));
        }
        let hub_period = self.hub_period_ps();
        for (i, h) in self.hubs.iter().enumerate() {
            check_ppm(&format!("hubs[{i}].ppm"), h.ppm)?;
            check_phase(&format!("hubs[{i}].phase_ps"), h.phase_ps, hub_period)?;
        }
        for (i, l) in self.interlinks.iter().enumerate() {
            check_delay(&format!("interlinks[{i}].h0_to_h1_ps"), l.h0_to_h1_ps)?;
            check_delay(&format!("interlinks[{i}].h1_to_h0_ps"), l.h1_to_h0_ps)?;
        }
        let d = &self.driver;
        for (k, v, lo_open, hi) in [
            ("driver.k_bits", d.k_bits, true, MAX_DRIVER_BITS),
            ("driver.app_delay_bits", d.app_delay_bits, false, MAX_DRIVER_BITS),
            ("driver.irq_latency_ns", d.irq_latency_ns, false, MAX_DELAY_PS as f64 / 1000.0),
        ] {
            let low_ok = if lo_open { v > 0.0 } else { v >= 0.0 };
            if !(v.is_finite() && low_ok && v <= hi) {
                return Err(format!("{k}: {v:?} (must be finite, {} 0 and at most {hi})", if lo_open { ">" } else { ">=" }));
            }
        }
        if d.max_inconsists == 0 {
            return Err("driver.max_inconsists: must be >= 1".into());
        }
        if d.warning_limit == 0 || d.warning_limit > 255 {
            return Err(format!("driver.warning_limit: {} (must be in 1..=255)", d.warning_limit));
        }
        if d.copy_tec > 255 {
            return Err(format!("driver.copy_tec: {} (must be in 0..=255)", d.copy_tec));
        }
        check_clock("driver.timer_clock_hz", d.timer_clock_hz)?;
        if d.tx_timeout_ticks == 0 || d.tx_timeout_ps() > MAX_TIMEOUT_PS {
            return Err(format!("driver.tx_timeout_ticks: {} (must be >= 1 and at most 1 s of the timer clock)", d.tx_timeout_ticks));
        }
        if d.start_bits > MAX_DRIVER_BITS as u32 {
            return Err(format!("driver.start_bits: {} (at most {MAX_DRIVER_BITS})", d.start_bits));
        }
        let hub_bit = self.bit_time_ps() as f64;
        let mut ids = Vec::new();
        for (k, n) in self.nodes.iter().enumerate() {
            let key = format!("nodes[{k}]");
            check_name(&format!("{key}.name"), &n.name, false)?;
            if self.nodes[..k].iter().any(|m| m.name == n.name) {
                return Err(format!("{key}.name: node name `{}` is used twice", n.name));
            }
            let who = format!("{key} ({})", n.name);
            if matches!(n.app, AppKind::Counter | AppKind::Blinker) {
                if n.id > 0x7FF {
                    return Err(format!("{key}.id: {who}: id {:#x} does not fit 11 bits", n.id));
                }
                if ids.contains(&n.id) {
                    return Err(format!("{key}.id: {who}: id {:#x} used by another sender", n.id));
                }
                ids.push(n.id);
            }
            if n.initial_tx > 1 {
                return Err(format!("{key}.initial_tx: {who}: initial_tx must be 0 (A) or 1 (B)"));
            }
            for (c, cs) in [(0, &n.a), (1, &n.b)] {
                let key = format!("{key}.{}", ["a", "b"][c]);
                let who = format!("{who} controller {}", ["a", "b"][c]);
                check_clock(&format!("{key}.clock_hz"), cs.clock_hz)?;
                check_phase(&format!("{key}.phase_ps"), cs.phase_ps, cs.period_ps())?;
                cs.timing.check().map_err(|e| format!("{key}: {who}: bit timing: {e}"))?;
                if !(1..=2).contains(&cs.sync_depth) {
                    return Err(format!("{key}.sync_depth: {who}: sync_depth must be 1 or 2"));
                }
                check_ppm(&format!("{key}.ppm"), cs.ppm)?;
                check_delay(&format!("{key}.up_ps"), cs.up_ps)?;
                check_delay(&format!("{key}.down_ps"), cs.down_ps)?;
                let bt = cs.bit_time_ps() as f64;
                if (bt - hub_bit).abs() > 0.01 * hub_bit {
                    return Err(format!(
                        "{key}: {who}: bit time {:.1} ns (clock_hz, brp, prop, ph1) differs from the hubs' {:.1} ns (hub.clock_hz, hub.timing) by more than 1 %",
                        bt / 1000.0,
                        hub_bit / 1000.0
                    ));
                }
                // one-way delay to the farthest controller must stay below half a bit
                let lat = self.hub.coupling_latency() as u64 * self.hub_period_ps();
                let sub = self.interlinks.iter().map(|l| l.h0_to_h1_ps.max(l.h1_to_h0_ps)).min().unwrap_or(0);
                let one_way = cs.up_ps + 2 * lat + sub + cs.down_ps;
                if one_way as f64 > 0.5 * hub_bit {
                    return Err(format!(
                        "{key}: {who}: the path through both hubs (up_ps, down_ps, interlinks, hub.sync_depth) takes {:.1} ns, more than half a bit",
                        one_way as f64 / 1000.0
                    ));
                }
            }
        }
        Ok(())
    }
}

/// Longest link delay, in ps (1 ms: far beyond any bit time).
pub const MAX_DELAY_PS: u64 = 1_000_000_000;

/// Largest driver parameter counted in bit times.
pub const MAX_DRIVER_BITS: f64 = 1_000_000.0;

/// Longest transmission timeout, in ps (1 s).
pub const MAX_TIMEOUT_PS: u64 = 1_000_000_000_000;

/// A name that becomes a VCD scope and a component name (the network's name
/// may also hold `-` and `.`).
fn check_name(key: &str, name: &str, network: bool) -> Result<(), String> {
    let ok = !name.is_empty()
        && name.len() <= 64
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || (network && matches!(c, '-' | '.')));
    if !ok {
        let extra = if network { ", '-', '.'" } else { "" };
        return Err(format!("{key}: name `{name}` must be 1 to 64 letters, digits, _{extra}"));
    }
    Ok(())
}

fn check_ppm(key: &str, ppm: f64) -> Result<(), String> {
    if !(ppm.is_finite() && ppm.abs() < 10_000.0) {
        return Err(format!("{key}: {ppm:?} out of range (finite, |ppm| < 10000)"));
    }
    Ok(())
}

/// Clocks from 1 kHz to 1 GHz: the period in ps is never 0.
fn check_clock(key: &str, hz: u64) -> Result<(), String> {
    if !(1_000..=1_000_000_000).contains(&hz) {
        return Err(format!("{key}: {hz} (must be 1 kHz ..= 1 GHz)"));
    }
    Ok(())
}

fn check_phase(key: &str, phase: Option<u64>, period: u64) -> Result<(), String> {
    match phase {
        Some(p) if p >= period => Err(format!("{key}: {p} (the first clock edge comes within one period, {period} ps)")),
        _ => Ok(()),
    }
}

fn check_delay(key: &str, ps: u64) -> Result<(), String> {
    if ps > MAX_DELAY_PS {
        return Err(format!("{key}: {ps} (at most {MAX_DELAY_PS} ps)"));
    }
    Ok(())
}
