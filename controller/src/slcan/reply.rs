//! [`Reply`]: composes the line the engine hands to the
//! [`LineTx`](super::linetx::LineTx) for a reply kind `rk` (combinational,
//! no state): 0 OK (CR), 1 error (BEL, no CR), 2 `z\r`, 3 `Z\r`, 4
//! `Fxx\r` from `flags`, 5 `V` + [`VERSION`], 6 `N` + [`SERIAL`], 7 the
//! line of the received frame in `rximg` (the 13 bytes of the SJA1000's
//! receive window, FI in bits 103..96): `t`/`T`/`r`/`R`, the identifier
//! (3 or 8 digits), the DLC digit (a DLC above 8 is sent as 8) and, for data
//! frames, min(DLC, 8) data bytes. Window bytes beyond the frame are stale;
//! only the digits of the frame are counted in `cnt`.

use rust_hdl::prelude::*;

/// The `V` reply's four hex digits (hardware 1, software 1).
pub const VERSION: u16 = 0x0101;
/// The `N` reply's four hex digits.
pub const SERIAL: u16 = 0xCA57;

#[derive(LogicBlock)]
pub struct Reply {
    pub rk: Signal<In, Bits<3>>,
    pub flags: Signal<In, Bits<8>>,
    pub rximg: Signal<In, Bits<104>>,
    pub pre: Signal<Out, Bits<8>>,
    pub haspre: Signal<Out, Bit>,
    pub nib: Signal<Out, Bits<128>>,
    pub cnt: Signal<Out, Bits<5>>,
    pub cr: Signal<Out, Bit>,

    /// The digits of the `V` and `N` replies at the top of 128 bits.
    vnib: Constant<Bits<128>>,
    nnib: Constant<Bits<128>>,
    l_rfi: Signal<Local, Bits<8>>,
    l_rdlc: Signal<Local, Bits<4>>,
    l_rn: Signal<Local, Bits<5>>,
    l_rnib: Signal<Local, Bits<128>>,
    l_rpre: Signal<Local, Bits<8>>,
    l_rcnt: Signal<Local, Bits<5>>,
    o_pre: Signal<Local, Bits<8>>,
    o_haspre: Signal<Local, Bit>,
    o_nib: Signal<Local, Bits<128>>,
    o_cnt: Signal<Local, Bits<5>>,
    o_cr: Signal<Local, Bit>,
}

impl Default for Reply {
    fn default() -> Self {
        Self {
            rk: Default::default(),
            flags: Default::default(),
            rximg: Default::default(),
            pre: Default::default(),
            haspre: Default::default(),
            nib: Default::default(),
            cnt: Default::default(),
            cr: Default::default(),
            vnib: Constant::new(super::bits128((VERSION as u128) << 112)),
            nnib: Constant::new(super::bits128((SERIAL as u128) << 112)),
            l_rfi: Default::default(),
            l_rdlc: Default::default(),
            l_rn: Default::default(),
            l_rnib: Default::default(),
            l_rpre: Default::default(),
            l_rcnt: Default::default(),
            o_pre: Default::default(),
            o_haspre: Default::default(),
            o_nib: Default::default(),
            o_cnt: Default::default(),
            o_cr: Default::default(),
        }
    }
}

impl Logic for Reply {
    #[hdl_gen]
    fn update(&mut self) {
        // ---- the line of a received frame ----
        self.l_rfi.next = self.rximg.val().get_bits::<8>(96);
        self.l_rdlc.next = self.l_rfi.val().get_bits::<4>(0);
        if self.l_rdlc.val() > 8 {
            self.l_rdlc.next = 8.into();
        }
        self.l_rn.next = bit_cast::<5, 4>(self.l_rdlc.val()) << 1;
        if self.l_rfi.val().get_bit(6) {
            self.l_rn.next = 0.into();
        }
        if self.l_rfi.val().get_bit(7) {
            self.l_rpre.next = 0x54.into();
            if self.l_rfi.val().get_bit(6) {
                self.l_rpre.next = 0x52.into();
            }
            self.l_rcnt.next = self.l_rn.val() + 9;
            self.l_rnib.next = (bit_cast::<128, 29>(self.rximg.val().get_bits::<29>(67)) << 96)
                | (bit_cast::<128, 4>(self.l_rdlc.val()) << 92)
                | (bit_cast::<128, 64>(self.rximg.val().get_bits::<64>(0)) << 28);
        } else {
            self.l_rpre.next = 0x74.into();
            if self.l_rfi.val().get_bit(6) {
                self.l_rpre.next = 0x72.into();
            }
            self.l_rcnt.next = self.l_rn.val() + 4;
            self.l_rnib.next = (bit_cast::<128, 11>(self.rximg.val().get_bits::<11>(85)) << 116)
                | (bit_cast::<128, 4>(self.l_rdlc.val()) << 112)
                | (bit_cast::<128, 64>(self.rximg.val().get_bits::<64>(16)) << 48);
        }

        self.o_pre.next = 0.into();
        self.o_nib.next = 0.into();
        self.o_cnt.next = 0.into();
        self.o_cr.next = true;
        self.o_haspre.next = true;
        if self.rk.val() == 0 {
            self.o_haspre.next = false;
        }
        if self.rk.val() == 1 {
            self.o_pre.next = 0x07.into();
            self.o_cr.next = false;
        }
        if self.rk.val() == 2 {
            self.o_pre.next = 0x7A.into();
        }
        if self.rk.val() == 3 {
            self.o_pre.next = 0x5A.into();
        }
        if self.rk.val() == 4 {
            self.o_pre.next = 0x46.into();
            self.o_nib.next = bit_cast::<128, 8>(self.flags.val()) << 120;
            self.o_cnt.next = 2.into();
        }
        if self.rk.val() == 5 {
            self.o_pre.next = 0x56.into();
            self.o_nib.next = self.vnib.val();
            self.o_cnt.next = 4.into();
        }
        if self.rk.val() == 6 {
            self.o_pre.next = 0x4E.into();
            self.o_nib.next = self.nnib.val();
            self.o_cnt.next = 4.into();
        }
        if self.rk.val() == 7 {
            self.o_pre.next = self.l_rpre.val();
            self.o_nib.next = self.l_rnib.val();
            self.o_cnt.next = self.l_rcnt.val();
        }
        // outputs assigned once (no glitch reaches another block)
        self.pre.next = self.o_pre.val();
        self.haspre.next = self.o_haspre.val();
        self.nib.next = self.o_nib.val();
        self.cnt.next = self.o_cnt.val();
        self.cr.next = self.o_cr.val();
    }
}
