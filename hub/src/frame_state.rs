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
//! | `crc_delim`, `ack_slot`, `ack_delim` | those fields |
//! | `eof_1_6` | field `Eof`, position 0..5 |
//! | `eof_last` | field `Eof`, position 6 (the last EOF bit) |
//! | `im_1_2` | field `Intermission`, position 0..1 |
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
    pub crc_delim: Signal<Out, Bit>,
    pub ack_slot: Signal<Out, Bit>,
    pub ack_delim: Signal<Out, Bit>,
    pub eof_1_6: Signal<Out, Bit>,
    pub eof_last: Signal<Out, Bit>,
    pub im_1_2: Signal<Out, Bit>,
    pub err_phase: Signal<Out, Bit>,
}

impl Logic for FrameDecode {
    #[hdl_gen]
    fn update(&mut self) {
        self.sof.next = self.field.val() == 1;
        self.tx_region.next = (self.field.val() >= 2) & (self.field.val() <= 7);
        self.crc_delim.next = self.field.val() == 8;
        self.ack_slot.next = self.field.val() == 9;
        self.ack_delim.next = self.field.val() == 10;
        self.eof_1_6.next = (self.field.val() == 11) & (self.pos.val() < 6);
        self.eof_last.next = (self.field.val() == 11) & (self.pos.val() == 6);
        self.im_1_2.next = (self.field.val() == 12) & (self.pos.val() < 2);
        self.err_phase.next = self.field.val() >= 13;
    }
}

canstar_hdl::impl_clocked!(FrameDecode);
