//! The CAN CRC-15: generator x^15 + x^14 + x^10 + x^8 + x^7 + x^4 + x^3 + 1
//! (polynomial 0x4599), initial value 0, no reflection, no final XOR.
//!
//! Per bit: `fb = bit ^ crc[14]; crc = (crc << 1) & 0x7FFF; if fb { crc ^= 0x4599 }`.
//! The check value (CRC of ASCII "123456789", MSB first) is 0x059E.
//!
//! # [`Crc15`] block
//!
//! | port    | dir | meaning |
//! |---------|-----|---------|
//! | `clock` | in  | system clock |
//! | `reset` | in  | synchronous, active high: CRC register becomes 0 |
//! | `clear` | in  | synchronous clear, same effect as `reset` (used at SOF); wins over `en` |
//! | `en`    | in  | strobe: shift `din` into the CRC at this clock |
//! | `din`   | in  | the (destuffed) bit to shift in |
//! | `crc`   | out | the registered CRC value (15 bits) |
//! | `crc_next` | out | combinational: the value `crc` would take if `din` were shifted in now (extra output) |
//!
//! The data input is called `din`, not `bit`: `bit` is a SystemVerilog
//! keyword, which Verilator and Icarus (`-g2012`) reject as a port name.
//!
//! # Software
//!
//! [`crc15_bits`] and [`crc15_bytes`] compute the same CRC in plain Rust, for
//! frame builders and as test oracles.

use rust_hdl::prelude::*;

/// The CRC-15 generator polynomial without the x^15 term.
pub const CRC15_POLY: u16 = 0x4599;

/// CRC-15 shift register with clear and shift strobe.
#[derive(LogicBlock)]
pub struct Crc15 {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub clear: Signal<In, Bit>,
    pub en: Signal<In, Bit>,
    pub din: Signal<In, Bit>,
    /// Registered CRC value.
    pub crc: Signal<Out, Bits<15>>,
    /// The CRC after shifting in `din` (combinational, independent of `en`).
    pub crc_next: Signal<Out, Bits<15>>,
    poly: Constant<Bits<15>>,
    state: DFF<Bits<15>>,
    fb: Signal<Local, Bit>,
    shifted: Signal<Local, Bits<15>>,
    nxt: Signal<Local, Bits<15>>,
}

impl Default for Crc15 {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            clear: Default::default(),
            en: Default::default(),
            din: Default::default(),
            crc: Default::default(),
            crc_next: Default::default(),
            poly: Constant::new((CRC15_POLY as u64).into()),
            state: Default::default(),
            fb: Default::default(),
            shifted: Default::default(),
            nxt: Default::default(),
        }
    }
}

impl Logic for Crc15 {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, state);
        self.fb.next = self.din.val() ^ self.state.q.val().get_bit(14);
        // A shift left by one, truncated to 15 bits. Written as a shift, not as
        // `q + q`: an adder with the same net on both operands becomes an iCE40
        // carry chain that nextpnr-ice40's router can swap forever (the flow's
        // `synth_check` refuses that pattern in every design).
        self.shifted.next = self.state.q.val() << 1;
        self.nxt.next = self.shifted.val();
        if self.fb.val() {
            self.nxt.next = self.shifted.val() ^ self.poly.val();
        }
        self.crc_next.next = self.nxt.val();
        if self.en.val() {
            self.state.d.next = self.nxt.val();
        }
        if self.reset.val() | self.clear.val() {
            self.state.d.next = 0.into();
        }
        self.crc.next = self.state.q.val();
    }
}

crate::impl_clocked!(Crc15);

/// Shift one bit into a CRC-15 value.
#[inline]
pub fn crc15_step(crc: u16, bit: bool) -> u16 {
    let fb = bit ^ (crc & 0x4000 != 0);
    let c = (crc << 1) & 0x7FFF;
    if fb {
        c ^ CRC15_POLY
    } else {
        c
    }
}

/// CRC-15 of a bit string (first bit first), initial value 0.
pub fn crc15_bits(bits: &[bool]) -> u16 {
    bits.iter().fold(0, |c, &b| crc15_step(c, b))
}

/// CRC-15 of a byte string, each byte MSB first, initial value 0.
pub fn crc15_bytes(bytes: &[u8]) -> u16 {
    bytes.iter().fold(0, |c, &byte| (0..8).rev().fold(c, |c, i| crc15_step(c, (byte >> i) & 1 == 1)))
}
