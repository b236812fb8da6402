//! Plain-Rust reference frame tracker (test only): the frame state C of hub.md §4, as
//! the real frame monitor will provide it.

use super::*;

/// What the tracker found at one sampled bit.
#[derive(Clone, Copy, Debug, Default)]
pub struct Event {
    /// Stuff, CRC or form error: an error flag starts at the next bit.
    pub error: bool,
    /// Overload condition: an overload flag starts at the next bit.
    pub overload: bool,
    /// Last EOF bit of a frame completed without error.
    pub frame_ok: bool,
    /// This bit was a stuff bit.
    pub stuff: bool,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Ph {
    Idle,
    Frame,
    CrcDelim,
    AckSlot,
    AckDelim,
    Eof(u8),
    Im(u8),
    Flag(u8, bool),  // position, overload?
    Wait(bool),      // waiting for recessive after the flag
    Delim(u8, bool), // delimiter position 0..7
}

/// Plain-Rust reference frame tracker (test only): the frame state C of hub.md §4.
pub struct Tracker {
    pub ph: Ph,
    bits: Vec<bool>,
    last: bool,
    run: u8,
    crc_err: bool,
    pub crc_ok: bool,
    prev_label: (Field, usize),
}

impl Default for Tracker {
    fn default() -> Self {
        Tracker { ph: Ph::Idle, bits: vec![], last: true, run: 0, crc_err: false, crc_ok: false, prev_label: (Field::Sof, 0) }
    }
}

impl Tracker {
    /// Destuffed length of the frame up to the end of the CRC, once known.
    fn frame_len(&self) -> Option<usize> {
        let b = &self.bits;
        if b.len() < 14 {
            return None;
        }
        let ext = b[13];
        let dlc_at = if ext { 35 } else { 15 };
        if b.len() < dlc_at + 4 {
            return None;
        }
        let rtr = if ext { b[32] } else { b[12] };
        let dlc = b[dlc_at..dlc_at + 4].iter().fold(0usize, |a, &x| a * 2 + x as usize);
        let n = if rtr { 0 } else { dlc.min(8) };
        Some(dlc_at + 4 + 8 * n + 15)
    }
    fn in_frame_field(&self) -> (Field, usize) {
        let k = self.bits.len();
        let b = &self.bits;
        if k <= 12 || (k <= 31 && b.len() > 13 && b[13]) || k == 13 {
            return (Field::Id, k - 1);
        }
        let ext = b[13];
        let (rtr_at, dlc_at) = if ext { (32, 35) } else { (12, 15) };
        if k == rtr_at {
            return (Field::Rtr, 0);
        }
        if k < dlc_at {
            return (Field::Res, k - rtr_at - 1);
        }
        if k < dlc_at + 4 {
            return (Field::Dlc, k - dlc_at);
        }
        let len = self.frame_len().unwrap();
        if k < len - 15 {
            (Field::Data, k - dlc_at - 4)
        } else {
            (Field::Crc, k - (len - 15))
        }
    }
    /// Field and position of the bit about to be pushed, given its value.
    pub fn classify(&self, bit: bool) -> (Field, usize) {
        match self.ph {
            Ph::Idle => {
                if bit {
                    (Field::Idle, 0)
                } else {
                    (Field::Sof, 0)
                }
            }
            // a stuff bit carries the FIELD and POSITION of the bit before it (can-protocol.md §4.5)
            Ph::Frame if self.run == 5 => self.prev_label,
            Ph::Frame => self.in_frame_field(),
            Ph::CrcDelim => (Field::CrcDelim, 0),
            Ph::AckSlot => (Field::AckSlot, 0),
            Ph::AckDelim => (Field::AckDelim, 0),
            Ph::Eof(p) => (Field::Eof, p as usize),
            Ph::Im(p) => {
                if p == 2 && !bit {
                    (Field::Sof, 0)
                } else {
                    (Field::Intermission, p as usize)
                }
            }
            Ph::Flag(p, ov) => (if ov { Field::Overload } else { Field::ErrorFlag }, p as usize),
            Ph::Wait(ov) => (if ov { Field::Overload } else { Field::ErrorFlag }, 6),
            Ph::Delim(p, ov) => (if ov { Field::Overload } else { Field::ErrorDelim }, p as usize),
        }
    }
    fn start_frame(&mut self) {
        self.prev_label = (Field::Sof, 0);
        self.ph = Ph::Frame;
        self.bits = vec![false];
        self.last = false;
        self.run = 1;
        self.crc_err = false;
        self.crc_ok = false;
    }
    fn error(&mut self, ev: &mut Event) {
        ev.error = true;
        self.ph = Ph::Flag(0, false);
    }
    /// Consume one sampled bit.
    pub fn push(&mut self, bit: bool) -> Event {
        let mut ev = Event::default();
        match self.ph {
            Ph::Idle => {
                if !bit {
                    self.start_frame();
                }
            }
            Ph::Frame => {
                if self.run == 5 {
                    // stuff bit
                    ev.stuff = true;
                    if bit == self.last {
                        self.error(&mut ev);
                        return ev;
                    }
                    self.last = bit;
                    self.run = 1;
                    if self.frame_len() == Some(self.bits.len()) {
                        self.ph = Ph::CrcDelim; // stuff bit after the last CRC bit
                    }
                    return ev;
                }
                self.prev_label = self.in_frame_field();
                if bit == self.last {
                    self.run += 1;
                } else {
                    self.last = bit;
                    self.run = 1;
                }
                self.bits.push(bit);
                if let Some(len) = self.frame_len() {
                    if self.bits.len() == len {
                        let crc = crc15(&self.bits[..len - 15]);
                        let got = self.bits[len - 15..].iter().fold(0u16, |a, &x| a * 2 + x as u16);
                        self.crc_ok = crc == got;
                        self.crc_err = !self.crc_ok;
                        if self.run < 5 {
                            self.ph = Ph::CrcDelim;
                        }
                    }
                }
            }
            Ph::CrcDelim => {
                if !bit {
                    self.error(&mut ev);
                } else {
                    self.ph = Ph::AckSlot;
                }
            }
            Ph::AckSlot => self.ph = Ph::AckDelim,
            Ph::AckDelim => {
                if !bit || self.crc_err {
                    self.error(&mut ev);
                } else {
                    self.ph = Ph::Eof(0);
                }
            }
            Ph::Eof(p) => {
                if p < 6 {
                    if !bit {
                        self.error(&mut ev);
                    } else {
                        self.ph = Ph::Eof(p + 1);
                    }
                } else {
                    ev.frame_ok = true;
                    if !bit {
                        ev.overload = true;
                        self.ph = Ph::Flag(0, true);
                    } else {
                        self.ph = Ph::Im(0);
                    }
                }
            }
            Ph::Im(p) => {
                if !bit {
                    if p == 2 {
                        self.start_frame();
                    } else {
                        ev.overload = true;
                        self.ph = Ph::Flag(0, true);
                    }
                } else if p == 2 {
                    self.ph = Ph::Idle;
                } else {
                    self.ph = Ph::Im(p + 1);
                }
            }
            Ph::Flag(p, ov) => {
                self.ph = if p == 5 { Ph::Wait(ov) } else { Ph::Flag(p + 1, ov) };
            }
            Ph::Wait(ov) => {
                if bit {
                    self.ph = Ph::Delim(1, ov);
                }
            }
            Ph::Delim(p, ov) => {
                if !bit {
                    if p == 7 {
                        ev.overload = true;
                        self.ph = Ph::Flag(0, true);
                    } else {
                        self.error(&mut ev);
                    }
                } else if p == 7 {
                    self.ph = Ph::Im(0);
                } else {
                    self.ph = Ph::Delim(p + 1, ov);
                }
            }
        }
        ev
    }
    pub fn in_arbitration(&self, field: Field) -> bool {
        matches!(field, Field::Sof | Field::Id | Field::Rtr)
    }
}

