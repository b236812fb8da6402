//! Generator configuration, read from TOML. Unknown keys are errors, and
//! every value is checked before anything is generated.

use anyhow::{bail, Result};
use serde::{Deserialize, Serialize};
use std::path::Path;

use canstar_controller::core::RecRule;
use canstar_hdl::timing::{BtlConfig, TimingPatch};

/// Power-up bit timing of the SJA1000-compatible top: the values a hardware
/// reset loads into BTR0/BTR1 (a real SJA1000 leaves them undefined; the host
/// may rewrite them in reset mode as usual), as `[bit_timing]` in time quanta
/// (not the register encoding); every key is optional. The default is the
/// ReCANcentrate reference profile on the XSA-3S1000's 14.74 MHz clock: 2
/// clocks per TQ, 8 TQ per bit, sample point after 6 TQ, SJW 1: 921.25 kbit/s.
pub const SJA1000_POWER_UP: BtlConfig = BtlConfig::new(2, 3, 2, 1);

fn power_up_default() -> BtlConfig {
    SJA1000_POWER_UP
}

fn power_up_timing<'de, D: serde::Deserializer<'de>>(d: D) -> std::result::Result<BtlConfig, D::Error> {
    Ok(TimingPatch::deserialize(d)?.over(SJA1000_POWER_UP))
}

/// Check a power-up timing: the ranges of can-protocol.md §2.2 (the bit timing
/// logic's own check, [`BtlConfig::check`]), that BTR0/BTR1 can express it
/// (clocks per TQ = 2·(BRP+1), TSEG1 = PROP + PH1 <= 16, TSEG2 = PH2) and that
/// the SJA1000 top maps those registers back onto the same bit
/// ([`canstar_controller::sja1000::timing::core_timing`]: same clocks per TQ,
/// sample point, bit time and SJW).
pub fn validate_power_up(t: &BtlConfig) -> Result<()> {
    if t.brp < 2 || t.brp > 128 || t.brp % 2 != 0 {
        bail!("bit_timing: invalid bit timing: brp = {} clocks per TQ (the SJA1000 top has 2·(BRP+1): even, 2..=128)", t.brp);
    }
    t.check().map_err(|e| anyhow::anyhow!("bit_timing: invalid bit timing: {e}"))?;
    if t.prop + t.ph1 > 16 {
        bail!("bit_timing: invalid bit timing: prop + ph1 = TSEG1 = {} TQ (must be <= 16)", t.prop + t.ph1);
    }
    let (b0, b1) = btr(t);
    let c = canstar_controller::sja1000::timing::core_timing(b0, b1).map_err(|e| anyhow::anyhow!("bit_timing: {e}"))?;
    let key = |t: &BtlConfig| (t.brp, t.sp(), t.ntq(), t.sjw, t.triple);
    if key(&c) != key(t) {
        bail!("bit_timing: BTR0/BTR1 0x{b0:02X}/0x{b1:02X} map onto {c:?}, not onto the same bit as {t:?}");
    }
    Ok(())
}

/// The BTR0 and BTR1 register values of a (valid) power-up timing.
pub fn btr(t: &BtlConfig) -> (u8, u8) {
    let btr0 = ((t.sjw - 1) << 6) | (t.brp / 2 - 1);
    let btr1 = ((t.triple as u32) << 7) | ((t.ph2 - 1) << 4) | (t.prop + t.ph1 - 1);
    (btr0 as u8, btr1 as u8)
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

/// The TOML spelling of [`RecRule`] (`controller.rec_rule`): serde's remote
/// definition, checked against the controller's enum by the compiler.
#[derive(Serialize, Deserialize)]
#[serde(remote = "RecRule")]
enum RecRuleToml {
    /// `"iso"`: REC − 1 at the ACK slot once the own ACK is read back
    /// dominant (ISO 11898-1, ISO 16845-1 7.6.7, 7.6.8, 7.6.16).
    #[serde(rename = "iso")]
    Iso,
    /// `"bosch-1999"`: REC − 1 at a recessive End_Of_Frame bit 7 only (the
    /// 1999 reference programs).
    #[serde(rename = "bosch-1999")]
    Bosch1999,
}

/// The CAN controller designs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Controller {
    /// Also emit the SJA1000-compatible (PeliCAN) register block on Wishbone
    /// (`canstar_sja1000`, 64-byte RX FIFO, acceptance filters) and its board
    /// pin files, and the slcan adapter around it (`canstar_slcan`); `false`
    /// emits only the core with its native interface.
    pub host_interface: bool,
    /// The bit at which a receiver counts a successful reception in REC
    /// (can-protocol.md C13), in the core and the SJA1000 top. `eof7_rec`,
    /// its name before it also covered the ACK slot, is still read.
    #[serde(with = "RecRuleToml", alias = "eof7_rec")]
    pub rec_rule: RecRule,
}

impl Default for Controller {
    fn default() -> Self {
        Self { host_interface: true, rec_rule: RecRule::Iso }
    }
}

/// `[slcan]`: the USB-to-CAN adapter top (`canstar_slcan`, controller/src/slcan/).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Slcan {
    /// The nominal design clock in Hz (the `Sn` bit-rate table and the UART
    /// divider are computed for it).
    pub clock_hz: u64,
    /// The host UART baud rate (the integer divider must be within 2 %).
    pub baud: u64,
}

impl Default for Slcan {
    fn default() -> Self {
        Self {
            clock_hz: canstar_controller::slcan::DEFAULT_CLOCK_HZ,
            baud: canstar_controller::slcan::DEFAULT_BAUD,
        }
    }
}

impl Slcan {
    /// The generation-time parameters; an error names the key.
    pub fn params(&self) -> Result<canstar_controller::slcan::SlcanParams> {
        if self.clock_hz == 0 {
            bail!("slcan.clock_hz: 0 (must be positive)");
        }
        if self.baud == 0 {
            bail!("slcan.baud: 0 (must be positive)");
        }
        let p = canstar_controller::slcan::SlcanParams::new(self.clock_hz, self.baud)
            .map_err(|e| anyhow::anyhow!("slcan.baud: {e}"))?;
        if p.table.iter().all(|e| e.is_none()) {
            bail!("slcan.clock_hz: {} Hz makes none of the slcan bit rates S0..S9 exactly", self.clock_hz);
        }
        Ok(p)
    }
}

/// The whole generator configuration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Config {
    /// `[bit_timing]`: the SJA1000 top's power-up BTR0/BTR1 ([`SJA1000_POWER_UP`] for missing keys).
    #[serde(deserialize_with = "power_up_timing", default = "power_up_default")]
    pub bit_timing: BtlConfig,
    pub rtl: Rtl,
    pub controller: Controller,
    /// The star hub (defaults: the reference ReCANcentrate hub, N = 3, M = 2,
    /// 14.74 MHz, 8 TQ of 2 clocks per bit). Bit-timing fields here use the
    /// register encoding (value - 1), read into `canstar_hdl::timing::BtlConfig`.
    pub hub: canstar_hub::config::HubConfig,
    pub slcan: Slcan,
}

impl Default for Config {
    fn default() -> Self {
        Config { bit_timing: SJA1000_POWER_UP, rtl: Rtl::default(), controller: Controller::default(), hub: Default::default(), slcan: Slcan::default() }
    }
}

impl Config {
    pub fn from_toml(text: &str) -> Result<Self> {
        let c: Config = toml::from_str(text).map_err(|e| anyhow::anyhow!("malformed configuration: {e}"))?;
        c.validate()?;
        Ok(c)
    }
    /// Read a configuration file (bounded, see [`crate::input`]); every error
    /// starts with the path and names the key.
    pub fn load(path: &Path) -> Result<Self> {
        let text = crate::input::read_toml(path)?;
        Self::from_toml(&text).map_err(|e| anyhow::anyhow!("{}: {e:#}", path.display()))
    }
    /// Check every value (the one place for this format).
    pub fn validate(&self) -> Result<()> {
        validate_power_up(&self.bit_timing)?;
        if !(1..=2).contains(&self.rtl.sync_depth) {
            bail!("rtl.sync_depth: {} (must be 1 or 2)", self.rtl.sync_depth);
        }
        self.hub.validate().map_err(|e| anyhow::anyhow!("hub: invalid [hub] configuration: {e}"))?;
        self.slcan.params()?;
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
        assert_eq!(SJA1000_POWER_UP.ntq(), 8);
        assert_eq!(SJA1000_POWER_UP.sp(), 6);
        assert_eq!(btr(&SJA1000_POWER_UP), (0x00, 0x14));
        let t = BtlConfig { triple: true, ..BtlConfig::new(128, 8, 8, 4) };
        validate_power_up(&t).unwrap();
        assert_eq!(btr(&t), (0xFF, 0xFF));
        // a partial [bit_timing] keeps the power-up default for the other keys
        let c = Config::from_toml("[bit_timing]\nprop = 4\n").unwrap();
        assert_eq!(c.bit_timing, BtlConfig { prop: 4, ..SJA1000_POWER_UP });
        let e = Config::from_toml("[bit_timing]\nbrp = 3\n").unwrap_err();
        assert!(format!("{e:#}").contains("even"), "{e:#}");
    }

    #[test]
    fn slcan_keys_are_checked() {
        let c = Config::from_toml("[slcan]\nclock_hz = 48000000\nbaud = 1000000\n").unwrap();
        assert_eq!(c.slcan.params().unwrap().clocks_per_bit, 48);
        let e = Config::from_toml("[slcan]\nclock_hz = 1000000\n").unwrap_err();
        assert!(format!("{e:#}").contains("slcan.baud") && format!("{e:#}").contains("% off"), "{e:#}");
        let e = Config::from_toml("[slcan]\nclock_hz = 0\n").unwrap_err();
        assert!(format!("{e:#}").contains("slcan.clock_hz"), "{e:#}");
        let e = Config::from_toml("[slcan]\nbaud = 0\n").unwrap_err();
        assert!(format!("{e:#}").contains("slcan.baud"), "{e:#}");
        let e = Config::from_toml("[slcan]\nbaudrate = 9600\n").unwrap_err();
        assert!(format!("{e:#}").contains("unknown field"), "{e:#}");
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

    #[test]
    fn ph2_is_a_power_up_key() {
        // 24 MHz, 500 kbit/s, 87.5 % (what can-calc-bit-timing gives for an
        // SJA1000 on a 24 MHz oscillator): 48 clocks per bit = 8 TQ of 6
        // clocks, TSEG1 = 6, TSEG2 = 1 TQ: BTR0 0x02, BTR1 0x05
        let c = Config::from_toml("[bit_timing]\nbrp = 6\nprop = 1\nph1 = 5\nph2 = 1\nsjw = 1\n").unwrap();
        assert_eq!((c.bit_timing.ntq(), c.bit_timing.sp(), c.bit_timing.ntq() * c.bit_timing.brp), (8, 7, 48));
        assert_eq!(btr(&c.bit_timing), (0x02, 0x05));
        // without ph2: max(PH1, 2), as before the key existed
        let c = Config::from_toml("[bit_timing]\nph1 = 3\n").unwrap();
        assert_eq!(c.bit_timing.ph2, 3);
        // SJW above PH2 is legal (C22), above PH1 not
        Config::from_toml("[bit_timing]\nbrp = 6\nprop = 1\nph1 = 5\nph2 = 1\nsjw = 4\n").unwrap();
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
