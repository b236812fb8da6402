//! Plain-Rust CAN frames and a bit-level frame builder (stuffing and CRC-15,
//! §4–6 of can-protocol.md).
//!
//! Used by the tests, by the conformance suite (to pick and check frame
//! contents) and by scripted test transmitters, which need frames the RTL
//! never sends (dominant SRR, recessive reserved bits): see [`BuildOptions`].

use crate::fsm::Field;

/// A data or remote frame as the host sees it.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Frame {
    /// Extended (29-bit) identifier.
    pub ide: bool,
    /// Remote frame.
    pub rtr: bool,
    /// 11-bit or 29-bit identifier (29-bit: `base << 18 | extension`).
    pub id: u32,
    /// Raw DLC code 0..15.
    pub dlc: u8,
    /// min(dlc, 8) bytes for data frames, empty for remote frames.
    pub data: Vec<u8>,
}

impl Frame {
    /// A data frame; `dlc` is the code sent, `data` is truncated or padded
    /// with zeros to min(dlc, 8) bytes.
    pub fn data(ide: bool, id: u32, dlc: u8, data: &[u8]) -> Frame {
        let n = data_len(dlc);
        let mut d: Vec<u8> = data.iter().copied().take(n).collect();
        d.resize(n, 0);
        let f = Frame { ide, rtr: false, id, dlc: dlc & 15, data: d };
        f.check();
        f
    }
    /// A standard data frame with DLC = data.len().
    pub fn std(id: u32, data: &[u8]) -> Frame {
        Frame::data(false, id, data.len() as u8, data)
    }
    /// An extended data frame with DLC = data.len().
    pub fn ext(id: u32, data: &[u8]) -> Frame {
        Frame::data(true, id, data.len() as u8, data)
    }
    /// A remote frame.
    pub fn remote(ide: bool, id: u32, dlc: u8) -> Frame {
        let f = Frame { ide, rtr: true, id, dlc: dlc & 15, data: vec![] };
        f.check();
        f
    }
    fn check(&self) {
        let max = if self.ide { 1 << 29 } else { 1 << 11 };
        assert!(self.id < max, "identifier {:#x} too wide", self.id);
    }
    /// The 64-bit data word of the native interface (byte 0 in bits 63..56).
    pub fn data_word(&self) -> u64 {
        let mut w = 0u64;
        for (i, b) in self.data.iter().enumerate() {
            w |= (*b as u64) << (56 - 8 * i);
        }
        w
    }
    /// Inverse of [`Frame::data_word`] for a received frame.
    pub fn from_native(ide: bool, rtr: bool, id: u32, dlc: u8, data: u64) -> Frame {
        if rtr {
            return Frame::remote(ide, id, dlc);
        }
        let n = data_len(dlc);
        let bytes: Vec<u8> = (0..n).map(|i| (data >> (56 - 8 * i)) as u8).collect();
        Frame::data(ide, id, dlc, &bytes)
    }
}

/// Number of data bytes of a DLC code (9..15 mean 8, §4.3).
pub fn data_len(dlc: u8) -> usize {
    (dlc as usize & 15).min(8)
}

/// CRC-15 of a bit sequence (polynomial 0x4599, initial 0, §6): the shared
/// software model [`canstar_hdl::crc15::crc15_bits`].
pub fn crc15(bits: &[bool]) -> u16 {
    canstar_hdl::crc15::crc15_bits(bits)
}

/// Insert stuff bits: after 5 equal bits, one of the opposite level (§5).
/// Returns the stuffed sequence and, per output bit, whether it is a stuff bit.
pub fn stuff(bits: &[bool]) -> Vec<(bool, bool)> {
    let mut out = Vec::with_capacity(bits.len() + bits.len() / 4);
    let mut last = None;
    let mut run = 0;
    for &b in bits {
        out.push((b, false));
        if Some(b) == last {
            run += 1;
        } else {
            last = Some(b);
            run = 1;
        }
        if run == 5 {
            out.push((!b, true));
            last = Some(!b);
            run = 1;
        }
    }
    out
}

/// Levels a scripted transmitter may use where the RTL has fixed values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BuildOptions {
    /// SRR level of an extended frame (true = recessive, the legal value).
    pub srr: bool,
    /// r1 (extended frames only); legal value false (dominant).
    pub r1: bool,
    /// r0; legal value false (dominant).
    pub r0: bool,
}

impl Default for BuildOptions {
    fn default() -> Self {
        BuildOptions { srr: true, r1: false, r0: false }
    }
}

/// One bit of a frame on the bus, with its FIELD/POSITION (§4.5).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BusBit {
    /// Level (true = recessive).
    pub level: bool,
    pub field: Field,
    /// POSITION; a stuff bit repeats the position of the bit before it.
    pub pos: u8,
    pub stuff: bool,
}

/// The unstuffed bits SOF .. end of data with their field and position.
pub fn unstuffed(f: &Frame, o: BuildOptions) -> Vec<BusBit> {
    let mut v = Vec::new();
    let mut push = |level: bool, field: Field, pos: u8| v.push(BusBit { level, field, pos, stuff: false });
    push(false, Field::Sof, 1);
    let base = if f.ide { f.id >> 18 } else { f.id };
    for i in 0..11 {
        push((base >> (10 - i)) & 1 == 1, Field::Ident, i as u8 + 1);
    }
    if f.ide {
        push(o.srr, Field::Srr, 1);
        push(true, Field::Ide, 1);
        for i in 0..18 {
            push((f.id >> (17 - i)) & 1 == 1, Field::ExIdent, i as u8 + 1);
        }
        push(f.rtr, Field::Rtr, 1);
        push(o.r1, Field::Resv, 1);
        push(o.r0, Field::Resv, 2);
    } else {
        push(f.rtr, Field::Rtr, 1);
        push(false, Field::Ide, 1);
        push(o.r0, Field::Resv, 1);
    }
    for i in 0..4 {
        push((f.dlc >> (3 - i)) & 1 == 1, Field::Dlc, i as u8 + 1);
    }
    if !f.rtr {
        for (k, byte) in f.data.iter().enumerate() {
            for i in 0..8 {
                push((byte >> (7 - i)) & 1 == 1, Field::Data, (8 * k + i + 1) as u8);
            }
        }
    }
    v
}

/// The CRC of a frame (over the unstuffed bits SOF .. data).
pub fn frame_crc(f: &Frame, o: BuildOptions) -> u16 {
    let bits: Vec<bool> = unstuffed(f, o).iter().map(|b| b.level).collect();
    crc15(&bits)
}

/// The complete frame as it appears on the bus: stuffed SOF .. CRC sequence,
/// CRC delimiter, ACK slot (dominant if `acked`), ACK delimiter and 7 EOF
/// bits. Intermission is not included.
pub fn bus_bits(f: &Frame, o: BuildOptions, acked: bool) -> Vec<BusBit> {
    let mut raw = unstuffed(f, o);
    let crc = crc15(&raw.iter().map(|b| b.level).collect::<Vec<_>>());
    for i in 0..15 {
        raw.push(BusBit { level: (crc >> (14 - i)) & 1 == 1, field: Field::Crc, pos: i as u8 + 1, stuff: false });
    }
    let levels: Vec<bool> = raw.iter().map(|b| b.level).collect();
    let mut out = Vec::new();
    let mut k = 0;
    for (level, is_stuff) in stuff(&levels) {
        if is_stuff {
            let prev: BusBit = raw[k - 1];
            out.push(BusBit { level, stuff: true, ..prev });
        } else {
            out.push(raw[k]);
            k += 1;
        }
    }
    let mut push = |level: bool, field: Field, pos: u8| out.push(BusBit { level, field, pos, stuff: false });
    push(true, Field::CrcDel, 1);
    push(!acked, Field::AckSlot, 1);
    push(true, Field::AckDel, 1);
    for i in 1..=7 {
        push(true, Field::Eof, i);
    }
    out
}

/// Just the levels of [`bus_bits`].
pub fn bus_levels(f: &Frame, acked: bool) -> Vec<bool> {
    bus_bits(f, BuildOptions::default(), acked).iter().map(|b| b.level).collect()
}

/// Number of stuff bits in a frame.
pub fn stuff_count(f: &Frame) -> usize {
    bus_bits(f, BuildOptions::default(), true).iter().filter(|b| b.stuff).count()
}

/// One stuffing situation of the stuffbit program (conformance-tests.md §11):
/// a stuff bit of level `level` (true = recessive) whose preceding bit is in
/// `field`, either inside the field or after its last bit (`after_last`),
/// followed by a bit of level `next`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct StuffCase {
    pub field: u8,
    pub level: bool,
    pub after_last: bool,
    pub next: bool,
}

/// The stuffing situations a frame's bus bits contain (see [`StuffCase`];
/// `field` is the FIELD code of [`Field`]).
pub fn stuff_cases(bits: &[BusBit]) -> std::collections::BTreeSet<StuffCase> {
    let mut out = std::collections::BTreeSet::new();
    for k in 1..bits.len().saturating_sub(1) {
        let b = bits[k];
        if !b.stuff {
            continue;
        }
        let prev = bits[k - 1];
        // the bit after the preceding one in transmission order, ignoring stuff bits
        let after_last = bits[k + 1..].iter().find(|x| !x.stuff).map(|x| x.field != prev.field).unwrap_or(true);
        out.insert(StuffCase { field: prev.field.code() as u8, level: b.level, after_last, next: bits[k + 1].level });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc_check_value() {
        let bits: Vec<bool> = b"123456789".iter().flat_map(|c| (0..8).map(move |i| (c >> (7 - i)) & 1 == 1)).collect();
        assert_eq!(crc15(&bits), 0x059E);
    }

    #[test]
    fn stuffing_agrees_with_the_shared_model() {
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..200 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let bits: Vec<bool> = (0..64).map(|i| (x >> i) & 3 != 0).collect();
            let mine: Vec<bool> = stuff(&bits).iter().map(|b| b.0).collect();
            assert_eq!(mine, canstar_hdl::stuff::stuff_bits(&bits));
        }
    }

    #[test]
    fn stuffing_inserts_after_five() {
        let s = stuff(&[false; 10]);
        let lv: Vec<bool> = s.iter().map(|x| x.0).collect();
        assert_eq!(lv, vec![false, false, false, false, false, true, false, false, false, false, false, true]);
        // stuff bits count towards the next run
        let s = stuff(&[false, false, false, false, false, true, true, true, true]);
        assert_eq!(s.iter().filter(|x| x.1).count(), 2);
    }

    #[test]
    fn lengths() {
        // unstuffed: std 44 + 8N, ext 64 + 8N (incl. CRC delim .. EOF, excl. stuffing)
        for n in 0..=8u8 {
            let d = vec![0x55; n as usize];
            let f = Frame::std(0x2AA, &d);
            let bb = bus_bits(&f, BuildOptions::default(), true);
            assert_eq!(bb.iter().filter(|b| !b.stuff).count(), 44 + 8 * n as usize);
            let f = Frame::ext(0x0AAA_AAAA & 0x1FFF_FFFF, &d);
            let bb = bus_bits(&f, BuildOptions::default(), true);
            assert_eq!(bb.iter().filter(|b| !b.stuff).count(), 64 + 8 * n as usize);
        }
        assert_eq!(Frame::data(false, 1, 12, &[1, 2, 3, 4, 5, 6, 7, 8, 9]).data.len(), 8);
    }

    #[test]
    fn data_word_roundtrip() {
        let f = Frame::std(0x123, &[1, 2, 3]);
        assert_eq!(f.data_word(), 0x0102_0300_0000_0000);
        assert_eq!(Frame::from_native(false, false, 0x123, 3, f.data_word()), f);
    }
}
