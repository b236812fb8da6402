//! The bit-stream processor: the complete CAN 2.0A/B frame state machine of
//! one node, in one rust-hdl block ([`CanFsm`]).
//!
//! It works on sampled bits only. Once per bit the bit timing logic raises
//! `sample` for one clock, with the sampled bus level on `busmon`. On that
//! clock the block processes the bit completely (destuffing, CRC, arbitration,
//! error detection, fault confinement, frame delivery) and latches its
//! decision: `drive` (the level wanted on TX for the next bit) and `hs_en`
//! (hard synchronisation enable) are functions of registers only (and of the
//! `listen_only` mode bit), valid from the next clock on, so with IPT = 2 TQ
//! they are ready at the earliest transmit point. Counter changes are visible
//! on the same clock (§13.4). Everything is normative per `can-protocol.md`;
//! the section numbers below refer to it.
//!
//! Summary of the behaviour (details in can-protocol.md):
//! - integration after reset (11 recessive bits), Bus_Idle, SOF on a pending
//!   request after Bus_Idle bits, a recessive third intermission bit or the
//!   last Suspend_Transmission bit; a dominant third intermission bit is a SOF
//!   (a node with a pending request continues as transmitter at Identifier 1,
//!   except an error-passive former transmitter, C15);
//! - standard and extended frames, SRR/r1/r0 accepted at either level, DLC
//!   9..15 carrying 8 bytes, remote frames without data;
//! - arbitration over identifier, SRR, IDE, extension and RTR (not at stuff
//!   bits), after a loss the node continues as a receiver;
//! - bit, stuff, CRC (signalled after ACK_Delimiter), form and ACK errors at
//!   the positions of §9; active and passive error flags, the 6-equal-bits
//!   rule of passive flags, dominant bits after a flag, error and overload
//!   delimiters, overload frames (intermission 1/2, delimiter bit 8, a
//!   receiver's End_Of_Frame bit 7, which still delivers the frame);
//! - fault confinement of §13 with both exceptions, REC saturation (C12) and
//!   the 127 restore (C11), error warning, error-passive with suspend
//!   transmission, bus-off at TEC > 255 and recovery after 128 runs of 11
//!   recessive bits (automatic, or started by `recover` with
//!   `host_recovery`).
//!
//! Bit stuffing and the CRC-15 use the shared blocks
//! [`canstar_hdl::stuff::BitDestuffer`] and [`canstar_hdl::crc15::Crc15`], both
//! fed with the sampled levels. §5: the stuff run counter runs on sampled
//! levels for every role, so one destuffer serves the transmitter and the
//! receivers; a transmitter's stuff bit is the destuffer's `stuff_level` (the
//! complement of the run it has just sampled), chosen combinationally for
//! `drive` while the destuffer says the next bit is a stuff bit. The CRC engine
//! also runs over the CRC sequence: a transmitter feeding back its own CRC bit
//! just shifts the register (so the next bit to send is always `crc[14]`), and a
//! receiver's register is zero after the last CRC bit exactly when the received
//! sequence matches.
//!
//! Field and position advance at every non-stuff bit; while the bit in
//! progress is a stuff bit the debug outputs show the FIELD/POSITION of the bit
//! before it (registers `pfld`/`ppos`).
//!
//! ## FIELD encoding (`field` output, `err_field` payload)
//!
//! | code | FIELD | code | FIELD |
//! |---|---|---|---|
//! | 0 | Reset | 13 | CRC_Sequence |
//! | 1 | Wait_For_Bus_Idle | 14 | CRC_Delimiter |
//! | 2 | Bus_Idle | 15 | ACK_Slot |
//! | 3 | Bus_Off | 16 | ACK_Delimiter |
//! | 4 | Start_Of_Frame | 17 | End_Of_Frame |
//! | 5 | Identifier | 18 | Active_Error_Flag |
//! | 6 | SRR_Bit | 19 | Passive_Error_Flag |
//! | 7 | IDE_Bit | 20 | Overload_Flag |
//! | 8 | RTR_Bit | 21 | Error_Delimiter |
//! | 9 | Ex_Identifier | 22 | Overload_Delimiter |
//! | 10 | Reserved_Bits | 23 | Intermission |
//! | 11 | Data_Length_Code | 24 | Suspend_Transmission |
//! | 12 | Data_Field | | |
//!
//! `field`/`pos`/`stuff`/`role` describe the bit in progress (the bit that the
//! next `sample` strobe will process), POSITION as in §4.5 (a stuff bit keeps
//! the FIELD and POSITION of the bit before it and has `stuff` set; positions
//! saturate at 255). `role` is 1 for the transmitter. SRR_Bit is shown only
//! by a transmitter of an extended frame; receivers label bit 12 RTR_Bit.
//!
//! ## Event word (`events` output)
//!
//! `events` is registered: it is valid during the clock after the `sample`
//! strobe, for one clock, and describes the bit just processed; bit
//! [`EV_BIT`] is set for every processed bit (the per-bit trace strobe of §18,
//! together with `tec`/`rec`/`state`, which show the values after processing).
//! See the `EV_*` constants for the bit positions.

// `#[hdl_gen]` has no match guards, so nested `if`s stay.
#![allow(clippy::collapsible_match)]

use canstar_hdl::crc15::Crc15;
use canstar_hdl::stuff::BitDestuffer;
use rust_hdl::prelude::*;

/// A SOF was sampled (own or received, including a dominant Intermission bit 3).
pub const EV_SOF: usize = 0;
/// Arbitration lost at this bit.
pub const EV_ARB_LOST: usize = 1;
/// Bit error detected at this bit.
pub const EV_BIT_ERR: usize = 2;
/// Stuff error detected at this bit.
pub const EV_STUFF_ERR: usize = 3;
/// CRC error signalled at this bit (ACK_Delimiter).
pub const EV_CRC_ERR: usize = 4;
/// Form error detected at this bit.
pub const EV_FORM_ERR: usize = 5;
/// ACK error detected at this bit.
pub const EV_ACK_ERR: usize = 6;
/// An active error flag starts with the next bit.
pub const EV_AEF: usize = 7;
/// A passive error flag starts with the next bit.
pub const EV_PEF: usize = 8;
/// An overload flag starts with the next bit.
pub const EV_OLF: usize = 9;
/// Overload condition detected at this bit.
pub const EV_OVL: usize = 10;
/// A dominant bit after an own flag was sampled.
pub const EV_DAF: usize = 11;
/// Successful transmission (End_Of_Frame bit 7 recessive, TEC -1).
pub const EV_TX_OK: usize = 12;
/// Frame delivered to the host (receiver, End_Of_Frame bit 7).
pub const EV_RX_OK: usize = 13;
/// TEC exception 1 applied (passive ACK error without dominant flag bit).
pub const EV_EXC1: usize = 14;
/// TEC exception 2 applied (stuff error at a stuff bit inside arbitration).
pub const EV_EXC2: usize = 15;
/// A bus-off recovery run of 11 recessive bits completed.
pub const EV_RUN: usize = 16;
/// Bus-off recovery completed (128 runs).
pub const EV_RECOVERED: usize = 17;
/// Integration completed (11 recessive bits after reset).
pub const EV_INTEGRATED: usize = 18;
/// A bit was processed (set with every `sample`).
pub const EV_BIT: usize = 19;
/// Width of the event word.
pub const EV_BITS: usize = 20;

/// Bit positions of the `err_kind` mask.
pub const ERRK_BIT: usize = 0;
pub const ERRK_STUFF: usize = 1;
pub const ERRK_CRC: usize = 2;
pub const ERRK_FORM: usize = 3;
pub const ERRK_ACK: usize = 4;

/// The FIELD of the bit in progress (§4.5). Codes are the declaration order,
/// see the module documentation.
#[derive(Copy, Clone, Debug, PartialEq, Eq, LogicState)]
pub enum Field {
    Reset,
    WaitIdle,
    Idle,
    BusOff,
    Sof,
    Ident,
    Srr,
    Ide,
    Rtr,
    ExIdent,
    Resv,
    Dlc,
    Data,
    Crc,
    CrcDel,
    AckSlot,
    AckDel,
    Eof,
    ActFlag,
    PasFlag,
    OvlFlag,
    ErrDel,
    OvlDel,
    Inter,
    Suspend,
}

impl Field {
    /// All fields in code order.
    pub const ALL: [Field; 25] = [
        Field::Reset,
        Field::WaitIdle,
        Field::Idle,
        Field::BusOff,
        Field::Sof,
        Field::Ident,
        Field::Srr,
        Field::Ide,
        Field::Rtr,
        Field::ExIdent,
        Field::Resv,
        Field::Dlc,
        Field::Data,
        Field::Crc,
        Field::CrcDel,
        Field::AckSlot,
        Field::AckDel,
        Field::Eof,
        Field::ActFlag,
        Field::PasFlag,
        Field::OvlFlag,
        Field::ErrDel,
        Field::OvlDel,
        Field::Inter,
        Field::Suspend,
    ];
    /// The field with code `c` (see the module documentation).
    pub fn from_code(c: u64) -> Option<Field> {
        Self::ALL.get(c as usize).copied()
    }
    /// The numeric code of the field.
    pub fn code(self) -> u64 {
        Self::ALL.iter().position(|f| *f == self).unwrap() as u64
    }
    /// The reference model's FIELD name (§4.5).
    pub fn name(self) -> &'static str {
        match self {
            Field::Reset => "Reset",
            Field::WaitIdle => "Wait_For_Bus_Idle",
            Field::Idle => "Bus_Idle",
            Field::BusOff => "Bus_Off",
            Field::Sof => "Start_Of_Frame",
            Field::Ident => "Identifier",
            Field::Srr => "SRR_Bit",
            Field::Ide => "IDE_Bit",
            Field::Rtr => "RTR_Bit",
            Field::ExIdent => "Ex_Identifier",
            Field::Resv => "Reserved_Bits",
            Field::Dlc => "Data_Length_Code",
            Field::Data => "Data_Field",
            Field::Crc => "CRC_Sequence",
            Field::CrcDel => "CRC_Delimiter",
            Field::AckSlot => "ACK_Slot",
            Field::AckDel => "ACK_Delimiter",
            Field::Eof => "End_Of_Frame",
            Field::ActFlag => "Active_Error_Flag",
            Field::PasFlag => "Passive_Error_Flag",
            Field::OvlFlag => "Overload_Flag",
            Field::ErrDel => "Error_Delimiter",
            Field::OvlDel => "Overload_Delimiter",
            Field::Inter => "Intermission",
            Field::Suspend => "Suspend_Transmission",
        }
    }
    /// Fields that carry a Tx_/Rx_ role prefix in the trace (§18).
    pub fn has_role(self) -> bool {
        !matches!(self, Field::Reset | Field::WaitIdle | Field::Idle | Field::BusOff)
    }
}

/// The frame state machine (see the module documentation).
///
/// Inputs: `sample` strobe and `busmon` level from the bit timing logic; the
/// mode bits `listen_only` (never drive dominant: no frame, no ACK, flags
/// kept recessive; error counters frozen),
/// `self_test` (a transmitter accepts a recessive ACK slot), `single_shot`
/// (no retransmission after an error or a lost arbitration),
/// `host_recovery` (bus-off recovery waits for a `recover` strobe); the
/// transmit request `tx_req` (level; `tx_ide`, `tx_rtr`, `tx_id`, `tx_dlc`,
/// `tx_data` are latched when a frame starts) and `tx_abort`.
///
/// Counter load: on every clock with `cnt_load` high, TEC and REC take
/// `tec_in` and `rec_in`; this has priority over `reset` and over the
/// protocol's own counter updates (the SJA1000 register block holds it high
/// while in reset mode, so host-written counters survive the release of
/// reset). The state follows from the loaded values as from counted ones
/// (error-passive from 128, bus-off from 256). A load with `tec_in` ≥ 256
/// also puts the node at the start of Bus_Off (recessive, recovery runs
/// counted from 0, waiting for `recover` with `host_recovery`), as a bus-off
/// from an error does; a load with `tec_in` < 256 while in Bus_Off leaves it
/// for Wait_For_Bus_Idle (11 recessive bits, as after reset). Tie
/// `cnt_load` low when unused.
///
/// Request handshake: while `tx_req` is high the controller (re)tries until
/// success; after `tx_done` (or, in single-shot mode, after the first failed
/// attempt, or after `tx_abort`) it starts no further attempt until `tx_req` has
/// been low for at least one clock.
#[derive(LogicBlock, Default)]
pub struct CanFsm {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub sample: Signal<In, Bit>,
    pub busmon: Signal<In, Bit>,
    pub listen_only: Signal<In, Bit>,
    pub self_test: Signal<In, Bit>,
    pub single_shot: Signal<In, Bit>,
    pub host_recovery: Signal<In, Bit>,
    pub recover: Signal<In, Bit>,
    pub tx_req: Signal<In, Bit>,
    pub tx_ide: Signal<In, Bit>,
    pub tx_rtr: Signal<In, Bit>,
    pub tx_id: Signal<In, Bits<29>>,
    pub tx_dlc: Signal<In, Bits<4>>,
    pub tx_data: Signal<In, Bits<64>>,
    pub tx_abort: Signal<In, Bit>,
    /// Load TEC/REC from `tec_in`/`rec_in` (see above).
    pub cnt_load: Signal<In, Bit>,
    pub tec_in: Signal<In, Bits<9>>,
    pub rec_in: Signal<In, Bits<8>>,

    /// Level wanted on TX from the next transmit point (1 = recessive).
    pub drive: Signal<Out, Bit>,
    /// Hard synchronisation enable (§3.3).
    pub hs_en: Signal<Out, Bit>,
    pub tx_done: Signal<Out, Bit>,
    pub arb_lost: Signal<Out, Bit>,
    /// Arbitration bit at which it was lost: Identifier 1..11, bit 12 (RTR/SRR)
    /// = 12, IDE = 13, Ex_Identifier 1..18 = 14..31, extended RTR = 32.
    pub arb_lost_pos: Signal<Out, Bits<6>>,
    pub error: Signal<Out, Bit>,
    /// Mask of `ERRK_*` bits.
    pub err_kind: Signal<Out, Bits<5>>,
    pub err_field: Signal<Out, Bits<5>>,
    pub err_pos: Signal<Out, Bits<8>>,
    /// The node was the transmitter when the error was detected.
    pub err_tx: Signal<Out, Bit>,
    pub rx_valid: Signal<Out, Bit>,
    pub rx_ide: Signal<Out, Bit>,
    pub rx_rtr: Signal<Out, Bit>,
    pub rx_id: Signal<Out, Bits<29>>,
    pub rx_dlc: Signal<Out, Bits<4>>,
    pub rx_data: Signal<Out, Bits<64>>,
    pub tec: Signal<Out, Bits<9>>,
    pub rec: Signal<Out, Bits<8>>,
    /// 0 error-active, 1 error-passive, 2 bus-off.
    pub state: Signal<Out, Bits<2>>,
    pub err_warn: Signal<Out, Bit>,
    /// The request as the protocol sees it (§15, §19).
    pub tx_rqst: Signal<Out, Bit>,
    pub field: Signal<Out, Bits<5>>,
    pub pos: Signal<Out, Bits<8>>,
    pub stuff: Signal<Out, Bit>,
    pub role: Signal<Out, Bit>,
    pub events: Signal<Out, Bits<EV_BITS>>,
    /// Completed bus-off recovery runs (0..127).
    pub runs: Signal<Out, Bits<8>>,

    // ---- state ----
    fld: DFF<Field>,
    fpos: DFF<Bits<8>>,
    pfld: DFF<Field>,
    ppos: DFF<Bits<8>>,
    rtx: DFF<Bit>,
    dom: DFF<Bit>,
    dstf: BitDestuffer,
    crcb: Crc15,
    crcerr: DFF<Bit>,
    tid: DFF<Bits<29>>,
    tdat: DFF<Bits<64>>,
    tdlc: DFF<Bits<4>>,
    tide: DFF<Bit>,
    trtr: DFF<Bit>,
    rid: DFF<Bits<29>>,
    rdat: DFF<Bits<64>>,
    rdlc: DFF<Bits<4>>,
    rrtr: DFF<Bit>,
    rext: DFF<Bit>,
    fdone: DFF<Bit>,
    eqcnt: DFF<Bits<3>>,
    eqlast: DFF<Bit>,
    dafc: DFF<Bits<3>>,
    dafany: DFF<Bit>,
    exc1: DFF<Bit>,
    tecr: DFF<Bits<9>>,
    recr: DFF<Bits<8>>,
    runr: DFF<Bits<8>>,
    rarmed: DFF<Bit>,
    req: DFF<Bit>,
    blocked: DFF<Bit>,
    evr: DFF<Bits<EV_BITS>>,
    arbpos_r: DFF<Bits<6>>,
    errf_r: DFF<Bits<5>>,
    errp_r: DFF<Bits<8>>,
    errtx_r: DFF<Bit>,
    rxide_r: DFF<Bit>,
    rxrtr_r: DFF<Bit>,
    rxid_r: DFF<Bits<29>>,
    rxdlc_r: DFF<Bits<4>>,
    rxdat_r: DFF<Bits<64>>,

    // ---- working copies (combinational) ----
    l_bit: Signal<Local, Bit>,
    l_sent: Signal<Local, Bit>,
    l_active: Signal<Local, Bit>,
    l_cantx: Signal<Local, Bit>,
    l_nf: Signal<Local, Field>,
    l_npos: Signal<Local, Bits<8>>,
    l_posinc: Signal<Local, Bits<8>>,
    l_curstf: Signal<Local, Bit>,
    l_dfld: Signal<Local, Field>,
    l_dpos: Signal<Local, Bits<8>>,
    l_crcen: Signal<Local, Bit>,
    l_ndom: Signal<Local, Bit>,
    l_usetx: Signal<Local, Bit>,
    l_txv: Signal<Local, Bit>,
    l_role: Signal<Local, Bit>,
    l_instf: Signal<Local, Bit>,
    l_arbf: Signal<Local, Bit>,
    l_arbstuff: Signal<Local, Bit>,
    l_adv: Signal<Local, Bit>,
    l_err: Signal<Local, Bit>,
    l_errk: Signal<Local, Bits<5>>,
    l_ovl: Signal<Local, Bit>,
    l_start: Signal<Local, Bit>,
    l_sofinit: Signal<Local, Bit>,
    l_txsof: Signal<Local, Bit>,
    l_tinc: Signal<Local, Bit>,
    l_tdec: Signal<Local, Bit>,
    l_rinc1: Signal<Local, Bit>,
    l_rinc8: Signal<Local, Bit>,
    l_rok: Signal<Local, Bit>,
    l_clear: Signal<Local, Bit>,
    l_deliver: Signal<Local, Bit>,
    l_crcerr: Signal<Local, Bit>,
    l_tid: Signal<Local, Bits<29>>,
    l_tdat: Signal<Local, Bits<64>>,
    l_tdlc: Signal<Local, Bits<4>>,
    l_tide: Signal<Local, Bit>,
    l_trtr: Signal<Local, Bit>,
    l_rid: Signal<Local, Bits<29>>,
    l_rdat: Signal<Local, Bits<64>>,
    l_rdlc: Signal<Local, Bits<4>>,
    l_rrtr: Signal<Local, Bit>,
    l_rext: Signal<Local, Bit>,
    l_nbytes: Signal<Local, Bits<4>>,
    l_nbits: Signal<Local, Bits<8>>,
    l_fdone: Signal<Local, Bit>,
    l_eqcnt: Signal<Local, Bits<3>>,
    l_eqlast: Signal<Local, Bit>,
    l_dafc: Signal<Local, Bits<3>>,
    l_dafany: Signal<Local, Bit>,
    l_exc1: Signal<Local, Bit>,
    l_ev: Signal<Local, Bits<EV_BITS>>,
    l_tec: Signal<Local, Bits<9>>,
    l_rec: Signal<Local, Bits<8>>,
    l_runs: Signal<Local, Bits<8>>,
    l_rarmed: Signal<Local, Bit>,
    l_shamt: Signal<Local, Bits<6>>,
    l_arbpos: Signal<Local, Bits<6>>,
}

impl CanFsm {
    /// A new frame state machine (all state is set by `reset`).
    pub fn new() -> Self {
        Self::default()
    }
}

impl Logic for CanFsm {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, fld, fpos, pfld, ppos, rtx, dom, crcerr, tid, tdat, tdlc, tide, trtr, rid, rdat,
            rdlc, rrtr, rext, fdone, eqcnt, eqlast, dafc, dafany, exc1, tecr, recr, runr, rarmed, req, blocked, evr,
            arbpos_r, errf_r, errp_r, errtx_r, rxide_r, rxrtr_r, rxid_r, rxdlc_r, rxdat_r
        );
        // ------------------------------------------------------------------
        // Defaults: working copies start from the registers.
        self.l_bit.next = self.busmon.val();
        self.l_sent.next = !self.dom.q.val();
        // Error-active (flags are typed from this).
        self.l_active.next = (self.tecr.q.val() < 128) & (self.recr.q.val() < 128);
        self.l_cantx.next = self.req.q.val() & !self.listen_only.val();
        self.l_nf.next = self.fld.q.val();
        self.l_npos.next = self.fpos.q.val();
        self.l_posinc.next = self.fpos.q.val() + 1;
        if self.fpos.q.val() == 255 {
            self.l_posinc.next = self.fpos.q.val();
        }
        self.l_ndom.next = false;
        self.l_usetx.next = false;
        self.l_txv.next = true;
        self.l_role.next = self.rtx.q.val();
        self.l_instf.next = false;
        self.l_arbf.next = false;
        self.l_arbstuff.next = false;
        self.l_adv.next = false;
        self.l_err.next = false;
        self.l_errk.next = 0.into();
        self.l_ovl.next = false;
        self.l_start.next = false;
        self.l_sofinit.next = false;
        self.l_txsof.next = false;
        self.l_tinc.next = false;
        self.l_tdec.next = false;
        self.l_rinc1.next = false;
        self.l_rinc8.next = false;
        self.l_rok.next = false;
        self.l_clear.next = false;
        self.l_deliver.next = false;
        self.l_crcen.next = false;
        self.l_crcerr.next = self.crcerr.q.val();
        self.l_tid.next = self.tid.q.val();
        self.l_tdat.next = self.tdat.q.val();
        self.l_tdlc.next = self.tdlc.q.val();
        self.l_tide.next = self.tide.q.val();
        self.l_trtr.next = self.trtr.q.val();
        self.l_rid.next = self.rid.q.val();
        self.l_rdat.next = self.rdat.q.val();
        self.l_rdlc.next = self.rdlc.q.val();
        self.l_rrtr.next = self.rrtr.q.val();
        self.l_rext.next = self.rext.q.val();
        self.l_fdone.next = self.fdone.q.val();
        self.l_eqcnt.next = self.eqcnt.q.val();
        self.l_eqlast.next = self.eqlast.q.val();
        self.l_dafc.next = self.dafc.q.val();
        self.l_dafany.next = self.dafany.q.val();
        self.l_exc1.next = self.exc1.q.val();
        self.l_ev.next = 0.into();
        self.l_tec.next = self.tecr.q.val();
        self.l_rec.next = self.recr.q.val();
        self.l_runs.next = self.runr.q.val();
        self.l_rarmed.next = self.rarmed.q.val() | self.recover.val();
        self.l_nbytes.next = self.rdlc.q.val();
        self.l_nbits.next = 0.into();
        self.l_shamt.next = 0.into();
        self.l_arbpos.next = 0.into();

        // Register defaults (hold), event strobes clear.
        self.fld.d.next = self.fld.q.val();
        self.fpos.d.next = self.fpos.q.val();
        self.pfld.d.next = self.pfld.q.val();
        self.ppos.d.next = self.ppos.q.val();
        self.rtx.d.next = self.rtx.q.val();
        self.dom.d.next = self.dom.q.val();
        self.crcerr.d.next = self.crcerr.q.val();
        self.tid.d.next = self.tid.q.val();
        self.tdat.d.next = self.tdat.q.val();
        self.tdlc.d.next = self.tdlc.q.val();
        self.tide.d.next = self.tide.q.val();
        self.trtr.d.next = self.trtr.q.val();
        self.rid.d.next = self.rid.q.val();
        self.rdat.d.next = self.rdat.q.val();
        self.rdlc.d.next = self.rdlc.q.val();
        self.rrtr.d.next = self.rrtr.q.val();
        self.rext.d.next = self.rext.q.val();
        self.fdone.d.next = self.fdone.q.val();
        self.eqcnt.d.next = self.eqcnt.q.val();
        self.eqlast.d.next = self.eqlast.q.val();
        self.dafc.d.next = self.dafc.q.val();
        self.dafany.d.next = self.dafany.q.val();
        self.exc1.d.next = self.exc1.q.val();
        self.tecr.d.next = self.tecr.q.val();
        self.recr.d.next = self.recr.q.val();
        self.runr.d.next = self.runr.q.val();
        self.rarmed.d.next = self.rarmed.q.val() | self.recover.val();
        self.evr.d.next = 0.into();
        self.arbpos_r.d.next = self.arbpos_r.q.val();
        self.errf_r.d.next = self.errf_r.q.val();
        self.errp_r.d.next = self.errp_r.q.val();
        self.errtx_r.d.next = self.errtx_r.q.val();
        self.rxide_r.d.next = self.rxide_r.q.val();
        self.rxrtr_r.d.next = self.rxrtr_r.q.val();
        self.rxid_r.d.next = self.rxid_r.q.val();
        self.rxdlc_r.d.next = self.rxdlc_r.q.val();
        self.rxdat_r.d.next = self.rxdat_r.q.val();

        // Request handshake (every clock).
        self.blocked.d.next = self.blocked.q.val();
        if self.tx_abort.val() {
            self.blocked.d.next = true;
        }
        if !self.tx_req.val() {
            self.blocked.d.next = false;
        }
        self.req.d.next = self.tx_req.val() & !self.blocked.q.val() & !self.tx_abort.val();

        if self.l_rdlc.val().get_bit(3) {
            self.l_nbytes.next = 8.into();
        }

        // Is the bit in progress inside the stuffed area, and a stuff bit?
        match self.fld.q.val() {
            Field::Sof => {
                self.l_instf.next = true;
            }
            Field::Ident => {
                self.l_instf.next = true;
            }
            Field::Srr => {
                self.l_instf.next = true;
            }
            Field::Ide => {
                self.l_instf.next = true;
            }
            Field::Rtr => {
                self.l_instf.next = true;
            }
            Field::ExIdent => {
                self.l_instf.next = true;
            }
            Field::Resv => {
                self.l_instf.next = true;
            }
            Field::Dlc => {
                self.l_instf.next = true;
            }
            Field::Data => {
                self.l_instf.next = true;
            }
            Field::Crc => {
                self.l_instf.next = true;
            }
            _ => {}
        }
        // The final stuff bit after CRC bit 15 comes while the field already
        // says CRC_Delimiter.
        self.l_curstf.next = self.dstf.next_is_stuff.val()
            & (self.l_instf.val() | (self.fld.q.val() == Field::CrcDel));
        self.l_instf.next = self.l_instf.val() | self.l_curstf.val();
        self.l_dfld.next = self.fld.q.val();
        self.l_dpos.next = self.fpos.q.val();
        if self.l_curstf.val() {
            self.l_dfld.next = self.pfld.q.val();
            self.l_dpos.next = self.ppos.q.val();
        }
        // TX level: a transmitter's stuff bit, else the registered decision.
        self.drive.next = !self.dom.q.val();
        if self.l_curstf.val() {
            self.drive.next = !self.rtx.q.val() | self.dstf.stuff_level.val();
        }
        if self.listen_only.val() {
            self.drive.next = true;
        }
        self.l_sent.next = self.drive.val();

        // FIELD code and hard-sync enable of the bit in progress.
        self.hs_en.next = false;
        self.field.next = 0.into();
        match self.l_dfld.val() {
            Field::Reset => {
                self.field.next = 0.into();
                self.hs_en.next = true;
            }
            Field::WaitIdle => {
                self.field.next = 1.into();
                self.hs_en.next = true;
            }
            Field::Idle => {
                self.field.next = 2.into();
                self.hs_en.next = true;
            }
            Field::BusOff => {
                self.field.next = 3.into();
                self.hs_en.next = true;
            }
            Field::Sof => {
                self.field.next = 4.into();
                self.hs_en.next = true;
            }
            Field::Ident => {
                self.field.next = 5.into();
            }
            Field::Srr => {
                self.field.next = 6.into();
            }
            Field::Ide => {
                self.field.next = 7.into();
            }
            Field::Rtr => {
                self.field.next = 8.into();
            }
            Field::ExIdent => {
                self.field.next = 9.into();
            }
            Field::Resv => {
                self.field.next = 10.into();
            }
            Field::Dlc => {
                self.field.next = 11.into();
            }
            Field::Data => {
                self.field.next = 12.into();
            }
            Field::Crc => {
                self.field.next = 13.into();
            }
            Field::CrcDel => {
                self.field.next = 14.into();
            }
            Field::AckSlot => {
                self.field.next = 15.into();
            }
            Field::AckDel => {
                self.field.next = 16.into();
            }
            Field::Eof => {
                self.field.next = 17.into();
            }
            Field::ActFlag => {
                self.field.next = 18.into();
            }
            Field::PasFlag => {
                self.field.next = 19.into();
            }
            Field::OvlFlag => {
                self.field.next = 20.into();
            }
            Field::ErrDel => {
                self.field.next = 21.into();
            }
            Field::OvlDel => {
                self.field.next = 22.into();
            }
            Field::Inter => {
                self.field.next = 23.into();
                self.hs_en.next = self.fpos.q.val() == 3;
            }
            Field::Suspend => {
                self.field.next = 24.into();
                self.hs_en.next = true;
            }
            _ => {}
        }
        // ------------------------------------------------------------------
        // Field classification (for a stuff bit: of the bit before it).
        match self.l_dfld.val() {
            Field::Ident => {
                self.l_arbf.next = true;
                self.l_arbstuff.next = true;
                self.l_arbpos.next = bit_cast::<6, 8>(self.l_dpos.val());
            }
            Field::Srr => {
                self.l_arbf.next = true;
                self.l_arbstuff.next = true;
                self.l_arbpos.next = 12.into();
            }
            Field::Ide => {
                self.l_arbf.next = true;
                self.l_arbstuff.next = self.rext.q.val();
                self.l_arbpos.next = 13.into();
            }
            Field::Rtr => {
                self.l_arbf.next = true;
                self.l_arbstuff.next = !self.rext.q.val();
                self.l_arbpos.next = 12.into();
                if self.rext.q.val() {
                    self.l_arbpos.next = 32.into();
                }
            }
            Field::ExIdent => {
                self.l_arbf.next = true;
                self.l_arbstuff.next = true;
                self.l_arbpos.next = bit_cast::<6, 8>(self.l_dpos.val()) + 13;
            }
            _ => {}
        }

        // ------------------------------------------------------------------
        if self.sample.val() {
            self.l_ev.next = self.l_ev.val().replace_bit(19 /* EV_BIT */, true);
            if self.l_instf.val() {
                // ---------------- stuffed area (SOF .. CRC sequence) ----------------
                if self.l_curstf.val() {
                    // A good stuff bit changes nothing but the destuffer.
                    self.l_ndom.next = self.dom.q.val();
                    if self.dstf.stuff_error.val() {
                        // Sixth equal bit: stuff error, or a bit error for a
                        // transmitter that sent a dominant stuff bit.
                        self.l_err.next = true;
                        if self.rtx.q.val() {
                            if self.l_bit.val() & !self.l_sent.val() {
                                self.l_errk.next = self.l_errk.val().replace_bit(0 /* ERRK_BIT */, true);
                                self.l_tinc.next = true;
                            } else {
                                self.l_errk.next = self.l_errk.val().replace_bit(1 /* ERRK_STUFF */, true);
                                if self.l_arbstuff.val() {
                                    self.l_ev.next = self.l_ev.val().replace_bit(15 /* EV_EXC2 */, true);
                                } else {
                                    self.l_tinc.next = true;
                                }
                            }
                        } else {
                            self.l_errk.next = self.l_errk.val().replace_bit(1 /* ERRK_STUFF */, true);
                            self.l_rinc1.next = true;
                        }
                    }
                } else {
                    if self.rtx.q.val() & (self.l_bit.val() != self.l_sent.val()) {
                        if self.l_arbf.val() & self.l_sent.val() {
                            self.l_role.next = false;
                            self.l_ev.next = self.l_ev.val().replace_bit(1 /* EV_ARB_LOST */, true);
                            if self.single_shot.val() {
                                self.blocked.d.next = true;
                            }
                        } else {
                            self.l_err.next = true;
                            self.l_errk.next = self.l_errk.val().replace_bit(0 /* ERRK_BIT */, true);
                            self.l_tinc.next = true;
                        }
                    }
                    if !self.l_err.val() {
                        // CRC over SOF .. CRC sequence (see the module docs).
                        self.l_crcen.next = true;
                        match self.fld.q.val() {
                            Field::Sof => {
                                self.l_sofinit.next = true;
                            }
                            Field::Ident => {
                                self.l_rid.next = self.rid.q.val() << 1;
                                if self.l_bit.val() {
                                    self.l_rid.next = self.l_rid.val() | 1;
                                }
                                self.l_tid.next = self.tid.q.val() << 1;
                            }
                            Field::ExIdent => {
                                self.l_rid.next = self.rid.q.val() << 1;
                                if self.l_bit.val() {
                                    self.l_rid.next = self.l_rid.val() | 1;
                                }
                                self.l_tid.next = self.tid.q.val() << 1;
                            }
                            Field::Srr => {
                                self.l_rrtr.next = self.l_bit.val();
                            }
                            Field::Rtr => {
                                self.l_rrtr.next = self.l_bit.val();
                            }
                            Field::Ide => {
                                self.l_rext.next = self.l_bit.val();
                            }
                            Field::Dlc => {
                                self.l_rdlc.next = self.rdlc.q.val() << 1;
                                if self.l_bit.val() {
                                    self.l_rdlc.next = self.l_rdlc.val() | 1;
                                }
                                self.l_tdlc.next = self.tdlc.q.val() << 1;
                            }
                            Field::Data => {
                                self.l_rdat.next = self.rdat.q.val() << 1;
                                if self.l_bit.val() {
                                    self.l_rdat.next = self.l_rdat.val() | 1;
                                }
                                self.l_tdat.next = self.tdat.q.val() << 1;
                            }
                            Field::Crc => {
                                if (self.fpos.q.val() == 15) & self.crcb.crc_next.val().any() {
                                    self.l_crcerr.next = true;
                                }
                            }
                            _ => {}
                        }
                        self.l_adv.next = true;
                    }
                }
            } else {
                // ---------------- fields outside the stuffed area ----------------
                match self.fld.q.val() {
                    Field::Reset => {
                        self.l_nf.next = Field::WaitIdle;
                        self.l_npos.next = 1.into();
                    }
                    Field::WaitIdle => {
                        if !self.l_bit.val() {
                            self.l_npos.next = 1.into();
                        } else if self.fpos.q.val() == 11 {
                            self.l_ev.next = self.l_ev.val().replace_bit(18 /* EV_INTEGRATED */, true);
                            self.l_start.next = true;
                        } else {
                            self.l_npos.next = self.l_posinc.val();
                        }
                    }
                    Field::Idle => {
                        if !self.l_bit.val() {
                            self.l_sofinit.next = true;
                            self.l_role.next = false;
                        } else {
                            self.l_start.next = true;
                        }
                    }
                    Field::BusOff => {
                        if (self.host_recovery.val() & !(self.rarmed.q.val() | self.recover.val())) | !self.l_bit.val() {
                            // waiting for the host (a `recover` strobe on this clock
                            // counts this bit), or a dominant bit restarts the run
                            self.l_npos.next = 1.into();
                        } else if self.fpos.q.val() == 11 {
                            self.l_ev.next = self.l_ev.val().replace_bit(16 /* EV_RUN */, true);
                            self.l_npos.next = 1.into();
                            self.l_runs.next = self.runr.q.val() + 1;
                            if self.runr.q.val() == 127 {
                                self.l_ev.next = self.l_ev.val().replace_bit(17 /* EV_RECOVERED */, true);
                                self.l_clear.next = true;
                                self.l_runs.next = 0.into();
                                self.l_rarmed.next = false;
                                self.l_start.next = true;
                            }
                        } else {
                            self.l_npos.next = self.l_posinc.val();
                        }
                    }
                    Field::CrcDel => {
                        if !self.l_bit.val() {
                            self.l_err.next = true;
                            self.l_errk.next = self.l_errk.val().replace_bit(3 /* ERRK_FORM */, true);
                            self.l_tinc.next = self.rtx.q.val();
                            self.l_rinc1.next = !self.rtx.q.val();
                        } else {
                            self.l_nf.next = Field::AckSlot;
                            self.l_npos.next = 1.into();
                            self.l_ndom.next =
                                !self.rtx.q.val() & !self.crcerr.q.val() & !self.listen_only.val();
                        }
                    }
                    Field::AckSlot => {
                        self.l_nf.next = Field::AckDel;
                        self.l_npos.next = 1.into();
                        if self.l_bit.val() {
                            if self.rtx.q.val() {
                                if !self.self_test.val() {
                                    self.l_err.next = true;
                                    self.l_errk.next = self.l_errk.val().replace_bit(4 /* ERRK_ACK */, true);
                                    if self.l_active.val() {
                                        self.l_tinc.next = true;
                                    } else {
                                        self.l_exc1.next = true;
                                    }
                                }
                            } else if self.dom.q.val() {
                                self.l_err.next = true;
                                self.l_errk.next = self.l_errk.val().replace_bit(0 /* ERRK_BIT */, true);
                                self.l_rinc1.next = true;
                            }
                        }
                    }
                    Field::AckDel => {
                        if !self.l_bit.val() {
                            self.l_err.next = true;
                            self.l_errk.next = self.l_errk.val().replace_bit(3 /* ERRK_FORM */, true);
                            self.l_tinc.next = self.rtx.q.val();
                            self.l_rinc1.next = !self.rtx.q.val();
                        }
                        if !self.rtx.q.val() & self.crcerr.q.val() {
                            // the pending CRC error; a form error here is the
                            // same error (one flag, one count, reported as CRC)
                            self.l_err.next = true;
                            self.l_errk.next = 0.into();
                            self.l_errk.next = self.l_errk.val().replace_bit(2 /* ERRK_CRC */, true);
                            self.l_rinc1.next = true;
                        }
                        self.l_nf.next = Field::Eof;
                        self.l_npos.next = 1.into();
                    }
                    Field::Eof => {
                        self.l_npos.next = self.l_posinc.val();
                        if self.fpos.q.val() == 7 {
                            self.l_nf.next = Field::Inter;
                            self.l_npos.next = 1.into();
                            if self.rtx.q.val() {
                                if !self.l_bit.val() {
                                    self.l_err.next = true;
                                    self.l_errk.next = self.l_errk.val().replace_bit(3 /* ERRK_FORM */, true);
                                    self.l_tinc.next = true;
                                } else {
                                    self.l_tdec.next = true;
                                    self.l_ev.next = self.l_ev.val().replace_bit(12 /* EV_TX_OK */, true);
                                    self.blocked.d.next = true;
                                }
                            } else {
                                self.l_deliver.next = true;
                                self.l_ev.next = self.l_ev.val().replace_bit(13 /* EV_RX_OK */, true);
                                if !self.l_bit.val() {
                                    self.l_ovl.next = true;
                                } else {
                                    self.l_rok.next = true;
                                }
                            }
                        } else if !self.l_bit.val() {
                            self.l_err.next = true;
                            self.l_errk.next = self.l_errk.val().replace_bit(3 /* ERRK_FORM */, true);
                            self.l_tinc.next = self.rtx.q.val();
                            self.l_rinc1.next = !self.rtx.q.val();
                        }
                    }
                    Field::ActFlag => {
                        if !self.fdone.q.val() {
                            // bit error: recessive read while driving dominant (a
                            // listen-only node drives its flags recessive)
                            if self.l_bit.val() & !self.l_sent.val() {
                                self.l_err.next = true;
                                self.l_errk.next = self.l_errk.val().replace_bit(0 /* ERRK_BIT */, true);
                                self.l_tinc.next = self.rtx.q.val();
                                self.l_rinc8.next = !self.rtx.q.val();
                            } else {
                                self.l_npos.next = self.l_posinc.val();
                                self.l_ndom.next = true;
                                if self.fpos.q.val() == 6 {
                                    self.l_fdone.next = true;
                                    self.l_ndom.next = false;
                                    self.l_dafc.next = 0.into();
                                    self.l_dafany.next = false;
                                }
                            }
                        } else if self.l_bit.val() {
                            self.l_nf.next = Field::ErrDel;
                            self.l_npos.next = 2.into();
                        } else {
                            self.l_npos.next = self.l_posinc.val();
                            self.l_ev.next = self.l_ev.val().replace_bit(11 /* EV_DAF */, true);
                            self.l_dafany.next = true;
                            self.l_dafc.next = self.dafc.q.val() + 1;
                            if !self.dafany.q.val() & !self.rtx.q.val() {
                                self.l_rinc8.next = true;
                            }
                            if self.dafc.q.val() == 7 {
                                self.l_tinc.next = self.rtx.q.val();
                                self.l_rinc8.next = !self.rtx.q.val();
                            }
                        }
                    }
                    Field::OvlFlag => {
                        if !self.fdone.q.val() {
                            // bit error: recessive read while driving dominant (a
                            // listen-only node drives its flags recessive)
                            if self.l_bit.val() & !self.l_sent.val() {
                                self.l_err.next = true;
                                self.l_errk.next = self.l_errk.val().replace_bit(0 /* ERRK_BIT */, true);
                                self.l_tinc.next = self.rtx.q.val();
                                self.l_rinc8.next = !self.rtx.q.val();
                            } else {
                                self.l_npos.next = self.l_posinc.val();
                                self.l_ndom.next = true;
                                if self.fpos.q.val() == 6 {
                                    self.l_fdone.next = true;
                                    self.l_ndom.next = false;
                                    self.l_dafc.next = 0.into();
                                    self.l_dafany.next = false;
                                }
                            }
                        } else if self.l_bit.val() {
                            self.l_nf.next = Field::OvlDel;
                            self.l_npos.next = 2.into();
                        } else {
                            self.l_npos.next = self.l_posinc.val();
                            self.l_ev.next = self.l_ev.val().replace_bit(11 /* EV_DAF */, true);
                            self.l_dafany.next = true;
                            self.l_dafc.next = self.dafc.q.val() + 1;
                            if self.dafc.q.val() == 7 {
                                self.l_tinc.next = self.rtx.q.val();
                                self.l_rinc8.next = !self.rtx.q.val();
                            }
                        }
                    }
                    Field::PasFlag => {
                        if !self.fdone.q.val() {
                            self.l_npos.next = self.l_posinc.val();
                            if self.fpos.q.val() == 1 {
                                self.l_eqcnt.next = 1.into();
                                self.l_eqlast.next = self.l_bit.val();
                            } else if self.l_bit.val() == self.eqlast.q.val() {
                                self.l_eqcnt.next = self.eqcnt.q.val() + 1;
                            } else {
                                self.l_eqcnt.next = 1.into();
                                self.l_eqlast.next = self.l_bit.val();
                            }
                            if self.exc1.q.val() & !self.l_bit.val() {
                                // Exception 1 not met: +8 once, at the first dominant bit.
                                self.l_exc1.next = false;
                                self.l_tinc.next = true;
                            }
                            if self.l_eqcnt.val() == 6 {
                                self.l_fdone.next = true;
                                self.l_dafc.next = 0.into();
                                self.l_dafany.next = false;
                                if self.l_exc1.val() {
                                    self.l_ev.next = self.l_ev.val().replace_bit(14 /* EV_EXC1 */, true);
                                }
                                self.l_exc1.next = false;
                            }
                        } else if self.l_bit.val() {
                            self.l_nf.next = Field::ErrDel;
                            self.l_npos.next = 2.into();
                        } else {
                            self.l_npos.next = self.l_posinc.val();
                            self.l_ev.next = self.l_ev.val().replace_bit(11 /* EV_DAF */, true);
                            self.l_dafany.next = true;
                            self.l_dafc.next = self.dafc.q.val() + 1;
                            if !self.dafany.q.val() & !self.rtx.q.val() {
                                self.l_rinc8.next = true;
                            }
                            if self.dafc.q.val() == 7 {
                                self.l_tinc.next = self.rtx.q.val();
                                self.l_rinc8.next = !self.rtx.q.val();
                            }
                        }
                    }
                    Field::ErrDel => {
                        self.l_npos.next = self.l_posinc.val();
                        if self.fpos.q.val() == 8 {
                            self.l_nf.next = Field::Inter;
                            self.l_npos.next = 1.into();
                            if !self.l_bit.val() {
                                self.l_ovl.next = true;
                            }
                        } else if !self.l_bit.val() {
                            self.l_err.next = true;
                            self.l_errk.next = self.l_errk.val().replace_bit(3 /* ERRK_FORM */, true);
                            self.l_tinc.next = self.rtx.q.val();
                            self.l_rinc1.next = !self.rtx.q.val();
                        }
                    }
                    Field::OvlDel => {
                        self.l_npos.next = self.l_posinc.val();
                        if self.fpos.q.val() == 8 {
                            self.l_nf.next = Field::Inter;
                            self.l_npos.next = 1.into();
                            if !self.l_bit.val() {
                                self.l_ovl.next = true;
                            }
                        } else if !self.l_bit.val() {
                            self.l_err.next = true;
                            self.l_errk.next = self.l_errk.val().replace_bit(3 /* ERRK_FORM */, true);
                            self.l_tinc.next = self.rtx.q.val();
                            self.l_rinc1.next = !self.rtx.q.val();
                        }
                    }
                    Field::Inter => {
                        self.l_npos.next = self.l_posinc.val();
                        if self.fpos.q.val() == 3 {
                            if !self.l_bit.val() {
                                // A dominant third intermission bit is a SOF.
                                self.l_sofinit.next = true;
                                if self.l_cantx.val() & !(self.rtx.q.val() & !self.l_active.val()) {
                                    self.l_role.next = true;
                                    self.l_txsof.next = true;
                                } else {
                                    self.l_role.next = false;
                                }
                            } else if self.rtx.q.val() & !self.l_active.val() {
                                self.l_nf.next = Field::Suspend;
                                self.l_npos.next = 1.into();
                            } else {
                                self.l_start.next = true;
                            }
                        } else if !self.l_bit.val() {
                            self.l_ovl.next = true;
                        }
                    }
                    Field::Suspend => {
                        self.l_npos.next = self.l_posinc.val();
                        if !self.l_bit.val() {
                            self.l_sofinit.next = true;
                            self.l_role.next = false;
                        } else if self.fpos.q.val() == 8 {
                            self.l_start.next = true;
                        }
                    }
                    _ => {}
                }
            }

            // ---------------- advance inside the stuffed area ----------------
            if self.l_adv.val() {
                self.l_usetx.next = true;
                self.l_npos.next = self.l_posinc.val();
                if self.l_rdlc.val().get_bit(3) {
                    self.l_nbytes.next = 8.into();
                } else {
                    self.l_nbytes.next = self.l_rdlc.val();
                }
                self.l_nbits.next = bit_cast::<8, 4>(self.l_nbytes.val()) << 3;
                match self.fld.q.val() {
                    Field::Sof => {
                        self.l_nf.next = Field::Ident;
                        self.l_npos.next = 1.into();
                    }
                    Field::Ident => {
                        if self.fpos.q.val() == 11 {
                            self.l_npos.next = 1.into();
                            if self.l_role.val() & self.tide.q.val() {
                                self.l_nf.next = Field::Srr;
                            } else {
                                self.l_nf.next = Field::Rtr;
                            }
                        }
                    }
                    Field::Srr => {
                        self.l_nf.next = Field::Ide;
                        self.l_npos.next = 1.into();
                    }
                    Field::Rtr => {
                        self.l_npos.next = 1.into();
                        if self.rext.q.val() {
                            self.l_nf.next = Field::Resv;
                        } else {
                            self.l_nf.next = Field::Ide;
                        }
                    }
                    Field::Ide => {
                        self.l_npos.next = 1.into();
                        if self.l_rext.val() {
                            self.l_nf.next = Field::ExIdent;
                        } else {
                            self.l_nf.next = Field::Resv;
                        }
                    }
                    Field::ExIdent => {
                        if self.fpos.q.val() == 18 {
                            self.l_nf.next = Field::Rtr;
                            self.l_npos.next = 1.into();
                        }
                    }
                    Field::Resv => {
                        if !(self.rext.q.val() & (self.fpos.q.val() == 1)) {
                            self.l_nf.next = Field::Dlc;
                            self.l_npos.next = 1.into();
                        }
                    }
                    Field::Dlc => {
                        if self.fpos.q.val() == 4 {
                            self.l_npos.next = 1.into();
                            if self.l_rrtr.val() | (self.l_nbytes.val() == 0) {
                                self.l_nf.next = Field::Crc;
                            } else {
                                self.l_nf.next = Field::Data;
                            }
                        }
                    }
                    Field::Data => {
                        if self.fpos.q.val() == self.l_nbits.val() {
                            self.l_nf.next = Field::Crc;
                            self.l_npos.next = 1.into();
                        }
                    }
                    Field::Crc => {
                        if self.fpos.q.val() == 15 {
                            self.l_nf.next = Field::CrcDel;
                            self.l_npos.next = 1.into();
                            self.l_usetx.next = false;
                        }
                    }
                    _ => {}
                }
            }

            // ---------------- start of a frame (SOF sampled) ----------------
            if self.l_sofinit.val() {
                self.l_ev.next = self.l_ev.val().replace_bit(0 /* EV_SOF */, true);
                self.l_crcerr.next = false;
                self.l_rid.next = 0.into();
                self.l_rdat.next = 0.into();
                self.l_rdlc.next = 0.into();
                self.l_rrtr.next = false;
                self.l_rext.next = false;
                self.l_nf.next = Field::Ident;
                self.l_npos.next = 1.into();
                self.l_usetx.next = true;
            }
            // Bus idle reached (or suspend over): start a frame if one is pending.
            if self.l_start.val() {
                if self.l_cantx.val() {
                    self.l_nf.next = Field::Sof;
                    self.l_npos.next = 1.into();
                    self.l_role.next = true;
                    self.l_txsof.next = true;
                    self.l_usetx.next = true;
                } else {
                    self.l_nf.next = Field::Idle;
                    self.l_npos.next = 1.into();
                    if self.fld.q.val() == Field::Idle {
                        self.l_npos.next = self.l_posinc.val();
                    }
                }
            }
            // Latch the request contents at the start of an own frame.
            if self.l_txsof.val() {
                self.l_tide.next = self.tx_ide.val();
                self.l_trtr.next = self.tx_rtr.val();
                if self.tx_ide.val() {
                    self.l_tid.next = self.tx_id.val();
                } else {
                    self.l_tid.next = self.tx_id.val() << 18;
                }
                self.l_tdlc.next = self.tx_dlc.val();
                self.l_tdat.next = self.tx_data.val();
            }

            // ---------------- level to send in the next bit ----------------
            if self.l_usetx.val() {
                match self.l_nf.val() {
                    Field::Sof => {
                        self.l_txv.next = false;
                    }
                    Field::Ident => {
                        self.l_txv.next = self.l_tid.val().get_bit(28);
                    }
                    Field::ExIdent => {
                        self.l_txv.next = self.l_tid.val().get_bit(28);
                    }
                    Field::Srr => {
                        self.l_txv.next = true;
                    }
                    Field::Ide => {
                        self.l_txv.next = self.l_tide.val();
                    }
                    Field::Rtr => {
                        self.l_txv.next = self.l_trtr.val();
                    }
                    Field::Resv => {
                        self.l_txv.next = false;
                    }
                    Field::Dlc => {
                        self.l_txv.next = self.l_tdlc.val().get_bit(3);
                    }
                    Field::Data => {
                        self.l_txv.next = self.l_tdat.val().get_bit(63);
                    }
                    Field::Crc => {
                        self.l_txv.next = self.crcb.crc_next.val().get_bit(14);
                    }
                    _ => {
                        self.l_txv.next = true;
                    }
                }
                self.l_ndom.next = self.l_role.val() & !self.l_txv.val();
            }

            // ---------------- error and overload frames ----------------
            if self.l_err.val() {
                self.l_npos.next = 1.into();
                self.l_fdone.next = false;
                self.l_crcerr.next = false;
                self.l_dafc.next = 0.into();
                self.l_dafany.next = false;
                self.l_ev.next = self.l_ev.val() | (bit_cast::<EV_BITS, 5>(self.l_errk.val()) << 2);
                if self.l_active.val() {
                    self.l_nf.next = Field::ActFlag;
                    self.l_ndom.next = true;
                    self.l_ev.next = self.l_ev.val().replace_bit(7 /* EV_AEF */, true);
                } else {
                    self.l_nf.next = Field::PasFlag;
                    self.l_ndom.next = false;
                    self.l_ev.next = self.l_ev.val().replace_bit(8 /* EV_PEF */, true);
                }
                if self.rtx.q.val() & self.single_shot.val() {
                    self.blocked.d.next = true;
                }
                self.errf_r.d.next = self.field.val();
                self.errp_r.d.next = self.l_dpos.val();
                self.errtx_r.d.next = self.rtx.q.val();
            } else if self.l_ovl.val() {
                self.l_nf.next = Field::OvlFlag;
                self.l_npos.next = 1.into();
                self.l_ndom.next = true;
                self.l_fdone.next = false;
                self.l_dafc.next = 0.into();
                self.l_dafany.next = false;
                self.l_ev.next = self.l_ev.val().replace_bit(10 /* EV_OVL */, true);
                self.l_ev.next = self.l_ev.val().replace_bit(9 /* EV_OLF */, true);
            }

            // ---------------- fault confinement (§13) ----------------
            // (frozen in listen-only mode, as in the SJA1000)
            if self.listen_only.val() {
                self.l_tec.next = self.tecr.q.val();
                self.l_rec.next = self.recr.q.val();
            } else if self.l_clear.val() {
                self.l_tec.next = 0.into();
                self.l_rec.next = 0.into();
            } else {
                if self.l_tinc.val() {
                    self.l_tec.next = self.tecr.q.val() + 8;
                } else if self.l_tdec.val() & (self.tecr.q.val() != 0) {
                    self.l_tec.next = self.tecr.q.val() - 1;
                }
                if self.recr.q.val() < 128 {
                    if self.l_rinc8.val() {
                        self.l_rec.next = self.recr.q.val() + 8;
                    } else if self.l_rinc1.val() {
                        self.l_rec.next = self.recr.q.val() + 1;
                    } else if self.l_rok.val() & (self.recr.q.val() != 0) {
                        self.l_rec.next = self.recr.q.val() - 1;
                    }
                } else if self.l_rok.val() {
                    self.l_rec.next = 127.into();
                }
            }
            // Bus-off as soon as TEC exceeds 255.
            if self.l_tec.val().get_bit(8) & (self.fld.q.val() != Field::BusOff) {
                // no flag is started after all
                self.l_ev.next = self.l_ev.val().replace_bit(7 /* EV_AEF */, false);
                self.l_ev.next = self.l_ev.val().replace_bit(8 /* EV_PEF */, false);
                self.l_ev.next = self.l_ev.val().replace_bit(9 /* EV_OLF */, false);
                self.l_nf.next = Field::BusOff;
                self.l_npos.next = 1.into();
                self.l_ndom.next = false;
                self.l_runs.next = 0.into();
                self.l_rarmed.next = false;
            }

            // ---------------- frame delivery ----------------
            if self.l_deliver.val() {
                self.rxide_r.d.next = self.rext.q.val();
                self.rxrtr_r.d.next = self.rrtr.q.val();
                self.rxid_r.d.next = self.rid.q.val();
                self.rxdlc_r.d.next = self.rdlc.q.val();
                // Left-align the received bytes: shift by (64 - 8N) mod 64.
                self.l_shamt.next = bit_cast::<6, 4>(self.l_nbytes.val()) << 3;
                self.l_shamt.next = (!self.l_shamt.val()) + 1;
                if self.rrtr.q.val() | (self.l_nbytes.val() == 0) {
                    self.rxdat_r.d.next = 0.into();
                } else {
                    self.rxdat_r.d.next = self.rdat.q.val() << self.l_shamt.val();
                }
            }
            if self.l_ev.val().get_bit(1 /* EV_ARB_LOST */) {
                self.arbpos_r.d.next = self.l_arbpos.val();
            }

            // ---------------- commit ----------------
            if !self.l_curstf.val() {
                self.pfld.d.next = self.fld.q.val();
                self.ppos.d.next = self.fpos.q.val();
            }
            self.fld.d.next = self.l_nf.val();
            self.fpos.d.next = self.l_npos.val();
            self.rtx.d.next = self.l_role.val();
            self.dom.d.next = self.l_ndom.val();
            self.crcerr.d.next = self.l_crcerr.val();
            self.tid.d.next = self.l_tid.val();
            self.tdat.d.next = self.l_tdat.val();
            self.tdlc.d.next = self.l_tdlc.val();
            self.tide.d.next = self.l_tide.val();
            self.trtr.d.next = self.l_trtr.val();
            self.rid.d.next = self.l_rid.val();
            self.rdat.d.next = self.l_rdat.val();
            self.rdlc.d.next = self.l_rdlc.val();
            self.rrtr.d.next = self.l_rrtr.val();
            self.rext.d.next = self.l_rext.val();
            self.fdone.d.next = self.l_fdone.val();
            self.eqcnt.d.next = self.l_eqcnt.val();
            self.eqlast.d.next = self.l_eqlast.val();
            self.dafc.d.next = self.l_dafc.val();
            self.dafany.d.next = self.l_dafany.val();
            self.exc1.d.next = self.l_exc1.val();
            self.tecr.d.next = self.l_tec.val();
            self.recr.d.next = self.l_rec.val();
            self.runr.d.next = self.l_runs.val();
            self.rarmed.d.next = self.l_rarmed.val();
            self.evr.d.next = self.l_ev.val();
        }

        // ------------------------------------------------------------------
        // Shared destuffer and CRC engine, both on the sampled levels.
        self.dstf.clock.next = self.clock.val();
        self.dstf.reset.next = self.reset.val();
        self.dstf.en.next = self.sample.val();
        self.dstf.din.next = self.busmon.val();
        self.dstf.active.next = self.l_instf.val() | self.l_sofinit.val();
        self.crcb.clock.next = self.clock.val();
        self.crcb.reset.next = self.reset.val();
        self.crcb.din.next = self.busmon.val();
        self.crcb.en.next = self.sample.val() & self.l_crcen.val();
        self.crcb.clear.next = self.sample.val() & self.l_sofinit.val();

        // ------------------------------------------------------------------
        // Synchronous reset.
        if self.reset.val() {
            self.fld.d.next = Field::WaitIdle;
            self.fpos.d.next = 1.into();
            self.rtx.d.next = false;
            self.dom.d.next = false;
            self.crcerr.d.next = false;
            self.fdone.d.next = false;
            self.eqcnt.d.next = 0.into();
            self.eqlast.d.next = false;
            self.dafc.d.next = 0.into();
            self.dafany.d.next = false;
            self.exc1.d.next = false;
            self.tecr.d.next = 0.into();
            self.recr.d.next = 0.into();
            self.runr.d.next = 0.into();
            self.rarmed.d.next = false;
            self.req.d.next = false;
            self.blocked.d.next = false;
            self.evr.d.next = 0.into();
            self.rext.d.next = false;
            self.rrtr.d.next = false;
        }
        // Counter load (priority over reset and the protocol).
        if self.cnt_load.val() {
            self.tecr.d.next = self.tec_in.val();
            self.recr.d.next = self.rec_in.val();
            if self.tec_in.val().get_bit(8) {
                self.fld.d.next = Field::BusOff;
                self.fpos.d.next = 1.into();
                self.rtx.d.next = false;
                self.dom.d.next = false;
                self.runr.d.next = 0.into();
                self.rarmed.d.next = false;
            } else if self.fld.q.val() == Field::BusOff {
                self.fld.d.next = Field::WaitIdle;
                self.fpos.d.next = 1.into();
                self.dom.d.next = false;
                self.runr.d.next = 0.into();
                self.rarmed.d.next = false;
            }
        }

        // ------------------------------------------------------------------
        // Outputs.
        self.pos.next = self.l_dpos.val();
        self.stuff.next = self.l_curstf.val();
        self.role.next = self.rtx.q.val();
        self.events.next = self.evr.q.val();
        self.tx_done.next = self.evr.q.val().get_bit(12 /* EV_TX_OK */);
        self.arb_lost.next = self.evr.q.val().get_bit(1 /* EV_ARB_LOST */);
        self.arb_lost_pos.next = self.arbpos_r.q.val();
        self.error.next = (self.evr.q.val().get_bits::<5>(2)).any();
        self.err_kind.next = self.evr.q.val().get_bits::<5>(2);
        self.err_field.next = self.errf_r.q.val();
        self.err_pos.next = self.errp_r.q.val();
        self.err_tx.next = self.errtx_r.q.val();
        self.rx_valid.next = self.evr.q.val().get_bit(13 /* EV_RX_OK */);
        self.rx_ide.next = self.rxide_r.q.val();
        self.rx_rtr.next = self.rxrtr_r.q.val();
        self.rx_id.next = self.rxid_r.q.val();
        self.rx_dlc.next = self.rxdlc_r.q.val();
        self.rx_data.next = self.rxdat_r.q.val();
        self.tec.next = self.tecr.q.val();
        self.rec.next = self.recr.q.val();
        self.state.next = 0.into();
        if self.tecr.q.val().get_bit(8) {
            self.state.next = 2.into();
        } else if (self.tecr.q.val() >= 128) | (self.recr.q.val() >= 128) {
            self.state.next = 1.into();
        }
        self.err_warn.next = (self.tecr.q.val() >= 96) | (self.recr.q.val() >= 96);
        self.tx_rqst.next = self.req.q.val();
        self.runs.next = self.runr.q.val();
    }
}

canstar_hdl::impl_clocked!(CanFsm);
