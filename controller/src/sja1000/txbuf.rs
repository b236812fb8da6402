//! [`TxBuffer`]: the 13-byte transmit buffer (frame information, identifier
//! bytes, data bytes; the PeliCAN layout of the data sheet) and the frame
//! it holds, in the core's native request format.
//!
//! Byte `idx` is written on `we` (the top decides when the host may write:
//! TBS = 1 in operating mode, or reset mode). The host reads the buffer
//! from a copy in block RAM that the top keeps (the same writes), so this
//! block has no read multiplexer. FI (byte
//! 0): FF in bit 7, RTR in bit 6, DLC in bits 3..0. Standard frame: ID
//! bits 10..3 in byte 1, 2..0 in byte 2 bits 7..5, data from byte 3.
//! Extended frame: ID bits 28..21, 20..13, 12..5 in bytes 1..3, 4..0 in
//! byte 4 bits 7..3, data from byte 5. `data` has data byte 0 in bits
//! 63..56.
//!
//! State: `b0` .. `b12` (the buffer bytes; not reset).

use rust_hdl::prelude::*;

#[derive(LogicBlock, Default)]
pub struct TxBuffer {
    pub clock: Signal<In, Clock>,
    pub we: Signal<In, Bit>,
    pub idx: Signal<In, Bits<4>>,
    pub wdata: Signal<In, Bits<8>>,
    pub ide: Signal<Out, Bit>,
    pub rtr: Signal<Out, Bit>,
    pub id: Signal<Out, Bits<29>>,
    pub dlc: Signal<Out, Bits<4>>,
    pub data: Signal<Out, Bits<64>>,

    b0: DFF<Bits<8>>,
    b1: DFF<Bits<8>>,
    b2: DFF<Bits<8>>,
    b3: DFF<Bits<8>>,
    b4: DFF<Bits<8>>,
    b5: DFF<Bits<8>>,
    b6: DFF<Bits<8>>,
    b7: DFF<Bits<8>>,
    b8: DFF<Bits<8>>,
    b9: DFF<Bits<8>>,
    b10: DFF<Bits<8>>,
    b11: DFF<Bits<8>>,
    b12: DFF<Bits<8>>,
}

impl Logic for TxBuffer {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, b0, b1, b2, b3, b4, b5, b6, b7, b8, b9, b10, b11, b12);
        match self.idx.val().index() {
            0 => {
                if self.we.val() {
                    self.b0.d.next = self.wdata.val();
                }
            }
            1 => {
                if self.we.val() {
                    self.b1.d.next = self.wdata.val();
                }
            }
            2 => {
                if self.we.val() {
                    self.b2.d.next = self.wdata.val();
                }
            }
            3 => {
                if self.we.val() {
                    self.b3.d.next = self.wdata.val();
                }
            }
            4 => {
                if self.we.val() {
                    self.b4.d.next = self.wdata.val();
                }
            }
            5 => {
                if self.we.val() {
                    self.b5.d.next = self.wdata.val();
                }
            }
            6 => {
                if self.we.val() {
                    self.b6.d.next = self.wdata.val();
                }
            }
            7 => {
                if self.we.val() {
                    self.b7.d.next = self.wdata.val();
                }
            }
            8 => {
                if self.we.val() {
                    self.b8.d.next = self.wdata.val();
                }
            }
            9 => {
                if self.we.val() {
                    self.b9.d.next = self.wdata.val();
                }
            }
            10 => {
                if self.we.val() {
                    self.b10.d.next = self.wdata.val();
                }
            }
            11 => {
                if self.we.val() {
                    self.b11.d.next = self.wdata.val();
                }
            }
            12 => {
                if self.we.val() {
                    self.b12.d.next = self.wdata.val();
                }
            }
            _ => {}
        }

        // The frame (FI: FF in bit 7, RTR in bit 6, DLC in bits 3..0).
        self.ide.next = self.b0.q.val().get_bit(7);
        self.rtr.next = self.b0.q.val().get_bit(6);
        self.dlc.next = self.b0.q.val().get_bits::<4>(0);
        if self.ide.val() {
            self.id.next = (bit_cast::<29, 8>(self.b1.q.val()) << 21)
                | (bit_cast::<29, 8>(self.b2.q.val()) << 13)
                | (bit_cast::<29, 8>(self.b3.q.val()) << 5)
                | (bit_cast::<29, 8>(self.b4.q.val()) >> 3);
            self.data.next = (bit_cast::<64, 8>(self.b5.q.val()) << 56)
                | (bit_cast::<64, 8>(self.b6.q.val()) << 48)
                | (bit_cast::<64, 8>(self.b7.q.val()) << 40)
                | (bit_cast::<64, 8>(self.b8.q.val()) << 32)
                | (bit_cast::<64, 8>(self.b9.q.val()) << 24)
                | (bit_cast::<64, 8>(self.b10.q.val()) << 16)
                | (bit_cast::<64, 8>(self.b11.q.val()) << 8)
                | bit_cast::<64, 8>(self.b12.q.val());
        } else {
            self.id.next = (bit_cast::<29, 8>(self.b1.q.val()) << 3) | (bit_cast::<29, 8>(self.b2.q.val()) >> 5);
            self.data.next = (bit_cast::<64, 8>(self.b3.q.val()) << 56)
                | (bit_cast::<64, 8>(self.b4.q.val()) << 48)
                | (bit_cast::<64, 8>(self.b5.q.val()) << 40)
                | (bit_cast::<64, 8>(self.b6.q.val()) << 32)
                | (bit_cast::<64, 8>(self.b7.q.val()) << 24)
                | (bit_cast::<64, 8>(self.b8.q.val()) << 16)
                | (bit_cast::<64, 8>(self.b9.q.val()) << 8)
                | bit_cast::<64, 8>(self.b10.q.val());
        }
    }
}

canstar_hdl::impl_clocked!(TxBuffer);

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::drive;

    fn load(bytes: &[u8]) -> TxBuffer {
        let mut u = TxBuffer::default();
        drive::init(&mut u);
        for (k, b) in bytes.iter().enumerate() {
            u.we.next = true;
            u.idx.next = (k as u64).into();
            u.wdata.next = (*b as u64).into();
            drive::cycle(&mut u);
        }
        u.we.next = false;
        drive::cycle(&mut u);
        u
    }

    #[test]
    fn standard_and_extended_layouts() {
        // SFF, RTR clear, DLC 3, ID 0x5A3: ID1 = ID10..3, ID2 bits 7..5 = ID2..0
        let u = load(&[0x03, 0xB4, 0x60, 0x11, 0x22, 0x33]);
        assert_eq!((u.ide.val(), u.rtr.val(), u.dlc.val().index()), (false, false, 3));
        assert_eq!(u.id.val().index(), 0x5A3);
        assert_eq!(u.data.val().to_u64() >> 40, 0x11_2233);
        // EFF, RTR set, DLC 8, ID 0x1234_5678
        let id: u32 = 0x1234_5678;
        let u = load(&[0xC8, (id >> 21) as u8, (id >> 13) as u8, (id >> 5) as u8, (id << 3) as u8, 1, 2, 3, 4, 5, 6, 7, 8]);
        assert_eq!((u.ide.val(), u.rtr.val(), u.dlc.val().index()), (true, true, 8));
        assert_eq!(u.id.val().index() as u32, id);
        assert_eq!(u.data.val().to_u64(), 0x0102_0304_0506_0708);
    }

    #[test]
    fn bytes_past_the_frame_do_not_move_it() {
        // bytes 11 and 12 are data bytes 6 and 7 of an extended frame only
        let mut bytes: Vec<u8> = (0..13).map(|k| 0x30 + k).collect();
        bytes[0] = 0x08;
        let u = load(&bytes);
        assert_eq!(u.data.val().to_u64(), 0x3334_3536_3738_393A);
        bytes[0] = 0x88;
        let u = load(&bytes);
        assert_eq!(u.data.val().to_u64(), 0x3536_3738_393A_3B3C);
    }
}
