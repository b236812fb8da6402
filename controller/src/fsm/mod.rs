//! The bit-stream processor: the complete CAN 2.0A/B frame state machine of
//! one node ([`CanFsm`], a composition of sub-blocks, see Structure).
//!
//! It works on sampled bits only. Once per bit the bit timing logic raises
//! `sample` for one clock, with the sampled bus level on `busmon`. On that
//! clock the block processes the bit completely (destuffing, CRC, arbitration,
//! error detection, fault confinement, frame delivery) and latches its
//! decision: `drive` (the level wanted on TX for the next bit) and `hs_en`
//! (hard synchronisation enable) are functions of registers only (and of the
//! `listen_only` mode bit), valid from the next clock on, so they are ready
//! at the earliest transmit point, 2 clocks after the sample point's tick
//! (the IPT of can-protocol.md §2.5: 2 TQ, or 1 TQ of at least 2 clocks).
//! Counter changes are visible on the same clock (§13.4). Everything is normative per `can-protocol.md`;
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
//!
//! ## Structure
//!
//! [`CanFsm`] is a composition of sub-blocks, one concern each; it only
//! wires them (and ORs the per-group strobes):
//!
//! - [`decode::BitDecode`]: what the bit in progress is (stuffed area, stuff
//!   bit, displayed FIELD/POSITION, hard-sync enable, arbitration bit, the
//!   level to drive), from registers only;
//! - [`frame_fields::FrameFields`] and [`flags::FlagFields`]: the decision
//!   for a sampled bit of a data/remote frame, and of an error or overload
//!   frame (one mechanism for the active error and the overload flag);
//! - [`seq::Sequencer`]: FIELD, POSITION, role and drive registers; the
//!   fields between frames; frame start, error/overload flag and bus-off
//!   entry;
//! - [`confine::FaultConfinement`]: TEC, REC, error state, bus-off recovery;
//! - [`txreq::TxRequest`]: the request handshake and the transmit register;
//! - [`rxframe::RxFrame`]: the receive register and frame delivery;
//! - [`report::EventReport`]: the event word and the error/arbitration
//!   report registers;
//! - the shared [`BitDestuffer`] and [`Crc15`].
//!
//! The decision blocks ([`frame_fields`], [`flags`], [`seq`], and the
//! bus-off test of [`confine`]) decide on the `sample` clock only (their
//! outputs are 0 between sample strobes), as the single block before the
//! split did; the registers take the decision at the end of that clock.
//! [`CanFsm::update`] only wires: each sub-block input is assigned once per
//! evaluation, so glitches inside one sub-block's `always @(*)` cannot
//! retrigger another one in an event-driven simulator (see the Verilog note
//! in `canstar_hub::hub`).

pub mod confine;
pub mod decode;
pub mod field;
pub mod flags;
pub mod frame_fields;
pub mod report;
pub mod rxframe;
pub mod seq;
pub mod txreq;

pub use field::Field;

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

// The error kinds sit in the event word in `err_kind` order (the report
// block reads `err_kind` as one slice of the word).
const _: () = assert!(ERRK_BIT == 0 && ERRK_STUFF == 1 && ERRK_CRC == 2 && ERRK_FORM == 3 && ERRK_ACK == 4);
const _: () = assert!(
    EV_STUFF_ERR == EV_BIT_ERR + ERRK_STUFF
        && EV_CRC_ERR == EV_BIT_ERR + ERRK_CRC
        && EV_FORM_ERR == EV_BIT_ERR + ERRK_FORM
        && EV_ACK_ERR == EV_BIT_ERR + ERRK_ACK
);

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
    /// C13: REC − 1 at a receiver's dominant End_Of_Frame bit 7 (see
    /// [`frame_fields::FrameFields`]); a constant of [`crate::core::CanCore`].
    pub rec_iso: Signal<In, Bit>,
    /// Two-clock mode: `sample` strobes at least 2 clocks apart, as from
    /// the bit timing logic; some register decodes of the per-bit decision
    /// are then taken from flip-flops a clock ahead (issue #16, see
    /// [`seq::Sequencer`] and [`frame_fields::FrameFields`]).
    /// [`crate::core::CanCore`] ties it high; tie it low when `sample` may
    /// come on consecutive clocks.
    pub pipe: Signal<In, Bit>,

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
    dstf: BitDestuffer,
    crcb: Crc15,
    dec: decode::BitDecode,
    seq: seq::Sequencer,
    frame: frame_fields::FrameFields,
    flags: flags::FlagFields,
    conf: confine::FaultConfinement,
    txq: txreq::TxRequest,
    rxf: rxframe::RxFrame,
    rpt: report::EventReport,
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
        // Shared destuffer and CRC engine, both on the sampled levels. The
        // destuffer reads `active` only on `en` clocks.
        self.dstf.clock.next = self.clock.val();
        self.dstf.reset.next = self.reset.val();
        self.dstf.en.next = self.sample.val();
        self.dstf.din.next = self.busmon.val();
        self.dstf.active.next = self.seq.pstuffed.val() | self.seq.sofinit.val();
        self.crcb.clock.next = self.clock.val();
        self.crcb.reset.next = self.reset.val();
        self.crcb.din.next = self.busmon.val();
        self.crcb.en.next = self.sample.val() & self.frame.adv.val();
        self.crcb.clear.next = self.sample.val() & self.seq.sofinit.val();

        self.dec.fld.next = self.seq.fld.val();
        self.dec.fpos.next = self.seq.fpos.val();
        self.dec.pfld.next = self.seq.pfld.val();
        self.dec.ppos.next = self.seq.ppos.val();
        self.dec.ext.next = self.rxf.ext.val();
        self.dec.tx_role.next = self.seq.tx_role.val();
        self.dec.dom.next = self.seq.dom.val();
        self.dec.listen_only.next = self.listen_only.val();
        self.dec.next_is_stuff.next = self.dstf.next_is_stuff.val();
        self.dec.stuff_level.next = self.dstf.stuff_level.val();
        self.dec.in_area.next = self.seq.area.val();
        self.dec.stuffable.next = self.seq.stuffable.val();
        self.dec.hs_fld.next = self.seq.hs_fld.val();
        self.dec.inter_fld.next = self.seq.inter_fld.val();
        self.dec.hs_pfld.next = self.seq.hs_pfld.val();
        self.dec.inter_pfld.next = self.seq.inter_pfld.val();
        self.dec.fpos3.next = self.seq.pos3.val();

        self.frame.clock.next = self.clock.val();
        self.frame.reset.next = self.reset.val();
        self.frame.sample.next = self.sample.val();
        self.frame.rxbit.next = self.busmon.val();
        self.frame.sent.next = self.dec.sent_bit.val();
        self.frame.sent_stuff.next = self.dec.sent_stuff.val();
        self.frame.rec_iso.next = self.rec_iso.val();
        self.frame.fld.next = self.seq.fld.val();
        self.frame.fpos.next = self.seq.fpos.val();
        self.frame.at_end.next = self.seq.at_end.val();
        self.frame.area.next = self.seq.area.val();
        self.frame.stuffable.next = self.seq.stuffable.val();
        self.frame.hs_fld.next = self.seq.hs_fld.val();
        self.frame.inter_fld.next = self.seq.inter_fld.val();
        self.frame.tx_role.next = self.seq.tx_role.val();
        self.frame.dom.next = self.seq.dom.val();
        self.frame.listen_only.next = self.listen_only.val();
        self.frame.self_test.next = self.self_test.val();
        self.frame.active.next = self.conf.active.val();
        self.frame.stuffed.next = self.seq.pstuffed.val();
        self.frame.stuff.next = self.seq.pstuff.val();
        self.frame.arb.next = self.dec.arb_bit.val();
        self.frame.arb_stuff.next = self.dec.arb_stuff_bit.val();
        self.frame.pipe.next = self.pipe.val();
        self.frame.stuff_error.next = self.dstf.next_is_stuff.val() & (self.busmon.val() != self.dstf.stuff_level.val());
        self.frame.crc_rem.next = self.crcb.crc_next.val().any();
        self.frame.ext.next = self.rxf.ext.val();
        self.frame.rtr.next = self.rxf.rtr.val();
        self.frame.dlc_lo_zero.next = self.rxf.dlc_lo_zero.val();
        self.frame.data_bits.next = self.rxf.data_bits.val();
        self.frame.tx_ide.next = self.txq.ide.val();
        self.frame.sofinit.next = self.seq.sofinit.val();
        self.frame.err_now.next = self.seq.err.val();

        self.flags.clock.next = self.clock.val();
        self.flags.reset.next = self.reset.val();
        self.flags.sample.next = self.sample.val();
        self.flags.rxbit.next = self.busmon.val();
        // the flags own no stuff bit: `drive` is `sent_bit` there
        self.flags.sent.next = self.dec.sent_bit.val();
        self.flags.fld.next = self.seq.fld.val();
        self.flags.fpos.next = self.seq.fpos.val();
        self.flags.at_end.next = self.seq.at_end.val();
        self.flags.area.next = self.seq.area.val();
        self.flags.stuffable.next = self.seq.stuffable.val();
        self.flags.hs_fld.next = self.seq.hs_fld.val();
        self.flags.inter_fld.next = self.seq.inter_fld.val();
        self.flags.tx_role.next = self.seq.tx_role.val();
        self.flags.flag_start.next = self.seq.flag_start.val();
        self.flags.exc1_set.next = self.frame.exc1.val();

        self.seq.clock.next = self.clock.val();
        self.seq.reset.next = self.reset.val();
        self.seq.sample.next = self.sample.val();
        self.seq.rxbit.next = self.busmon.val();
        self.seq.listen_only.next = self.listen_only.val();
        self.seq.host_recovery.next = self.host_recovery.val();
        self.seq.cnt_load.next = self.cnt_load.val();
        self.seq.tec_in.next = self.tec_in.val();
        self.seq.stuff.next = self.dec.stuff.val();
        self.seq.pipe.next = self.pipe.val();
        self.seq.ext.next = self.rxf.ext.val();
        self.seq.data_bits.next = self.rxf.data_bits.val();
        self.seq.req.next = self.txq.req.val();
        self.seq.active.next = self.conf.active.val();
        self.seq.armed.next = self.conf.armed.val();
        self.seq.last_run.next = self.conf.last_run.val();
        self.seq.busoff.next = self.conf.busoff.val();
        self.seq.in_frame.next = self.dec.area.val();
        self.seq.level.next = self.txq.level.val();
        self.seq.level_sof.next = self.txq.level_sof.val();
        self.seq.f_own.next = self.frame.own.val();
        self.seq.f_nf.next = self.frame.nf.val();
        self.seq.f_na.next = self.frame.narea.val();
        self.seq.f_nsa.next = self.frame.nsa.val();
        self.seq.f_nhs.next = self.frame.nhs.val();
        self.seq.f_ni.next = self.frame.ninter.val();
        self.seq.f_npc.next = self.frame.npc.val();
        self.seq.f_ndom.next = self.frame.ndom.val();
        self.seq.f_usetx.next = self.frame.usetx.val();
        self.seq.f_lost.next = self.frame.lost.val();
        self.seq.f_err.next = self.frame.err.val();
        self.seq.f_ovl.next = self.frame.ovl.val();
        self.seq.f_sof.next = self.frame.sof.val();
        self.seq.g_own.next = self.flags.own.val();
        self.seq.g_nf.next = self.flags.nf.val();
        self.seq.g_na.next = self.flags.narea.val();
        self.seq.g_nsa.next = self.flags.nsa.val();
        self.seq.g_nhs.next = self.flags.nhs.val();
        self.seq.g_ni.next = self.flags.ninter.val();
        self.seq.g_npc.next = self.flags.npc.val();
        self.seq.g_ndom.next = self.flags.ndom.val();
        self.seq.g_err.next = self.flags.err.val();
        self.seq.g_ovl.next = self.flags.ovl.val();

        self.conf.clock.next = self.clock.val();
        self.conf.reset.next = self.reset.val();
        self.conf.sample.next = self.sample.val();
        self.conf.listen_only.next = self.listen_only.val();
        self.conf.recover.next = self.recover.val();
        self.conf.tinc.next = self.frame.tinc.val() | self.flags.tinc.val();
        self.conf.tdec.next = self.frame.tx_ok.val();
        self.conf.rinc1.next = self.frame.rinc1.val() | self.flags.rinc1.val();
        self.conf.rinc8.next = self.flags.rinc8.val();
        self.conf.rok.next = self.frame.rok.val();
        self.conf.run.next = self.seq.ev_run.val();
        self.conf.in_busoff.next = self.seq.in_busoff.val();
        self.conf.cnt_load.next = self.cnt_load.val();
        self.conf.tec_in.next = self.tec_in.val();
        self.conf.rec_in.next = self.rec_in.val();

        self.txq.clock.next = self.clock.val();
        self.txq.reset.next = self.reset.val();
        self.txq.sample.next = self.sample.val();
        self.txq.tx_req.next = self.tx_req.val();
        self.txq.tx_abort.next = self.tx_abort.val();
        self.txq.single_shot.next = self.single_shot.val();
        self.txq.tx_ide.next = self.tx_ide.val();
        self.txq.tx_rtr.next = self.tx_rtr.val();
        self.txq.tx_id.next = self.tx_id.val();
        self.txq.tx_dlc.next = self.tx_dlc.val();
        self.txq.tx_data.next = self.tx_data.val();
        self.txq.load.next = self.seq.txsof.val();
        self.txq.adv.next = self.frame.adv.val();
        self.txq.fld.next = self.seq.fld.val();
        self.txq.nf.next = self.frame.lnf.val();
        // the MSB of the CRC register after this bit: the next CRC bit to send
        self.txq.crc_bit.next = self.crcb.crc_next.val().get_bit(14);
        self.txq.lost.next = self.frame.lost.val();
        self.txq.done.next = self.frame.tx_ok.val();
        self.txq.err_now.next = self.seq.err.val();
        self.txq.tx_role.next = self.seq.tx_role.val();

        self.rxf.clock.next = self.clock.val();
        self.rxf.reset.next = self.reset.val();
        self.rxf.sample.next = self.sample.val();
        self.rxf.rxbit.next = self.busmon.val();
        self.rxf.adv.next = self.frame.adv.val();
        self.rxf.fld.next = self.seq.fld.val();
        self.rxf.sofinit.next = self.seq.sofinit.val();
        self.rxf.deliver.next = self.frame.rx_ok.val();

        self.rpt.clock.next = self.clock.val();
        self.rpt.reset.next = self.reset.val();
        self.rpt.sample.next = self.sample.val();
        self.rpt.ev_sof.next = self.seq.sofinit.val();
        self.rpt.ev_arb_lost.next = self.frame.lost.val();
        self.rpt.ev_bit_err.next = self.frame.err_bit.val() | self.flags.err_bit.val();
        self.rpt.ev_stuff_err.next = self.frame.err_stuff.val();
        self.rpt.ev_crc_err.next = self.frame.err_crc.val();
        self.rpt.ev_form_err.next = self.frame.err_form.val() | self.flags.err_form.val();
        self.rpt.ev_ack_err.next = self.frame.err_ack.val();
        self.rpt.ev_aef.next = self.seq.ev_aef.val();
        self.rpt.ev_pef.next = self.seq.ev_pef.val();
        self.rpt.ev_olf.next = self.seq.ev_olf.val();
        self.rpt.ev_ovl.next = self.seq.ev_ovl.val();
        self.rpt.ev_daf.next = self.flags.daf.val();
        self.rpt.ev_tx_ok.next = self.frame.tx_ok.val();
        self.rpt.ev_rx_ok.next = self.frame.rx_ok.val();
        self.rpt.ev_exc1.next = self.flags.exc1_met.val();
        self.rpt.ev_exc2.next = self.frame.exc2.val();
        self.rpt.ev_run.next = self.seq.ev_run.val();
        self.rpt.ev_recovered.next = self.seq.ev_recovered.val();
        self.rpt.ev_integrated.next = self.seq.ev_integrated.val();
        self.rpt.err_now.next = self.seq.err.val();
        self.rpt.code.next = self.dec.code.val();
        self.rpt.pos.next = self.dec.pos.val();
        self.rpt.tx_role.next = self.seq.tx_role.val();
        self.rpt.arb_pos.next = self.dec.arb_pos.val();

        // Outputs.
        self.drive.next = self.dec.drive.val();
        self.hs_en.next = self.dec.hs_en.val();
        self.tx_done.next = self.rpt.tx_done.val();
        self.arb_lost.next = self.rpt.arb_lost.val();
        self.arb_lost_pos.next = self.rpt.arb_lost_pos.val();
        self.error.next = self.rpt.error.val();
        self.err_kind.next = self.rpt.err_kind.val();
        self.err_field.next = self.rpt.err_field.val();
        self.err_pos.next = self.rpt.err_pos.val();
        self.err_tx.next = self.rpt.err_tx.val();
        self.rx_valid.next = self.rpt.rx_valid.val();
        self.rx_ide.next = self.rxf.rx_ide.val();
        self.rx_rtr.next = self.rxf.rx_rtr.val();
        self.rx_id.next = self.rxf.rx_id.val();
        self.rx_dlc.next = self.rxf.rx_dlc.val();
        self.rx_data.next = self.rxf.rx_data.val();
        self.tec.next = self.conf.tec.val();
        self.rec.next = self.conf.rec.val();
        self.state.next = self.conf.state.val();
        self.err_warn.next = self.conf.err_warn.val();
        self.tx_rqst.next = self.txq.req.val();
        self.field.next = self.dec.code.val();
        self.pos.next = self.dec.pos.val();
        self.stuff.next = self.dec.stuff.val();
        self.role.next = self.seq.tx_role.val();
        self.events.next = self.rpt.events.val();
        self.runs.next = self.conf.runs.val();
    }
}

canstar_hdl::impl_clocked!(CanFsm);

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::drive;

    /// Issue #16: the sequencer's POSITION-is-3 register (`pos3`, which
    /// `hs_en` reads instead of a comparator) equals `fpos == 3` on every
    /// clock, and the POSITION choice of the frame and the flag fields
    /// (`npc`, which the sequencer takes) gives their `npos` on every
    /// `sample` clock. A node on a bus of its own `drive` and random dominant
    /// glitches, with random requests, resets, counter loads (some to
    /// Bus_Off), aborts and mode bits; `sample` every 2..4 clocks with `pipe`
    /// high (as in [`crate::core::CanCore`]) and on random clocks, also
    /// consecutive ones, with `pipe` low.
    #[test]
    fn position_choice_and_pos3_register_equal_what_they_replace() {
        for pipe in [true, false] {
            let mut u = CanFsm::new();
            drive::init(&mut u);
            let mut s: u64 = 0x9e37_79b9_7f4a_7c15 ^ pipe as u64;
            let mut rnd = move || {
                s ^= s << 13;
                s ^= s >> 7;
                s ^= s << 17;
                s
            };
            u.pipe.next = pipe;
            u.reset.next = true;
            drive::cycle(&mut u);
            u.reset.next = false;
            let (mut gap, mut seen3, mut own_f, mut own_g) = (0u64, 0u64, 0u64, 0u64);
            for clk in 0..300_000u64 {
                let r = rnd();
                u.reset.next = r % 40_000 == 0;
                u.cnt_load.next = r % 25_000 == 1;
                u.tec_in.next = ((r >> 8) % 300).into();
                u.rec_in.next = ((r >> 20) % 140).into();
                if clk % 5_000 == 0 {
                    u.tx_req.next = r & 3 != 0;
                    u.tx_ide.next = r & 4 != 0;
                    u.tx_rtr.next = r & 8 != 0;
                    u.tx_id.next = ((r >> 16) & 0x1fff_ffff).into();
                    u.tx_dlc.next = ((r >> 48) & 15).into();
                    u.tx_data.next = rnd().into();
                    u.self_test.next = r & 16 != 0;
                    u.single_shot.next = r & 32 != 0;
                    u.listen_only.next = r % 13 == 0;
                    u.host_recovery.next = r & 64 != 0;
                }
                u.tx_abort.next = r % 3_000 == 2;
                u.recover.next = r % 2_000 == 3;
                let smp = if pipe {
                    gap += 1;
                    gap >= 2 + (r >> 40) % 3
                } else {
                    (r >> 40) % 3 != 0
                };
                if smp {
                    gap = 0;
                }
                u.sample.next = smp;
                // the bus: the own level, with rare dominant glitches
                u.busmon.next = u.drive.val() && (r >> 32) % 200 != 0;
                drive::settle(&mut u);
                let fpos = u.seq.fpos.val().index() as u64;
                assert_eq!(u.seq.pos3.val(), fpos == 3, "clock {clk}");
                seen3 += (fpos == 3) as u64;
                if u.sample.val() {
                    let choice = |npc: Bits<2>| seq::pos_of_choice(npc.index() as u64, fpos);
                    if u.frame.own.val() {
                        own_f += 1;
                        assert_eq!(choice(u.frame.npc.val()), u.frame.npos.val().index() as u64, "clock {clk}");
                    }
                    if u.flags.own.val() {
                        own_g += 1;
                        assert_eq!(choice(u.flags.npc.val()), u.flags.npos.val().index() as u64, "clock {clk}");
                    }
                }
                drive::cycle(&mut u);
            }
            assert!(seen3 > 1_000 && own_f > 1_000 && own_g > 1_000, "{seen3} {own_f} {own_g}");
        }
    }
}
