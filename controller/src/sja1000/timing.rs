//! [`BusTiming`]: the bus timing registers BTR0/BTR1 and their mapping onto
//! the core's bit timing fields (see the module documentation of
//! [`super`], "Bit timing").
//!
//! The mapping is exact for every setting the core accepts: TQ = 2·(BRP+1)
//! clocks (the core's prescaler field is 2·BRP+1); with t1 = TSEG1+1
//! (1..16 TQ) and t2 = TSEG2+1 (1..8 TQ), PROP + PH1 = t1 with
//! PH1 = min(t1 − 1, 8) and PROP = t1 − PH1, and PH2 = t2, so the bit is
//! 1 + t1 + t2 TQ with the sample point after 1 + t1 TQ, as on the SJA1000.
//! PH2 = 1 TQ is legal because a TQ is at least 2 clocks (the information
//! processing time, can-protocol.md §2.5). SJW may exceed PH2 (C22, as on
//! the SJA1000) but is limited to PH1, which reduces it only when t1 ≤ SJW
//! (to t1 − 1).
//! What the core refuses (`cfg_err`, it stays inert with TX recessive): bits
//! under 8 TQ (1 + t1 + t2 < 8) and t1 = 1 (TSEG1 = 0: a sample point 2 TQ
//! after the bit start, which PROP ≥ 1 and PH1 ≥ 1 cannot express; the
//! block then hands the core a 4-TQ bit so that it refuses it).
//! [`mapped`] is the same mapping in Rust; [`core_timing`] also rejects, with
//! a message naming the field, the settings the core does not honour exactly.
//!
//! State: `r0`, `r1` (BTR0, BTR1: written by `we0`/`we1`, loaded with the
//! generation-time power-up values `v0`/`v1` by `rst`); `o_brp`, `o_prop`,
//! `o_ph1`, `o_ph2`, `o_sjw`, `o_tri` (the core's fields, mapped from the
//! byte written to BTR0/BTR1 and loaded with it, and loaded with the
//! mapping of `v0`/`v1` by `rst`, so that on every clock they are the
//! mapping of `r0`/`r1` without the mapping between these registers and
//! the core; BTR0 = BTR1 = 0, the flip-flops' power-up value, maps to
//! all-zero fields and BRP 0). The mapping of the written byte is a table
//! of TSEG1 and a few gates, not adders and comparators, which Yosys maps
//! to carry chains behind the host's write decode.

use canstar_hdl::timing::BtlConfig;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct BusTiming {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    pub we0: Signal<In, Bit>,
    pub we1: Signal<In, Bit>,
    pub wdata: Signal<In, Bits<8>>,
    pub btr0: Signal<Out, Bits<8>>,
    pub btr1: Signal<Out, Bits<8>>,
    /// The core's timing fields (value − 1) and triple sampling.
    pub brp: Signal<Out, Bits<7>>,
    pub prop: Signal<Out, Bits<4>>,
    pub ph1: Signal<Out, Bits<3>>,
    pub ph2: Signal<Out, Bits<3>>,
    pub sjw: Signal<Out, Bits<2>>,
    pub triple: Signal<Out, Bit>,

    r0: DFF<Bits<8>>,
    r1: DFF<Bits<8>>,
    o_brp: DFF<Bits<6>>,
    o_prop: DFF<Bits<4>>,
    o_ph1: DFF<Bits<3>>,
    o_ph2: DFF<Bits<3>>,
    o_sjw: DFF<Bits<2>>,
    o_tri: DFF<Bit>,
    v0: Constant<Bits<8>>,
    v1: Constant<Bits<8>>,
    /// The core's fields for `v0`/`v1` (loaded with them by `rst`).
    v_prop: Constant<Bits<4>>,
    v_ph1: Constant<Bits<3>>,
    v_ph2: Constant<Bits<3>>,
    v_sjw: Constant<Bits<2>>,

    l_k: Signal<Local, Bits<4>>,
    l_wprop: Signal<Local, Bits<4>>,
    l_wph1: Signal<Local, Bits<3>>,
    l_wph2: Signal<Local, Bits<3>>,
    l_ssjw: Signal<Local, Bits<2>>,
    l_sph1: Signal<Local, Bits<3>>,
    l_msjw: Signal<Local, Bits<2>>,
}

impl BusTiming {
    /// BTR0/BTR1 take `btr0`/`btr1` at a hardware reset.
    pub fn new(btr0: u8, btr1: u8) -> Self {
        let f = mapped(btr0, btr1).fields();
        Self {
            clock: Default::default(),
            rst: Default::default(),
            we0: Default::default(),
            we1: Default::default(),
            wdata: Default::default(),
            btr0: Default::default(),
            btr1: Default::default(),
            brp: Default::default(),
            prop: Default::default(),
            ph1: Default::default(),
            ph2: Default::default(),
            sjw: Default::default(),
            triple: Default::default(),
            r0: Default::default(),
            r1: Default::default(),
            o_brp: Default::default(),
            o_prop: Default::default(),
            o_ph1: Default::default(),
            o_ph2: Default::default(),
            o_sjw: Default::default(),
            o_tri: Default::default(),
            v0: Constant::new((btr0 as u64).into()),
            v1: Constant::new((btr1 as u64).into()),
            v_prop: Constant::new((f.1 as u64).into()),
            v_ph1: Constant::new((f.2 as u64).into()),
            v_ph2: Constant::new((f.3 as u64).into()),
            v_sjw: Constant::new((f.4 as u64).into()),
            l_k: Default::default(),
            l_wprop: Default::default(),
            l_wph1: Default::default(),
            l_wph2: Default::default(),
            l_ssjw: Default::default(),
            l_sph1: Default::default(),
            l_msjw: Default::default(),
        }
    }
}

impl Default for BusTiming {
    fn default() -> Self {
        Self::new(0, 0)
    }
}

impl Logic for BusTiming {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, r0, r1, o_brp, o_prop, o_ph1, o_ph2, o_sjw, o_tri);
        // BTR0: SJW in bits 7..6, BRP in bits 5..0; BTR1: SAM in bit 7,
        // TSEG2 in bits 6..4, TSEG1 in bits 3..0. The core's fields are
        // mapped from the byte written (`we0`, `we1`, never both) and from the
        // power-up values (`rst`, constants): BTR0/BTR1 change only then.
        //
        // With k = TSEG1 (t1 = k + 1), exact: PROP + PH1 = t1 with PH1 =
        // min(t1 - 1, 8) (the largest PH1, so that the SJW limit bites
        // least), PH2 = t2; as fields (value - 1) PH1 = min(k, 8) - 1 and
        // PROP = max(k - 8, 0), written as a table of k (no adders or
        // comparators, which Yosys maps to carry chains). TSEG1 = 0: a sample
        // point 2 TQ after the bit start needs PROP + PH1 = 1, which the core
        // cannot express; 1 + 1 + 1 + 1 = 4 TQ (all fields 0) makes it refuse
        // the setting (cfg_err), as it refuses every bit under 8 TQ.
        self.l_k.next = self.wdata.val().get_bits::<4>(0);
        self.l_wph1.next = 7.into();
        self.l_wprop.next = 0.into();
        match self.l_k.val().index() {
            0 => {
                self.l_wph1.next = 0.into();
            }
            1 => {
                self.l_wph1.next = 0.into();
            }
            2 => {
                self.l_wph1.next = 1.into();
            }
            3 => {
                self.l_wph1.next = 2.into();
            }
            4 => {
                self.l_wph1.next = 3.into();
            }
            5 => {
                self.l_wph1.next = 4.into();
            }
            6 => {
                self.l_wph1.next = 5.into();
            }
            7 => {
                self.l_wph1.next = 6.into();
            }
            9 => {
                self.l_wprop.next = 1.into();
            }
            10 => {
                self.l_wprop.next = 2.into();
            }
            11 => {
                self.l_wprop.next = 3.into();
            }
            12 => {
                self.l_wprop.next = 4.into();
            }
            13 => {
                self.l_wprop.next = 5.into();
            }
            14 => {
                self.l_wprop.next = 6.into();
            }
            15 => {
                self.l_wprop.next = 7.into();
            }
            _ => {}
        }
        self.l_wph2.next = self.wdata.val().get_bits::<3>(4);
        if self.l_k.val() == 0 {
            self.l_wph2.next = 0.into();
        }
        // SJW <= PH1 (C22; SJW > PH2 is legal): as fields, min(SJW, PH1),
        // of the SJW written with the PH1 held, or of the SJW held with the
        // PH1 written; only PH1 fields 0..2 reduce it.
        self.l_ssjw.next = self.wdata.val().get_bits::<2>(6);
        self.l_sph1.next = self.o_ph1.q.val();
        if self.we1.val() {
            self.l_ssjw.next = self.r0.q.val().get_bits::<2>(6);
            self.l_sph1.next = self.l_wph1.val();
        }
        self.l_msjw.next = self.l_ssjw.val();
        if self.l_sph1.val() == 2 {
            self.l_msjw.next = self
                .l_ssjw
                .val()
                .replace_bit(0, self.l_ssjw.val().get_bit(0) & !self.l_ssjw.val().get_bit(1));
        }
        if self.l_sph1.val() == 1 {
            self.l_msjw.next = 0.into();
            if self.l_ssjw.val() != 0 {
                self.l_msjw.next = 1.into();
            }
        }
        if self.l_sph1.val() == 0 {
            self.l_msjw.next = 0.into();
        }

        if self.we0.val() {
            self.r0.d.next = self.wdata.val();
            self.o_brp.d.next = self.wdata.val().get_bits::<6>(0);
            self.o_sjw.d.next = self.l_msjw.val();
        }
        if self.we1.val() {
            self.r1.d.next = self.wdata.val();
            self.o_prop.d.next = self.l_wprop.val();
            self.o_ph1.d.next = self.l_wph1.val();
            self.o_ph2.d.next = self.l_wph2.val();
            self.o_sjw.d.next = self.l_msjw.val();
            self.o_tri.d.next = self.wdata.val().get_bit(7);
        }
        if self.rst.val() {
            self.r0.d.next = self.v0.val();
            self.r1.d.next = self.v1.val();
            self.o_brp.d.next = self.v0.val().get_bits::<6>(0);
            self.o_prop.d.next = self.v_prop.val();
            self.o_ph1.d.next = self.v_ph1.val();
            self.o_ph2.d.next = self.v_ph2.val();
            self.o_sjw.d.next = self.v_sjw.val();
            self.o_tri.d.next = self.v1.val().get_bit(7);
        }
        self.brp.next = (bit_cast::<7, 6>(self.o_brp.q.val()) << 1) | 1;
        self.prop.next = self.o_prop.q.val();
        self.ph1.next = self.o_ph1.q.val();
        self.ph2.next = self.o_ph2.q.val();
        self.sjw.next = self.o_sjw.q.val();
        self.triple.next = self.o_tri.q.val();
        self.btr0.next = self.r0.q.val();
        self.btr1.next = self.r1.q.val();
    }
}

canstar_hdl::impl_clocked!(BusTiming);

/// The core timing [`BusTiming`] hands the core for `btr0`/`btr1` (the RTL's
/// mapping in Rust, including the SJW limit and the refused 4-TQ bit for
/// TSEG1 = 0), whether or not the core accepts it.
pub fn mapped(btr0: u8, btr1: u8) -> BtlConfig {
    let brp = 2 * ((btr0 & 0x3F) as u32 + 1);
    let t1 = (btr1 & 0x0F) as u32 + 1;
    let t2 = ((btr1 >> 4) & 7) as u32 + 1;
    let (prop, ph1, ph2) = if t1 == 1 { (1, 1, 1) } else { (t1 - (t1 - 1).min(8), (t1 - 1).min(8), t2) };
    let sjw = ((btr0 >> 6) as u32 + 1).min(ph1);
    BtlConfig { triple: btr1 & 0x80 != 0, ..BtlConfig::new(brp, prop, ph1, sjw).with_ph2(ph2) }
}

/// The core timing for `btr0`/`btr1` when the core honours the setting
/// exactly (the datasheet's bit time, sample point and SJW), else a message
/// naming the register field and why.
pub fn core_timing(btr0: u8, btr1: u8) -> Result<BtlConfig, String> {
    let t1 = (btr1 & 0x0F) as u32 + 1;
    let t2 = ((btr1 >> 4) & 7) as u32 + 1;
    let sjw = (btr0 >> 6) as u32 + 1;
    let at = format!("BTR0/BTR1 = 0x{btr0:02X}/0x{btr1:02X}");
    if t1 == 1 {
        return Err(format!(
            "{at}: TSEG1 = 0 (a sample point 2 TQ after the bit start) is not supported: the core needs PROP + PH1 = TSEG1 + 1 >= 2 TQ"
        ));
    }
    if 1 + t1 + t2 < 8 {
        return Err(format!(
            "{at}: 1 + (TSEG1 + 1) + (TSEG2 + 1) = {} TQ per bit: the core needs 8..=25 TQ (can-protocol.md §2.2)",
            1 + t1 + t2
        ));
    }
    if sjw > t1 - 1 {
        return Err(format!(
            "{at}: SJW = {sjw} TQ with TSEG1 + 1 = {t1} TQ: the core limits SJW to PH1 = TSEG1 = {} TQ (can-protocol.md C22)",
            t1 - 1
        ));
    }
    let t = mapped(btr0, btr1);
    t.check().map_err(|e| format!("{at}: {e}"))?;
    Ok(t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::drive;

    /// The core timing the RTL hands the core for BTR0/BTR1.
    fn map(btr0: u8, btr1: u8) -> BtlConfig {
        let mut u = BusTiming::new(btr0, btr1);
        drive::init(&mut u);
        u.rst.next = true;
        drive::cycle(&mut u);
        let f = |x: usize| x as u32;
        BtlConfig::from_fields(
            f(u.brp.val().index()),
            f(u.prop.val().index()),
            f(u.ph1.val().index()),
            f(u.ph2.val().index()),
            f(u.sjw.val().index()),
            u.triple.val(),
        )
    }

    #[test]
    fn btr_values_map_onto_the_core_fields() {
        // TQ = 2 (BRP + 1) clocks; t1 = 6, t2 = 3 -> PH1 5, PROP 1, PH2 3
        assert_eq!(map(0x00, 0x25), BtlConfig::new(2, 1, 5, 1).with_ph2(3));
        assert_eq!(map(0x41, 0x25), BtlConfig::new(4, 1, 5, 2).with_ph2(3));
        let t = map(0xC0, 0xA5);
        assert_eq!((t.sjw, t.triple), (4, true), "SJW 4 with PH2 3 kept; SAM");
        // t2 = 1: PH2 = 1 TQ, bit time and sample point exact
        assert_eq!(map(0x00, 0x05), BtlConfig::new(2, 1, 5, 1).with_ph2(1));
        // t1 = 16: PH1 8, PROP 8; t1 <= t2 exact too
        assert_eq!(map(0x00, 0x0F), BtlConfig::new(2, 8, 8, 1).with_ph2(1));
        assert_eq!(map(0x00, 0x52), BtlConfig::new(2, 1, 2, 1).with_ph2(6));
        // SJW limited to PH1 = t1 - 1 when t1 <= SJW
        assert_eq!(map(0xC0, 0x72).sjw, 2);
        // TSEG1 = 0: a 4-TQ bit that the core refuses
        assert_eq!(map(0x00, 0x70).ntq(), 4);
        assert!(!map(0x00, 0x70).is_valid());
    }

    /// The RTL and [`mapped`] agree on every BTR1 and SJW, and [`core_timing`]
    /// gives the datasheet's bit time and sample point whenever it accepts.
    #[test]
    fn every_btr_value_maps_like_the_rust_mapping() {
        for btr0 in [0x00u8, 0x40, 0x80, 0xC0, 0x3F, 0xC5] {
            for btr1 in 0..=255u8 {
                let t = map(btr0, btr1);
                assert_eq!(t, mapped(btr0, btr1), "BTR {btr0:#04x}/{btr1:#04x}");
                let (t1, t2) = ((btr1 & 15) as u32 + 1, ((btr1 >> 4) & 7) as u32 + 1);
                match core_timing(btr0, btr1) {
                    Ok(c) => {
                        assert_eq!(c, t);
                        assert_eq!(
                            (c.brp, c.ntq(), c.sp(), c.sjw),
                            (2 * ((btr0 & 63) as u32 + 1), 1 + t1 + t2, 1 + t1, (btr0 >> 6) as u32 + 1)
                        );
                    }
                    Err(e) => {
                        assert!(e.contains(&format!("0x{btr1:02X}")), "{e}");
                        let refused = !t.is_valid();
                        assert_eq!(refused, t1 == 1 || 1 + t1 + t2 < 8, "{e}");
                        assert!(refused || e.contains("SJW"), "{e}");
                    }
                }
            }
        }
        assert!(core_timing(0x00, 0x70).unwrap_err().contains("TSEG1 = 0"));
        assert!(core_timing(0x00, 0x12).unwrap_err().contains("6 TQ per bit"));
        assert!(core_timing(0xC0, 0x72).unwrap_err().contains("SJW = 4 TQ"));
    }

    /// Host writes keep the fields the mapping of BTR0/BTR1 (they are
    /// loaded from the byte written, not from the registers).
    #[test]
    fn written_values_map_like_the_rust_mapping() {
        let mut u = BusTiming::new(0x00, 0x00);
        drive::init(&mut u);
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12345);
        let (mut b0, mut b1) = (0u8, 0u8);
        for i in 0..3000 {
            let x: u32 = rng.gen();
            let v = (x >> 16) as u8;
            let w1 = (x >> 8) & 1 == 1;
            if i % 500 == 7 {
                u.rst.next = true;
                (b0, b1) = (0, 0);
            } else if w1 {
                u.we1.next = true;
                b1 = v;
            } else {
                u.we0.next = true;
                b0 = v;
            }
            u.wdata.next = (v as u64).into();
            drive::cycle(&mut u);
            (u.rst.next, u.we0.next, u.we1.next) = (false, false, false);
            let f = |x: usize| x as u32;
            let t = BtlConfig::from_fields(
                f(u.brp.val().index()),
                f(u.prop.val().index()),
                f(u.ph1.val().index()),
                f(u.ph2.val().index()),
                f(u.sjw.val().index()),
                u.triple.val(),
            );
            assert_eq!(t, mapped(b0, b1), "BTR {b0:#04x}/{b1:#04x} after write {i}");
            assert_eq!((u.btr0.val().index(), u.btr1.val().index()), (b0 as usize, b1 as usize));
        }
    }

    #[test]
    fn writes_and_power_up_values() {
        let mut u = BusTiming::new(0x12, 0x34);
        drive::init(&mut u);
        u.rst.next = true;
        drive::cycle(&mut u);
        u.rst.next = false;
        assert_eq!((u.btr0.val().index(), u.btr1.val().index()), (0x12, 0x34));
        u.we1.next = true;
        u.wdata.next = 0x7F.into();
        drive::cycle(&mut u);
        u.we1.next = false;
        drive::cycle(&mut u);
        assert_eq!((u.btr0.val().index(), u.btr1.val().index()), (0x12, 0x7F));
    }
}
