//! [`ErrorCapture`]: the arbitration lost capture (ALC) and error code
//! capture (ECC) registers.
//!
//! Each captures on an arbitration loss / bus error while re-armed, and a
//! host read re-arms it. ALC = the core's position − 1 (0..31, SJA1000
//! coding: 11 = SRR/standard RTR, 12 = IDE, 31 = extended RTR). ECC: error
//! code (bit, form, stuff, other = CRC or ACK error), DIR (1 = receiving)
//! and the SJA1000 segment code derived from the core's FIELD/POSITION.
//! The overload delimiter maps to 0x17 (delimiter); bit errors in
//! Suspend/Intermission map to 0x12. FIELD codes and the error-kind bit
//! positions come from `Constant` fields initialised from
//! [`crate::fsm::Field`] and the `ERRK_*` constants.
//!
//! State: `alc`, `ecc` (the captured values; reset to 0); `alc_lock`,
//! `ecc_lock` (a value has been captured and not read yet; reset to 0);
//! `seen_ext` (the frame in progress has an Ex_Identifier field: set at
//! Ex_Identifier, cleared at Start_Of_Frame; it tells extended RTR and r1
//! from standard RTR and r0).

use super::regs;
use crate::fsm::{Field, ERRK_BIT, ERRK_FORM, ERRK_STUFF};
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct ErrorCapture {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    /// The core's strobes and report (see [`crate::core::CanCore`]).
    pub arb_lost: Signal<In, Bit>,
    pub arb_lost_pos: Signal<In, Bits<6>>,
    pub error: Signal<In, Bit>,
    pub err_kind: Signal<In, Bits<5>>,
    pub err_field: Signal<In, Bits<5>>,
    pub err_pos: Signal<In, Bits<8>>,
    pub err_tx: Signal<In, Bit>,
    /// The FIELD of the bit in progress.
    pub field: Signal<In, Bits<5>>,
    /// Host reads of ALC and ECC (re-arm).
    pub rd_alc: Signal<In, Bit>,
    pub rd_ecc: Signal<In, Bit>,
    pub alc: Signal<Out, Bits<5>>,
    pub ecc: Signal<Out, Bits<8>>,

    alc_r: DFF<Bits<5>>,
    alc_lock: DFF<Bit>,
    ecc_r: DFF<Bits<8>>,
    ecc_lock: DFF<Bit>,
    seen_ext: DFF<Bit>,

    // FIELD codes.
    f_sof: Constant<Bits<5>>,
    f_ident: Constant<Bits<5>>,
    f_srr: Constant<Bits<5>>,
    f_ide: Constant<Bits<5>>,
    f_rtr: Constant<Bits<5>>,
    f_exident: Constant<Bits<5>>,
    f_resv: Constant<Bits<5>>,
    f_dlc: Constant<Bits<5>>,
    f_data: Constant<Bits<5>>,
    f_crc: Constant<Bits<5>>,
    f_crcdel: Constant<Bits<5>>,
    f_ackslot: Constant<Bits<5>>,
    f_ackdel: Constant<Bits<5>>,
    f_eof: Constant<Bits<5>>,
    f_actflag: Constant<Bits<5>>,
    f_pasflag: Constant<Bits<5>>,
    f_ovlflag: Constant<Bits<5>>,
    f_errdel: Constant<Bits<5>>,
    f_ovldel: Constant<Bits<5>>,
    // Error kinds (bit positions in `err_kind`) and ECC fields.
    k_bit: Constant<Bits<3>>,
    k_stuff: Constant<Bits<3>>,
    k_form: Constant<Bits<3>>,
    c_bit: Constant<Bits<8>>,
    c_stuff: Constant<Bits<8>>,
    c_form: Constant<Bits<8>>,
    c_other: Constant<Bits<8>>,
    c_dir: Constant<Bits<8>>,

    l_alcm1: Signal<Local, Bits<6>>,
    l_seg: Signal<Local, Bits<5>>,
    l_ecode: Signal<Local, Bits<8>>,
}

fn f(x: Field) -> Constant<Bits<5>> {
    Constant::new(x.code().into())
}

fn k(i: usize) -> Constant<Bits<3>> {
    Constant::new((i as u64).into())
}

fn c(v: u8) -> Constant<Bits<8>> {
    Constant::new((v as u64).into())
}

impl Default for ErrorCapture {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            rst: Default::default(),
            arb_lost: Default::default(),
            arb_lost_pos: Default::default(),
            error: Default::default(),
            err_kind: Default::default(),
            err_field: Default::default(),
            err_pos: Default::default(),
            err_tx: Default::default(),
            field: Default::default(),
            rd_alc: Default::default(),
            rd_ecc: Default::default(),
            alc: Default::default(),
            ecc: Default::default(),
            alc_r: Default::default(),
            alc_lock: Default::default(),
            ecc_r: Default::default(),
            ecc_lock: Default::default(),
            seen_ext: Default::default(),
            f_sof: f(Field::Sof),
            f_ident: f(Field::Ident),
            f_srr: f(Field::Srr),
            f_ide: f(Field::Ide),
            f_rtr: f(Field::Rtr),
            f_exident: f(Field::ExIdent),
            f_resv: f(Field::Resv),
            f_dlc: f(Field::Dlc),
            f_data: f(Field::Data),
            f_crc: f(Field::Crc),
            f_crcdel: f(Field::CrcDel),
            f_ackslot: f(Field::AckSlot),
            f_ackdel: f(Field::AckDel),
            f_eof: f(Field::Eof),
            f_actflag: f(Field::ActFlag),
            f_pasflag: f(Field::PasFlag),
            f_ovlflag: f(Field::OvlFlag),
            f_errdel: f(Field::ErrDel),
            f_ovldel: f(Field::OvlDel),
            k_bit: k(ERRK_BIT),
            k_stuff: k(ERRK_STUFF),
            k_form: k(ERRK_FORM),
            c_bit: c(regs::ECC_BIT),
            c_stuff: c(regs::ECC_STUFF),
            c_form: c(regs::ECC_FORM),
            c_other: c(regs::ECC_OTHER),
            c_dir: c(regs::ECC_DIR),
            l_alcm1: Default::default(),
            l_seg: Default::default(),
            l_ecode: Default::default(),
        }
    }
}

impl Logic for ErrorCapture {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, alc_r, alc_lock, ecc_r, ecc_lock, seen_ext);
        if self.field.val() == self.f_exident.val() {
            self.seen_ext.d.next = true;
        }
        if self.field.val() == self.f_sof.val() {
            self.seen_ext.d.next = false;
        }

        // Host reads re-arm (a capture on the same clock wins).
        if self.rd_alc.val() {
            self.alc_lock.d.next = false;
        }
        if self.rd_ecc.val() {
            self.ecc_lock.d.next = false;
        }

        self.l_alcm1.next = self.arb_lost_pos.val() - 1;
        if self.arb_lost.val() & !self.alc_lock.q.val() {
            self.alc_r.d.next = self.l_alcm1.val().get_bits::<5>(0);
            self.alc_lock.d.next = true;
        }

        // Segment code (SJA1000 data sheet, ECC bits 4..0).
        self.l_seg.next = 0x12.into();
        if self.err_field.val() == self.f_sof.val() {
            self.l_seg.next = 0x03.into();
        }
        if self.err_field.val() == self.f_ident.val() {
            // ID.28..21, then ID.20..18
            self.l_seg.next = 0x02.into();
            if self.err_pos.val() > 8 {
                self.l_seg.next = 0x06.into();
            }
        }
        if self.err_field.val() == self.f_srr.val() {
            self.l_seg.next = 0x04.into();
        }
        if self.err_field.val() == self.f_ide.val() {
            self.l_seg.next = 0x05.into();
        }
        if self.err_field.val() == self.f_rtr.val() {
            self.l_seg.next = 0x04.into();
            if self.seen_ext.q.val() {
                self.l_seg.next = 0x0C.into();
            }
        }
        if self.err_field.val() == self.f_exident.val() {
            // ID.17..13, ID.12..5, ID.4..0
            self.l_seg.next = 0x07.into();
            if self.err_pos.val() > 5 {
                self.l_seg.next = 0x0F.into();
            }
            if self.err_pos.val() > 13 {
                self.l_seg.next = 0x0E.into();
            }
        }
        if self.err_field.val() == self.f_resv.val() {
            // r0, or r1 of an extended frame
            self.l_seg.next = 0x09.into();
            if self.seen_ext.q.val() & (self.err_pos.val() == 1) {
                self.l_seg.next = 0x0D.into();
            }
        }
        if self.err_field.val() == self.f_dlc.val() {
            self.l_seg.next = 0x0B.into();
        }
        if self.err_field.val() == self.f_data.val() {
            self.l_seg.next = 0x0A.into();
        }
        if self.err_field.val() == self.f_crc.val() {
            self.l_seg.next = 0x08.into();
        }
        if self.err_field.val() == self.f_crcdel.val() {
            self.l_seg.next = 0x18.into();
        }
        if self.err_field.val() == self.f_ackslot.val() {
            self.l_seg.next = 0x19.into();
        }
        if self.err_field.val() == self.f_ackdel.val() {
            self.l_seg.next = 0x1B.into();
        }
        if self.err_field.val() == self.f_eof.val() {
            self.l_seg.next = 0x1A.into();
        }
        if self.err_field.val() == self.f_actflag.val() {
            self.l_seg.next = 0x11.into();
        }
        if self.err_field.val() == self.f_pasflag.val() {
            self.l_seg.next = 0x16.into();
        }
        if self.err_field.val() == self.f_ovlflag.val() {
            self.l_seg.next = 0x1C.into();
        }
        if (self.err_field.val() == self.f_errdel.val()) | (self.err_field.val() == self.f_ovldel.val()) {
            self.l_seg.next = 0x17.into();
        }
        // Error code: bit, else stuff, else form, else other (CRC, ACK).
        self.l_ecode.next = self.c_other.val();
        if self.err_kind.val().get_bit(self.k_form.val().index()) {
            self.l_ecode.next = self.c_form.val();
        }
        if self.err_kind.val().get_bit(self.k_stuff.val().index()) {
            self.l_ecode.next = self.c_stuff.val();
        }
        if self.err_kind.val().get_bit(self.k_bit.val().index()) {
            self.l_ecode.next = self.c_bit.val();
        }
        self.l_ecode.next = self.l_ecode.val() | bit_cast::<8, 5>(self.l_seg.val());
        if !self.err_tx.val() {
            self.l_ecode.next = self.l_ecode.val() | self.c_dir.val();
        }
        if self.error.val() & !self.ecc_lock.q.val() {
            self.ecc_r.d.next = self.l_ecode.val();
            self.ecc_lock.d.next = true;
        }

        if self.rst.val() {
            self.alc_r.d.next = 0.into();
            self.alc_lock.d.next = false;
            self.ecc_r.d.next = 0.into();
            self.ecc_lock.d.next = false;
        }
        self.alc.next = self.alc_r.q.val();
        self.ecc.next = self.ecc_r.q.val();
    }
}

canstar_hdl::impl_clocked!(ErrorCapture);

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::drive;

    fn block() -> ErrorCapture {
        let mut u = ErrorCapture::default();
        drive::init(&mut u);
        u.rst.next = true;
        drive::cycle(&mut u);
        u.rst.next = false;
        u
    }

    fn error(u: &mut ErrorCapture, kind: usize, field: Field, pos: u64, tx: bool) {
        u.error.next = true;
        u.err_kind.next = ((1 << kind) as u64).into();
        u.err_field.next = field.code().into();
        u.err_pos.next = pos.into();
        u.err_tx.next = tx;
        drive::cycle(u);
        u.error.next = false;
        drive::cycle(u);
    }

    fn read_ecc(u: &mut ErrorCapture) -> u8 {
        let v = u.ecc.val().index() as u8;
        u.rd_ecc.next = true;
        drive::cycle(u);
        u.rd_ecc.next = false;
        v
    }

    #[test]
    fn error_codes_segments_and_rearming() {
        let mut u = block();
        error(&mut u, ERRK_BIT, Field::Data, 3, true);
        // held until read: a second error is not captured
        error(&mut u, ERRK_STUFF, Field::Ident, 2, false);
        assert_eq!(read_ecc(&mut u), regs::ECC_BIT | 0x0A);
        error(&mut u, ERRK_STUFF, Field::Ident, 9, false);
        assert_eq!(read_ecc(&mut u), regs::ECC_STUFF | regs::ECC_DIR | 0x06);
        error(&mut u, ERRK_FORM, Field::AckDel, 1, false);
        assert_eq!(read_ecc(&mut u), regs::ECC_FORM | regs::ECC_DIR | 0x1B);
        error(&mut u, crate::fsm::ERRK_CRC, Field::AckDel, 1, false);
        assert_eq!(read_ecc(&mut u), regs::ECC_OTHER | regs::ECC_DIR | 0x1B);
        error(&mut u, ERRK_FORM, Field::OvlDel, 4, true);
        assert_eq!(read_ecc(&mut u), regs::ECC_FORM | 0x17);
        // RTR and r1/r0 of an extended frame (Ex_Identifier seen)
        u.field.next = Field::ExIdent.code().into();
        drive::cycle(&mut u);
        error(&mut u, ERRK_BIT, Field::Rtr, 1, true);
        assert_eq!(read_ecc(&mut u), 0x0C);
        error(&mut u, ERRK_BIT, Field::Resv, 1, true);
        assert_eq!(read_ecc(&mut u), 0x0D);
        u.field.next = Field::Sof.code().into();
        drive::cycle(&mut u);
        error(&mut u, ERRK_BIT, Field::Rtr, 1, true);
        assert_eq!(read_ecc(&mut u), 0x04);
    }

    #[test]
    fn arbitration_lost_capture() {
        let mut u = block();
        for (pos, want) in [(12u64, 11u64), (5, 4)] {
            u.arb_lost.next = true;
            u.arb_lost_pos.next = pos.into();
            drive::cycle(&mut u);
            u.arb_lost.next = false;
            drive::cycle(&mut u);
            assert_eq!(u.alc.val().index() as u64, want);
            u.rd_alc.next = true;
            drive::cycle(&mut u);
            u.rd_alc.next = false;
        }
    }
}
