//! [`TxRequest`]: the transmit request handshake and the transmit frame
//! register.
//!
//! Handshake (every clock): `req` (the request as the protocol sees it,
//! registered) follows `tx_req` unless the request is `blocked`. A request
//! is blocked by `tx_abort`, by a successful transmission (`done`) and, in
//! single-shot mode, by a lost arbitration (`lost`) or an error detected as
//! transmitter; it stays blocked until `tx_req` has been low for a clock.
//!
//! Frame register: `load` (the own frame starts) latches `tx_ide`, `tx_rtr`,
//! `tx_id` (a standard identifier moved to bits 28..18), `tx_dlc` and
//! `tx_data`; each identifier, DLC and data bit taken (`adv` in that field)
//! shifts its register left, so the bit to send next is always the MSB.
//! `level` is the level of the next bit of the own frame, for the field
//! `nf` the frame fields go to after a taken bit of the stuffed area (or
//! Start_Of_Frame): combinational, it sees the shift of this bit, which such
//! a bit makes exactly when `fld` is a shifting field; the CRC sequence comes
//! from the CRC engine (`crc_bit`). `level_sof` is the level of Identifier
//! bit 1 when a SOF is sampled outside the frame fields (it sees `load`).
//! Both are read only on a `sample` clock whose next bit is an own frame bit.
//!
//! State: `req` (see above), `blocked` (no further attempt until `tx_req`
//! falls; cleared by `reset` and by `tx_req` low), `tid`, `tdat`, `tdlc`,
//! `tide`, `trtr` (the own frame; loaded at its start, shifted as sent; not
//! reset).

use super::field::Field;
use rust_hdl::prelude::*;

#[derive(LogicBlock, Default)]
pub struct TxRequest {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub sample: Signal<In, Bit>,
    pub tx_req: Signal<In, Bit>,
    pub tx_abort: Signal<In, Bit>,
    pub single_shot: Signal<In, Bit>,
    pub tx_ide: Signal<In, Bit>,
    pub tx_rtr: Signal<In, Bit>,
    pub tx_id: Signal<In, Bits<29>>,
    pub tx_dlc: Signal<In, Bits<4>>,
    pub tx_data: Signal<In, Bits<64>>,
    /// The own frame starts: latch the request contents.
    pub load: Signal<In, Bit>,
    /// A frame bit was taken in field `fld`.
    pub adv: Signal<In, Bit>,
    pub fld: Signal<In, Field>,
    /// The field of the next bit.
    pub nf: Signal<In, Field>,
    /// The next CRC bit to send.
    pub crc_bit: Signal<In, Bit>,
    /// Outcome of the bit: arbitration lost, transmission successful, an
    /// error (the sequencer's final decision) while `tx_role`.
    pub lost: Signal<In, Bit>,
    pub done: Signal<In, Bit>,
    pub err_now: Signal<In, Bit>,
    pub tx_role: Signal<In, Bit>,

    pub req: Signal<Out, Bit>,
    /// The own frame is extended.
    pub ide: Signal<Out, Bit>,
    pub level: Signal<Out, Bit>,
    /// The level of Identifier bit 1 of an own frame whose SOF is sampled
    /// outside the frame fields (Bus_Idle, Intermission 3, Suspend), with
    /// the frame loaded on this clock if `load` is set.
    pub level_sof: Signal<Out, Bit>,

    rq: DFF<Bit>,
    blocked: DFF<Bit>,
    tid: DFF<Bits<29>>,
    tdat: DFF<Bits<64>>,
    tdlc: DFF<Bits<4>>,
    tide: DFF<Bit>,
    trtr: DFF<Bit>,

    l_tid: Signal<Local, Bits<29>>,
    l_tdat: Signal<Local, Bits<64>>,
    l_tdlc: Signal<Local, Bits<4>>,
    l_tide: Signal<Local, Bit>,
    l_trtr: Signal<Local, Bit>,
    lv_tid: Signal<Local, Bits<29>>,
    lv_tdat: Signal<Local, Bits<64>>,
    lv_tdlc: Signal<Local, Bits<4>>,
}

impl Logic for TxRequest {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, rq, blocked, tid, tdat, tdlc, tide, trtr);
        // Handshake.
        self.blocked.d.next = self.blocked.q.val() | self.tx_abort.val();
        if !self.tx_req.val() {
            self.blocked.d.next = false;
        }
        if self.sample.val()
            & (self.done.val() | (self.single_shot.val() & (self.lost.val() | (self.err_now.val() & self.tx_role.val()))))
        {
            self.blocked.d.next = true;
        }
        self.rq.d.next = self.tx_req.val() & !self.blocked.q.val() & !self.tx_abort.val();
        if self.reset.val() {
            self.rq.d.next = false;
            self.blocked.d.next = false;
        }

        // Frame register: shift the bit just sent, or load a new frame; the
        // level of the next bit (the MSB of each shift register). Both
        // matter on `sample` only.
        self.l_tid.next = self.tid.q.val();
        self.l_tdat.next = self.tdat.q.val();
        self.l_tdlc.next = self.tdlc.q.val();
        self.l_tide.next = self.tide.q.val();
        self.l_trtr.next = self.trtr.q.val();
        if self.sample.val() {
            if self.adv.val() {
                match self.fld.val() {
                    Field::Ident => {
                        self.l_tid.next = self.tid.q.val() << 1;
                    }
                    Field::ExIdent => {
                        self.l_tid.next = self.tid.q.val() << 1;
                    }
                    Field::Dlc => {
                        self.l_tdlc.next = self.tdlc.q.val() << 1;
                    }
                    Field::Data => {
                        self.l_tdat.next = self.tdat.q.val() << 1;
                    }
                    _ => {}
                }
            }
            if self.load.val() {
                self.l_tide.next = self.tx_ide.val();
                self.l_trtr.next = self.tx_rtr.val();
                if self.tx_ide.val() {
                    self.l_tid.next = self.tx_id.val();
                } else {
                    self.l_tid.next = self.tx_id.val() << 18;
                }
                self.l_tdlc.next = self.tx_dlc.val();
                self.l_tdat.next = self.tx_data.val();
            }
            self.tid.d.next = self.l_tid.val();
            self.tdat.d.next = self.l_tdat.val();
            self.tdlc.d.next = self.l_tdlc.val();
            self.tide.d.next = self.l_tide.val();
            self.trtr.d.next = self.l_trtr.val();
        }
        // The level of the next own bit, read by the sequencer only on a
        // `sample` clock whose next bit is an own frame bit. For a bit of the
        // stuffed area that is taken, `adv` is set and `load` is not, so the
        // registers shift exactly when `fld` is a shifting field: `level` does
        // not wait for `adv` (the bit and arbitration checks) nor for `load`.
        self.lv_tid.next = self.tid.q.val();
        self.lv_tdlc.next = self.tdlc.q.val();
        self.lv_tdat.next = self.tdat.q.val();
        match self.fld.val() {
            Field::Ident => {
                self.lv_tid.next = self.tid.q.val() << 1;
            }
            Field::ExIdent => {
                self.lv_tid.next = self.tid.q.val() << 1;
            }
            Field::Dlc => {
                self.lv_tdlc.next = self.tdlc.q.val() << 1;
            }
            Field::Data => {
                self.lv_tdat.next = self.tdat.q.val() << 1;
            }
            _ => {}
        }
        self.level.next = true;
        match self.nf.val() {
            Field::Sof => {
                self.level.next = false;
            }
            Field::Ident => {
                self.level.next = self.lv_tid.val().get_bit(28);
            }
            Field::ExIdent => {
                self.level.next = self.lv_tid.val().get_bit(28);
            }
            Field::Ide => {
                self.level.next = self.tide.q.val();
            }
            Field::Rtr => {
                self.level.next = self.trtr.q.val();
            }
            Field::Resv => {
                self.level.next = false;
            }
            Field::Dlc => {
                self.level.next = self.lv_tdlc.val().get_bit(3);
            }
            Field::Data => {
                self.level.next = self.lv_tdat.val().get_bit(63);
            }
            Field::Crc => {
                self.level.next = self.crc_bit.val();
            }
            _ => {}
        }
        self.level_sof.next = self.tid.q.val().get_bit(28);
        if self.load.val() {
            self.level_sof.next = self.tx_id.val().get_bit(10);
            if self.tx_ide.val() {
                self.level_sof.next = self.tx_id.val().get_bit(28);
            }
        }

        self.req.next = self.rq.q.val();
        self.ide.next = self.tide.q.val();
    }
}

canstar_hdl::impl_clocked!(TxRequest);

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::drive;

    fn block() -> TxRequest {
        let mut u = TxRequest::default();
        drive::init(&mut u);
        u.reset.next = true;
        drive::cycle(&mut u);
        u.reset.next = false;
        drive::cycle(&mut u);
        u
    }

    /// One sampled bit: `nf` is the next field; returns the level for it.
    fn bit(u: &mut TxRequest, fld: Field, nf: Field, adv: bool, load: bool) -> bool {
        u.sample.next = true;
        u.fld.next = fld;
        u.nf.next = nf;
        u.adv.next = adv;
        u.load.next = load;
        drive::settle(u);
        let l = u.level.val();
        drive::cycle(u);
        u.sample.next = false;
        u.adv.next = false;
        u.load.next = false;
        u.done.next = false;
        u.lost.next = false;
        drive::cycle(u);
        l
    }

    #[test]
    fn handshake_blocks_after_success_abort_and_single_shot_failure() {
        let mut u = block();
        assert!(!u.req.val());
        u.tx_req.next = true;
        drive::cycle(&mut u);
        assert!(u.req.val(), "the request is seen on the next clock");
        // success blocks further attempts until tx_req falls
        u.done.next = true;
        bit(&mut u, Field::Eof, Field::Inter, false, false);
        drive::cycle(&mut u);
        assert!(!u.req.val());
        u.tx_req.next = false;
        drive::cycle(&mut u);
        u.tx_req.next = true;
        drive::cycle(&mut u);
        drive::cycle(&mut u);
        assert!(u.req.val());
        // abort
        u.tx_abort.next = true;
        drive::cycle(&mut u);
        u.tx_abort.next = false;
        drive::cycle(&mut u);
        assert!(!u.req.val(), "aborted");
        u.tx_req.next = false;
        drive::cycle(&mut u);
        u.tx_req.next = true;
        drive::cycle(&mut u);
        drive::cycle(&mut u);
        assert!(u.req.val());
        // single shot: a lost arbitration ends the attempts; without it, not
        u.lost.next = true;
        bit(&mut u, Field::Ident, Field::Ident, true, false);
        assert!(u.req.val(), "retried after a lost arbitration");
        u.single_shot.next = true;
        u.lost.next = true;
        bit(&mut u, Field::Ident, Field::Ident, true, false);
        assert!(!u.req.val(), "single shot: no retry");
    }

    #[test]
    fn frame_register_gives_the_bits_of_the_own_frame_in_order() {
        let mut u = block();
        // standard frame 0x5A3, DLC 2, data 0xC3 0x81
        u.tx_ide.next = false;
        u.tx_rtr.next = false;
        u.tx_id.next = 0x5A3.into();
        u.tx_dlc.next = 2.into();
        u.tx_data.next = 0xC381_0000_0000_0000u64.into();
        assert!(!bit(&mut u, Field::Idle, Field::Sof, false, true), "SOF dominant");
        let mut got = vec![bit(&mut u, Field::Sof, Field::Ident, true, false)];
        for _ in 0..10 {
            got.push(bit(&mut u, Field::Ident, Field::Ident, true, false));
        }
        let id: Vec<bool> = (0..11).rev().map(|k| (0x5A3 >> k) & 1 == 1).collect();
        assert_eq!(got, id);
        assert!(!bit(&mut u, Field::Ident, Field::Rtr, true, false), "RTR dominant (data frame)");
        assert!(!bit(&mut u, Field::Rtr, Field::Ide, true, false), "IDE dominant");
        assert!(!bit(&mut u, Field::Ide, Field::Resv, true, false), "r0 dominant");
        let mut dlc = vec![bit(&mut u, Field::Resv, Field::Dlc, true, false)];
        for _ in 0..3 {
            dlc.push(bit(&mut u, Field::Dlc, Field::Dlc, true, false));
        }
        assert_eq!(dlc, [false, false, true, false]);
        let mut data = vec![bit(&mut u, Field::Dlc, Field::Data, true, false)];
        for _ in 0..15 {
            data.push(bit(&mut u, Field::Data, Field::Data, true, false));
        }
        let want: Vec<bool> = (0..16).rev().map(|k| (0xC381u32 >> k) & 1 == 1).collect();
        assert_eq!(data, want);
        u.crc_bit.next = false;
        assert!(!bit(&mut u, Field::Data, Field::Crc, true, false), "CRC bits from the CRC engine");
        assert!(bit(&mut u, Field::Crc, Field::CrcDel, true, false), "recessive outside the frame fields");
    }
}
