//! CAN frames, the CRC-15 of can-protocol.md §6 and the bit-level frame builder.
//!
//! [`frame_bits`] turns a [`Frame`] into the exact bit sequence a transmitter sends: SOF
//! through the CRC sequence stuffed (§5), then CRC delimiter, ACK slot (`R`, as sent by the
//! transmitter), ACK delimiter and End_Of_Frame. Each bit carries its FIELD and POSITION
//! (§4.5) and a stuff marker. [`FrameVariant`] produces the test-only frames of the
//! conformance plan (dominant SRR, recessive reserved bits) that a real controller never sends.

use super::Field;

/// One data or remote frame, as the host gives it and as a receiver delivers it.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Frame {
    /// Extended (29-bit) identifier.
    pub ide: bool,
    /// 11-bit identifier, or 29-bit identifier `base << 18 | extension`.
    pub id: u32,
    /// Remote frame.
    pub rtr: bool,
    /// Raw data length code 0..15 (9..15 mean 8 bytes).
    pub dlc: u8,
    /// `min(dlc, 8)` bytes for data frames, none for remote frames.
    pub data: Vec<u8>,
}

impl Frame {
    /// Standard data frame; `data.len()` must equal `min(dlc, 8)`.
    pub fn std_data(id: u32, dlc: u8, data: &[u8]) -> Frame {
        Frame { ide: false, id, rtr: false, dlc, data: data.to_vec() }.checked()
    }
    /// Extended data frame.
    pub fn ext_data(id: u32, dlc: u8, data: &[u8]) -> Frame {
        Frame { ide: true, id, rtr: false, dlc, data: data.to_vec() }.checked()
    }
    /// Standard remote frame.
    pub fn std_remote(id: u32, dlc: u8) -> Frame {
        Frame { ide: false, id, rtr: true, dlc, data: vec![] }.checked()
    }
    /// Extended remote frame.
    pub fn ext_remote(id: u32, dlc: u8) -> Frame {
        Frame { ide: true, id, rtr: true, dlc, data: vec![] }.checked()
    }
    /// Number of data bytes carried: `min(dlc, 8)` for data frames, 0 for remote frames.
    pub fn data_len(&self) -> usize {
        if self.rtr {
            0
        } else {
            (self.dlc.min(8)) as usize
        }
    }
    fn checked(self) -> Frame {
        assert!(self.dlc <= 15, "dlc must be 0..15");
        if self.ide {
            assert!(self.id < (1 << 29), "extended id must be < 2^29");
        } else {
            assert!(self.id < (1 << 11), "standard id must be < 2^11");
        }
        assert_eq!(self.data.len(), self.data_len(), "data length must be min(dlc, 8), 0 for remote");
        self
    }
}

/// Test-only deviations from what a controller sends (conformance plan "test-only
/// transmitters"). The default is the normal frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameVariant {
    /// Send SRR dominant (extended frames only).
    pub srr_dominant: bool,
    /// Send r1 recessive (extended frames only).
    pub r1_recessive: bool,
    /// Send r0 recessive.
    pub r0_recessive: bool,
}

/// One bit on the wire: level (`true` = recessive), FIELD, POSITION, stuff marker.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BitInfo {
    pub bit: bool,
    pub field: Field,
    pub pos: u16,
    pub stuff: bool,
}

/// CRC-15 register update for one bit (§6): generator 0x4599, init 0, MSB first.
pub fn crc15_step(crc: u16, bit: bool) -> u16 {
    let fb = bit ^ ((crc >> 14) & 1 == 1);
    let mut c = (crc << 1) & 0x7FFF;
    if fb {
        c ^= 0x4599;
    }
    c
}

/// CRC-15 of a bit sequence.
pub fn crc15(bits: impl IntoIterator<Item = bool>) -> u16 {
    bits.into_iter().fold(0, crc15_step)
}

fn push_bits(out: &mut Vec<BitInfo>, value: u32, n: u32, field: Field) {
    for i in 0..n {
        let bit = (value >> (n - 1 - i)) & 1 == 1;
        out.push(BitInfo { bit, field, pos: (i + 1) as u16, stuff: false });
    }
}

/// The unstuffed bits SOF .. last CRC bit, with fields and positions.
pub fn unstuffed_bits(f: &Frame, v: FrameVariant) -> Vec<BitInfo> {
    let mut out = Vec::with_capacity(140);
    push_bits(&mut out, 0, 1, Field::StartOfFrame);
    if f.ide {
        push_bits(&mut out, f.id >> 18, 11, Field::Identifier);
        push_bits(&mut out, (!v.srr_dominant) as u32, 1, Field::SrrBit);
        push_bits(&mut out, 1, 1, Field::IdeBit);
        push_bits(&mut out, f.id & 0x3FFFF, 18, Field::ExIdentifier);
        push_bits(&mut out, f.rtr as u32, 1, Field::RtrBit);
        push_bits(&mut out, ((v.r1_recessive as u32) << 1) | v.r0_recessive as u32, 2, Field::ReservedBits);
    } else {
        push_bits(&mut out, f.id, 11, Field::Identifier);
        push_bits(&mut out, f.rtr as u32, 1, Field::RtrBit);
        push_bits(&mut out, 0, 1, Field::IdeBit);
        push_bits(&mut out, v.r0_recessive as u32, 1, Field::ReservedBits);
    }
    push_bits(&mut out, f.dlc as u32, 4, Field::DataLengthCode);
    let mut pos = 0u16;
    for &b in f.data.iter().take(f.data_len()) {
        for i in 0..8 {
            pos += 1;
            out.push(BitInfo { bit: (b >> (7 - i)) & 1 == 1, field: Field::DataField, pos, stuff: false });
        }
    }
    let crc = crc15(out.iter().map(|b| b.bit));
    push_bits(&mut out, crc as u32, 15, Field::CrcSequence);
    out
}

/// The complete bit sequence a transmitter sends for `f`: stuffed SOF..CRC, then CRC
/// delimiter, ACK slot (`R`), ACK delimiter and 7 EOF bits.
pub fn frame_bits(f: &Frame, v: FrameVariant) -> Vec<BitInfo> {
    let mut out = Vec::with_capacity(170);
    let mut run_level = false;
    let mut run_len = 0;
    for b in unstuffed_bits(f, v) {
        out.push(b);
        if run_len > 0 && b.bit == run_level {
            run_len += 1;
        } else {
            run_level = b.bit;
            run_len = 1;
        }
        if run_len == 5 {
            out.push(BitInfo { bit: !run_level, stuff: true, ..b });
            run_level = !run_level;
            run_len = 1;
        }
    }
    for (field, n) in [(Field::CrcDelimiter, 1), (Field::AckSlot, 1), (Field::AckDelimiter, 1), (Field::EndOfFrame, 7)] {
        for p in 1..=n {
            out.push(BitInfo { bit: true, field, pos: p, stuff: false });
        }
    }
    out
}
