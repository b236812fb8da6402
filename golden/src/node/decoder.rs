//! Receive-side decoding of the golden node: the layout of the received frame from the
//! destuffed bits (FIELD and POSITION, can-protocol.md §4.5) and the frame being received.

use super::super::frame::{crc15_step, Frame};
use super::super::Field;

/// Layout of the received frame, derived from the bits received so far.
pub(super) fn rx_field(bits: &[bool], i: usize) -> Option<(Field, u32)> {
    let p = |x: usize| x as u32;
    match i {
        0 => return Some((Field::StartOfFrame, 1)),
        1..=11 => return Some((Field::Identifier, p(i))),
        12 => return Some((Field::RtrBit, 1)),
        13 => return Some((Field::IdeBit, 1)),
        _ => {}
    }
    let ext = bits[13];
    let data_start = if ext {
        match i {
            14..=31 => return Some((Field::ExIdentifier, p(i - 13))),
            32 => return Some((Field::RtrBit, 1)),
            33..=34 => return Some((Field::ReservedBits, p(i - 32))),
            35..=38 => return Some((Field::DataLengthCode, p(i - 34))),
            _ => 39,
        }
    } else {
        match i {
            14 => return Some((Field::ReservedBits, 1)),
            15..=18 => return Some((Field::DataLengthCode, p(i - 14))),
            _ => 19,
        }
    };
    let rtr = if ext { bits[32] } else { bits[12] };
    let dlc = bits[data_start - 4..data_start].iter().fold(0u8, |a, &b| (a << 1) | b as u8);
    let ndata = if rtr { 0 } else { 8 * dlc.min(8) as usize };
    let crc_start = data_start + ndata;
    if i < crc_start {
        Some((Field::DataField, p(i - data_start + 1)))
    } else if i < crc_start + 15 {
        Some((Field::CrcSequence, p(i - crc_start + 1)))
    } else {
        None
    }
}

/// Destuffing frame decoder working on sampled levels (§5, §6).
#[derive(Clone, Debug, Default)]
pub(super) struct Decoder {
    pub(super) bits: Vec<bool>,
    pub(super) run_level: bool,
    pub(super) run_len: u8,
    pub(super) stuff_next: bool,
    pub(super) crc: u16,
    pub(super) crc_rx: u16,
}

impl Decoder {
    pub(super) fn clear(&mut self) {
        self.bits.clear();
        self.run_len = 0;
        self.stuff_next = false;
        self.crc = 0;
        self.crc_rx = 0;
    }
    pub(super) fn next_field(&self) -> Option<(Field, u32)> {
        rx_field(&self.bits, self.bits.len())
    }
    pub(super) fn push(&mut self, s: bool) {
        let (f, _) = self.next_field().expect("decoder past CRC");
        if f == Field::CrcSequence {
            self.crc_rx = (self.crc_rx << 1) | s as u16;
        } else {
            self.crc = crc15_step(self.crc, s);
        }
        self.bits.push(s);
        if self.run_len > 0 && s == self.run_level {
            self.run_len += 1;
        } else {
            self.run_level = s;
            self.run_len = 1;
        }
        self.stuff_next = self.run_len == 5;
    }
    pub(super) fn push_stuff(&mut self, s: bool) {
        self.run_level = s;
        self.run_len = 1;
        self.stuff_next = false;
    }
    /// All bits through the last CRC bit received (a stuff bit may still follow).
    pub(super) fn crc_done(&self) -> bool {
        !self.bits.is_empty() && self.next_field().is_none()
    }
    pub(super) fn frame(&self) -> Frame {
        let b = &self.bits;
        let num = |r: std::ops::Range<usize>| b[r].iter().fold(0u32, |a, &x| (a << 1) | x as u32);
        let ext = b[13];
        let (id, rtr, ds) = if ext {
            ((num(1..12) << 18) | num(14..32), b[32], 39)
        } else {
            (num(1..12), b[12], 19)
        };
        let dlc = num(ds - 4..ds) as u8;
        let n = if rtr { 0 } else { dlc.min(8) as usize };
        let data = (0..n).map(|k| num(ds + 8 * k..ds + 8 * k + 8) as u8).collect();
        Frame { ide: ext, id, rtr, dlc, data }
    }
}

