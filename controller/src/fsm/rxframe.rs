//! [`RxFrame`]: the receive frame register and the delivery of a received
//! frame to the host outputs.
//!
//! Every frame bit taken (`adv`, on `sample`) is shifted into its register
//! by field: identifier (base and extension) into `rid`, the SRR/RTR bit
//! into `rrtr` (the last one, RTR, stays), IDE into `rext`, DLC into `rdlc`
//! and data bytes into `rdat` (the last byte received in bits 7..0). A
//! frame start (`sofinit`) clears them. On delivery (`deliver`, End_Of_Frame
//! bit 7) the frame is copied to the `rx_*` outputs, the data left-aligned
//! (byte 0 in bits 63..56; zero for remote frames and DLC 0); they hold
//! until the next delivery.
//!
//! Towards the sequencer: `ext` and `rtr` (the IDE and RTR bits received),
//! `dlc_lo_zero` (DLC bits 2..0 received so far are zero: after a dominant
//! last DLC bit the DLC is 0) and `data_bits` (length of the data field in
//! bits, 8·min(DLC, 8)).
//!
//! State: `rid`, `rdat`, `rdlc`, `rrtr`, `rext` (the frame being received;
//! cleared at its start; `rrtr` and `rext` also by `reset`); `rxide_r`,
//! `rxrtr_r`, `rxid_r`, `rxdlc_r`, `rxdat_r` (the last delivered frame;
//! written on delivery only).

use super::field::Field;
use rust_hdl::prelude::*;

#[derive(LogicBlock, Default)]
pub struct RxFrame {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub sample: Signal<In, Bit>,
    pub rxbit: Signal<In, Bit>,
    /// A frame bit was taken in field `fld`.
    pub adv: Signal<In, Bit>,
    pub fld: Signal<In, Field>,
    /// A frame starts (SOF sampled).
    pub sofinit: Signal<In, Bit>,
    /// Deliver the received frame.
    pub deliver: Signal<In, Bit>,

    pub ext: Signal<Out, Bit>,
    pub rtr: Signal<Out, Bit>,
    pub dlc_lo_zero: Signal<Out, Bit>,
    pub data_bits: Signal<Out, Bits<8>>,
    pub rx_ide: Signal<Out, Bit>,
    pub rx_rtr: Signal<Out, Bit>,
    pub rx_id: Signal<Out, Bits<29>>,
    pub rx_dlc: Signal<Out, Bits<4>>,
    pub rx_data: Signal<Out, Bits<64>>,

    rid: DFF<Bits<29>>,
    rdat: DFF<Bits<64>>,
    rdlc: DFF<Bits<4>>,
    rrtr: DFF<Bit>,
    rext: DFF<Bit>,
    rxide_r: DFF<Bit>,
    rxrtr_r: DFF<Bit>,
    rxid_r: DFF<Bits<29>>,
    rxdlc_r: DFF<Bits<4>>,
    rxdat_r: DFF<Bits<64>>,

    l_rid: Signal<Local, Bits<29>>,
    l_rdat: Signal<Local, Bits<64>>,
    l_rdlc: Signal<Local, Bits<4>>,
    l_rrtr: Signal<Local, Bit>,
    l_rext: Signal<Local, Bit>,
    l_nbytes: Signal<Local, Bits<4>>,
    l_shamt: Signal<Local, Bits<6>>,
}

impl Logic for RxFrame {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, rid, rdat, rdlc, rrtr, rext, rxide_r, rxrtr_r, rxid_r, rxdlc_r, rxdat_r);
        // Bytes carried (DLC 9..15: 8), from the registered DLC.
        self.l_nbytes.next = self.rdlc.q.val();
        if self.rdlc.q.val() >= 8 {
            self.l_nbytes.next = 8.into();
        }
        // Left-align the received bytes: shift by (64 - 8N) mod 64.
        self.l_shamt.next = bit_cast::<6, 4>(self.l_nbytes.val()) << 3;
        self.l_shamt.next = (!self.l_shamt.val()) + 1;

        self.l_rid.next = self.rid.q.val();
        self.l_rdat.next = self.rdat.q.val();
        self.l_rdlc.next = self.rdlc.q.val();
        self.l_rrtr.next = self.rrtr.q.val();
        self.l_rext.next = self.rext.q.val();
        // Shift and deliver on `sample`.
        if self.sample.val() {
            if self.adv.val() {
                match self.fld.val() {
                    Field::Ident => {
                        self.l_rid.next = self.rid.q.val() << 1;
                        if self.rxbit.val() {
                            self.l_rid.next = self.l_rid.val() | 1;
                        }
                    }
                    Field::ExIdent => {
                        self.l_rid.next = self.rid.q.val() << 1;
                        if self.rxbit.val() {
                            self.l_rid.next = self.l_rid.val() | 1;
                        }
                    }
                    Field::Srr => {
                        self.l_rrtr.next = self.rxbit.val();
                    }
                    Field::Rtr => {
                        self.l_rrtr.next = self.rxbit.val();
                    }
                    Field::Ide => {
                        self.l_rext.next = self.rxbit.val();
                    }
                    Field::Dlc => {
                        self.l_rdlc.next = self.rdlc.q.val() << 1;
                        if self.rxbit.val() {
                            self.l_rdlc.next = self.l_rdlc.val() | 1;
                        }
                    }
                    Field::Data => {
                        self.l_rdat.next = self.rdat.q.val() << 1;
                        if self.rxbit.val() {
                            self.l_rdat.next = self.l_rdat.val() | 1;
                        }
                    }
                    _ => {}
                }
            }
            if self.sofinit.val() {
                self.l_rid.next = 0.into();
                self.l_rdat.next = 0.into();
                self.l_rdlc.next = 0.into();
                self.l_rrtr.next = false;
                self.l_rext.next = false;
            }
            self.rid.d.next = self.l_rid.val();
            self.rdat.d.next = self.l_rdat.val();
            self.rdlc.d.next = self.l_rdlc.val();
            self.rrtr.d.next = self.l_rrtr.val();
            self.rext.d.next = self.l_rext.val();
            if self.deliver.val() {
                self.rxide_r.d.next = self.rext.q.val();
                self.rxrtr_r.d.next = self.rrtr.q.val();
                self.rxid_r.d.next = self.rid.q.val();
                self.rxdlc_r.d.next = self.rdlc.q.val();
                if self.rrtr.q.val() | (self.l_nbytes.val() == 0) {
                    self.rxdat_r.d.next = 0.into();
                } else {
                    self.rxdat_r.d.next = self.rdat.q.val() << self.l_shamt.val();
                }
            }
        }
        if self.reset.val() {
            self.rrtr.d.next = false;
            self.rext.d.next = false;
        }

        self.ext.next = self.rext.q.val();
        self.rtr.next = self.rrtr.q.val();
        self.dlc_lo_zero.next = self.rdlc.q.val().get_bits::<3>(0) == 0;
        self.data_bits.next = bit_cast::<8, 4>(self.l_nbytes.val()) << 3;
        self.rx_ide.next = self.rxide_r.q.val();
        self.rx_rtr.next = self.rxrtr_r.q.val();
        self.rx_id.next = self.rxid_r.q.val();
        self.rx_dlc.next = self.rxdlc_r.q.val();
        self.rx_data.next = self.rxdat_r.q.val();
    }
}

canstar_hdl::impl_clocked!(RxFrame);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::Frame;
    use canstar_hdl::drive;

    /// Shift a frame's fields in as the sequencer does (taken bits, no stuff bits).
    fn receive(u: &mut RxFrame, f: &Frame) {
        let mut bits: Vec<(Field, bool)> = vec![(Field::Sof, false)];
        let b = |v: u64, n: usize| (0..n).rev().map(move |k| (v >> k) & 1 == 1);
        if f.ide {
            bits.extend(b((f.id >> 18) as u64, 11).map(|x| (Field::Ident, x)));
            bits.push((Field::Srr, true));
            bits.push((Field::Ide, true));
            bits.extend(b((f.id & 0x3FFFF) as u64, 18).map(|x| (Field::ExIdent, x)));
        } else {
            bits.extend(b(f.id as u64, 11).map(|x| (Field::Ident, x)));
        }
        bits.push((Field::Rtr, f.rtr));
        if !f.ide {
            bits.push((Field::Ide, false));
        }
        bits.extend(b(f.dlc as u64, 4).map(|x| (Field::Dlc, x)));
        for byte in &f.data {
            bits.extend(b(*byte as u64, 8).map(|x| (Field::Data, x)));
        }
        for (k, (fld, level)) in bits.into_iter().enumerate() {
            u.sample.next = true;
            u.sofinit.next = k == 0;
            u.adv.next = true;
            u.fld.next = fld;
            u.rxbit.next = level;
            drive::cycle(u);
        }
        u.adv.next = false;
        u.sofinit.next = false;
        u.deliver.next = true;
        drive::cycle(u);
        u.deliver.next = false;
        u.sample.next = false;
        drive::cycle(u);
    }

    #[test]
    fn delivers_every_frame_layout() {
        let mut u = RxFrame::default();
        drive::init(&mut u);
        let frames = [
            Frame::std(0x7FF, &[]),
            Frame::std(0x123, &[0xAB]),
            Frame::std(0x001, &[1, 2, 3, 4, 5, 6, 7, 8]),
            Frame::data(false, 0x55, 12, &[9, 8, 7, 6, 5, 4, 3, 2]),
            Frame::ext(0x1ABC_DEF0, &[0x11, 0x22, 0x33]),
            Frame::remote(false, 0x2AA, 5),
            Frame::remote(true, 0x0000_0001, 15),
        ];
        for f in &frames {
            receive(&mut u, f);
            let got = Frame::from_native(
                u.rx_ide.val(),
                u.rx_rtr.val(),
                u.rx_id.val().index() as u32,
                u.rx_dlc.val().index() as u8,
                u.rx_data.val().to_u64(),
            );
            assert_eq!(&got, f);
            let n = if f.rtr { 0 } else { f.dlc.min(8) as usize };
            assert_eq!(u.data_bits.val().index(), 8 * f.dlc.min(8) as usize);
            assert_eq!(u.rx_data.val().to_u64() == 0, n == 0 || f.data.iter().all(|b| *b == 0));
        }
    }
}
