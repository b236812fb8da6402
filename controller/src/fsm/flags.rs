//! [`FlagFields`]: the per-bit decision for error and overload frames (§10,
//! §11, §13): the flags, the dominant bits after a flag, and the
//! delimiters.
//!
//! One mechanism serves the three flags. An active error flag and an
//! overload flag are 6 dominant bits sent with bit-error checking (a
//! listen-only node sends them recessive and sees no bit error); a passive
//! error flag ends after 6 consecutive equal bits on the bus. After its
//! flag the node waits for a recessive bit, counting dominant bits after
//! the flag (`daf`): every 8th one costs TEC +8 (transmitter) or REC +8
//! (receiver); after an error flag a receiver also counts the first one
//! (+8). The recessive bit is delimiter bit 2 of the Error_Delimiter, or of
//! the Overload_Delimiter after an overload flag. Both delimiters: a
//! dominant bit is a form error before bit 8 and an overload condition at
//! bit 8.
//!
//! Exception 1 (§13): an error-passive transmitter's ACK error does not
//! raise TEC if no dominant bit is seen during its passive flag; the first
//! dominant bit costs +8 after all.
//!
//! Decided on the `sample` clock like [`super::frame_fields`]; all outputs
//! are 0 on other clocks and while the bit in progress is not a flag or
//! delimiter bit (`own` low).
//!
//! State (updated on `sample`, cleared by `reset`):
//! - `fdone`: the flag has been sent (6 bits; passive: 6 equal bits seen);
//!   cleared when a flag starts;
//! - `eqcnt`, `eqlast`: length and level of the current run of equal bits
//!   during a passive flag (restarted at its first bit);
//! - `dafc`: dominant bits after the flag, modulo 8; cleared when a flag
//!   starts and when it has been sent;
//! - `dafany`: a dominant bit after the flag has been seen (cleared likewise);
//! - `exc1`: exception 1 pending: set by a passive transmitter's ACK error
//!   (`exc1_set`), cleared at the first dominant bit of the passive flag
//!   (TEC +8 after all) or when the flag has been sent (`EV_EXC1`).

use super::field::Field;
use rust_hdl::prelude::*;

#[derive(LogicBlock, Default)]
pub struct FlagFields {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub sample: Signal<In, Bit>,
    pub rxbit: Signal<In, Bit>,
    pub sent: Signal<In, Bit>,
    pub fld: Signal<In, Field>,
    pub fpos: Signal<In, Bits<8>>,
    pub tx_role: Signal<In, Bit>,
    /// A flag starts with the next bit (the sequencer's final decision).
    pub flag_start: Signal<In, Bit>,
    /// Exception 1 becomes pending (passive ACK error of a transmitter).
    pub exc1_set: Signal<In, Bit>,

    /// The bit in progress is a flag or delimiter bit: the outputs apply.
    pub own: Signal<Out, Bit>,
    pub nf: Signal<Out, Field>,
    pub npos: Signal<Out, Bits<8>>,
    pub ndom: Signal<Out, Bit>,
    pub err: Signal<Out, Bit>,
    pub err_bit: Signal<Out, Bit>,
    pub err_form: Signal<Out, Bit>,
    pub tinc: Signal<Out, Bit>,
    pub rinc1: Signal<Out, Bit>,
    pub rinc8: Signal<Out, Bit>,
    pub ovl: Signal<Out, Bit>,
    /// A dominant bit after an own flag (`EV_DAF`).
    pub daf: Signal<Out, Bit>,
    /// The passive flag ended with exception 1 met (`EV_EXC1`).
    pub exc1_met: Signal<Out, Bit>,

    fdone: DFF<Bit>,
    eqcnt: DFF<Bits<3>>,
    eqlast: DFF<Bit>,
    dafc: DFF<Bits<3>>,
    dafany: DFF<Bit>,
    exc1: DFF<Bit>,

    // Working values.
    l_posinc: Signal<Local, Bits<8>>,
    l_flag: Signal<Local, Bit>,
    l_delim: Signal<Local, Bit>,
    l_errflag: Signal<Local, Bit>,
    l_fdone: Signal<Local, Bit>,
    l_eqcnt: Signal<Local, Bits<3>>,
    l_eqlast: Signal<Local, Bit>,
    l_dafc: Signal<Local, Bits<3>>,
    l_dafany: Signal<Local, Bit>,
    l_exc1: Signal<Local, Bit>,
}

impl Logic for FlagFields {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, fdone, eqcnt, eqlast, dafc, dafany, exc1);
        self.l_posinc.next = self.fpos.val() + 1;
        if self.fpos.val() == 255 {
            self.l_posinc.next = self.fpos.val();
        }
        // Decided on `sample` only (all outputs 0 between sample strobes).
        self.l_errflag.next = (self.fld.val() == Field::ActFlag) | (self.fld.val() == Field::PasFlag);
        self.l_flag.next = self.sample.val() & (self.l_errflag.val() | (self.fld.val() == Field::OvlFlag));
        self.l_delim.next = self.sample.val() & ((self.fld.val() == Field::ErrDel) | (self.fld.val() == Field::OvlDel));
        self.own.next = self.l_flag.val() | self.l_delim.val();
        self.nf.next = self.fld.val();
        self.npos.next = self.fpos.val();
        self.ndom.next = false;
        self.err.next = false;
        self.err_bit.next = false;
        self.err_form.next = false;
        self.tinc.next = false;
        self.rinc1.next = false;
        self.rinc8.next = false;
        self.ovl.next = false;
        self.daf.next = false;
        self.exc1_met.next = false;
        self.l_fdone.next = self.fdone.q.val();
        self.l_eqcnt.next = self.eqcnt.q.val();
        self.l_eqlast.next = self.eqlast.q.val();
        self.l_dafc.next = self.dafc.q.val();
        self.l_dafany.next = self.dafany.q.val();
        self.l_exc1.next = self.exc1.q.val() | self.exc1_set.val();

        if self.l_flag.val() {
            if !self.fdone.q.val() {
                self.npos.next = self.l_posinc.val();
                if self.fld.val() == Field::PasFlag {
                    // 6 consecutive equal bits, counted from the flag's first bit
                    if self.fpos.val() == 1 {
                        self.l_eqcnt.next = 1.into();
                        self.l_eqlast.next = self.rxbit.val();
                    } else if self.rxbit.val() == self.eqlast.q.val() {
                        self.l_eqcnt.next = self.eqcnt.q.val() + 1;
                    } else {
                        self.l_eqcnt.next = 1.into();
                        self.l_eqlast.next = self.rxbit.val();
                    }
                    if self.exc1.q.val() & !self.rxbit.val() {
                        // exception 1 not met: +8 once, at the first dominant bit
                        self.l_exc1.next = false;
                        self.tinc.next = true;
                    }
                    if self.l_eqcnt.val() == 6 {
                        self.l_fdone.next = true;
                        self.exc1_met.next = self.l_exc1.val();
                        self.l_exc1.next = false;
                    }
                } else if self.rxbit.val() & !self.sent.val() {
                    // bit error: recessive read while driving dominant
                    self.err.next = true;
                    self.err_bit.next = true;
                    self.tinc.next = self.tx_role.val();
                    self.rinc8.next = !self.tx_role.val();
                } else {
                    self.ndom.next = true;
                    if self.fpos.val() == 6 {
                        self.l_fdone.next = true;
                        self.ndom.next = false;
                    }
                }
                if self.l_fdone.val() {
                    self.l_dafc.next = 0.into();
                    self.l_dafany.next = false;
                }
            } else if self.rxbit.val() {
                // delimiter bit 2 (bit 1 was the last flag or dominant bit)
                self.npos.next = 2.into();
                if self.fld.val() == Field::OvlFlag {
                    self.nf.next = Field::OvlDel;
                } else {
                    self.nf.next = Field::ErrDel;
                }
            } else {
                self.npos.next = self.l_posinc.val();
                self.daf.next = true;
                self.l_dafany.next = true;
                self.l_dafc.next = self.dafc.q.val() + 1;
                if self.l_errflag.val() & !self.dafany.q.val() & !self.tx_role.val() {
                    self.rinc8.next = true;
                }
                if self.dafc.q.val() == 7 {
                    self.tinc.next = self.tx_role.val();
                    self.rinc8.next = !self.tx_role.val();
                }
            }
        }
        if self.l_delim.val() {
            self.npos.next = self.l_posinc.val();
            if self.fpos.val() == 8 {
                self.nf.next = Field::Inter;
                self.npos.next = 1.into();
                self.ovl.next = !self.rxbit.val();
            } else if !self.rxbit.val() {
                self.err.next = true;
                self.err_form.next = true;
                self.tinc.next = self.tx_role.val();
                self.rinc1.next = !self.tx_role.val();
            }
        }

        if self.sample.val() {
            self.fdone.d.next = self.l_fdone.val() & !self.flag_start.val();
            self.eqcnt.d.next = self.l_eqcnt.val();
            self.eqlast.d.next = self.l_eqlast.val();
            self.dafc.d.next = self.l_dafc.val();
            self.dafany.d.next = self.l_dafany.val() & !self.flag_start.val();
            if self.flag_start.val() {
                self.dafc.d.next = 0.into();
            }
            self.exc1.d.next = self.l_exc1.val();
        }
        if self.reset.val() {
            self.fdone.d.next = false;
            self.eqcnt.d.next = 0.into();
            self.eqlast.d.next = false;
            self.dafc.d.next = 0.into();
            self.dafany.d.next = false;
            self.exc1.d.next = false;
        }

    }
}
