//! iCE40 PLL settings: the `SB_PLL40_CORE` (simple feedback) parameters that
//! bring a board's oscillator closest to a design's clock, and the accuracy
//! check `canstar build` applies to them.
//!
//! The ranges are those of Lattice's iCE40 sysCLOCK PLL Design and Usage Guide
//! (TN1251): reference clock and phase-detector input 10..133 MHz (PFD =
//! f_in / (DIVR + 1), DIVR 0..15), VCO 533..1066 MHz (VCO = PFD · (DIVF + 1),
//! DIVF 0..127 with simple feedback), PLLOUT = VCO / 2^DIVQ (DIVQ 1..6)
//! 16..275 MHz, FILTER_RANGE from the PFD frequency. `PLLOUT_SELECT =
//! "GENCLK_HALF"` halves PLLOUT, which the hub needs: its 14.74 MHz is below the
//! PLL's 16 MHz minimum.
//!
//! Why not `rust_hdl_fpga_support::lattice::ice40::ice_pll::ICE40PLLBlock`:
//! its frequencies are const generics (`ICE40PLLBlock<FIN, FOUT>`), fixed at
//! compile time, while a board file's oscillator and a configuration's hub
//! clock are run-time data; its search panics (rather than failing) below
//! 16 MHz out, so it cannot serve the hub at all; its settings are private (only
//! its Verilog text shows them) and it has no `GENCLK_HALF`. The search here is
//! canstar's own, over the same ranges; the unit tests check that it finds the
//! same frequency as the library's monomorphic instances for the clocks the
//! library can make (the controller's 16 MHz and twice the hub's clock from
//! the Alchitry Cu's 100 MHz).

use anyhow::{bail, Result};

/// Default accuracy a PLL setting must reach, in ppm of the design clock. The
/// CAN bit timing of the reference profiles (8 TQ, SJW 1, PH1 = PH2 = 2 TQ)
/// tolerates 6250 ppm per node (ISO 11898-1: min(SJW / (20 NBT), min(PH1, PH2) /
/// (2 (13 NBT - PH2)))); the PLL may spend under a third of it, leaving the
/// rest to the oscillator itself and to the other nodes.
pub const DEFAULT_TOLERANCE_PPM: f64 = 2000.0;

/// One `SB_PLL40_CORE` setting and what it gives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PllSettings {
    /// Reference (board oscillator) frequency in Hz.
    pub fin_hz: u64,
    pub divr: u8,
    pub divf: u8,
    pub divq: u8,
    /// `PLLOUT_SELECT = "GENCLK_HALF"`: the output is PLLOUT / 2.
    pub half: bool,
}

impl PllSettings {
    /// Phase-detector input frequency, Hz.
    pub fn pfd_hz(&self) -> f64 {
        self.fin_hz as f64 / (self.divr as f64 + 1.0)
    }

    /// VCO frequency, Hz.
    pub fn vco_hz(&self) -> f64 {
        self.pfd_hz() * (self.divf as f64 + 1.0)
    }

    /// PLLOUT (before the optional halving), Hz.
    pub fn pllout_hz(&self) -> f64 {
        self.vco_hz() / f64::from(1u32 << self.divq)
    }

    /// The design clock the setting gives, Hz.
    pub fn fout_hz(&self) -> f64 {
        if self.half {
            self.pllout_hz() / 2.0
        } else {
            self.pllout_hz()
        }
    }

    /// Error of the design clock against `target_hz`, in ppm.
    pub fn error_ppm(&self, target_hz: u64) -> f64 {
        (self.fout_hz() / target_hz as f64 - 1.0) * 1e6
    }

    /// FILTER_RANGE for the PFD frequency (TN1251's table).
    pub fn filter_range(&self) -> u8 {
        let pfd_mhz = self.pfd_hz() / 1e6;
        [17.0, 26.0, 44.0, 66.0, 101.0].iter().position(|&lim| pfd_mhz < lim).map_or(6, |i| i as u8 + 1)
    }

    /// Every frequency within the PLL's ranges?
    pub fn in_range(&self) -> bool {
        let mhz = |hz: f64| hz / 1e6;
        (10.0..=133.0).contains(&mhz(self.fin_hz as f64))
            && (10.0..=133.0).contains(&mhz(self.pfd_hz()))
            && (533.0..=1066.0).contains(&mhz(self.vco_hz()))
            && (16.0..=275.0).contains(&mhz(self.pllout_hz()))
            && self.divr <= 15
            && self.divf <= 127
            && (1..=6).contains(&self.divq)
    }

    /// The `SB_PLL40_CORE` parameter list (`#( ... )` contents).
    pub fn parameters(&self) -> String {
        format!(
            ".FEEDBACK_PATH(\"SIMPLE\"), .PLLOUT_SELECT(\"{}\"), .DIVR(4'd{}), .DIVF(7'd{}), .DIVQ(3'd{}), .FILTER_RANGE(3'd{})",
            if self.half { "GENCLK_HALF" } else { "GENCLK" },
            self.divr,
            self.divf,
            self.divq,
            self.filter_range()
        )
    }

    /// "DIVR 6, DIVF 65, DIVQ 5, GENCLK_HALF: PFD 14.286 MHz, VCO 942.857 MHz".
    pub fn describe(&self) -> String {
        format!(
            "DIVR {}, DIVF {}, DIVQ {}, FILTER_RANGE {}{}: PFD {:.3} MHz, VCO {:.3} MHz",
            self.divr,
            self.divf,
            self.divq,
            self.filter_range(),
            if self.half { ", PLLOUT_SELECT GENCLK_HALF" } else { "" },
            self.pfd_hz() / 1e6,
            self.vco_hz() / 1e6
        )
    }
}

/// The in-range setting whose design clock is closest to `target_hz` (ties: the
/// full-rate output first, then the lowest DIVR, DIVF, DIVQ); `None` when the
/// reference clock is outside 10..133 MHz or no setting is in range.
pub fn closest(fin_hz: u64, target_hz: u64) -> Option<PllSettings> {
    let mut best: Option<(f64, PllSettings)> = None;
    for half in [false, true] {
        for divr in 0..=15u8 {
            for divf in 0..=127u8 {
                for divq in 1..=6u8 {
                    let s = PllSettings { fin_hz, divr, divf, divq, half };
                    if !s.in_range() {
                        continue;
                    }
                    let err = (s.fout_hz() - target_hz as f64).abs();
                    if best.is_none_or(|(e, _)| err < e) {
                        best = Some((err, s));
                    }
                }
            }
        }
    }
    best.map(|(_, s)| s)
}

/// The setting for a design clock of `target_hz` from the board oscillator
/// `fin_hz`, within `tolerance_ppm`; `board` names the board file in messages
/// (the key is its `clock.hz`).
pub fn choose(fin_hz: u64, target_hz: u64, tolerance_ppm: f64, board: &str) -> Result<PllSettings> {
    if !(10_000_000..=133_000_000).contains(&fin_hz) {
        bail!(
            "{board}: clock.hz: {fin_hz} Hz is outside the iCE40 PLL's reference range 10..133 MHz, \
             so no {:.6} MHz design clock can be derived from it",
            target_hz as f64 / 1e6
        );
    }
    let Some(s) = closest(fin_hz, target_hz) else {
        bail!("{board}: clock.hz: no iCE40 PLL setting turns {fin_hz} Hz into anything near {target_hz} Hz (output 8..137.5 MHz)");
    };
    let e = s.error_ppm(target_hz);
    if e.abs() > tolerance_ppm {
        bail!(
            "{board}: clock.hz: the iCE40 PLL's closest setting to {:.6} MHz from {} Hz gives {:.6} MHz, {e:+.0} ppm, \
             outside the tolerance of ±{tolerance_ppm} ppm ({}); use another oscillator or design clock, or --pll-tolerance-ppm",
            target_hz as f64 / 1e6,
            fin_hz,
            s.fout_hz() / 1e6,
            s.describe()
        );
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rust_hdl::core::prelude::{Logic, Verilog};
    use rust_hdl_fpga_support::lattice::ice40::ice_pll::ICE40PLLBlock;

    #[test]
    fn hub_and_controller_clocks_from_100_mhz() {
        // The hub: 14.74 MHz is below PLLOUT's 16 MHz, so GENCLK_HALF of 29.464 MHz.
        let h = choose(100_000_000, 14_740_000, DEFAULT_TOLERANCE_PPM, "b").unwrap();
        assert!(h.half && h.in_range(), "{h:?}");
        assert_eq!((h.divr, h.divf, h.divq), (6, 65, 5));
        assert!((h.fout_hz() - 14_732_142.857).abs() < 0.01, "{}", h.fout_hz());
        assert!((h.error_ppm(14_740_000) - -533.05).abs() < 0.01, "{}", h.error_ppm(14_740_000));
        // The controller: 16 MHz directly.
        let c = choose(100_000_000, 16_000_000, DEFAULT_TOLERANCE_PPM, "b").unwrap();
        assert!(!c.half && c.in_range(), "{c:?}");
        assert_eq!(c.fout_hz(), 16_015_625.0);
        assert!((c.error_ppm(16_000_000) - 976.5625).abs() < 1e-6);
        for s in [h, c] {
            assert!((10e6..=133e6).contains(&s.pfd_hz()) && (533e6..=1066e6).contains(&s.vco_hz()), "{}", s.describe());
            assert!(s.parameters().contains(&format!(".DIVF(7'd{})", s.divf)), "{}", s.parameters());
        }
        assert_eq!(h.filter_range(), 1); // PFD 14.3 MHz
        assert!(h.parameters().contains("GENCLK_HALF") && c.parameters().contains("\"GENCLK\""));
    }

    #[test]
    fn the_closest_setting_is_the_closest() {
        // Exhaustive check on a few targets: no in-range setting is nearer.
        for (fin, target) in [(100_000_000, 14_740_000), (12_000_000, 16_000_000), (25_000_000, 48_000_000)] {
            let best = closest(fin, target).unwrap();
            let e = (best.fout_hz() - target as f64).abs();
            for half in [false, true] {
                for divr in 0..=15 {
                    for divf in 0..=127 {
                        for divq in 1..=6 {
                            let s = PllSettings { fin_hz: fin, divr, divf, divq, half };
                            assert!(!s.in_range() || (s.fout_hz() - target as f64).abs() >= e, "{s:?} beats {best:?}");
                        }
                    }
                }
            }
        }
        // 12 MHz (iCEstick) to 48 MHz is exact.
        assert_eq!(closest(12_000_000, 48_000_000).unwrap().fout_hz(), 48e6);
    }

    #[test]
    fn out_of_tolerance_and_out_of_range_are_errors_naming_the_board_key() {
        let e = choose(100_000_000, 14_740_000, 100.0, "boards/x.toml: board x").unwrap_err().to_string();
        assert!(e.starts_with("boards/x.toml: board x: clock.hz:") && e.contains("-533 ppm") && e.contains("±100 ppm"), "{e}");
        let e = choose(5_000_000, 16_000_000, 2000.0, "b").unwrap_err().to_string();
        assert!(e.contains("clock.hz: 5000000 Hz is outside") && e.contains("10..133 MHz"), "{e}");
        let e = choose(100_000_000, 1_000_000, 2000.0, "b").unwrap_err().to_string();
        assert!(e.contains("clock.hz:"), "{e}");
    }

    /// DIVR/DIVF/DIVQ of the library's `SB_PLL40_CORE` text.
    fn library_settings(v: Verilog, fin_hz: u64) -> PllSettings {
        let Verilog::Custom(text) = v else { panic!("the library's PLL is no longer custom Verilog") };
        let param = |name: &str| -> u8 {
            let rest = text.split(&format!(".{name}(")).nth(1).unwrap_or_else(|| panic!("{name} in {text}"));
            let lit = rest.split(')').next().unwrap().trim();
            // "6", "32'd6", "32'h6", "4'b0110"
            match lit.split_once('\'') {
                None => lit.parse().unwrap(),
                Some((_, r)) => u8::from_str_radix(&r[1..].replace('_', ""), match &r[..1] { "h" => 16, "b" => 2, "o" => 8, _ => 10 }).unwrap(),
            }
        };
        PllSettings { fin_hz, divr: param("DIVR"), divf: param("DIVF"), divq: param("DIVQ"), half: false }
    }

    #[test]
    fn same_frequency_as_rust_hdl_fpga_support() {
        let lib = library_settings(ICE40PLLBlock::<100_000_000, 16_000_000>::default().hdl(), 100_000_000);
        let ours = closest(100_000_000, 16_000_000).unwrap();
        assert_eq!(lib.fout_hz(), ours.fout_hz(), "library {lib:?}, ours {ours:?}");
        assert!(!ours.half);
        // The hub: the library makes twice its clock, canstar halves it in the PLL.
        let lib = library_settings(ICE40PLLBlock::<100_000_000, 29_480_000>::default().hdl(), 100_000_000);
        let ours = closest(100_000_000, 14_740_000).unwrap();
        assert_eq!(lib.fout_hz(), ours.pllout_hz(), "library {lib:?}, ours {ours:?}");
        // ... and cannot make 14.74 MHz itself (it panics below 16 MHz out).
        assert!(std::panic::catch_unwind(ICE40PLLBlock::<100_000_000, 14_740_000>::default).is_err());
    }
}
