//! Frame state C (hub.md §4): the field codes the frame monitor reports and their
//! decoding into the per-bit conditions the judge units use.
//!
//! The monitor reports, for the bit being sampled on BT at each `sample` strobe, the
//! 4-bit field code ([`Field`], the 16-state encoding of H9) and the bit's position in
//! that field (0-based, saturating at 15). [`FrameDecode`] turns that into the judges'
//! boolean inputs:
//!
//! | output | condition |
//! |---|---|
//! | `sof` | field `Sof` |
//! | `tx_region` | fields `Id`, `Rtr`, `Res`, `Dlc`, `Data`, `Crc` (first identifier bit to last CRC bit, stuff bits included; SRR, IDE and the extended identifier are reported as `Id`) |
//! | `arb` | fields `Sof`, `Id`, `Rtr` (the arbitration field) |
//! | `crc_delim`, `ack_slot`, `ack_delim` | those fields |
//! | `eof_1_6` | field `Eof`, position 0..5 |
//! | `eof_last` | field `Eof`, position 6 (the last EOF bit) |
//! | `im_2` | field `Intermission`, position 1 (the second intermission bit) |
//! | `im_12` | field `Intermission`, position 0 or 1 (a dominant level there is an overload condition) |
//! | `err_phase` | fields `ErrorFlag`, `ErrorDelim`, `Overload` (the monitor's error or overload phase: from the bit after an error / overload condition until the end of the delimiter) |
//!
//! All outputs are combinational; they are meaningful at `sample` strobes.

use rust_hdl::prelude::*;

/// Field codes of the frame state (4 bits).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Field {
    Idle = 0,
    Sof = 1,
    /// Arbitration: base identifier, SRR, IDE, extended identifier.
    Id = 2,
    Rtr = 3,
    /// Reserved bits (r0, r1).
    Res = 4,
    Dlc = 5,
    Data = 6,
    Crc = 7,
    CrcDelim = 8,
    AckSlot = 9,
    AckDelim = 10,
    Eof = 11,
    Intermission = 12,
    ErrorFlag = 13,
    ErrorDelim = 14,
    /// Overload flag and overload delimiter.
    Overload = 15,
}

impl Field {
    pub fn code(self) -> u64 {
        self as u64
    }
    pub fn from_code(c: u64) -> Field {
        use Field::*;
        [Idle, Sof, Id, Rtr, Res, Dlc, Data, Crc, CrcDelim, AckSlot, AckDelim, Eof, Intermission, ErrorFlag, ErrorDelim, Overload]
            [(c & 15) as usize]
    }
}

/// Combinational decoder from (field, position) to the judges' conditions.
#[derive(LogicBlock, Default)]
pub struct FrameDecode {
    /// Unused (the decoder is combinational); present so that the block can be
    /// driven and co-simulated like every other block.
    pub clock: Signal<In, Clock>,
    pub field: Signal<In, Bits<4>>,
    pub pos: Signal<In, Bits<4>>,
    pub sof: Signal<Out, Bit>,
    pub tx_region: Signal<Out, Bit>,
    pub arb: Signal<Out, Bit>,
    pub crc_delim: Signal<Out, Bit>,
    pub ack_slot: Signal<Out, Bit>,
    pub ack_delim: Signal<Out, Bit>,
    pub eof_1_6: Signal<Out, Bit>,
    pub eof_last: Signal<Out, Bit>,
    pub im_2: Signal<Out, Bit>,
    pub im_12: Signal<Out, Bit>,
    pub err_phase: Signal<Out, Bit>,
}

impl Logic for FrameDecode {
    #[hdl_gen]
    fn update(&mut self) {
        self.sof.next = self.field.val() == 1;
        self.tx_region.next = (self.field.val() >= 2) & (self.field.val() <= 7);
        self.arb.next = (self.field.val() >= 1) & (self.field.val() <= 3);
        self.crc_delim.next = self.field.val() == 8;
        self.ack_slot.next = self.field.val() == 9;
        self.ack_delim.next = self.field.val() == 10;
        self.eof_1_6.next = (self.field.val() == 11) & (self.pos.val() < 6);
        self.eof_last.next = (self.field.val() == 11) & (self.pos.val() == 6);
        self.im_2.next = (self.field.val() == 12) & (self.pos.val() == 1);
        self.im_12.next = (self.field.val() == 12) & (self.pos.val() < 2);
        self.err_phase.next = self.field.val() >= 13;
    }
}

canstar_hdl::impl_clocked!(FrameDecode);

/// FIELD codes of the controller's debug bundle (`canstar_controller::fsm`), as used
/// by [`MonitorAdapter`].
pub mod ctrl_field {
    pub const BUS_IDLE: u64 = 2;
    pub const START_OF_FRAME: u64 = 4;
    pub const IDENTIFIER: u64 = 5;
    pub const SRR: u64 = 6;
    pub const IDE: u64 = 7;
    pub const RTR: u64 = 8;
    pub const EX_IDENTIFIER: u64 = 9;
    pub const RESERVED: u64 = 10;
    pub const DLC: u64 = 11;
    pub const DATA: u64 = 12;
    pub const CRC: u64 = 13;
    pub const CRC_DELIMITER: u64 = 14;
    pub const ACK_SLOT: u64 = 15;
    pub const ACK_DELIMITER: u64 = 16;
    pub const END_OF_FRAME: u64 = 17;
    pub const ACTIVE_ERROR_FLAG: u64 = 18;
    pub const PASSIVE_ERROR_FLAG: u64 = 19;
    pub const OVERLOAD_FLAG: u64 = 20;
    pub const ERROR_DELIMITER: u64 = 21;
    pub const OVERLOAD_DELIMITER: u64 = 22;
    pub const INTERMISSION: u64 = 23;
}

/// The frame-state adapter: maps the debug bundle of the CAN controller that serves
/// as the hub's frame monitor (`canstar_controller::CanCore` in listen-only mode,
/// following BT) onto the `mon_*` inputs of [`crate::hub::HubCore`].
///
/// Inputs: the controller's `dbg_sample`, `dbg_field` (5-bit FIELD), `dbg_pos`
/// (1-based POSITION) and `dbg_events` (event word, valid on the clock *after* the
/// sample strobe). Everything is registered on the sample strobe and presented one
/// clock later, together with the events of that bit:
/// - `mon_sample`: the delayed strobe.
/// - `mon_field`: the hub's 4-bit [`Field`] code of the sampled bit (held until the
///   next sample). A bit sampled in
///   Bus_Idle or Intermission that the controller took as SOF (event `EV_SOF`) is
///   reported as `Sof`; SRR, IDE and the extended identifier as `Id`; both error-flag
///   kinds as `ErrorFlag`; overload flag and delimiter as `Overload`; Reset,
///   Wait_For_Bus_Idle, Bus_Off and Suspend_Transmission (never reached by a
///   listen-only monitor) as `Idle`.
/// - `mon_pos`: POSITION - 1 (0-based), saturating at 15.
/// - `mon_error`: stuff, CRC or form error signalled at this bit (`EV_STUFF_ERR`,
///   `EV_CRC_ERR`, `EV_FORM_ERR`; bit and ACK errors are transmitter errors).
/// - `mon_crc_ok`: no CRC error signalled at this bit (read by the judges in the ACK
///   delimiter). `mon_frame_ok`: `EV_RX_OK` (frame delivered at End_Of_Frame bit 7).
/// - `mon_stuff`: the sampled bit is a stuff bit (the controller's `dbg_stuff` at the
///   sample strobe; held until the next sample).
/// - `bit_start`: an estimate of the next bit's start (the controller does not export
///   its transmit points): `bs_delay` clocks after `mon_sample`, i.e. PH2 time quanta
///   after the sample point when `bs_delay` = PH2 x TQ - 2 clocks. A
///   resynchronisation in that bit moves the real bit start by at most SJW; the
///   hub's error flag then starts that much early or late, far from any sample point.
#[derive(LogicBlock)]
pub struct MonitorAdapter {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub sample: Signal<In, Bit>,
    pub field: Signal<In, Bits<5>>,
    pub pos: Signal<In, Bits<8>>,
    pub events: Signal<In, Bits<20>>,
    /// The controller's `dbg_stuff`: the bit being received is a stuff bit.
    pub stuff: Signal<In, Bit>,
    pub mon_sample: Signal<Out, Bit>,
    pub mon_field: Signal<Out, Bits<4>>,
    pub mon_pos: Signal<Out, Bits<4>>,
    pub mon_error: Signal<Out, Bit>,
    pub mon_crc_ok: Signal<Out, Bit>,
    pub mon_frame_ok: Signal<Out, Bit>,
    pub mon_stuff: Signal<Out, Bit>,
    pub bit_start: Signal<Out, Bit>,
    bs_delay: Constant<Bits<6>>,
    s_r: DFF<Bit>,
    fm_r: DFF<Bits<4>>,
    p_r: DFF<Bits<4>>,
    st_r: DFF<Bit>,
    bs_pending: DFF<Bit>,
    bs_cnt: DFF<Bits<6>>,
    f_map: DFF<Bits<4>>,
    fl: Signal<Local, Bits<4>>,
    pl: Signal<Local, Bits<4>>,
}

/// Event bit positions of the controller's event word used by the adapter.
pub const EV_SOF: usize = 0;
pub const EV_STUFF_ERR: usize = 3;
pub const EV_CRC_ERR: usize = 4;
pub const EV_FORM_ERR: usize = 5;
pub const EV_RX_OK: usize = 13;

impl MonitorAdapter {
    /// `bs_delay`: clocks from `mon_sample` to the estimated next bit start (0..=63).
    pub fn new(bs_delay: u64) -> Self {
        assert!(bs_delay < 64);
        Self {
            clock: Default::default(),
            reset: Default::default(),
            sample: Default::default(),
            field: Default::default(),
            pos: Default::default(),
            events: Default::default(),
            stuff: Default::default(),
            mon_sample: Default::default(),
            mon_field: Default::default(),
            mon_pos: Default::default(),
            mon_error: Default::default(),
            mon_crc_ok: Default::default(),
            mon_frame_ok: Default::default(),
            mon_stuff: Default::default(),
            bit_start: Default::default(),
            bs_delay: Constant::new(bs_delay.into()),
            s_r: Default::default(),
            fm_r: Default::default(),
            p_r: Default::default(),
            st_r: Default::default(),
            bs_pending: Default::default(),
            bs_cnt: Default::default(),
            f_map: Default::default(),
            fl: Default::default(),
            pl: Default::default(),
        }
    }
}

impl Logic for MonitorAdapter {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, s_r, fm_r, p_r, st_r, bs_pending, bs_cnt, f_map);
        self.s_r.d.next = self.sample.val();
        // field mapping (single assignment of the outputs, see the hub module docs),
        // done on the controller's FIELD at the sample strobe and registered (`fm_r`),
        // so that only the EV_SOF override is left for the clock after it; event bits:
        // 0 EV_SOF, 3 EV_STUFF_ERR, 4 EV_CRC_ERR, 5 EV_FORM_ERR, 13 EV_RX_OK
        if self.field.val() == 4 {
            self.fl.next = 1.into();
        } else if (self.field.val() == 5) | (self.field.val() == 6) | (self.field.val() == 7) | (self.field.val() == 9) {
            self.fl.next = 2.into();
        } else if self.field.val() == 8 {
            self.fl.next = 3.into();
        } else if self.field.val() == 10 {
            self.fl.next = 4.into();
        } else if self.field.val() == 11 {
            self.fl.next = 5.into();
        } else if self.field.val() == 12 {
            self.fl.next = 6.into();
        } else if self.field.val() == 13 {
            self.fl.next = 7.into();
        } else if self.field.val() == 14 {
            self.fl.next = 8.into();
        } else if self.field.val() == 15 {
            self.fl.next = 9.into();
        } else if self.field.val() == 16 {
            self.fl.next = 10.into();
        } else if self.field.val() == 17 {
            self.fl.next = 11.into();
        } else if self.field.val() == 23 {
            self.fl.next = 12.into();
        } else if (self.field.val() == 18) | (self.field.val() == 19) {
            self.fl.next = 13.into();
        } else if self.field.val() == 21 {
            self.fl.next = 14.into();
        } else if (self.field.val() == 20) | (self.field.val() == 22) {
            self.fl.next = 15.into();
        } else {
            self.fl.next = 0.into();
        }
        // POSITION - 1 (0-based), saturating at 15, likewise registered at the sample
        if self.pos.val() > 15 {
            self.pl.next = 15.into();
        } else if self.pos.val() == 0 {
            self.pl.next = 0.into();
        } else {
            self.pl.next = self.pos.val().get_bits::<4>(0) - 1;
        }
        if self.sample.val() {
            self.fm_r.d.next = self.fl.val();
            self.p_r.d.next = self.pl.val();
            self.st_r.d.next = self.stuff.val();
        }
        if self.s_r.q.val() {
            if self.events.val().get_bit(0) {
                self.f_map.d.next = 1.into();
                self.mon_field.next = 1.into();
            } else {
                self.f_map.d.next = self.fm_r.q.val();
                self.mon_field.next = self.fm_r.q.val();
            }
        } else {
            self.mon_field.next = self.f_map.q.val();
        }
        self.mon_pos.next = self.p_r.q.val();
        self.mon_sample.next = self.s_r.q.val();
        self.mon_error.next = self.s_r.q.val()
            & (self.events.val().get_bit(3) | self.events.val().get_bit(4) | self.events.val().get_bit(5));
        self.mon_crc_ok.next = !self.events.val().get_bit(4);
        self.mon_frame_ok.next = self.s_r.q.val() & self.events.val().get_bit(13);
        self.mon_stuff.next = self.st_r.q.val();
        // bit start estimate
        if self.s_r.q.val() {
            self.bs_pending.d.next = true;
            self.bs_cnt.d.next = self.bs_delay.val();
        } else if self.bs_pending.q.val() {
            if self.bs_cnt.q.val() == 0 {
                self.bs_pending.d.next = false;
            } else {
                self.bs_cnt.d.next = self.bs_cnt.q.val() - 1;
            }
        }
        if self.reset.val() {
            self.s_r.d.next = false;
            self.fm_r.d.next = 0.into();
            self.p_r.d.next = 0.into();
            self.st_r.d.next = false;
            self.bs_pending.d.next = false;
            self.f_map.d.next = 0.into();
        }
        self.bit_start.next = self.bs_pending.q.val() & (self.bs_cnt.q.val() == 0) & !self.s_r.q.val();
    }
}

canstar_hdl::impl_clocked!(MonitorAdapter);
