//! Generator configuration, read from TOML. Unknown keys are errors, and
//! every value is checked before anything is generated.

use anyhow::{bail, Context, Result};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// CAN bit timing in time quanta (real values, not the register encoding).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BitTiming {
    /// Prescaler: clocks per time quantum, 1..=32.
    pub brp: u32,
    /// Propagation segment, 1..=8 TQ.
    pub prop: u32,
    /// Phase segment 1, 1..=8 TQ. Phase segment 2 is max(PH1, IPT = 2).
    pub ph1: u32,
    /// Synchronisation jump width, 1..=min(4, PH1) TQ.
    pub sjw: u32,
    /// Triple sampling.
    pub triple: bool,
}

impl Default for BitTiming {
    /// The conformance default T10/6/4: NTQ 10, sample point 6, SJW 4.
    fn default() -> Self {
        Self { brp: 1, prop: 1, ph1: 4, sjw: 4, triple: false }
    }
}

/// Information processing time in TQ (a fixed property of the design).
pub const IPT: u32 = 2;

impl BitTiming {
    pub fn ph2(&self) -> u32 {
        self.ph1.max(IPT)
    }
    pub fn ntq(&self) -> u32 {
        1 + self.prop + self.ph1 + self.ph2()
    }
    pub fn sample_point(&self) -> u32 {
        1 + self.prop + self.ph1
    }
    /// Check the ranges of can-protocol.md §2.2.
    pub fn validate(&self) -> Result<()> {
        if !(1..=32).contains(&self.brp) {
            bail!("invalid bit timing: brp = {} (must be 1..=32)", self.brp);
        }
        if !(1..=8).contains(&self.prop) {
            bail!("invalid bit timing: prop = {} TQ (must be 1..=8)", self.prop);
        }
        if !(1..=8).contains(&self.ph1) {
            bail!("invalid bit timing: ph1 = {} TQ (must be 1..=8)", self.ph1);
        }
        if !(1..=4).contains(&self.sjw) {
            bail!("invalid bit timing: sjw = {} TQ (must be 1..=4)", self.sjw);
        }
        if self.sjw > self.ph1 {
            bail!("invalid bit timing: sjw = {} TQ exceeds ph1 = {} TQ", self.sjw, self.ph1);
        }
        let ntq = self.ntq();
        if !(8..=25).contains(&ntq) {
            bail!("invalid bit timing: 1 + prop + ph1 + ph2 = {ntq} TQ per bit (must be 8..=25)");
        }
        Ok(())
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
    /// register encoding (value - 1), see `canstar_hub::hub::HubBitTiming`.
    pub hub: canstar_hub::hub::HubConfig,
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
        assert_eq!(BitTiming::default().ntq(), 10);
        assert_eq!(BitTiming::default().sample_point(), 6);
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
