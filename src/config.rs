//! Generator configuration, read from TOML. Unknown keys are errors, and
//! every value is checked before anything is generated.

use anyhow::{bail, Context, Result};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Power-up bit timing of the SJA1000-compatible top: the values a hardware
/// reset loads into BTR0/BTR1 (a real SJA1000 leaves them undefined; the host
/// may rewrite them in reset mode as usual). In time quanta, not the register
/// encoding. The default is the ReCANcentrate reference profile on the
/// XSA-3S1000's 14.74 MHz clock: 2 clocks per TQ, 8 TQ per bit, sample point
/// after 6 TQ, SJW 1: 921.25 kbit/s.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BitTiming {
    /// Clocks per time quantum: 2·(BRP+1) on the SJA1000, so even, 2..=128.
    pub brp: u32,
    /// Propagation segment in TQ (TSEG1 = PROP + PH1 <= 16).
    pub prop: u32,
    /// Phase segment 1, 1..=8 TQ. Phase segment 2 (TSEG2) is max(PH1, IPT = 2).
    pub ph1: u32,
    /// Synchronisation jump width, 1..=min(4, PH1) TQ.
    pub sjw: u32,
    /// Triple sampling (BTR1 SAM).
    pub triple: bool,
}

impl Default for BitTiming {
    fn default() -> Self {
        Self { brp: 2, prop: 3, ph1: 2, sjw: 1, triple: false }
    }
}

impl BitTiming {
    fn btl(&self) -> canstar_hdl::btl::BtlConfig {
        canstar_hdl::btl::BtlConfig { triple: self.triple, ..canstar_hdl::btl::BtlConfig::new(self.brp, self.prop, self.ph1, self.sjw) }
    }
    pub fn ph2(&self) -> u32 {
        self.btl().ph2()
    }
    pub fn ntq(&self) -> u32 {
        self.btl().ntq()
    }
    pub fn sample_point(&self) -> u32 {
        self.btl().sp()
    }
    /// Check the ranges of can-protocol.md §2.2 (the bit timing logic's own
    /// check, `BtlConfig::is_valid`) and that BTR0/BTR1 can express it.
    pub fn validate(&self) -> Result<()> {
        if self.brp < 2 || self.brp > 128 || self.brp % 2 != 0 {
            bail!("invalid bit timing: brp = {} clocks per TQ (the SJA1000 top has 2·(BRP+1): even, 2..=128)", self.brp);
        }
        if self.prop + self.ph1 > 16 {
            bail!("invalid bit timing: prop + ph1 = TSEG1 = {} TQ (must be <= 16)", self.prop + self.ph1);
        }
        self.btl().check().map_err(|e| anyhow::anyhow!("invalid bit timing: {e}"))?;
        Ok(())
    }
    /// The BTR0 and BTR1 register values of this timing.
    pub fn btr(&self) -> (u8, u8) {
        let btr0 = ((self.sjw - 1) << 6) | (self.brp / 2 - 1);
        let btr1 = ((self.triple as u32) << 7) | ((self.ph2() - 1) << 4) | (self.prop + self.ph1 - 1);
        (btr0 as u8, btr1 as u8)
    }
}

/// RTL-level options shared by the designs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Rtl {
    /// Input synchroniser depth: 1 or 2 flip-flops.
    pub sync_depth: usize,
}

impl Default for Rtl {
    fn default() -> Self {
        Self { sync_depth: 2 }
    }
}

/// The CAN controller designs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Controller {
    /// Also emit the SJA1000-compatible (PeliCAN) register block on Wishbone
    /// (`canstar_sja1000`, 64-byte RX FIFO, acceptance filters) and its board
    /// pin files; `false` emits only the core with its native interface.
    pub host_interface: bool,
}

impl Default for Controller {
    fn default() -> Self {
        Self { host_interface: true }
    }
}

/// The whole generator configuration.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Config {
    pub bit_timing: BitTiming,
    pub rtl: Rtl,
    pub controller: Controller,
    /// The star hub (defaults: the reference ReCANcentrate hub, N = 3, M = 2,
    /// 14.74 MHz, 8 TQ of 2 clocks per bit). Bit-timing fields here use the
    /// register encoding (value - 1), see `canstar_hub::config::HubBitTiming`.
    pub hub: canstar_hub::config::HubConfig,
}

impl Config {
    pub fn from_toml(text: &str) -> Result<Self> {
        let c: Config = toml::from_str(text).map_err(|e| anyhow::anyhow!("malformed configuration: {e}"))?;
        c.validate()?;
        Ok(c)
    }
    pub fn load(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).with_context(|| format!("reading config {}", path.display()))?;
        Self::from_toml(&text).with_context(|| format!("in config {}", path.display()))
    }
    pub fn validate(&self) -> Result<()> {
        self.bit_timing.validate()?;
        if !(1..=2).contains(&self.rtl.sync_depth) {
            bail!("invalid rtl.sync_depth = {} (must be 1 or 2)", self.rtl.sync_depth);
        }
        self.hub.validate().map_err(|e| anyhow::anyhow!("invalid [hub] configuration: {e}"))?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid() {
        Config::default().validate().unwrap();
        // the reference profile: 8 TQ, sample point after 6, BTR0 0x00, BTR1 0x14
        assert_eq!(BitTiming::default().ntq(), 8);
        assert_eq!(BitTiming::default().sample_point(), 6);
        assert_eq!(BitTiming::default().btr(), (0x00, 0x14));
        let t = BitTiming { brp: 128, prop: 8, ph1: 8, sjw: 4, triple: true };
        t.validate().unwrap();
        assert_eq!(t.btr(), (0xFF, 0xFF));
        let e = Config::from_toml("[bit_timing]\nbrp = 3\n").unwrap_err();
        assert!(format!("{e:#}").contains("even"), "{e:#}");
    }

    #[test]
    fn unknown_key_is_rejected() {
        let e = Config::from_toml("[bit_timing]\nbrp = 2\nfoo = 1\n").unwrap_err();
        assert!(format!("{e:#}").contains("unknown field"), "{e:#}");
    }

    #[test]
    fn impossible_bit_timing_is_rejected() {
        // 1 + 8 + 8 + 8 = 25 TQ is the longest legal bit ...
        Config::from_toml("[bit_timing]\nprop = 8\nph1 = 8\nsjw = 1\n").unwrap();
        // ... and 1 + 1 + 2 + 2 = 6 TQ is too short.
        let e = Config::from_toml("[bit_timing]\nprop = 1\nph1 = 2\nsjw = 1\n").unwrap_err();
        assert!(format!("{e:#}").contains("must be 8..=25"), "{e:#}");
        let e = Config::from_toml("[bit_timing]\nbrp = 0\n").unwrap_err();
        assert!(format!("{e:#}").contains("brp"), "{e:#}");
    }

    #[test]
    fn sjw_above_ph1_is_rejected() {
        let e = Config::from_toml("[bit_timing]\nph1 = 2\nsjw = 3\nprop = 4\n").unwrap_err();
        assert!(format!("{e:#}").contains("exceeds ph1"), "{e:#}");
    }
}

#[cfg(test)]
mod shipped {
    use super::*;

    /// `configs/default.toml` documents every key; it must stay equal to the defaults.
    #[test]
    fn shipped_default_config_equals_the_defaults() {
        let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/default.toml");
        assert_eq!(Config::load(&p).unwrap(), Config::default());
        let c = Config::from_toml("[hub.fault_injection]\npoint = { Uplink = 0 }\nkind = \"StuckDominant\"\nstart_field = 6\n").unwrap();
        assert!(c.hub.fault_injection.is_some());
    }
}
