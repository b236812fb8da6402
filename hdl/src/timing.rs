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

/// Information processing time in TQ (can-protocol.md §2.2, C1).
pub const IPT: u32 = 2;

/// Bit timing configuration in real values (not value − 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BtlConfig {
    /// Prescaler 1..128.
    pub brp: u32,
    /// PROP_SEG 1..16 (wider than §2.2's 1..8, for the SJA1000 block).
    pub prop: u32,
    /// PHASE_SEG1 1..8.
    pub ph1: u32,
    /// SJW 1..4.
    pub sjw: u32,
    /// Triple sampling (optional in files, default off).
    #[serde(default)]
    pub triple: bool,
}

impl BtlConfig {
    /// Build from real values.
    pub const fn new(brp: u32, prop: u32, ph1: u32, sjw: u32) -> Self {
        Self { brp, prop, ph1, sjw, triple: false }
    }
    /// From the host fields (value − 1 encoding); out-of-range bits ignored.
    pub fn from_fields(brp: u32, prop: u32, ph1: u32, sjw: u32, triple: bool) -> Self {
        Self { brp: (brp & 127) + 1, prop: (prop & 15) + 1, ph1: (ph1 & 7) + 1, sjw: (sjw & 3) + 1, triple }
    }
    /// The host fields (value − 1): (brp, prop, ph1, sjw).
    pub fn fields(&self) -> (u32, u32, u32, u32) {
        (self.brp - 1, self.prop - 1, self.ph1 - 1, self.sjw - 1)
    }
    /// PH2 = max(PH1, IPT).
    pub fn ph2(&self) -> u32 {
        self.ph1.max(IPT)
    }
    /// Sample point, TQ from the start of the bit.
    pub fn sp(&self) -> u32 {
        1 + self.prop + self.ph1
    }
    /// Bit time in TQ.
    pub fn ntq(&self) -> u32 {
        self.sp() + self.ph2()
    }
    /// Is the configuration accepted (§2.2)?
    pub fn is_valid(&self) -> bool {
        self.check().is_ok()
    }
    /// The ranges of §2.2 (as widened for the SJA1000 top), with a message
    /// naming the first value out of range. The one bit-timing check that the
    /// configuration, scenario and network file readers all use.
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
        if !(1..=4).contains(&self.sjw) {
            return Err(format!("sjw = {} TQ (must be 1..=4)", self.sjw));
        }
        if self.sjw > self.ph1 {
            return Err(format!("sjw = {} TQ exceeds ph1 = {} TQ", self.sjw, self.ph1));
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
/// of a file-specific default ([`TimingPatch::over`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimingPatch {
    pub brp: Option<u32>,
    pub prop: Option<u32>,
    pub ph1: Option<u32>,
    pub sjw: Option<u32>,
    pub triple: Option<bool>,
}

impl TimingPatch {
    /// `base` with the keys this patch gives.
    pub fn over(self, base: BtlConfig) -> BtlConfig {
        BtlConfig {
            brp: self.brp.unwrap_or(base.brp),
            prop: self.prop.unwrap_or(base.prop),
            ph1: self.ph1.unwrap_or(base.ph1),
            sjw: self.sjw.unwrap_or(base.sjw),
            triple: self.triple.unwrap_or(base.triple),
        }
    }
}

/// Serde form of a [`BtlConfig`] in the controller's register encoding (every field
/// the value − 1, no triple sampling). Writing: `#[serde(serialize_with =
/// "canstar_hdl::timing::encoded::serialize")]`; reading, with the keys left out taken
/// from a file-specific default: [`encoded::deserialize_over`]. Values that do not fit
/// the ports (brp > 127, prop > 15, ph1 > 7, sjw > 3) are rejected when read.
pub mod encoded {
    use super::BtlConfig;
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    #[derive(Serialize)]
    struct Encoded {
        brp: u32,
        prop: u32,
        ph1: u32,
        sjw: u32,
    }

    #[derive(Deserialize)]
    #[serde(deny_unknown_fields)]
    struct EncodedPatch {
        brp: Option<u32>,
        prop: Option<u32>,
        ph1: Option<u32>,
        sjw: Option<u32>,
    }

    pub fn serialize<S: Serializer>(t: &BtlConfig, s: S) -> Result<S::Ok, S::Error> {
        let (brp, prop, ph1, sjw) = t.fields();
        Encoded { brp, prop, ph1, sjw }.serialize(s)
    }

    /// Read an encoded timing; keys left out keep `base`'s values.
    pub fn deserialize_over<'de, D: Deserializer<'de>>(d: D, base: BtlConfig) -> Result<BtlConfig, D::Error> {
        let p = EncodedPatch::deserialize(d)?;
        let (b0, b1, b2, b3) = base.fields();
        let (brp, prop, ph1, sjw) = (p.brp.unwrap_or(b0), p.prop.unwrap_or(b1), p.ph1.unwrap_or(b2), p.sjw.unwrap_or(b3));
        if brp > 127 || prop > 15 || ph1 > 7 || sjw > 3 {
            return Err(serde::de::Error::custom(format!(
                "register encoding out of range: brp = {brp}, prop = {prop}, ph1 = {ph1}, sjw = {sjw} (at most 127, 15, 7, 3)"
            )));
        }
        Ok(BtlConfig::from_fields(brp, prop, ph1, sjw, false))
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
}
