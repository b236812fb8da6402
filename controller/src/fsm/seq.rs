//! [`Sequencer`]: the bit-level frame sequencer: FIELD, POSITION and role
//! of the bit in progress, and the level to drive in the next bit.
//!
//! For the bit just sampled it takes the decision of the field group that
//! owns the current field ([`super::frame_fields::FrameFields`] for
//! Start_Of_Frame .. End_Of_Frame, [`super::flags::FlagFields`] for flags
//! and delimiters) and decides itself for the fields between frames:
//! - Reset, then Wait_For_Bus_Idle until 11 recessive bits (integration);
//! - Bus_Idle; a dominant bit there is a SOF received;
//! - Bus_Off: runs of 11 recessive bits (waiting for a `recover` strobe
//!   with `host_recovery`), the 128th ends the recovery;
//! - Intermission: a dominant bit 1 or 2 is an overload condition, a
//!   dominant bit 3 a SOF (a node with a pending request continues as
//!   transmitter at Identifier 1, except an error-passive former
//!   transmitter, C15); after it an error-passive former transmitter
//!   suspends transmission for 8 bits (a dominant bit there is a SOF).
//!
//! Then, in this order: a SOF sampled starts a frame (Identifier 1 next); a
//! free bus (11 recessive bits after reset or recovery, recessive Bus_Idle,
//! Intermission bit 3 or Suspend_Transmission bit 8) starts an own frame if
//! one is pending (`req`, not in listen-only mode), else Bus_Idle; while
//! the next bit is an own frame bit its level comes from the transmit
//! register (`level`, `level_sof` in); an error starts an active or passive
//! error flag, otherwise an overload condition an overload flag; a TEC above
//! 255 (`busoff` from fault confinement) makes it Bus_Off instead, with no
//! flag. The registers take the result on `sample`.
//!
//! State: `fld`, `fpos` (FIELD and POSITION of the next non-stuff bit;
//! positions saturate at 255); `pfld`, `ppos` (those of the last non-stuff
//! bit, shown while a stuff bit is in progress; not reset); `rtx` (the node
//! is the transmitter of the frame in progress); `dom` (drive the next bit
//! dominant). `reset` gives Wait_For_Bus_Idle 1, receiver, recessive; a
//! counter load (`cnt_load`, priority over `reset`) with `tec_in` ≥ 256
//! gives Bus_Off 1, one with `tec_in` < 256 while in Bus_Off gives
//! Wait_For_Bus_Idle 1.

use super::field::Field;
use rust_hdl::prelude::*;

/// The choices of the next POSITION (`npc` of the frame and flag fields,
/// `f_npc`/`g_npc` here): keep it, increment it (saturating at 255), 1, 2.
pub const POS_KEEP: u64 = 0;
pub const POS_INC: u64 = 1;
pub const POS_ONE: u64 = 2;
pub const POS_TWO: u64 = 3;

/// The POSITION a choice gives from `fpos` (for the unit tests).
pub fn pos_of_choice(npc: u64, fpos: u64) -> u64 {
    match npc {
        POS_KEEP => fpos,
        POS_INC => (fpos + 1).min(255),
        POS_ONE => 1,
        _ => 2,
    }
}

#[derive(LogicBlock, Default)]
pub struct Sequencer {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub sample: Signal<In, Bit>,
    pub rxbit: Signal<In, Bit>,
    pub listen_only: Signal<In, Bit>,
    pub host_recovery: Signal<In, Bit>,
    pub cnt_load: Signal<In, Bit>,
    pub tec_in: Signal<In, Bits<9>>,
    /// The bit in progress is a stuff bit.
    pub stuff: Signal<In, Bit>,
    /// Two-clock mode (issue #16; [`crate::core::CanCore`] ties it high, its
    /// `sample` strobes are at least 2 clocks apart): `at_end` and `pstuff`
    /// come from flip-flops that take their decodes on every clock, so they
    /// are valid from the second clock after a `sample` on. Low: the same
    /// decodes combinationally (`sample` may come on every clock).
    pub pipe: Signal<In, Bit>,
    /// From the receive register: extended frame, data field length in bits
    /// (for `at_end`).
    pub ext: Signal<In, Bit>,
    pub data_bits: Signal<In, Bits<8>>,
    /// A transmission is requested.
    pub req: Signal<In, Bit>,
    /// From fault confinement: error-active, recovery armed, the next run is
    /// the last, this bit takes the node to Bus_Off.
    pub active: Signal<In, Bit>,
    pub armed: Signal<In, Bit>,
    pub last_run: Signal<In, Bit>,
    pub busoff: Signal<In, Bit>,
    /// Level of the next own frame bit: `level` after a taken bit of the
    /// stuffed area (`in_frame`, the bit in progress lies there), `level_sof`
    /// (Identifier 1) after a SOF sampled outside it.
    pub in_frame: Signal<In, Bit>,
    pub level: Signal<In, Bit>,
    pub level_sof: Signal<In, Bit>,
    /// The decision of [`super::frame_fields::FrameFields`].
    pub f_own: Signal<In, Bit>,
    pub f_nf: Signal<In, Field>,
    /// The classes of `f_nf` (see `area` below), set along with it.
    pub f_na: Signal<In, Bit>,
    pub f_nsa: Signal<In, Bit>,
    pub f_nhs: Signal<In, Bit>,
    pub f_ni: Signal<In, Bit>,
    /// The next POSITION as a choice (issue #16): 0 keep, 1 the increment
    /// (saturating at 255), 2 one, 3 two (see [`POS_KEEP`] ..), so that
    /// each bit of POSITION is one LUT on the choice, its own bit and the
    /// increment's, instead of an 8-bit multiplexer behind the decisions.
    pub f_npc: Signal<In, Bits<2>>,
    pub f_ndom: Signal<In, Bit>,
    pub f_usetx: Signal<In, Bit>,
    pub f_lost: Signal<In, Bit>,
    pub f_err: Signal<In, Bit>,
    pub f_ovl: Signal<In, Bit>,
    pub f_sof: Signal<In, Bit>,
    /// The decision of [`super::flags::FlagFields`].
    pub g_own: Signal<In, Bit>,
    pub g_nf: Signal<In, Field>,
    pub g_na: Signal<In, Bit>,
    pub g_nsa: Signal<In, Bit>,
    pub g_nhs: Signal<In, Bit>,
    pub g_ni: Signal<In, Bit>,
    pub g_npc: Signal<In, Bits<2>>,
    pub g_ndom: Signal<In, Bit>,
    pub g_err: Signal<In, Bit>,
    pub g_ovl: Signal<In, Bit>,

    pub fld: Signal<Out, Field>,
    pub fpos: Signal<Out, Bits<8>>,
    pub pfld: Signal<Out, Field>,
    pub ppos: Signal<Out, Bits<8>>,
    pub tx_role: Signal<Out, Bit>,
    pub dom: Signal<Out, Bit>,
    pub in_busoff: Signal<Out, Bit>,
    /// POSITION is 3 (`fpos` = 3), kept in a register of its own (issue #16)
    /// that takes, along every branch that sets POSITION, whether the value
    /// set is 3 (from the choice `l_npc`: an increment from 2, or POSITION
    /// kept at 3), so that the hard-sync enable of Intermission bit 3 does
    /// not wait for a comparator on POSITION.
    pub pos3: Signal<Out, Bit>,
    /// POSITION is the one at which the field's decision depends on it
    /// (issue #16): Wait_For_Bus_Idle, Bus_Off, Identifier 11;
    /// Ex_Identifier 18; Reserved_Bits 1 of an extended frame; DLC 4; Data
    /// `data_bits`; CRC_Sequence 15; End_Of_Frame 7; Passive_Error_Flag 1;
    /// Active_Error_Flag, Overload_Flag 6; the delimiters and
    /// Suspend_Transmission 8; Intermission 3. Valid on `sample` clocks.
    pub at_end: Signal<Out, Bit>,
    /// `stuff`, and the stuffed area or `stuff` (the destuffer's and the
    /// frame fields' `stuffed`), valid on `sample` clocks (see `pipe`).
    pub pstuff: Signal<Out, Bit>,
    pub pstuffed: Signal<Out, Bit>,
    /// Decodes of `fld` and `pfld`, kept in registers of their own (issue
    /// #16) that take the decode of the next FIELD along every branch that
    /// sets it, so that they always equal the decode of `fld`/`pfld`:
    /// `fld` lies in the stuffed area (Start_Of_Frame .. CRC_Sequence); there
    /// or CRC_Delimiter (a stuff bit may be in progress); `fld` is one of the
    /// fields with hard synchronisation at every position (Reset,
    /// Wait_For_Bus_Idle, Bus_Idle, Bus_Off, Start_Of_Frame,
    /// Suspend_Transmission); `fld` is Intermission; the last two for `pfld`.
    pub area: Signal<Out, Bit>,
    pub stuffable: Signal<Out, Bit>,
    pub hs_fld: Signal<Out, Bit>,
    pub inter_fld: Signal<Out, Bit>,
    pub hs_pfld: Signal<Out, Bit>,
    pub inter_pfld: Signal<Out, Bit>,
    /// This bit's outcome: an error flag starts; an error or overload flag
    /// starts; a frame starts (SOF sampled); an own frame starts.
    pub err: Signal<Out, Bit>,
    pub flag_start: Signal<Out, Bit>,
    pub sofinit: Signal<Out, Bit>,
    pub txsof: Signal<Out, Bit>,
    /// Events (`EV_*`) decided here.
    pub ev_aef: Signal<Out, Bit>,
    pub ev_pef: Signal<Out, Bit>,
    pub ev_olf: Signal<Out, Bit>,
    pub ev_ovl: Signal<Out, Bit>,
    pub ev_integrated: Signal<Out, Bit>,
    pub ev_run: Signal<Out, Bit>,
    pub ev_recovered: Signal<Out, Bit>,

    rfld: DFF<Field>,
    rpos: DFF<Bits<8>>,
    rpfld: DFF<Field>,
    rppos: DFF<Bits<8>>,
    rtx: DFF<Bit>,
    rdom: DFF<Bit>,
    // The decodes (see `area` above); the hard-sync ones inverted, so that
    // the flip-flops' power-up 0 matches FIELD Reset (code 0) of `rfld` and
    // `rpfld`.
    rarea: DFF<Bit>,
    rsa: DFF<Bit>,
    rnhs: DFF<Bit>,
    rinter: DFF<Bit>,
    rnphs: DFF<Bit>,
    rpinter: DFF<Bit>,
    // `at_end` and `stuff` one clock late (see `pipe`).
    rend: DFF<Bit>,
    rp3: DFF<Bit>,
    rstp: DFF<Bit>,

    l_posinc: Signal<Local, Bits<8>>,
    l_endc: Signal<Local, Bit>,
    l_end: Signal<Local, Bit>,
    l_stuff: Signal<Local, Bit>,
    l_cantx: Signal<Local, Bit>,
    l_nf: Signal<Local, Field>,
    /// The next POSITION's choice (see `f_npc`), set along with `l_nf`.
    l_npc: Signal<Local, Bits<2>>,
    l_npos: Signal<Local, Bits<8>>,
    /// POSITION is 2 (its increment is 3).
    l_pos2: Signal<Local, Bit>,
    l_ndom: Signal<Local, Bit>,
    l_usetx: Signal<Local, Bit>,
    l_role: Signal<Local, Bit>,
    l_start: Signal<Local, Bit>,
    l_ovl: Signal<Local, Bit>,
    l_lvl: Signal<Local, Bit>,
    /// A SOF sampled in a field of the sequencer's own.
    l_sofs: Signal<Local, Bit>,
    /// The decodes of `l_nf` (see `area`), set along with it.
    l_na: Signal<Local, Bit>,
    l_nsa: Signal<Local, Bit>,
    l_nhs: Signal<Local, Bit>,
    l_ni: Signal<Local, Bit>,
}

impl Logic for Sequencer {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, rfld, rpos, rpfld, rppos, rtx, rdom, rarea, rsa, rnhs, rinter, rnphs, rpinter, rend, rstp, rp3
        );
        self.l_posinc.next = self.rpos.q.val() + 1;
        if self.rpos.q.val() == 255 {
            self.l_posinc.next = self.rpos.q.val();
        }
        self.l_cantx.next = self.req.val() & !self.listen_only.val();
        // The decisive position of the field (see `at_end`).
        self.l_endc.next = false;
        match self.rfld.q.val() {
            Field::WaitIdle => {
                self.l_endc.next = self.rpos.q.val() == 11;
            }
            Field::BusOff => {
                self.l_endc.next = self.rpos.q.val() == 11;
            }
            Field::Ident => {
                self.l_endc.next = self.rpos.q.val() == 11;
            }
            Field::ExIdent => {
                self.l_endc.next = self.rpos.q.val() == 18;
            }
            Field::Resv => {
                self.l_endc.next = self.ext.val() & (self.rpos.q.val() == 1);
            }
            Field::Dlc => {
                self.l_endc.next = self.rpos.q.val() == 4;
            }
            Field::Data => {
                self.l_endc.next = self.rpos.q.val() == self.data_bits.val();
            }
            Field::Crc => {
                self.l_endc.next = self.rpos.q.val() == 15;
            }
            Field::Eof => {
                self.l_endc.next = self.rpos.q.val() == 7;
            }
            Field::PasFlag => {
                self.l_endc.next = self.rpos.q.val() == 1;
            }
            Field::ActFlag => {
                self.l_endc.next = self.rpos.q.val() == 6;
            }
            Field::OvlFlag => {
                self.l_endc.next = self.rpos.q.val() == 6;
            }
            Field::ErrDel => {
                self.l_endc.next = self.rpos.q.val() == 8;
            }
            Field::OvlDel => {
                self.l_endc.next = self.rpos.q.val() == 8;
            }
            Field::Inter => {
                self.l_endc.next = self.rpos.q.val() == 3;
            }
            Field::Suspend => {
                self.l_endc.next = self.rpos.q.val() == 8;
            }
            _ => {}
        }
        self.l_end.next = self.l_endc.val();
        self.l_stuff.next = self.stuff.val();
        if self.pipe.val() {
            self.l_end.next = self.rend.q.val();
            self.l_stuff.next = self.rstp.q.val();
        }
        self.l_nf.next = self.rfld.q.val();
        self.l_na.next = self.rarea.q.val();
        self.l_nsa.next = self.rsa.q.val();
        self.l_nhs.next = !self.rnhs.q.val();
        self.l_ni.next = self.rinter.q.val();
        self.l_npc.next = 0.into();
        self.l_ndom.next = false;
        self.l_usetx.next = false;
        self.l_role.next = self.rtx.q.val();
        self.l_start.next = false;
        self.l_ovl.next = false;
        self.sofinit.next = false;
        self.l_sofs.next = false;
        self.txsof.next = false;
        self.err.next = false;
        self.ev_integrated.next = false;
        self.ev_run.next = false;
        self.ev_recovered.next = false;

        // Decided on `sample` only (the outputs below are 0 between sample
        // strobes).
        if self.sample.val() {
            if self.f_own.val() {
                self.l_nf.next = self.f_nf.val();
                self.l_na.next = self.f_na.val();
                self.l_nsa.next = self.f_nsa.val();
                self.l_nhs.next = self.f_nhs.val();
                self.l_ni.next = self.f_ni.val();
                self.l_npc.next = self.f_npc.val();
                self.l_ndom.next = self.f_ndom.val();
                self.l_usetx.next = self.f_usetx.val();
                self.l_role.next = self.rtx.q.val() & !self.f_lost.val();
                self.sofinit.next = self.f_sof.val();
                self.err.next = self.f_err.val();
                self.l_ovl.next = self.f_ovl.val();
            } else if self.g_own.val() {
                self.l_nf.next = self.g_nf.val();
                self.l_na.next = self.g_na.val();
                self.l_nsa.next = self.g_nsa.val();
                self.l_nhs.next = self.g_nhs.val();
                self.l_ni.next = self.g_ni.val();
                self.l_npc.next = self.g_npc.val();
                self.l_ndom.next = self.g_ndom.val();
                self.err.next = self.g_err.val();
                self.l_ovl.next = self.g_ovl.val();
            } else {
                match self.rfld.q.val() {
                    Field::Reset => {
                        self.l_nf.next = Field::WaitIdle;
                        self.l_na.next = false;
                        self.l_nsa.next = false;
                        self.l_nhs.next = true;
                        self.l_ni.next = false;
                        self.l_npc.next = 2.into();
                    }
                    Field::WaitIdle => {
                        if !self.rxbit.val() {
                            self.l_npc.next = 2.into();
                        } else if self.l_end.val() {
                            self.ev_integrated.next = true;
                            self.l_start.next = true;
                        } else {
                            self.l_npc.next = 1.into();
                        }
                    }
                    Field::Idle => {
                        if !self.rxbit.val() {
                            self.sofinit.next = true;
                            self.l_sofs.next = true;
                            self.l_role.next = false;
                        } else {
                            self.l_start.next = true;
                        }
                    }
                    Field::BusOff => {
                        if (self.host_recovery.val() & !self.armed.val()) | !self.rxbit.val() {
                            // waiting for the host, or a dominant bit restarts the run
                            self.l_npc.next = 2.into();
                        } else if self.l_end.val() {
                            self.ev_run.next = true;
                            self.l_npc.next = 2.into();
                            if self.last_run.val() {
                                self.ev_recovered.next = true;
                                self.l_start.next = true;
                            }
                        } else {
                            self.l_npc.next = 1.into();
                        }
                    }
                    Field::Inter => {
                        self.l_npc.next = 1.into();
                        if self.l_end.val() {
                            if !self.rxbit.val() {
                                // a dominant third intermission bit is a SOF
                                self.sofinit.next = true;
                                self.l_sofs.next = true;
                                if self.l_cantx.val() & !(self.rtx.q.val() & !self.active.val()) {
                                    self.l_role.next = true;
                                    self.txsof.next = true;
                                } else {
                                    self.l_role.next = false;
                                }
                            } else if self.rtx.q.val() & !self.active.val() {
                                self.l_nf.next = Field::Suspend;
                                self.l_na.next = false;
                                self.l_nsa.next = false;
                                self.l_nhs.next = true;
                                self.l_ni.next = false;
                                self.l_npc.next = 2.into();
                            } else {
                                self.l_start.next = true;
                            }
                        } else if !self.rxbit.val() {
                            self.l_ovl.next = true;
                        }
                    }
                    Field::Suspend => {
                        self.l_npc.next = 1.into();
                        if !self.rxbit.val() {
                            self.sofinit.next = true;
                            self.l_sofs.next = true;
                            self.l_role.next = false;
                        } else if self.l_end.val() {
                            self.l_start.next = true;
                        }
                    }
                    _ => {}
                }
            }

            // A SOF was sampled outside the frame fields: the frame starts
            // (Identifier 1 next; a taken Start_Of_Frame bit of the frame
            // fields decides the same, so their `f_sof` is not waited for).
            if self.l_sofs.val() {
                self.l_nf.next = Field::Ident;
                self.l_na.next = true;
                self.l_nsa.next = true;
                self.l_nhs.next = false;
                self.l_ni.next = false;
                self.l_npc.next = 2.into();
                self.l_usetx.next = true;
            }
            // The bus is free: start a frame if one is pending.
            if self.l_start.val() {
                if self.l_cantx.val() {
                    self.l_nf.next = Field::Sof;
                    self.l_na.next = true;
                    self.l_nsa.next = true;
                    self.l_nhs.next = true;
                    self.l_ni.next = false;
                    self.l_npc.next = 2.into();
                    self.l_role.next = true;
                    self.txsof.next = true;
                    self.l_usetx.next = true;
                } else {
                    self.l_nf.next = Field::Idle;
                    self.l_na.next = false;
                    self.l_nsa.next = false;
                    self.l_nhs.next = true;
                    self.l_ni.next = false;
                    self.l_npc.next = 2.into();
                    if self.rfld.q.val() == Field::Idle {
                        self.l_npc.next = 1.into();
                    }
                }
            }
        }
        // The level of an own frame bit. Inside the stuffed area the next own
        // bit follows a taken frame bit (`level`, or Identifier 1 after the
        // SOF bit); outside it, it is Identifier 1 after a SOF sampled here
        // (`level_sof`) or a SOF of an own frame started here (dominant).
        self.l_lvl.next = self.level.val();
        if !self.in_frame.val() {
            self.l_lvl.next = self.level_sof.val() & !self.l_start.val();
        }
        if self.l_usetx.val() {
            self.l_ndom.next = self.l_role.val() & !self.l_lvl.val();
        }
        // Error and overload flags.
        self.ev_aef.next = false;
        self.ev_pef.next = false;
        self.ev_olf.next = false;
        if self.err.val() {
            self.l_npc.next = 2.into();
            if self.active.val() {
                self.l_nf.next = Field::ActFlag;
                self.l_na.next = false;
                self.l_nsa.next = false;
                self.l_nhs.next = false;
                self.l_ni.next = false;
                self.l_ndom.next = true;
                self.ev_aef.next = true;
            } else {
                self.l_nf.next = Field::PasFlag;
                self.l_na.next = false;
                self.l_nsa.next = false;
                self.l_nhs.next = false;
                self.l_ni.next = false;
                self.l_ndom.next = false;
                self.ev_pef.next = true;
            }
        } else if self.l_ovl.val() {
            self.l_nf.next = Field::OvlFlag;
            self.l_na.next = false;
            self.l_nsa.next = false;
            self.l_nhs.next = false;
            self.l_ni.next = false;
            self.l_npc.next = 2.into();
            self.l_ndom.next = true;
            self.ev_olf.next = true;
        }
        // Bus-off as soon as TEC exceeds 255: no flag is started after all.
        if self.busoff.val() {
            self.ev_aef.next = false;
            self.ev_pef.next = false;
            self.ev_olf.next = false;
            self.l_nf.next = Field::BusOff;
            self.l_na.next = false;
            self.l_nsa.next = false;
            self.l_nhs.next = true;
            self.l_ni.next = false;
            self.l_npc.next = 2.into();
            self.l_ndom.next = false;
        }
        self.flag_start.next = self.err.val() | self.l_ovl.val();
        self.ev_ovl.next = self.l_ovl.val() & !self.err.val();

        self.l_pos2.next = self.rpos.q.val() == 2;
        // The next POSITION from its choice (`POS_*`).
        self.l_npos.next = self.rpos.q.val();
        if self.l_npc.val().get_bit(1) {
            self.l_npos.next = 1.into();
            if self.l_npc.val().get_bit(0) {
                self.l_npos.next = 2.into();
            }
        } else if self.l_npc.val().get_bit(0) {
            self.l_npos.next = self.l_posinc.val();
        }

        if self.sample.val() {
            if !self.l_stuff.val() {
                self.rpfld.d.next = self.rfld.q.val();
                self.rppos.d.next = self.rpos.q.val();
                self.rnphs.d.next = self.rnhs.q.val();
                self.rpinter.d.next = self.rinter.q.val();
            }
            self.rfld.d.next = self.l_nf.val();
            self.rarea.d.next = self.l_na.val();
            self.rsa.d.next = self.l_nsa.val();
            self.rnhs.d.next = !self.l_nhs.val();
            self.rinter.d.next = self.l_ni.val();
            self.rpos.d.next = self.l_npos.val();
            // keep (0): stays 3 if it is; increment (1): 3 from 2; 1 or 2: not 3
            self.rp3.d.next = !self.l_npc.val().get_bit(1) & self.rp3.q.val();
            if !self.l_npc.val().get_bit(1) & self.l_npc.val().get_bit(0) {
                self.rp3.d.next = self.l_pos2.val();
            }
            self.rtx.d.next = self.l_role.val();
            self.rdom.d.next = self.l_ndom.val();
        }
        // The decodes for the next clock (see `pipe`): FIELD and POSITION
        // after a reset or a counter load that sets them are outside the
        // fields that read `at_end` and outside the stuffed area.
        self.rend.d.next = self.l_endc.val();
        self.rstp.d.next = self.stuff.val();
        if self.reset.val() {
            self.rend.d.next = false;
            self.rstp.d.next = false;
            self.rfld.d.next = Field::WaitIdle;
            self.rarea.d.next = false;
            self.rsa.d.next = false;
            self.rnhs.d.next = false;
            self.rinter.d.next = false;
            self.rpos.d.next = 1.into();
            self.rp3.d.next = false;
            self.rtx.d.next = false;
            self.rdom.d.next = false;
        }
        // Counter load (priority over reset and the protocol).
        if self.cnt_load.val() {
            if (self.tec_in.val() >= 256) | (self.rfld.q.val() == Field::BusOff) {
                self.rend.d.next = false;
                self.rstp.d.next = false;
            }
            if self.tec_in.val() >= 256 {
                self.rfld.d.next = Field::BusOff;
                self.rarea.d.next = false;
                self.rsa.d.next = false;
                self.rnhs.d.next = false;
                self.rinter.d.next = false;
                self.rpos.d.next = 1.into();
                self.rp3.d.next = false;
                self.rtx.d.next = false;
                self.rdom.d.next = false;
            } else if self.rfld.q.val() == Field::BusOff {
                self.rfld.d.next = Field::WaitIdle;
                self.rarea.d.next = false;
                self.rsa.d.next = false;
                self.rnhs.d.next = false;
                self.rinter.d.next = false;
                self.rpos.d.next = 1.into();
                self.rp3.d.next = false;
                self.rdom.d.next = false;
            }
        }

        self.fld.next = self.rfld.q.val();
        self.fpos.next = self.rpos.q.val();
        self.pfld.next = self.rpfld.q.val();
        self.ppos.next = self.rppos.q.val();
        self.tx_role.next = self.rtx.q.val();
        self.dom.next = self.rdom.q.val();
        self.in_busoff.next = self.rfld.q.val() == Field::BusOff;
        self.pos3.next = self.rp3.q.val();
        self.area.next = self.rarea.q.val();
        self.at_end.next = self.l_end.val();
        self.pstuff.next = self.l_stuff.val();
        self.pstuffed.next = self.rarea.q.val() | self.l_stuff.val();
        self.stuffable.next = self.rsa.q.val();
        self.hs_fld.next = !self.rnhs.q.val();
        self.inter_fld.next = self.rinter.q.val();
        self.hs_pfld.next = !self.rnphs.q.val();
        self.inter_pfld.next = self.rpinter.q.val();
    }
}

canstar_hdl::impl_clocked!(Sequencer);
