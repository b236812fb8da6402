//! [`BusTiming`]: the bus timing registers BTR0/BTR1 and their mapping onto
//! the core's bit timing fields (see the module documentation of
//! [`super`], "Bit timing").
//!
//! TQ = 2·(BRP+1) clocks: the core's prescaler field is 2·BRP+1. With
//! t1 = TSEG1+1 and t2 = TSEG2+1 the bit is 1 + t1 + t2 TQ; exact when
//! t1 > t2 ≥ 2 (PROP = t1 − t2, PH1 = PH2 = t2); t2 = 1 gives PROP = t1 − 2,
//! PH1 = 1; t1 ≤ t2 gives PH1 = ⌊(t1 + t2 − 1)/2⌋, PROP = t1 + t2 − 2·PH1;
//! below 8 TQ a setting the core rejects. SJW is limited to PH1.
//!
//! State: `r0`, `r1` (BTR0, BTR1: written by `we0`/`we1`, loaded with the
//! generation-time power-up values `v0`/`v1` by `rst`).

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
    pub sjw: Signal<Out, Bits<2>>,
    pub triple: Signal<Out, Bit>,

    r0: DFF<Bits<8>>,
    r1: DFF<Bits<8>>,
    v0: Constant<Bits<8>>,
    v1: Constant<Bits<8>>,

    l_t1: Signal<Local, Bits<6>>,
    l_t2: Signal<Local, Bits<6>>,
    l_s: Signal<Local, Bits<6>>,
    l_prop: Signal<Local, Bits<6>>,
    l_ph1: Signal<Local, Bits<6>>,
    l_sjw: Signal<Local, Bits<6>>,
}

impl BusTiming {
    /// BTR0/BTR1 take `btr0`/`btr1` at a hardware reset.
    pub fn new(btr0: u8, btr1: u8) -> Self {
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
            sjw: Default::default(),
            triple: Default::default(),
            r0: Default::default(),
            r1: Default::default(),
            v0: Constant::new((btr0 as u64).into()),
            v1: Constant::new((btr1 as u64).into()),
            l_t1: Default::default(),
            l_t2: Default::default(),
            l_s: Default::default(),
            l_prop: Default::default(),
            l_ph1: Default::default(),
            l_sjw: Default::default(),
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
        dff_setup!(self, clock, r0, r1);
        if self.we0.val() {
            self.r0.d.next = self.wdata.val();
        }
        if self.we1.val() {
            self.r1.d.next = self.wdata.val();
        }
        if self.rst.val() {
            self.r0.d.next = self.v0.val();
            self.r1.d.next = self.v1.val();
        }

        // BTR0: SJW in bits 7..6, BRP in bits 5..0; BTR1: SAM in bit 7,
        // TSEG2 in bits 6..4, TSEG1 in bits 3..0.
        self.brp.next = (bit_cast::<7, 6>(self.r0.q.val().get_bits::<6>(0)) << 1) | 1;
        self.l_t1.next = bit_cast::<6, 4>(self.r1.q.val().get_bits::<4>(0)) + 1;
        self.l_t2.next = bit_cast::<6, 3>(self.r1.q.val().get_bits::<3>(4)) + 1;
        self.l_s.next = self.l_t1.val() + self.l_t2.val();
        // exact: PH1 = PH2 = t2, PROP = t1 - t2 (t1 > t2 >= 2)
        self.l_ph1.next = self.l_t2.val();
        self.l_prop.next = self.l_t1.val() - self.l_t2.val();
        if self.l_t2.val() == 1 {
            // PH2 is at least 2: keep the bit time, sample point 1 TQ earlier
            self.l_ph1.next = 1.into();
            self.l_prop.next = self.l_t1.val() - 2;
        } else if self.l_t1.val() <= self.l_t2.val() {
            // keep the bit time and PH2 = PH1, sample point later
            self.l_ph1.next = (self.l_s.val() - 1) >> 1;
            self.l_prop.next = self.l_s.val() - (self.l_ph1.val() << 1);
        }
        if self.l_s.val() < 7 {
            // under 8 TQ: a setting the core rejects
            self.l_prop.next = 1.into();
            self.l_ph1.next = 1.into();
        }
        self.l_sjw.next = bit_cast::<6, 2>(self.r0.q.val().get_bits::<2>(6)) + 1;
        if self.l_sjw.val() > self.l_ph1.val() {
            self.l_sjw.next = self.l_ph1.val();
        }
        self.l_prop.next = self.l_prop.val() - 1;
        self.l_ph1.next = self.l_ph1.val() - 1;
        self.l_sjw.next = self.l_sjw.val() - 1;
        self.prop.next = self.l_prop.val().get_bits::<4>(0);
        self.ph1.next = self.l_ph1.val().get_bits::<3>(0);
        self.sjw.next = self.l_sjw.val().get_bits::<2>(0);
        self.triple.next = self.r1.q.val().get_bit(7);
        self.btr0.next = self.r0.q.val();
        self.btr1.next = self.r1.q.val();
    }
}

canstar_hdl::impl_clocked!(BusTiming);

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::drive;

    /// (BRP, PROP, PH1, SJW) in TQ and clocks per TQ for BTR0/BTR1.
    fn map(btr0: u8, btr1: u8) -> (u64, u64, u64, u64, bool) {
        let mut u = BusTiming::new(btr0, btr1);
        drive::init(&mut u);
        u.rst.next = true;
        drive::cycle(&mut u);
        let v = |x: usize| x as u64 + 1;
        (v(u.brp.val().index()), v(u.prop.val().index()), v(u.ph1.val().index()), v(u.sjw.val().index()), u.triple.val())
    }

    #[test]
    fn btr_values_map_onto_the_core_fields() {
        // TQ = 2 (BRP + 1) clocks; exact: t1 = 6, t2 = 3 -> PROP 3, PH1 = PH2 = 3
        assert_eq!(map(0x00, 0x25), (2, 3, 3, 1, false));
        assert_eq!(map(0x41, 0x25), (4, 3, 3, 2, false));
        assert_eq!(map(0xC0, 0xA5), (2, 3, 3, 3, true), "SJW 4 limited to PH1; SAM");
        // t2 = 1: PH1 1 (PH2 2), PROP t1 - 2, bit time kept (1 + 6 + 1 = 8 = 1 + 4 + 1 + 2)
        assert_eq!(map(0x00, 0x05), (2, 4, 1, 1, false));
        // t1 <= t2: PH1 = PH2 = (t1 + t2 - 1) / 2, PROP = t1 + t2 - 2 PH1
        // (t1 = 3, t2 = 6: PH1 = 4, PROP = 1; 1 + 1 + 4 + 4 = 1 + 3 + 6)
        assert_eq!(map(0x00, 0x52), (2, 1, 4, 1, false));
        // under 8 TQ: PROP 1, PH1 1 (the core rejects it)
        assert_eq!(map(0x00, 0x11).1, 1);
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
