//! Bit timing configuration: the one type that carries bit timing through canstar
//! ([`BtlConfig`], real values: clocks per time quantum and segment lengths in time
//! quanta, never the "value − 1" register encoding).
//!
//! Every reader of a file converts into it at the file boundary and checks it once
//! with [`BtlConfig::check`] (the ranges of can-protocol.md §2.2, widened for the
//! SJA1000 top). Files that write the controller's register encoding (the hub's
//! `[hub.timing]`) use [`encoded`]; files where every key is optional and the
//! default depends on the file use [`TimingPatch`] (or [`encoded::deserialize_over`]). The RTL ports take the
//! register encoding from [`BtlConfig::fields`].

use serde::{Deserialize, Serialize};

/// Information processing time in TQ (can-protocol.md §2.5, C1): 2 TQ, or
/// 1 TQ when PH2 is 1 TQ ([`BtlConfig::ipt`]).
pub const IPT: u32 = 2;

/// Clocks the bit-stream logic needs from the tick clock of a sample point to
/// the tick clock of the next transmit point (the sample strobe is registered,
/// `drive` follows one clock later: can-protocol.md §2.5). A setting whose IPT
/// is shorter than this is refused.
pub const IPT_CLOCKS: u32 = 2;

/// PH2 of a setting that does not name it: max(PH1, IPT), the Bosch rule and
/// the only PH2 before PH2 became a field (C2).
pub const fn default_ph2(ph1: u32) -> u32 {
    if ph1 > IPT {
        ph1
    } else {
        IPT
    }
}

/// Bit timing configuration in real values (not value − 1). In files `ph2`
/// may be left out: it is then [`default_ph2`] = max(PH1, 2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(from = "BtlConfigFile", into = "BtlConfigFile")]
pub struct BtlConfig {
    /// Prescaler 1..128.
    pub brp: u32,
    /// PROP_SEG 1..16 (wider than §2.2's 1..8, for the SJA1000 block).
    pub prop: u32,
    /// PHASE_SEG1 1..8.
    pub ph1: u32,
    /// PHASE_SEG2 1..8 (1 only with a TQ of at least 2 clocks).
    pub ph2: u32,
    /// SJW 1..4, at most PH1 (not bounded by PH2: C22).
    pub sjw: u32,
    /// Triple sampling (optional in files, default off).
    pub triple: bool,
}

/// The file form of [`BtlConfig`]: `ph2` and `triple` optional, `ph2` written
/// only when it differs from [`default_ph2`] (so files written before PH2 was
/// a field read and write the same).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct BtlConfigFile {
    brp: u32,
    prop: u32,
    ph1: u32,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    ph2: Option<u32>,
    sjw: u32,
    #[serde(default)]
    triple: bool,
}

impl From<BtlConfigFile> for BtlConfig {
    fn from(f: BtlConfigFile) -> Self {
        let ph2 = f.ph2.unwrap_or(default_ph2(f.ph1));
        BtlConfig { brp: f.brp, prop: f.prop, ph1: f.ph1, ph2, sjw: f.sjw, triple: f.triple }
    }
}

impl From<BtlConfig> for BtlConfigFile {
    fn from(t: BtlConfig) -> Self {
        let ph2 = (t.ph2 != default_ph2(t.ph1)).then_some(t.ph2);
        BtlConfigFile { brp: t.brp, prop: t.prop, ph1: t.ph1, ph2, sjw: t.sjw, triple: t.triple }
    }
}

impl BtlConfig {
    /// Build from real values, PH2 = max(PH1, 2) ([`default_ph2`]).
    pub const fn new(brp: u32, prop: u32, ph1: u32, sjw: u32) -> Self {
        Self { brp, prop, ph1, ph2: default_ph2(ph1), sjw, triple: false }
    }
    /// The same setting with PH2 = `ph2` TQ.
    pub const fn with_ph2(self, ph2: u32) -> Self {
        Self { ph2, ..self }
    }
    /// From the host fields (value − 1 encoding); out-of-range bits ignored.
    pub fn from_fields(brp: u32, prop: u32, ph1: u32, ph2: u32, sjw: u32, triple: bool) -> Self {
        Self {
            brp: (brp & 127) + 1,
            prop: (prop & 15) + 1,
            ph1: (ph1 & 7) + 1,
            ph2: (ph2 & 7) + 1,
            sjw: (sjw & 3) + 1,
            triple,
        }
    }
    /// The host fields (value − 1): (brp, prop, ph1, ph2, sjw).
    pub fn fields(&self) -> (u32, u32, u32, u32, u32) {
        (self.brp - 1, self.prop - 1, self.ph1 - 1, self.ph2 - 1, self.sjw - 1)
    }
    /// Information processing time in TQ (§2.5): min(PH2, [`IPT`]), so that
    /// a bit with PH2 = 1 TQ ends at its normal end.
    pub fn ipt(&self) -> u32 {
        self.ph2.min(IPT)
    }
    /// Sample point, TQ from the start of the bit.
    pub fn sp(&self) -> u32 {
        1 + self.prop + self.ph1
    }
    /// Bit time in TQ.
    pub fn ntq(&self) -> u32 {
        self.sp() + self.ph2
    }
    /// Is the configuration accepted (§2.2)?
    pub fn is_valid(&self) -> bool {
        self.check().is_ok()
    }
    /// The ranges of §2.2 (as widened for the SJA1000 top), with a message
    /// naming the first value out of range and why. The one bit-timing check
    /// that the configuration, scenario and network file readers all use; the
    /// RTL refuses the same settings (`cfg_err`).
    pub fn check(&self) -> Result<(), String> {
        if !(1..=128).contains(&self.brp) {
            return Err(format!("brp = {} clocks per TQ (must be 1..=128)", self.brp));
        }
        if !(1..=16).contains(&self.prop) {
            return Err(format!("prop = {} TQ (must be 1..=16)", self.prop));
        }
        if !(1..=8).contains(&self.ph1) {
            return Err(format!("ph1 = {} TQ (must be 1..=8)", self.ph1));
        }
        if !(1..=8).contains(&self.ph2) {
            return Err(format!("ph2 = {} TQ (must be 1..=8)", self.ph2));
        }
        if !(1..=4).contains(&self.sjw) {
            return Err(format!("sjw = {} TQ (must be 1..=4)", self.sjw));
        }
        if self.sjw > self.ph1 {
            return Err(format!("sjw = {} TQ exceeds ph1 = {} TQ", self.sjw, self.ph1));
        }
        if self.ipt() * self.brp < IPT_CLOCKS {
            return Err(format!(
                "ph2 = {} TQ with brp = {} clock per TQ: the information processing time after a sample point is \
                 {IPT_CLOCKS} clocks, so PH2 = 1 TQ needs brp >= {IPT_CLOCKS}",
                self.ph2, self.brp
            ));
        }
        if !(8..=25).contains(&self.ntq()) {
            return Err(format!("1 + prop + ph1 + ph2 = {} TQ per bit (must be 8..=25)", self.ntq()));
        }
        Ok(())
    }
    /// T10/6/4 (default timing, PROP 1, PH1 4, SJW 4).
    pub const T10_6_4: Self = Self::new(1, 1, 4, 4);
    /// T25/17/1 (PROP 8, PH1 8, SJW 1).
    pub const T25_17_1: Self = Self::new(1, 8, 8, 1);
    /// T10/8/1 (PROP 5, PH1 2, SJW 1).
    pub const T10_8_1: Self = Self::new(1, 5, 2, 1);
    /// T10/6/2 (PROP 1, PH1 4, SJW 2).
    pub const T10_6_2: Self = Self::new(1, 1, 4, 2);
    /// Same timing with another prescaler.
    pub const fn with_brp(self, brp: u32) -> Self {
        Self { brp, ..self }
    }
}

/// A bit timing where every key may be left out: the keys given replace those
/// of a file-specific default ([`TimingPatch::over`]). A `ph2` left out is
/// max(PH1, 2) of the resulting PH1 ([`default_ph2`]), whatever the default's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimingPatch {
    pub brp: Option<u32>,
    pub prop: Option<u32>,
    pub ph1: Option<u32>,
    pub ph2: Option<u32>,
    pub sjw: Option<u32>,
    pub triple: Option<bool>,
}

impl TimingPatch {
    /// `base` with the keys this patch gives.
    pub fn over(self, base: BtlConfig) -> BtlConfig {
        let ph1 = self.ph1.unwrap_or(base.ph1);

        BtlConfig {
            brp: self.brp.unwrap_or(base.brp),
            prop: self.prop.unwrap_or(base.prop),
            ph1,
            ph2: self.ph2.unwrap_or(default_ph2(ph1)),
            sjw: self.sjw.unwrap_or(base.sjw),
            triple: self.triple.unwrap_or(base.triple),
        }
    }
}

/// Serde form of a [`BtlConfig`] in the controller's register encoding (every field
/// the value − 1, no triple sampling). Writing: `#[serde(serialize_with =
/// "canstar_hdl::timing::encoded::serialize")]`; reading, with the keys left out taken
/// from a file-specific default: [`encoded::deserialize_over`]. `ph2` is optional in
/// both directions: left out it is max(PH1, 2) ([`super::default_ph2`]), and it is
/// written only when it differs from that. Values that do not fit the ports
/// (brp > 127, prop > 15, ph1 > 7, ph2 > 7, sjw > 3) are rejected when read.
pub mod encoded {
    use super::{default_ph2, BtlConfig};
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    #[derive(Serialize)]
    struct Encoded {
        brp: u32,
        prop: u32,
        ph1: u32,
        #[serde(skip_serializing_if = "Option::is_none")]
        ph2: Option<u32>,
        sjw: u32,
    }

    #[derive(Deserialize)]
    #[serde(deny_unknown_fields)]
    struct EncodedPatch {
        brp: Option<u32>,
        prop: Option<u32>,
        ph1: Option<u32>,
        ph2: Option<u32>,
        sjw: Option<u32>,
    }

    pub fn serialize<S: Serializer>(t: &BtlConfig, s: S) -> Result<S::Ok, S::Error> {
        let (brp, prop, ph1, ph2, sjw) = t.fields();
        let ph2 = (t.ph2 != default_ph2(t.ph1)).then_some(ph2);
        Encoded { brp, prop, ph1, ph2, sjw }.serialize(s)
    }

    /// Read an encoded timing; keys left out keep `base`'s values (`ph2`:
    /// max(PH1, 2) of the resulting PH1).
    pub fn deserialize_over<'de, D: Deserializer<'de>>(d: D, base: BtlConfig) -> Result<BtlConfig, D::Error> {
        let p = EncodedPatch::deserialize(d)?;
        let (b0, b1, b2, _, b4) = base.fields();
        let (brp, prop, ph1, sjw) =
            (p.brp.unwrap_or(b0), p.prop.unwrap_or(b1), p.ph1.unwrap_or(b2), p.sjw.unwrap_or(b4));
        let ph2 = p.ph2.unwrap_or(default_ph2(ph1.saturating_add(1)) - 1);
        if brp > 127 || prop > 15 || ph1 > 7 || ph2 > 7 || sjw > 3 {
            return Err(serde::de::Error::custom(format!(
                "register encoding out of range: brp = {brp}, prop = {prop}, ph1 = {ph1}, ph2 = {ph2}, sjw = {sjw} (at most 127, 15, 7, 7, 3)"
            )));
        }
        Ok(BtlConfig::from_fields(brp, prop, ph1, ph2, sjw, false))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encoded_round_trip_and_range() {
        fn base<'de, D: serde::Deserializer<'de>>(d: D) -> Result<BtlConfig, D::Error> {
            encoded::deserialize_over(d, BtlConfig::T10_6_4)
        }
        #[derive(Serialize, Deserialize, PartialEq, Debug)]
        struct W {
            #[serde(serialize_with = "encoded::serialize", deserialize_with = "base")]
            t: BtlConfig,
        }
        let w: W = toml::from_str("[t]\nbrp = 1\nprop = 2\nph1 = 1\nsjw = 0\n").unwrap();
        assert_eq!(w.t, BtlConfig::new(2, 3, 2, 1));
        assert_eq!(toml::from_str::<W>(&toml::to_string(&w).unwrap()).unwrap(), w);
        let e = toml::from_str::<W>("[t]\nbrp = 1\nprop = 16\nph1 = 1\nsjw = 0\n").unwrap_err();
        assert!(e.to_string().contains("out of range"), "{e}");
        // keys left out keep the default's
        let w: W = toml::from_str("[t]\nsjw = 1\n").unwrap();
        assert_eq!(w.t, BtlConfig { sjw: 2, ..BtlConfig::T10_6_4 });
        // ph2: optional, written only when not max(PH1, 2)
        assert!(!toml::to_string(&w).unwrap().contains("ph2"));
        let w: W = toml::from_str("[t]\nbrp = 1\nph1 = 3\nph2 = 0\n").unwrap();
        assert_eq!(w.t, BtlConfig { brp: 2, ..BtlConfig::T10_6_4.with_ph2(1) });
        assert_eq!(toml::from_str::<W>(&toml::to_string(&w).unwrap()).unwrap(), w);
        assert!(toml::from_str::<W>("[t]\nph2 = 8\n").unwrap_err().to_string().contains("out of range"));
    }

    #[test]
    fn patch_replaces_only_the_keys_given() {
        let p: TimingPatch = toml::from_str("prop = 5\nsjw = 2\n").unwrap();
        let base = BtlConfig::T10_6_4;
        assert_eq!(p.over(base), BtlConfig { prop: 5, sjw: 2, ..base });
        assert!(toml::from_str::<TimingPatch>("prpo = 5\n").is_err());
    }

    #[test]
    fn real_values_all_required_but_triple() {
        let t: BtlConfig = toml::from_str("brp = 4\nprop = 3\nph1 = 2\nsjw = 1\n").unwrap();
        assert_eq!(t, BtlConfig::new(4, 3, 2, 1));
        assert!(toml::from_str::<BtlConfig>("brp = 4\nprop = 3\nph1 = 2\n").is_err());
        assert_eq!(t.check(), Ok(()));
        assert!(BtlConfig::new(4, 3, 2, 3).check().unwrap_err().contains("sjw"));
    }

    #[test]
    fn ph2_is_optional_and_defaults_to_max_ph1_2() {
        let t: BtlConfig = toml::from_str("brp = 4\nprop = 3\nph1 = 1\nsjw = 1\n").unwrap();
        assert_eq!(t.ph2, 2);
        let t: BtlConfig = toml::from_str("brp = 4\nprop = 3\nph1 = 5\nsjw = 1\n").unwrap();
        assert_eq!(t.ph2, 5);
        // written only when it is not the default, so old files round-trip unchanged
        assert!(!toml::to_string(&t).unwrap().contains("ph2"));
        let t: BtlConfig = toml::from_str("brp = 4\nprop = 3\nph1 = 5\nph2 = 1\nsjw = 1\n").unwrap();
        assert_eq!(t, BtlConfig::new(4, 3, 5, 1).with_ph2(1));
        assert!(toml::to_string(&t).unwrap().contains("ph2 = 1"));
        assert_eq!(toml::from_str::<BtlConfig>(&toml::to_string(&t).unwrap()).unwrap(), t);
        // patches: a missing ph2 follows the resulting ph1
        let p: TimingPatch = toml::from_str("ph1 = 6\n").unwrap();
        assert_eq!(p.over(BtlConfig::T10_8_1).ph2, 6);
        let p: TimingPatch = toml::from_str("ph2 = 1\nbrp = 2\n").unwrap();
        assert_eq!(p.over(BtlConfig::T10_8_1), BtlConfig::T10_8_1.with_brp(2).with_ph2(1));
    }

    #[test]
    fn ph2_checks_name_the_field_and_the_reason() {
        // PH2 = 1 TQ needs a TQ of at least IPT_CLOCKS clocks
        let t = BtlConfig::new(1, 5, 3, 1).with_ph2(1);
        let e = t.check().unwrap_err();
        assert!(e.contains("ph2 = 1") && e.contains("brp >= 2") && e.contains("information processing"), "{e}");
        assert_eq!(t.with_brp(2).check(), Ok(()));
        assert_eq!((t.ipt(), BtlConfig::T10_8_1.ipt()), (1, 2));
        // SJW is bounded by PH1, not by PH2 (C22)
        assert_eq!(BtlConfig::new(2, 5, 4, 4).with_ph2(1).check(), Ok(()));
        assert!(BtlConfig::new(2, 5, 3, 4).with_ph2(1).check().unwrap_err().contains("exceeds ph1"));
        assert!(BtlConfig::new(2, 5, 3, 1).with_ph2(9).check().unwrap_err().contains("ph2 = 9"));
        assert!(BtlConfig::new(2, 1, 2, 1).with_ph2(3).check().unwrap_err().contains("must be 8..=25"));
    }
}
