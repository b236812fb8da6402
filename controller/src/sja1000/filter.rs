//! [`AcceptanceFilter`]: the acceptance code and mask registers (ACR0..3,
//! AMR0..3) and the single and dual filters of the data sheet.
//!
//! The code and mask form 32-bit words, ACR0/AMR0 in bits 31..24; a mask
//! bit 1 means "don't care". Single filter, standard frame: ID 10..0 and
//! RTR against bits 31..20, data bytes 0 and 1 against bits 15..0 (bits
//! 19..16 unused); extended frame: ID 28..0 and RTR against bits 31..2
//! (bits 1..0 unused). Dual filter, standard frame: filter 1 is ID, RTR and
//! data byte 0 against bits 31..20 and 19..16 + 3..0, filter 2 is ID and
//! RTR against bits 15..4; extended frame: ID 28..13 against bits 31..16
//! (filter 1) or 15..0 (filter 2). Data bytes that the frame does not carry
//! (`n` bytes: remote frames and DLC < 2) match any code.
//!
//! The filter is combinational in the frame ([`FilterMatch`]), for two
//! frames side by side: `accept` for the frame on `ide`, `rtr`, `id`, `n`,
//! `d01` (the received frame) and `accept_own` for the one on `own_*` (the
//! transmit buffer's), so that the FIFO selects a verdict, not the frame
//! in front of the filter. The registers are
//! written on `we` at index `idx` (0..3 ACR0..3, 4..7 AMR0..3). The host
//! reads them from a copy in block RAM that the top keeps (the same writes;
//! AMR bytes since a hardware reset read 0xFF there).
//!
//! State: `acr0`..`acr3` (not reset), `amr0`..`amr3` (reset to the table's
//! AMR value, 0xFF: accept all).

use super::regs;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct AcceptanceFilter {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    pub we: Signal<In, Bit>,
    pub idx: Signal<In, Bits<3>>,
    pub wdata: Signal<In, Bits<8>>,
    /// Single filter mode (MOD.AFM).
    pub single: Signal<In, Bit>,
    /// The frame: IDE, RTR, identifier, data bytes carried, data bytes 0
    /// (bits 15..8) and 1.
    pub ide: Signal<In, Bit>,
    pub rtr: Signal<In, Bit>,
    pub id: Signal<In, Bits<29>>,
    pub n: Signal<In, Bits<4>>,
    pub d01: Signal<In, Bits<16>>,
    pub accept: Signal<Out, Bit>,
    /// A second frame (the own frame), its verdict.
    pub own_ide: Signal<In, Bit>,
    pub own_rtr: Signal<In, Bit>,
    pub own_id: Signal<In, Bits<29>>,
    pub own_n: Signal<In, Bits<4>>,
    pub own_d01: Signal<In, Bits<16>>,
    pub accept_own: Signal<Out, Bit>,

    acr0: DFF<Bits<8>>,
    acr1: DFF<Bits<8>>,
    acr2: DFF<Bits<8>>,
    acr3: DFF<Bits<8>>,
    amr0: DFF<Bits<8>>,
    amr1: DFF<Bits<8>>,
    amr2: DFF<Bits<8>>,
    amr3: DFF<Bits<8>>,
    amr_reset: Constant<Bits<8>>,
    m_rx: FilterMatch,
    m_own: FilterMatch,

    l_acr: Signal<Local, Bits<32>>,
    l_amr: Signal<Local, Bits<32>>,
}

impl Default for AcceptanceFilter {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            rst: Default::default(),
            we: Default::default(),
            idx: Default::default(),
            wdata: Default::default(),
            single: Default::default(),
            ide: Default::default(),
            rtr: Default::default(),
            id: Default::default(),
            n: Default::default(),
            d01: Default::default(),
            accept: Default::default(),
            own_ide: Default::default(),
            own_rtr: Default::default(),
            own_id: Default::default(),
            own_n: Default::default(),
            own_d01: Default::default(),
            accept_own: Default::default(),
            acr0: Default::default(),
            acr1: Default::default(),
            acr2: Default::default(),
            acr3: Default::default(),
            amr0: Default::default(),
            amr1: Default::default(),
            amr2: Default::default(),
            amr3: Default::default(),
            amr_reset: Constant::new((regs::AMR.reset.unwrap() as u64).into()),
            m_rx: Default::default(),
            m_own: Default::default(),
            l_acr: Default::default(),
            l_amr: Default::default(),
        }
    }
}

impl Logic for AcceptanceFilter {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, acr0, acr1, acr2, acr3, amr0, amr1, amr2, amr3);
        match self.idx.val().index() {
            0 => {
                if self.we.val() {
                    self.acr0.d.next = self.wdata.val();
                }
            }
            1 => {
                if self.we.val() {
                    self.acr1.d.next = self.wdata.val();
                }
            }
            2 => {
                if self.we.val() {
                    self.acr2.d.next = self.wdata.val();
                }
            }
            3 => {
                if self.we.val() {
                    self.acr3.d.next = self.wdata.val();
                }
            }
            4 => {
                if self.we.val() {
                    self.amr0.d.next = self.wdata.val();
                }
            }
            5 => {
                if self.we.val() {
                    self.amr1.d.next = self.wdata.val();
                }
            }
            6 => {
                if self.we.val() {
                    self.amr2.d.next = self.wdata.val();
                }
            }
            7 => {
                if self.we.val() {
                    self.amr3.d.next = self.wdata.val();
                }
            }
            _ => {}
        }
        if self.rst.val() {
            self.amr0.d.next = self.amr_reset.val();
            self.amr1.d.next = self.amr_reset.val();
            self.amr2.d.next = self.amr_reset.val();
            self.amr3.d.next = self.amr_reset.val();
        }

        self.l_acr.next = (bit_cast::<32, 8>(self.acr0.q.val()) << 24)
            | (bit_cast::<32, 8>(self.acr1.q.val()) << 16)
            | (bit_cast::<32, 8>(self.acr2.q.val()) << 8)
            | bit_cast::<32, 8>(self.acr3.q.val());
        self.l_amr.next = (bit_cast::<32, 8>(self.amr0.q.val()) << 24)
            | (bit_cast::<32, 8>(self.amr1.q.val()) << 16)
            | (bit_cast::<32, 8>(self.amr2.q.val()) << 8)
            | bit_cast::<32, 8>(self.amr3.q.val());
        self.m_rx.acr.next = self.l_acr.val();
        self.m_rx.amr.next = self.l_amr.val();
        self.m_rx.single.next = self.single.val();
        self.m_rx.ide.next = self.ide.val();
        self.m_rx.rtr.next = self.rtr.val();
        self.m_rx.id.next = self.id.val();
        self.m_rx.n.next = self.n.val();
        self.m_rx.d01.next = self.d01.val();
        self.accept.next = self.m_rx.accept.val();
        self.m_own.acr.next = self.l_acr.val();
        self.m_own.amr.next = self.l_amr.val();
        self.m_own.single.next = self.single.val();
        self.m_own.ide.next = self.own_ide.val();
        self.m_own.rtr.next = self.own_rtr.val();
        self.m_own.id.next = self.own_id.val();
        self.m_own.n.next = self.own_n.val();
        self.m_own.d01.next = self.own_d01.val();
        self.accept_own.next = self.m_own.accept.val();
    }
}

canstar_hdl::impl_clocked!(AcceptanceFilter);

/// The single and dual filters of the data sheet on one frame (IDE, RTR,
/// identifier, data bytes carried, data bytes 0 and 1) against the code
/// `acr` and mask `amr` words (ACR0/AMR0 in bits 31..24), combinational.
#[derive(LogicBlock, Default)]
pub struct FilterMatch {
    pub acr: Signal<In, Bits<32>>,
    pub amr: Signal<In, Bits<32>>,
    pub single: Signal<In, Bit>,
    pub ide: Signal<In, Bit>,
    pub rtr: Signal<In, Bit>,
    pub id: Signal<In, Bits<29>>,
    pub n: Signal<In, Bits<4>>,
    pub d01: Signal<In, Bits<16>>,
    pub accept: Signal<Out, Bit>,

    l_v1: Signal<Local, Bits<32>>,
    l_v2: Signal<Local, Bits<32>>,
    l_m1: Signal<Local, Bits<32>>,
    l_m2: Signal<Local, Bits<32>>,
}

impl Logic for FilterMatch {
    #[hdl_gen]
    fn update(&mut self) {
        if self.single.val() {
            if self.ide.val() {
                self.l_v1.next = bit_cast::<32, 29>(self.id.val()) << 3;
                self.l_v1.next = self.l_v1.val().replace_bit(2, self.rtr.val());
                self.l_m1.next = self.amr.val() | 3;
            } else {
                self.l_v1.next =
                    (bit_cast::<32, 11>(self.id.val().get_bits::<11>(0)) << 21) | bit_cast::<32, 16>(self.d01.val());
                self.l_v1.next = self.l_v1.val().replace_bit(20, self.rtr.val());
                self.l_m1.next = self.amr.val() | 0x000F_0000;
                if self.n.val().get_bits::<3>(1) == 0 {
                    self.l_m1.next = self.l_m1.val() | 0xFF;
                }
                if self.n.val() == 0 {
                    self.l_m1.next = self.l_m1.val() | 0xFF00;
                }
            }
            self.l_v2.next = 0.into();
            self.l_m2.next = 0.into();
            self.accept.next = ((self.l_v1.val() ^ self.acr.val()) & !self.l_m1.val()) == 0;
        } else {
            if self.ide.val() {
                self.l_v1.next = bit_cast::<32, 16>(self.id.val().get_bits::<16>(13)) << 16;
                self.l_m1.next = self.amr.val() | 0xFFFF;
                self.l_v2.next = bit_cast::<32, 16>(self.id.val().get_bits::<16>(13));
                self.l_m2.next = self.amr.val() | 0xFFFF_0000_u64;
            } else {
                self.l_v1.next = (bit_cast::<32, 11>(self.id.val().get_bits::<11>(0)) << 21)
                    | (bit_cast::<32, 4>(self.d01.val().get_bits::<4>(12)) << 16)
                    | bit_cast::<32, 4>(self.d01.val().get_bits::<4>(8));
                self.l_v1.next = self.l_v1.val().replace_bit(20, self.rtr.val());
                self.l_m1.next = self.amr.val() | 0xFFF0;
                if self.n.val() == 0 {
                    self.l_m1.next = self.l_m1.val() | 0x000F_000F;
                }
                self.l_v2.next = bit_cast::<32, 11>(self.id.val().get_bits::<11>(0)) << 5;
                self.l_v2.next = self.l_v2.val().replace_bit(4, self.rtr.val());
                self.l_m2.next = self.amr.val() | 0xFFFF_000F_u64;
            }
            self.accept.next = (((self.l_v1.val() ^ self.acr.val()) & !self.l_m1.val()) == 0)
                | (((self.l_v2.val() ^ self.acr.val()) & !self.l_m2.val()) == 0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::drive;

    fn filter(single: bool, acr: [u8; 4], amr: [u8; 4]) -> AcceptanceFilter {
        let mut u = AcceptanceFilter::default();
        drive::init(&mut u);
        for (k, v) in acr.iter().chain(amr.iter()).enumerate() {
            u.we.next = true;
            u.idx.next = (k as u64).into();
            u.wdata.next = (*v as u64).into();
            drive::cycle(&mut u);
        }
        u.we.next = false;
        u.single.next = single;
        u
    }

    fn accepts(u: &mut AcceptanceFilter, ide: bool, rtr: bool, id: u32, data: &[u8]) -> bool {
        u.ide.next = ide;
        u.rtr.next = rtr;
        u.id.next = (id as u64).into();
        u.n.next = (data.len() as u64).into();
        let d0 = *data.first().unwrap_or(&0) as u64;
        let d1 = *data.get(1).unwrap_or(&0) as u64;
        u.d01.next = ((d0 << 8) | d1).into();
        u.own_ide.next = ide;
        u.own_rtr.next = rtr;
        u.own_id.next = (id as u64).into();
        u.own_n.next = (data.len() as u64).into();
        u.own_d01.next = ((d0 << 8) | d1).into();
        drive::settle(u);
        assert_eq!(u.accept.val(), u.accept_own.val(), "the two frames' verdicts");
        u.accept.val()
    }

    /// The two verdicts agree for the same frame (random frames, codes and
    /// masks, both filter modes), and differ for different frames.
    #[test]
    fn both_frames_have_the_same_filter() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(77);
        let mut r = || rng.gen::<u32>() as u64;
        let (mut hits, mut differ) = (0, 0);
        for _ in 0..200 {
            let single = r() & 1 == 1;
            let acr = [r() as u8, r() as u8, r() as u8, r() as u8];
            let m = r() as u8;
            let amr = [m | r() as u8, m | r() as u8, r() as u8, r() as u8];
            let mut u = filter(single, acr, amr);
            for _ in 0..20 {
                let n = (r() % 9) as usize;
                let data: Vec<u8> = (0..n).map(|_| r() as u8).collect();
                let (ide, rtr, id) = (r() & 1 == 1, r() % 5 == 0, (r() & 0x1FFF_FFFF) as u32);
                hits += accepts(&mut u, ide, rtr, id, &data) as u32;
                u.own_id.next = ((id ^ 0x1FFF_FFFF) as u64).into();
                drive::settle(&mut u);
                differ += (u.accept.val() != u.accept_own.val()) as u32;
            }
        }
        assert!(hits > 50 && differ > 20, "{hits} accepted, {differ} differ");
    }

    #[test]
    fn single_filter_standard_frames_with_data_bytes() {
        // ID 0x123 (ID1 = 0x24, ID2 = 0x60 | RTR 0x10), data 0xAB 0xCD; AMR3 don't care
        let mut u = filter(true, [0x24, 0x60, 0xAB, 0x00], [0x00, 0x0F, 0x00, 0xFF]);
        assert!(accepts(&mut u, false, false, 0x123, &[0xAB, 0x11]));
        assert!(!accepts(&mut u, false, false, 0x123, &[0xAC]), "data byte 0 compared");
        assert!(!accepts(&mut u, false, true, 0x123, &[]), "RTR compared");
        assert!(!accepts(&mut u, false, false, 0x122, &[0xAB]));
        // bytes the frame does not carry match any code
        assert!(accepts(&mut u, false, false, 0x123, &[]));
    }

    #[test]
    fn dual_filter_extended_frames_and_reset_mask() {
        // filter 1: ID 28..13 = 0x1234 >> ..., filter 2 matches anything
        let id: u32 = 0x0246_8ACE;
        let hi = (id >> 13) as u16;
        let mut u = filter(false, [(hi >> 8) as u8, hi as u8, 0x00, 0x00], [0x00, 0x00, 0x00, 0x00]);
        assert!(accepts(&mut u, true, false, id, &[]));
        assert!(accepts(&mut u, true, true, id ^ 0x1FFF, &[]), "ID 12..0 and RTR not compared");
        assert!(!accepts(&mut u, true, false, id ^ (1 << 20), &[]));
        // a hardware reset sets AMR to the table's value: accept all
        u.rst.next = true;
        drive::cycle(&mut u);
        u.rst.next = false;
        assert!(accepts(&mut u, true, false, id ^ (1 << 20), &[]));
        assert_eq!(regs::AMR.reset, Some(0xFF));
    }
}
