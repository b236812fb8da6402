//! [`FrameFields`]: the per-bit decision for the bits of a data or remote
//! frame, Start_Of_Frame to End_Of_Frame (can-protocol.md §4, §5, §6, §9).
//!
//! Decided on the `sample` clock, combinationally from the bit just sampled
//! (`rxbit`, with `sent` the level this node drove) and the registers; the
//! sequencer ([`super::seq`]) applies the decision on the same clock. All
//! outputs are 0 on other clocks and while the bit in progress is not a
//! frame bit (`own` low).
//!
//! - Stuffed area: a stuff bit changes nothing but the destuffer, unless it
//!   is the sixth equal bit (stuff error, or bit error for a transmitter that
//!   sent a dominant stuff bit; TEC exception 2 inside arbitration). Other
//!   bits: a transmitter reading back another level has lost arbitration
//!   (recessive sent in an arbitration bit) or sees a bit error; otherwise
//!   the bit is taken (`adv`: shifted into the receive register and the CRC)
//!   and the field advances.
//! - CRC_Delimiter, ACK_Slot, ACK_Delimiter, End_Of_Frame: form errors,
//!   ACK errors (exception 1 for an error-passive transmitter), the pending
//!   CRC error signalled at ACK_Delimiter, success of a transmission
//!   (`tx_ok`) and delivery of a received frame (`rx_ok`, End_Of_Frame bit 7
//!   even if dominant: an overload condition). A receiver counts the
//!   successful reception for REC (`rok`, C13) at the ACK slot when it read
//!   its own ACK back dominant if `rec_iso` is set (ISO 11898-1, ISO
//!   16845-1 7.6.7, 7.6.8, 7.6.16), else at a recessive End_Of_Frame bit 7
//!   only (the 1999 reference programs).
//!
//! State: `crcerr`, a CRC error seen at the last CRC bit by a receiver and
//! not yet signalled (set at CRC bit 15 when the CRC register is not zero
//! after it; cleared when a frame starts or an error flag starts).

// `#[hdl_gen]` has no match guards, so nested `if`s stay.
#![allow(clippy::collapsible_match)]

use super::field::Field;
use rust_hdl::prelude::*;

#[derive(LogicBlock, Default)]
pub struct FrameFields {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub sample: Signal<In, Bit>,
    /// The sampled level, and the level this node drove for it: `sent` if
    /// the bit is not a stuff bit, `sent_stuff` if it is (each is read in
    /// its own case only, so neither waits for the stuff-bit decode).
    pub rxbit: Signal<In, Bit>,
    pub sent: Signal<In, Bit>,
    pub sent_stuff: Signal<In, Bit>,
    /// C13: REC − 1 for a successful reception at the ACK slot (ISO);
    /// low: at a recessive End_Of_Frame bit 7 only (the 1999 programs).
    pub rec_iso: Signal<In, Bit>,
    pub fld: Signal<In, Field>,
    pub fpos: Signal<In, Bits<8>>,
    /// POSITION is the field's decisive one (the sequencer's `at_end`:
    /// Identifier 11, Ex_Identifier 18, Reserved_Bits 1 of an extended
    /// frame, DLC 4, Data `data_bits`, CRC_Sequence 15, End_Of_Frame 7).
    pub at_end: Signal<In, Bit>,
    /// The classes of `fld` (the sequencer's registers, see
    /// [`super::seq::Sequencer`]): stuffed area, there or CRC_Delimiter,
    /// hard synchronisation at every position, Intermission.
    pub area: Signal<In, Bit>,
    pub stuffable: Signal<In, Bit>,
    pub hs_fld: Signal<In, Bit>,
    pub inter_fld: Signal<In, Bit>,
    pub tx_role: Signal<In, Bit>,
    pub dom: Signal<In, Bit>,
    pub listen_only: Signal<In, Bit>,
    pub self_test: Signal<In, Bit>,
    /// Error-active (error flags are active flags).
    pub active: Signal<In, Bit>,
    /// From [`super::decode::BitDecode`]; `arb` is read for a bit that is
    /// not a stuff bit only, `arb_stuff` for a stuff bit only.
    pub stuffed: Signal<In, Bit>,
    pub stuff: Signal<In, Bit>,
    pub arb: Signal<In, Bit>,
    pub arb_stuff: Signal<In, Bit>,
    /// Two-clock mode (see [`super::seq::Sequencer`]): `arb` and
    /// `arb_stuff`, decodes of `fld`, `pfld` and `ext` alone, are taken from
    /// flip-flops that load them on every clock (issue #16). Those registers
    /// change on `sample` clocks and with `reset`; a counter load changes
    /// `fld` only to fields where `own` is 0, where neither is read.
    pub pipe: Signal<In, Bit>,
    /// The sampled bit is a sixth equal bit: the destuffer has seen 5
    /// (`next_is_stuff`) and the sampled level continues the run. Read on a
    /// stuff bit of the stuffed area only, where the destuffer is active, so
    /// it equals the destuffer's `stuff_error` there; taken without the
    /// destuffer's `active` input, which holds the sequencer's SOF decision
    /// (issue #16; the destuffer's own `stuff_error` is not used).
    pub stuff_error: Signal<In, Bit>,
    /// The CRC register is not zero after this bit (a receiver's CRC check).
    pub crc_rem: Signal<In, Bit>,
    /// From the receive register: extended frame, remote frame, DLC bits
    /// 2..0 all zero, data field length in bits.
    pub ext: Signal<In, Bit>,
    pub rtr: Signal<In, Bit>,
    pub dlc_lo_zero: Signal<In, Bit>,
    pub data_bits: Signal<In, Bits<8>>,
    /// The own frame is extended (the transmit register's IDE).
    pub tx_ide: Signal<In, Bit>,
    /// The sequencer's final decision for this bit: a frame starts, an
    /// error flag starts (both clear a pending CRC error).
    pub sofinit: Signal<In, Bit>,
    pub err_now: Signal<In, Bit>,

    /// The bit in progress is a frame bit: the outputs below apply.
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
    /// Drive dominant in the next bit (the ACK; a stuff bit keeps `dom`).
    pub ndom: Signal<Out, Bit>,
    /// The next bit is a bit of the own frame (see the transmit register).
    pub usetx: Signal<Out, Bit>,
    /// The field of the next bit if the bit in progress is a bit of the
    /// stuffed area, not a stuff bit, and is taken without an error, with
    /// the role kept: `nf` whenever `usetx` is set, except at Identifier 11
    /// of a transmitter that loses arbitration there, whose next bit is not
    /// driven. It selects the level of the next own bit
    /// ([`super::txreq::TxRequest`]) without waiting for the bit and
    /// arbitration checks (issue #16); any value on other clocks.
    pub lnf: Signal<Out, Field>,
    /// Arbitration lost at this bit: the node continues as a receiver.
    pub lost: Signal<Out, Bit>,
    pub err: Signal<Out, Bit>,
    pub err_bit: Signal<Out, Bit>,
    pub err_stuff: Signal<Out, Bit>,
    pub err_crc: Signal<Out, Bit>,
    pub err_form: Signal<Out, Bit>,
    pub err_ack: Signal<Out, Bit>,
    /// Counter strobes (§13): TEC +8, REC +1, REC -1 (successful reception).
    pub tinc: Signal<Out, Bit>,
    pub rinc1: Signal<Out, Bit>,
    pub rok: Signal<Out, Bit>,
    /// Overload condition (a receiver's dominant End_Of_Frame bit 7).
    pub ovl: Signal<Out, Bit>,
    /// Passive ACK error of a transmitter: exception 1 pending.
    pub exc1: Signal<Out, Bit>,
    /// Stuff error inside arbitration: exception 2 (no TEC increment).
    pub exc2: Signal<Out, Bit>,
    /// Successful transmission (TEC -1).
    pub tx_ok: Signal<Out, Bit>,
    /// A received frame is delivered.
    pub rx_ok: Signal<Out, Bit>,
    /// The Start_Of_Frame bit was taken.
    pub sof: Signal<Out, Bit>,
    /// The bit is taken into the frame (receive register, CRC).
    pub adv: Signal<Out, Bit>,

    crcerr: DFF<Bit>,
    // `arb` and `arb_stuff` one clock late (see `pipe`).
    rarb: DFF<Bit>,
    rarbs: DFF<Bit>,

    // Working values.
    l_posinc: Signal<Local, Bits<8>>,
    l_role: Signal<Local, Bit>,
    l_form: Signal<Local, Bit>,
    l_crcset: Signal<Local, Bit>,
    l_arb: Signal<Local, Bit>,
    l_arbs: Signal<Local, Bit>,
}

impl Logic for FrameFields {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, crcerr, rarb, rarbs);
        self.rarb.d.next = self.arb.val();
        self.rarbs.d.next = self.arb_stuff.val();
        self.l_arb.next = self.arb.val();
        self.l_arbs.next = self.arb_stuff.val();
        if self.pipe.val() {
            self.l_arb.next = self.rarb.q.val();
            self.l_arbs.next = self.rarbs.q.val();
        }
        self.l_posinc.next = self.fpos.val() + 1;
        if self.fpos.val() == 255 {
            self.l_posinc.next = self.fpos.val();
        }
        // Decided on `sample` only (all outputs 0 between sample strobes).
        self.own.next = self.sample.val()
            & (self.stuffed.val()
                | (self.fld.val() == Field::CrcDel)
                | (self.fld.val() == Field::AckSlot)
                | (self.fld.val() == Field::AckDel)
                | (self.fld.val() == Field::Eof));
        self.nf.next = self.fld.val();
        self.narea.next = self.area.val();
        self.nsa.next = self.stuffable.val();
        self.nhs.next = self.hs_fld.val();
        self.ninter.next = self.inter_fld.val();
        self.npos.next = self.fpos.val();
        self.npc.next = 0.into();
        self.ndom.next = false;
        self.usetx.next = false;
        self.l_role.next = self.tx_role.val();
        self.err.next = false;
        self.err_bit.next = false;
        self.err_stuff.next = false;
        self.err_crc.next = false;
        self.err_form.next = false;
        self.err_ack.next = false;
        self.l_form.next = false;
        self.tinc.next = false;
        self.rinc1.next = false;
        self.rok.next = false;
        self.ovl.next = false;
        self.exc1.next = false;
        self.exc2.next = false;
        self.tx_ok.next = false;
        self.rx_ok.next = false;
        self.adv.next = false;
        self.l_crcset.next = false;

        if self.own.val() {
            if self.stuffed.val() {
                if self.stuff.val() {
                    self.ndom.next = self.dom.val();
                    if self.stuff_error.val() {
                        self.err.next = true;
                        if self.tx_role.val() & self.rxbit.val() & !self.sent_stuff.val() {
                            self.err_bit.next = true;
                            self.tinc.next = true;
                        } else {
                            self.err_stuff.next = true;
                            if !self.tx_role.val() {
                                self.rinc1.next = true;
                            } else if self.l_arbs.val() {
                                self.exc2.next = true;
                            } else {
                                self.tinc.next = true;
                            }
                        }
                    }
                } else {
                    if self.tx_role.val() & (self.rxbit.val() != self.sent.val()) {
                        if self.l_arb.val() & self.sent.val() {
                            self.l_role.next = false;
                        } else {
                            self.err.next = true;
                            self.err_bit.next = true;
                            self.tinc.next = true;
                        }
                    }
                    if !self.err.val() {
                        self.adv.next = true;
                        self.usetx.next = true;
                        self.npos.next = self.l_posinc.val();
                        self.npc.next = 1.into();
                        match self.fld.val() {
                            Field::Sof => {
                                self.nf.next = Field::Ident;
                                self.narea.next = true;
                                self.nsa.next = true;
                                self.nhs.next = false;
                                self.ninter.next = false;
                                self.npos.next = 1.into();
                                self.npc.next = 2.into();
                            }
                            Field::Ident => {
                                if self.at_end.val() {
                                    self.npos.next = 1.into();
                                    self.npc.next = 2.into();
                                    if self.l_role.val() & self.tx_ide.val() {
                                        self.nf.next = Field::Srr;
                                        self.narea.next = true;
                                        self.nsa.next = true;
                                        self.nhs.next = false;
                                        self.ninter.next = false;
                                    } else {
                                        self.nf.next = Field::Rtr;
                                        self.narea.next = true;
                                        self.nsa.next = true;
                                        self.nhs.next = false;
                                        self.ninter.next = false;
                                    }
                                }
                            }
                            Field::Srr => {
                                self.nf.next = Field::Ide;
                                self.narea.next = true;
                                self.nsa.next = true;
                                self.nhs.next = false;
                                self.ninter.next = false;
                                self.npos.next = 1.into();
                                self.npc.next = 2.into();
                            }
                            Field::Rtr => {
                                self.npos.next = 1.into();
                                self.npc.next = 2.into();
                                if self.ext.val() {
                                    self.nf.next = Field::Resv;
                                    self.narea.next = true;
                                    self.nsa.next = true;
                                    self.nhs.next = false;
                                    self.ninter.next = false;
                                } else {
                                    self.nf.next = Field::Ide;
                                    self.narea.next = true;
                                    self.nsa.next = true;
                                    self.nhs.next = false;
                                    self.ninter.next = false;
                                }
                            }
                            Field::Ide => {
                                // the IDE bit just taken: recessive = extended
                                self.npos.next = 1.into();
                                self.npc.next = 2.into();
                                if self.rxbit.val() {
                                    self.nf.next = Field::ExIdent;
                                    self.narea.next = true;
                                    self.nsa.next = true;
                                    self.nhs.next = false;
                                    self.ninter.next = false;
                                } else {
                                    self.nf.next = Field::Resv;
                                    self.narea.next = true;
                                    self.nsa.next = true;
                                    self.nhs.next = false;
                                    self.ninter.next = false;
                                }
                            }
                            Field::ExIdent => {
                                if self.at_end.val() {
                                    self.nf.next = Field::Rtr;
                                    self.narea.next = true;
                                    self.nsa.next = true;
                                    self.nhs.next = false;
                                    self.ninter.next = false;
                                    self.npos.next = 1.into();
                                    self.npc.next = 2.into();
                                }
                            }
                            Field::Resv => {
                                // r1 and r0 (extended) or r0 (standard)
                                if !self.at_end.val() {
                                    self.nf.next = Field::Dlc;
                                    self.narea.next = true;
                                    self.nsa.next = true;
                                    self.nhs.next = false;
                                    self.ninter.next = false;
                                    self.npos.next = 1.into();
                                    self.npc.next = 2.into();
                                }
                            }
                            Field::Dlc => {
                                if self.at_end.val() {
                                    // no data: a remote frame, or DLC 0 (the
                                    // last DLC bit is this one)
                                    self.npos.next = 1.into();
                                    self.npc.next = 2.into();
                                    if self.rtr.val() | (self.dlc_lo_zero.val() & !self.rxbit.val()) {
                                        self.nf.next = Field::Crc;
                                        self.narea.next = true;
                                        self.nsa.next = true;
                                        self.nhs.next = false;
                                        self.ninter.next = false;
                                    } else {
                                        self.nf.next = Field::Data;
                                        self.narea.next = true;
                                        self.nsa.next = true;
                                        self.nhs.next = false;
                                        self.ninter.next = false;
                                    }
                                }
                            }
                            Field::Data => {
                                if self.at_end.val() {
                                    self.nf.next = Field::Crc;
                                    self.narea.next = true;
                                    self.nsa.next = true;
                                    self.nhs.next = false;
                                    self.ninter.next = false;
                                    self.npos.next = 1.into();
                                    self.npc.next = 2.into();
                                }
                            }
                            Field::Crc => {
                                if self.at_end.val() {
                                    self.nf.next = Field::CrcDel;
                                    self.narea.next = false;
                                    self.nsa.next = true;
                                    self.nhs.next = false;
                                    self.ninter.next = false;
                                    self.npos.next = 1.into();
                                    self.npc.next = 2.into();
                                    self.usetx.next = false;
                                    self.l_crcset.next = self.crc_rem.val();
                                }
                            }
                            _ => {}
                        }
                    }
                }
            } else {
                match self.fld.val() {
                    Field::CrcDel => {
                        if !self.rxbit.val() {
                            self.l_form.next = true;
                        } else {
                            self.nf.next = Field::AckSlot;
                            self.narea.next = false;
                            self.nsa.next = false;
                            self.nhs.next = false;
                            self.ninter.next = false;
                            self.npos.next = 1.into();
                            self.npc.next = 2.into();
                            self.ndom.next = !self.tx_role.val() & !self.crcerr.q.val() & !self.listen_only.val();
                        }
                    }
                    Field::AckSlot => {
                        self.nf.next = Field::AckDel;
                        self.narea.next = false;
                        self.nsa.next = false;
                        self.nhs.next = false;
                        self.ninter.next = false;
                        self.npos.next = 1.into();
                        self.npc.next = 2.into();
                        if self.rxbit.val() {
                            if self.tx_role.val() {
                                if !self.self_test.val() {
                                    self.err.next = true;
                                    self.err_ack.next = true;
                                    if self.active.val() {
                                        self.tinc.next = true;
                                    } else {
                                        self.exc1.next = true;
                                    }
                                }
                            } else if self.dom.val() {
                                // the own ACK read back recessive
                                self.err.next = true;
                                self.err_bit.next = true;
                                self.rinc1.next = true;
                            }
                        } else if self.dom.val() {
                            // the own ACK read back dominant: ISO counts
                            // the reception as successful here (C13)
                            self.rok.next = self.rec_iso.val();
                        }
                    }
                    Field::AckDel => {
                        self.l_form.next = !self.rxbit.val();
                        self.nf.next = Field::Eof;
                        self.narea.next = false;
                        self.nsa.next = false;
                        self.nhs.next = false;
                        self.ninter.next = false;
                        self.npos.next = 1.into();
                        self.npc.next = 2.into();
                    }
                    Field::Eof => {
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
                            if self.tx_role.val() {
                                if !self.rxbit.val() {
                                    self.l_form.next = true;
                                } else {
                                    self.tx_ok.next = true;
                                }
                            } else {
                                self.rx_ok.next = true;
                                if !self.rxbit.val() {
                                    self.ovl.next = true;
                                } else {
                                    self.rok.next = !self.rec_iso.val();
                                }
                            }
                        } else {
                            self.l_form.next = !self.rxbit.val();
                        }
                    }
                    _ => {}
                }
                // A dominant bit in a fixed-form recessive bit.
                if self.l_form.val() {
                    self.err.next = true;
                    self.err_form.next = true;
                    self.tinc.next = self.tx_role.val();
                    self.rinc1.next = !self.tx_role.val();
                }
                // The pending CRC error; a form error at ACK_Delimiter is the
                // same error (one flag, one count, reported as CRC).
                if (self.fld.val() == Field::AckDel) & !self.tx_role.val() & self.crcerr.q.val() {
                    self.err.next = true;
                    self.err_form.next = false;
                    self.err_crc.next = true;
                    self.rinc1.next = true;
                }
            }
        }

        if self.sample.val() {
            self.crcerr.d.next =
                (self.crcerr.q.val() | self.l_crcset.val()) & !self.sofinit.val() & !self.err_now.val();
        }
        if self.reset.val() {
            self.crcerr.d.next = false;
        }

        // The next field of a taken bit of the stuffed area (see `lnf`): the
        // field advance above without the error and arbitration checks.
        self.lnf.next = self.fld.val();
        match self.fld.val() {
            Field::Sof => {
                self.lnf.next = Field::Ident;
            }
            Field::Ident => {
                if self.at_end.val() {
                    if self.tx_role.val() & self.tx_ide.val() {
                        self.lnf.next = Field::Srr;
                    } else {
                        self.lnf.next = Field::Rtr;
                    }
                }
            }
            Field::Srr => {
                self.lnf.next = Field::Ide;
            }
            Field::Rtr => {
                if self.ext.val() {
                    self.lnf.next = Field::Resv;
                } else {
                    self.lnf.next = Field::Ide;
                }
            }
            Field::Ide => {
                if self.rxbit.val() {
                    self.lnf.next = Field::ExIdent;
                } else {
                    self.lnf.next = Field::Resv;
                }
            }
            Field::ExIdent => {
                if self.at_end.val() {
                    self.lnf.next = Field::Rtr;
                }
            }
            Field::Resv => {
                if !self.at_end.val() {
                    self.lnf.next = Field::Dlc;
                }
            }
            Field::Dlc => {
                if self.at_end.val() {
                    if self.rtr.val() | (self.dlc_lo_zero.val() & !self.rxbit.val()) {
                        self.lnf.next = Field::Crc;
                    } else {
                        self.lnf.next = Field::Data;
                    }
                }
            }
            Field::Data => {
                if self.at_end.val() {
                    self.lnf.next = Field::Crc;
                }
            }
            Field::Crc => {
                if self.at_end.val() {
                    self.lnf.next = Field::CrcDel;
                }
            }
            _ => {}
        }

        self.sof.next = self.adv.val() & (self.fld.val() == Field::Sof);
        self.lost.next = self.tx_role.val() & !self.l_role.val();
    }
}

canstar_hdl::impl_clocked!(FrameFields);
