//! [`BitDecode`] (can-protocol.md): what the bit in progress is, from the sequencer's registers
//! alone (combinational, independent of the sampled level and of `sample`).
//!
//! - `stuffed`: the bit lies in the stuffed area (Start_Of_Frame ..
//!   CRC_Sequence), or it is the stuff bit that may follow the last CRC bit
//!   (the field then already says CRC_Delimiter);
//! - `stuff`: the bit is a stuff bit (the destuffer has seen 5 equal bits);
//! - `code`/`pos`: FIELD code and POSITION shown for the bit; a stuff bit
//!   shows those of the bit before it (the sequencer's `pfld`/`ppos`);
//! - `hs_en`: hard synchronisation enable (§3.3): Reset, Wait_For_Bus_Idle,
//!   Bus_Idle, Bus_Off, Start_Of_Frame, Suspend_Transmission and the third
//!   Intermission bit;
//! - `arb`, `arb_stuff`, `arb_pos`: the bit (for a stuff bit: the bit before
//!   it) is an arbitration bit; a stuff error there is TEC exception 2
//!   (`arb_stuff`: identifier, SRR, the IDE bit of an extended frame and the
//!   RTR bit of a standard frame); `arb_pos` is the `arb_lost_pos` coding of
//!   [`super::CanFsm`];
//! - `drive`: the level wanted on TX for the bit: a transmitter's stuff bit
//!   (the complement of the run), else the sequencer's registered decision
//!   `dom`; always recessive in listen-only mode.
//! - `arb_bit`, `arb_stuff_bit`, `sent_bit`, `sent_stuff`: the same decisions
//!   for the frame fields' two cases taken separately, without the stuff-bit
//!   selection in front of them: `arb` and the level driven for a bit that is
//!   not a stuff bit (from `fld`, `dom`), `arb_stuff` and the level driven for
//!   a stuff bit (from `pfld`, the stuff level). The frame fields use each
//!   only in its own case (`stuff` low, resp. high), where it equals `arb`,
//!   `arb_stuff` or `drive`; the flags only while `stuff` is low. This keeps
//!   the destuffer's count (`next_is_stuff`) out of the field decode in front
//!   of the per-bit decision (issue #16).

use super::field::Field;
use rust_hdl::prelude::*;

#[derive(LogicBlock, Default)]
pub struct BitDecode {
    pub fld: Signal<In, Field>,
    pub fpos: Signal<In, Bits<8>>,
    pub pfld: Signal<In, Field>,
    pub ppos: Signal<In, Bits<8>>,
    /// The frame in progress is an extended frame (IDE received recessive).
    pub ext: Signal<In, Bit>,
    pub tx_role: Signal<In, Bit>,
    pub dom: Signal<In, Bit>,
    pub listen_only: Signal<In, Bit>,
    pub next_is_stuff: Signal<In, Bit>,
    pub stuff_level: Signal<In, Bit>,
    /// The sequencer's registered decodes of `fld`, `fpos` and `pfld`:
    /// `fld` in the stuffed area (Start_Of_Frame .. CRC_Sequence), `fld` there
    /// or CRC_Delimiter, `fld` one of the fields with hard synchronisation at
    /// every position, `fld` Intermission, and the last two for `pfld` (see
    /// [`super::seq::Sequencer`]).
    pub in_area: Signal<In, Bit>,
    pub stuffable: Signal<In, Bit>,
    pub hs_fld: Signal<In, Bit>,
    pub inter_fld: Signal<In, Bit>,
    pub hs_pfld: Signal<In, Bit>,
    pub inter_pfld: Signal<In, Bit>,
    /// POSITION (`fpos`) is 3, a register of the sequencer (issue #16).
    pub fpos3: Signal<In, Bit>,

    pub stuffed: Signal<Out, Bit>,
    /// The field is one of the stuffed area (Start_Of_Frame .. CRC_Sequence).
    pub area: Signal<Out, Bit>,
    pub stuff: Signal<Out, Bit>,
    pub code: Signal<Out, Bits<5>>,
    pub pos: Signal<Out, Bits<8>>,
    pub hs_en: Signal<Out, Bit>,
    pub arb: Signal<Out, Bit>,
    pub arb_stuff: Signal<Out, Bit>,
    pub arb_pos: Signal<Out, Bits<6>>,
    pub drive: Signal<Out, Bit>,
    /// `arb` and `drive` of a bit that is not a stuff bit.
    pub arb_bit: Signal<Out, Bit>,
    pub sent_bit: Signal<Out, Bit>,
    /// `arb_stuff` and `drive` of a stuff bit.
    pub arb_stuff_bit: Signal<Out, Bit>,
    pub sent_stuff: Signal<Out, Bit>,

    // Working values.
    l_dfld: Signal<Local, Field>,
}

impl Logic for BitDecode {
    #[hdl_gen]
    fn update(&mut self) {
        // The final stuff bit after CRC bit 15 comes while the field already
        // says CRC_Delimiter (`stuffable`: the stuffed area or CRC_Delimiter,
        // a register of the sequencer, so that `stuff` is one LUT on the
        // destuffer's count, issue #16).
        self.stuff.next = self.next_is_stuff.val() & self.stuffable.val();
        self.l_dfld.next = self.fld.val();
        self.pos.next = self.fpos.val();
        self.drive.next = !self.dom.val();
        if self.stuff.val() {
            self.l_dfld.next = self.pfld.val();
            self.pos.next = self.ppos.val();
            self.drive.next = !self.tx_role.val() | self.stuff_level.val();
        }
        if self.listen_only.val() {
            self.drive.next = true;
        }

        self.arb.next = false;
        self.arb_stuff.next = false;
        self.arb_pos.next = 0.into();
        match self.l_dfld.val() {
            Field::Ident => {
                self.arb.next = true;
                self.arb_stuff.next = true;
                self.arb_pos.next = bit_cast::<6, 8>(self.pos.val());
            }
            Field::Srr => {
                self.arb.next = true;
                self.arb_stuff.next = true;
                self.arb_pos.next = 12.into();
            }
            Field::Ide => {
                self.arb.next = true;
                self.arb_stuff.next = self.ext.val();
                self.arb_pos.next = 13.into();
            }
            Field::Rtr => {
                self.arb.next = true;
                self.arb_stuff.next = !self.ext.val();
                self.arb_pos.next = 12.into();
                if self.ext.val() {
                    self.arb_pos.next = 32.into();
                }
            }
            Field::ExIdent => {
                self.arb.next = true;
                self.arb_stuff.next = true;
                self.arb_pos.next = bit_cast::<6, 8>(self.pos.val()) + 13;
            }
            _ => {}
        }

        // The two cases without the stuff-bit selection (see the module doc).
        self.arb_bit.next = (self.fld.val() == Field::Ident)
            | (self.fld.val() == Field::Srr)
            | (self.fld.val() == Field::Ide)
            | (self.fld.val() == Field::Rtr)
            | (self.fld.val() == Field::ExIdent);
        self.arb_stuff_bit.next = (self.pfld.val() == Field::Ident)
            | (self.pfld.val() == Field::Srr)
            | (self.pfld.val() == Field::ExIdent)
            | ((self.pfld.val() == Field::Ide) & self.ext.val())
            | ((self.pfld.val() == Field::Rtr) & !self.ext.val());
        self.sent_bit.next = !self.dom.val() | self.listen_only.val();
        self.sent_stuff.next = !self.tx_role.val() | self.stuff_level.val() | self.listen_only.val();

        self.stuffed.next = self.in_area.val() | self.stuff.val();
        self.area.next = self.in_area.val();
        self.code.next = self.l_dfld.val().into();
        // `hs_en` of the displayed field: the decodes of `fld` and of `pfld`
        // (registers of the sequencer, with Intermission bit 3 from `fpos3`, the sequencer's POSITION-is-3 register)
        // selected by `stuff` (the bit timing reads it on every clock).
        self.hs_en.next = self.hs_fld.val() | (self.inter_fld.val() & self.fpos3.val());
        if self.stuff.val() {
            self.hs_en.next = self.hs_pfld.val() | (self.inter_pfld.val() & self.fpos3.val());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::drive;

    fn decode(f: impl Fn(&mut BitDecode)) -> BitDecode {
        let mut u = BitDecode::default();
        u.connect_all();
        u.fld.next = Field::Idle;
        u.pfld.next = Field::Idle;
        u.dom.next = false;
        f(&mut u);
        // the sequencer's registered decodes of the fields set above
        let (fld, pfld) = (u.fld.next, u.pfld.next);
        u.in_area.next = fld.in_stuffed_area();
        u.stuffable.next = fld.in_stuffed_area() || fld == Field::CrcDel;
        u.hs_fld.next = fld.hard_sync();
        u.inter_fld.next = fld == Field::Inter;
        u.hs_pfld.next = pfld.hard_sync();
        u.inter_pfld.next = pfld == Field::Inter;
        u.fpos3.next = u.fpos.next.index() == 3;
        drive::settle(&mut u);
        u
    }

    #[test]
    fn stuff_bits_show_the_bit_before_and_carry_the_stuff_level() {
        // the destuffer has seen 5 equal bits in the identifier
        let u = decode(|u| {
            u.fld.next = Field::Ident;
            u.fpos.next = 6.into();
            u.pfld.next = Field::Ident;
            u.ppos.next = 5.into();
            u.next_is_stuff.next = true;
            u.stuff_level.next = false;
            u.tx_role.next = true;
        });
        assert!(u.stuffed.val() && u.stuff.val());
        assert_eq!((u.code.val().index(), u.pos.val().index()), (Field::Ident.code() as usize, 5));
        assert!(!u.drive.val(), "a transmitter sends the stuff level");
        assert_eq!((u.arb.val(), u.arb_stuff.val(), u.arb_pos.val().index()), (true, true, 5));
        // a receiver drives nothing on a stuff bit; listen-only nodes never do
        let u = decode(|u| {
            u.fld.next = Field::Ident;
            u.next_is_stuff.next = true;
            u.stuff_level.next = false;
        });
        assert!(u.drive.val());
        let u = decode(|u| {
            u.dom.next = true;
            u.listen_only.next = true;
        });
        assert!(u.drive.val());
        // after CRC bit 15 the stuff bit comes while the field says CRC_Delimiter
        let u = decode(|u| {
            u.fld.next = Field::CrcDel;
            u.pfld.next = Field::Crc;
            u.ppos.next = 15.into();
            u.next_is_stuff.next = true;
        });
        assert!(u.stuff.val() && u.stuffed.val());
        assert_eq!(u.code.val().index(), Field::Crc.code() as usize);
        // outside the stuffed area, 5 equal bits mean nothing
        let u = decode(|u| {
            u.fld.next = Field::Eof;
            u.next_is_stuff.next = true;
        });
        assert!(!u.stuff.val() && !u.stuffed.val());
    }

    #[test]
    fn arbitration_positions_and_hard_sync() {
        let cases = [
            (Field::Ident, 11, false, 11),
            (Field::Srr, 1, true, 12),
            (Field::Ide, 1, true, 13),
            (Field::ExIdent, 18, true, 31),
            (Field::Rtr, 1, true, 32),
            (Field::Rtr, 1, false, 12),
        ];
        for (f, pos, ext, want) in cases {
            let u = decode(|u| {
                u.fld.next = f;
                u.fpos.next = pos.into();
                u.ext.next = ext;
            });
            assert!(u.arb.val());
            assert_eq!(u.arb_pos.val().index(), want, "{f:?} {pos}");
        }
        for f in Field::ALL {
            let u = decode(|u| {
                u.fld.next = f;
                u.fpos.next = 3.into();
            });
            let want = matches!(f, Field::Reset | Field::WaitIdle | Field::Idle | Field::BusOff | Field::Sof | Field::Suspend | Field::Inter);
            assert_eq!(u.hs_en.val(), want, "{f:?}");
            assert_eq!(u.code.val().index() as u64, f.code());
        }
    }
}
