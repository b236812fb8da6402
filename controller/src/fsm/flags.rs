//! [`FlagFields`]: the per-bit decision for error and overload frames (can-protocol.md §10,
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
    /// POSITION is the field's decisive one (the sequencer's `at_end`:
    /// Passive_Error_Flag 1, Active_Error_Flag and Overload_Flag 6, the
    /// delimiters 8).
    pub at_end: Signal<In, Bit>,
    /// The classes of `fld` (the sequencer's registers, see
    /// [`super::seq::Sequencer`]): stuffed area, there or CRC_Delimiter,
    /// hard synchronisation at every position, Intermission.
    pub area: Signal<In, Bit>,
    pub stuffable: Signal<In, Bit>,
    pub hs_fld: Signal<In, Bit>,
    pub inter_fld: Signal<In, Bit>,
    pub tx_role: Signal<In, Bit>,
    /// A flag starts with the next bit (the sequencer's final decision).
    pub flag_start: Signal<In, Bit>,
    /// Exception 1 becomes pending (passive ACK error of a transmitter).
    pub exc1_set: Signal<In, Bit>,

    /// The bit in progress is a flag or delimiter bit: the outputs apply.
    pub own: Signal<Out, Bit>,
    pub nf: Signal<Out, Field>,
    pub npos: Signal<Out, Bits<8>>,
    /// `npos` as a choice ([`super::seq::POS_KEEP`] ..), set along with it;
    /// the sequencer takes this one (issue #16), `npos` is kept for the tests.
    pub npc: Signal<Out, Bits<2>>,
    /// The classes of `nf` (as `area` .. `inter_fld`), set along with it
    /// (issue #16: no decode of `nf` after its multiplexers).
    pub narea: Signal<Out, Bit>,
    pub nsa: Signal<Out, Bit>,
    pub nhs: Signal<Out, Bit>,
    pub ninter: Signal<Out, Bit>,
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
        self.narea.next = self.area.val();
        self.nsa.next = self.stuffable.val();
        self.nhs.next = self.hs_fld.val();
        self.ninter.next = self.inter_fld.val();
        self.npos.next = self.fpos.val();
        self.npc.next = 0.into();
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
                self.npc.next = 1.into();
                if self.fld.val() == Field::PasFlag {
                    // 6 consecutive equal bits, counted from the flag's first bit
                    if self.at_end.val() {
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
                    if self.at_end.val() {
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
                self.npc.next = 3.into();
                if self.fld.val() == Field::OvlFlag {
                    self.nf.next = Field::OvlDel;
                    self.narea.next = false;
                    self.nsa.next = false;
                    self.nhs.next = false;
                    self.ninter.next = false;
                } else {
                    self.nf.next = Field::ErrDel;
                    self.narea.next = false;
                    self.nsa.next = false;
                    self.nhs.next = false;
                    self.ninter.next = false;
                }
            } else {
                self.npos.next = self.l_posinc.val();
                self.npc.next = 1.into();
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
            self.npc.next = 1.into();
            if self.at_end.val() {
                self.nf.next = Field::Inter;
                self.narea.next = false;
                self.nsa.next = false;
                self.nhs.next = false;
                self.ninter.next = true;
                self.npos.next = 1.into();
                self.npc.next = 2.into();
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

canstar_hdl::impl_clocked!(FlagFields);

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::drive;

    #[derive(Debug, Default, Clone, Copy, PartialEq)]
    struct Out {
        nf: Option<Field>,
        npos: u64,
        ndom: bool,
        err: bool,
        err_bit: bool,
        err_form: bool,
        tinc: bool,
        rinc1: bool,
        rinc8: bool,
        ovl: bool,
        daf: bool,
        met: bool,
    }

    fn block(tx: bool) -> FlagFields {
        let mut u = FlagFields::default();
        drive::init(&mut u);
        u.reset.next = true;
        drive::cycle(&mut u);
        u.reset.next = false;
        u.tx_role.next = tx;
        u
    }

    /// One sampled bit in field `fld`/`fpos`; returns the decision.
    fn bit(u: &mut FlagFields, fld: Field, fpos: u64, level: bool, sent: bool) -> Out {
        u.sample.next = true;
        u.fld.next = fld;
        u.fpos.next = fpos.into();
        u.at_end.next = fld.at_end(fpos, false, 0);
        u.rxbit.next = level;
        u.sent.next = sent;
        drive::settle(u);
        // issue #16: the POSITION choice the sequencer takes gives `npos`
        assert_eq!(
            super::super::seq::pos_of_choice(u.npc.val().index() as u64, fpos),
            u.npos.val().index() as u64,
            "{fld:?} {fpos}"
        );
        let o = Out {
            nf: u.own.val().then(|| u.nf.val()),
            npos: u.npos.val().index() as u64,
            ndom: u.ndom.val(),
            err: u.err.val(),
            err_bit: u.err_bit.val(),
            err_form: u.err_form.val(),
            tinc: u.tinc.val(),
            rinc1: u.rinc1.val(),
            rinc8: u.rinc8.val(),
            ovl: u.ovl.val(),
            daf: u.daf.val(),
            met: u.exc1_met.val(),
        };
        drive::cycle(u);
        u.sample.next = false;
        u.flag_start.next = false;
        u.exc1_set.next = false;
        drive::cycle(u);
        o
    }

    /// The bit before a flag (the sequencer starts the flag).
    fn start(u: &mut FlagFields, exc1: bool) {
        u.flag_start.next = true;
        u.exc1_set.next = exc1;
        let o = bit(u, Field::AckSlot, 1, true, true);
        assert!(o.nf.is_none(), "not a flag field");
    }

    /// Drive `n` dominant bits after the flag; the receiver/transmitter counts.
    fn dafs(u: &mut FlagFields, fld: Field, from: u64, n: u64) -> Vec<Out> {
        (0..n).map(|k| bit(u, fld, from + k, false, true)).collect()
    }

    #[test]
    fn active_error_flag_then_dominant_bits_then_delimiter() {
        for tx in [false, true] {
            let mut u = block(tx);
            start(&mut u, false);
            for pos in 1..=6 {
                let o = bit(&mut u, Field::ActFlag, pos, false, false);
                assert_eq!(
                    (o.nf, o.npos, o.ndom, o.err),
                    (Some(Field::ActFlag), pos + 1, pos < 6, false),
                    "flag bit {pos}"
                );
            }
            let d = dafs(&mut u, Field::ActFlag, 7, 16);
            assert!(d.iter().all(|o| o.daf && !o.err));
            // a receiver: +8 at the first dominant bit after an error flag;
            // both: +8 at every 8th
            let counted: Vec<usize> = d.iter().enumerate().filter(|(_, o)| o.rinc8 || o.tinc).map(|(k, _)| k).collect();
            assert_eq!(counted, if tx { vec![7, 15] } else { vec![0, 7, 15] });
            assert!(d.iter().all(|o| if tx { !o.rinc8 } else { !o.tinc }));
            let o = bit(&mut u, Field::ActFlag, 23, true, true);
            assert_eq!((o.nf, o.npos), (Some(Field::ErrDel), 2));
        }
    }

    #[test]
    fn overload_flag_shares_the_mechanism_but_not_the_first_dominant_bit_rule() {
        let mut u = block(false);
        start(&mut u, false);
        for pos in 1..=6 {
            assert_eq!(bit(&mut u, Field::OvlFlag, pos, false, false).ndom, pos < 6);
        }
        let d = dafs(&mut u, Field::OvlFlag, 7, 8);
        let counted: Vec<usize> = d.iter().enumerate().filter(|(_, o)| o.rinc8).map(|(k, _)| k).collect();
        assert_eq!(counted, vec![7], "only every 8th dominant bit after an overload flag");
        let o = bit(&mut u, Field::OvlFlag, 15, true, true);
        assert_eq!((o.nf, o.npos), (Some(Field::OvlDel), 2));
    }

    #[test]
    fn flag_bit_error_and_delimiter_errors() {
        let mut u = block(false);
        start(&mut u, false);
        bit(&mut u, Field::ActFlag, 1, false, false);
        // recessive read while driving dominant: bit error, REC +8
        let o = bit(&mut u, Field::ActFlag, 2, true, false);
        assert!(o.err && o.err_bit && o.rinc8 && !o.tinc);
        // a listen-only node sends its flag recessive: no bit error
        let o = bit(&mut u, Field::ActFlag, 3, true, true);
        assert!(!o.err);
        // delimiters: dominant before bit 8 is a form error, at bit 8 an overload condition
        for del in [Field::ErrDel, Field::OvlDel] {
            let o = bit(&mut u, del, 3, false, true);
            assert!(o.err && o.err_form && o.rinc1 && !o.ovl, "{del:?}");
            let o = bit(&mut u, del, 5, true, true);
            assert_eq!((o.nf, o.npos, o.err), (Some(del), 6, false));
            let o = bit(&mut u, del, 8, false, true);
            assert_eq!((o.nf, o.npos, o.ovl, o.err), (Some(Field::Inter), 1, true, false));
        }
    }

    #[test]
    fn passive_flag_six_equal_bits_and_exception_1() {
        // 6 equal bits end the flag, counted from its first bit
        let mut u = block(true);
        start(&mut u, true);
        let levels = [true, true, false, false, false, false, false, false];
        let mut outs = vec![];
        for (k, l) in levels.iter().enumerate() {
            outs.push(bit(&mut u, Field::PasFlag, k as u64 + 1, *l, true));
        }
        // the first dominant bit costs TEC +8 after all (exception 1 not met)
        let tinc: Vec<usize> = outs.iter().enumerate().filter(|(_, o)| o.tinc).map(|(k, _)| k).collect();
        assert_eq!(tinc, vec![2]);
        assert!(outs.iter().all(|o| !o.met && !o.ndom));
        // done after the 6th equal (dominant) bit: the next dominant bit is a DAF
        assert!(bit(&mut u, Field::PasFlag, 9, false, true).daf);

        // no dominant bit during the passive flag: exception 1 met, no TEC change
        let mut u = block(true);
        start(&mut u, true);
        let outs: Vec<Out> = (1..=6).map(|p| bit(&mut u, Field::PasFlag, p, true, true)).collect();
        assert!(outs.iter().all(|o| !o.tinc));
        assert_eq!(outs.iter().map(|o| o.met).collect::<Vec<_>>(), [false, false, false, false, false, true]);
        let o = bit(&mut u, Field::PasFlag, 7, true, true);
        assert_eq!((o.nf, o.npos), (Some(Field::ErrDel), 2));
    }
}
