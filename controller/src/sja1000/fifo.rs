//! [`RxFifo`]: the 64-byte receive FIFO (one block RAM) with its writer,
//! the release of the message at RBSA, and the data overrun status.
//!
//! A message takes 3 + n (standard) or 5 + n (extended) bytes (n data bytes
//! carried: 0 for remote frames, else min(DLC, 8)): FI (FF, RTR, the raw
//! DLC), the identifier bytes (unused bits 0; SFF ID2 bit 4 / EFF ID4 bit 2
//! show RTR) and the data. A frame is offered on the clock the core
//! delivers it (`offer_rx`, the `rx_*` inputs) or, for a self reception
//! request, on the clock the own frame was sent (`offer_own`, the `own_*`
//! inputs from the transmit buffer); while the writer runs, the candidate
//! frame (`f_*`) is the frame being written (both sources hold their
//! frame). The acceptance filter judges both sources side by side
//! (`accept`, `accept_own`; `rx_n`, `own_n` are their data bytes carried),
//! and the candidate's verdict is selected. A frame that passes the filter is
//! written one byte per clock from RAM[(RBSA + used) mod 64] on; RMC counts
//! it when the last byte is written. A frame that passes the filter but
//! does not fit (or arrives while the writer is busy) is dropped whole and
//! sets DOS (`overrun` on its rising edge). For the own frame, `own_done`
//! when it is stored, `own_dropped` when it is not.
//!
//! Releasing (`rrb`) moves RBSA past the message at RBSA, whose length
//! comes from its FI byte: the RAM read port fetches the FI at RBSA
//! whenever the host does not read the RAM. `clear` (reset mode entry)
//! empties the FIFO and stops the writer, keeping RBSA; a host write of
//! RBSA (`rbsa_we`) empties it too. In reset mode the host reads and
//! writes RAM bytes directly (`host_idx`); in operating mode it reads the
//! receive window, RAM[(RBSA + host_idx) mod 64] (`host_win`).
//!
//! State: `rbsa_r` (RX buffer start address), `used` (bytes held), `rmc_r`
//! (messages held), `dos_r` (data overrun status; cleared by `cdo`),
//! `wr_busy`/`wr_src`/`wr_idx`/`wr_len` (writer running, writing the own
//! frame, next byte, message length), `fetch_q`/`fetch_a` (the RAM read
//! port fetched the FI at RBSA `fetch_a` on the last clock), `cur_fi` (the
//! FI of the message at RBSA), `own_acc` (the acceptance filter's verdict on
//! the own frame, from the last clock it saw it). A hardware reset clears
//! all but the RAM, `wr_src`, `wr_idx`, `wr_len`, the fetch registers,
//! `cur_fi` and `own_acc`.

use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct RxFifo {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    pub clear: Signal<In, Bit>,
    /// The core delivers a received frame (`rx_*`); the own frame of a self
    /// reception request was sent (`own_*`, the transmit buffer).
    pub offer_rx: Signal<In, Bit>,
    pub offer_own: Signal<In, Bit>,
    pub rx_ide: Signal<In, Bit>,
    pub rx_rtr: Signal<In, Bit>,
    pub rx_id: Signal<In, Bits<29>>,
    pub rx_dlc: Signal<In, Bits<4>>,
    pub rx_data: Signal<In, Bits<64>>,
    pub own_ide: Signal<In, Bit>,
    pub own_rtr: Signal<In, Bit>,
    pub own_id: Signal<In, Bits<29>>,
    pub own_dlc: Signal<In, Bits<4>>,
    pub own_data: Signal<In, Bits<64>>,
    /// The acceptance filter passes the received frame (`rx_*`), the own
    /// frame (`own_*`).
    pub accept: Signal<In, Bit>,
    pub accept_own: Signal<In, Bit>,
    pub rrb: Signal<In, Bit>,
    pub cdo: Signal<In, Bit>,
    pub rbsa_we: Signal<In, Bit>,
    pub ram_we: Signal<In, Bit>,
    pub wdata: Signal<In, Bits<8>>,
    pub host_rd: Signal<In, Bit>,
    pub host_win: Signal<In, Bit>,
    pub host_idx: Signal<In, Bits<6>>,

    /// The data bytes carried by the received frame and by the own frame
    /// (for the acceptance filter).
    pub rx_n: Signal<Out, Bits<4>>,
    pub own_n: Signal<Out, Bits<4>>,
    /// The candidate frame (the offered one, or the one being written):
    /// IDE, RTR, identifier, data bytes carried, data bytes 0 (bits 15..8)
    /// and 1.
    pub f_ide: Signal<Out, Bit>,
    pub f_rtr: Signal<Out, Bit>,
    pub f_id: Signal<Out, Bits<29>>,
    pub f_n: Signal<Out, Bits<4>>,
    pub f_d01: Signal<Out, Bits<16>>,
    /// The RAM byte read on the previous clock.
    pub rdata: Signal<Out, Bits<8>>,
    pub rmc: Signal<Out, Bits<5>>,
    pub rbsa: Signal<Out, Bits<6>>,
    pub dos: Signal<Out, Bit>,
    pub overrun: Signal<Out, Bit>,
    pub own_done: Signal<Out, Bit>,
    pub own_dropped: Signal<Out, Bit>,
    /// The writer is busy (with the own frame).
    pub busy: Signal<Out, Bit>,
    pub busy_own: Signal<Out, Bit>,

    ram: RAM<Bits<8>, 6>,
    rbsa_r: DFF<Bits<6>>,
    used: DFF<Bits<7>>,
    rmc_r: DFF<Bits<5>>,
    dos_r: DFF<Bit>,
    wr_busy: DFF<Bit>,
    wr_src: DFF<Bit>,
    wr_idx: DFF<Bits<4>>,
    wr_len: DFF<Bits<4>>,
    fetch_q: DFF<Bit>,
    fetch_a: DFF<Bits<6>>,
    cur_fi: DFF<Bits<8>>,
    own_acc: DFF<Bit>,

    l_own: Signal<Local, Bit>,
    l_acc: Signal<Local, Bit>,
    l_dlc: Signal<Local, Bits<4>>,
    l_data: Signal<Local, Bits<64>>,
    l_len: Signal<Local, Bits<4>>,
    l_hb: Signal<Local, Bits<8>>,
    l_hdr: Signal<Local, Bit>,
    l_j: Signal<Local, Bits<4>>,
    l_db: Signal<Local, Bits<8>>,
    l_wbyte: Signal<Local, Bits<8>>,
    l_wdone: Signal<Local, Bit>,
    l_fsff: Signal<Local, Bits<16>>,
    l_feff: Signal<Local, Bits<16>>,
    l_rn: Signal<Local, Bits<4>>,
    l_on: Signal<Local, Bits<4>>,
    l_rfits: Signal<Local, Bit>,
    l_ofits: Signal<Local, Bit>,
    l_sfits: Signal<Local, Bit>,
    l_le: Signal<Local, Bits<11>>,
    l_th: Signal<Local, Bits<11>>,
    l_fi: Signal<Local, Bits<8>>,
    l_cur_n: Signal<Local, Bits<4>>,
    l_cur_len: Signal<Local, Bits<4>>,
}

impl Default for RxFifo {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            rst: Default::default(),
            clear: Default::default(),
            offer_rx: Default::default(),
            offer_own: Default::default(),
            rx_ide: Default::default(),
            rx_rtr: Default::default(),
            rx_id: Default::default(),
            rx_dlc: Default::default(),
            rx_data: Default::default(),
            own_ide: Default::default(),
            own_rtr: Default::default(),
            own_id: Default::default(),
            own_dlc: Default::default(),
            own_data: Default::default(),
            accept: Default::default(),
            accept_own: Default::default(),
            rx_n: Default::default(),
            own_n: Default::default(),
            rrb: Default::default(),
            cdo: Default::default(),
            rbsa_we: Default::default(),
            ram_we: Default::default(),
            wdata: Default::default(),
            host_rd: Default::default(),
            host_win: Default::default(),
            host_idx: Default::default(),
            f_ide: Default::default(),
            f_rtr: Default::default(),
            f_id: Default::default(),
            f_n: Default::default(),
            f_d01: Default::default(),
            rdata: Default::default(),
            rmc: Default::default(),
            rbsa: Default::default(),
            dos: Default::default(),
            overrun: Default::default(),
            own_done: Default::default(),
            own_dropped: Default::default(),
            busy: Default::default(),
            busy_own: Default::default(),
            // zero-initialised block RAM
            ram: (0..64).map(|_| Bits::<8>::from(0u64)).into(),
            rbsa_r: Default::default(),
            used: Default::default(),
            rmc_r: Default::default(),
            dos_r: Default::default(),
            wr_busy: Default::default(),
            wr_src: Default::default(),
            wr_idx: Default::default(),
            wr_len: Default::default(),
            fetch_q: Default::default(),
            fetch_a: Default::default(),
            cur_fi: Default::default(),
            own_acc: Default::default(),
            l_own: Default::default(),
            l_acc: Default::default(),
            l_dlc: Default::default(),
            l_data: Default::default(),
            l_len: Default::default(),
            l_hb: Default::default(),
            l_hdr: Default::default(),
            l_j: Default::default(),
            l_db: Default::default(),
            l_wbyte: Default::default(),
            l_wdone: Default::default(),
            l_fsff: Default::default(),
            l_feff: Default::default(),
            l_rn: Default::default(),
            l_on: Default::default(),
            l_rfits: Default::default(),
            l_ofits: Default::default(),
            l_sfits: Default::default(),
            l_le: Default::default(),
            l_th: Default::default(),
            l_fi: Default::default(),
            l_cur_n: Default::default(),
            l_cur_len: Default::default(),
        }
    }
}

impl Logic for RxFifo {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, rbsa_r, used, rmc_r, dos_r, wr_busy, wr_src, wr_idx, wr_len, fetch_q, fetch_a, cur_fi, own_acc);
        self.ram.read_clock.next = self.clock.val();
        self.ram.write_clock.next = self.clock.val();

        // The candidate frame: the core's delivery, or the own frame (also
        // on every clock without an offer, for `own_acc`); while the writer
        // runs, the frame it writes (both stay on the inputs).
        self.l_own.next = self.offer_own.val() | !self.offer_rx.val();
        if self.wr_busy.q.val() {
            self.l_own.next = self.wr_src.q.val();
        }
        self.f_ide.next = self.rx_ide.val();
        self.f_rtr.next = self.rx_rtr.val();
        self.f_id.next = self.rx_id.val();
        self.l_dlc.next = self.rx_dlc.val();
        self.l_data.next = self.rx_data.val();
        if self.l_own.val() {
            self.f_ide.next = self.own_ide.val();
            self.f_rtr.next = self.own_rtr.val();
            self.f_id.next = self.own_id.val();
            self.l_dlc.next = self.own_dlc.val();
            self.l_data.next = self.own_data.val();
        }
        // data bytes carried
        self.f_n.next = self.l_dlc.val();
        if self.l_dlc.val().get_bit(3) {
            self.f_n.next = 8.into();
        }
        if self.f_rtr.val() {
            self.f_n.next = 0.into();
        }
        self.f_d01.next = self.l_data.val().get_bits::<16>(48);

        self.l_len.next = self.f_n.val() + 3;
        if self.f_ide.val() {
            self.l_len.next = self.f_n.val() + 5;
        }
        // The byte to write next (wr_idx < l_len while the writer runs): a
        // header byte (FI, then the identifier bytes; unused bits 0, RTR in
        // SFF ID2 bit 4 / EFF ID4 bit 2) or data byte j = wr_idx - 3 (- 5
        // extended).
        self.l_hb.next = bit_cast::<8, 4>(self.l_dlc.val());
        self.l_hb.next = self.l_hb.val().replace_bit(7, self.f_ide.val());
        self.l_hb.next = self.l_hb.val().replace_bit(6, self.f_rtr.val());
        if self.wr_idx.q.val() == 1 {
            self.l_hb.next = self.f_id.val().get_bits::<8>(3);
            if self.f_ide.val() {
                self.l_hb.next = self.f_id.val().get_bits::<8>(21);
            }
        }
        if self.wr_idx.q.val() == 2 {
            self.l_hb.next = bit_cast::<8, 3>(self.f_id.val().get_bits::<3>(0)) << 5;
            self.l_hb.next = self.l_hb.val().replace_bit(4, self.f_rtr.val());
            if self.f_ide.val() {
                self.l_hb.next = self.f_id.val().get_bits::<8>(13);
            }
        }
        if self.wr_idx.q.val() == 3 {
            self.l_hb.next = self.f_id.val().get_bits::<8>(5);
        }
        if self.wr_idx.q.val() == 4 {
            self.l_hb.next = bit_cast::<8, 5>(self.f_id.val().get_bits::<5>(0)) << 3;
            self.l_hb.next = self.l_hb.val().replace_bit(2, self.f_rtr.val());
        }
        // header: wr_idx < 3 (< 5 extended), written on the bits (no carry chain)
        self.l_hdr.next = !self.wr_idx.q.val().get_bit(3)
            & !self.wr_idx.q.val().get_bit(2)
            & !(self.wr_idx.q.val().get_bit(1) & self.wr_idx.q.val().get_bit(0));
        if self.f_ide.val() {
            self.l_hdr.next = !self.wr_idx.q.val().get_bit(3)
                & (!self.wr_idx.q.val().get_bit(2)
                    | (!self.wr_idx.q.val().get_bit(1) & !self.wr_idx.q.val().get_bit(0)));
        }
        self.l_j.next = self.wr_idx.q.val() - 3;
        if self.f_ide.val() {
            self.l_j.next = self.wr_idx.q.val() - 5;
        }
        self.l_db.next = self.l_data.val().get_bits::<8>(56);
        match self.l_j.val().get_bits::<3>(0).index() {
            1 => {
                self.l_db.next = self.l_data.val().get_bits::<8>(48);
            }
            2 => {
                self.l_db.next = self.l_data.val().get_bits::<8>(40);
            }
            3 => {
                self.l_db.next = self.l_data.val().get_bits::<8>(32);
            }
            4 => {
                self.l_db.next = self.l_data.val().get_bits::<8>(24);
            }
            5 => {
                self.l_db.next = self.l_data.val().get_bits::<8>(16);
            }
            6 => {
                self.l_db.next = self.l_data.val().get_bits::<8>(8);
            }
            7 => {
                self.l_db.next = self.l_data.val().get_bits::<8>(0);
            }
            _ => {}
        }
        self.l_wbyte.next = self.l_db.val();
        if self.l_hdr.val() {
            self.l_wbyte.next = self.l_hb.val();
        }
        self.l_wdone.next = self.wr_busy.q.val() & ((self.wr_idx.q.val() + 1) == self.wr_len.q.val());
        // used + l_len <= 64 without an adder on the offer path: l_len is
        // f_n + 3 (f_n + 5 extended), f_n 0..8, so the frame fits when used
        // <= 61 - f_n (59 - f_n); bit j of `l_th` is used <= 51 + j, from
        // the register alone and without comparators (which Yosys maps to
        // carry chains): used <= 51 + j is used < 64 and either used < 48 or
        // used[3:0] <= 3 + j (`l_le` bit j).
        self.l_le.next = 0.into();
        self.l_le.next = self.l_le.val().replace_bit(0, !self.used.q.val().get_bit(3) & !self.used.q.val().get_bit(2));
        self.l_le.next = self.l_le.val().replace_bit(1, !self.used.q.val().get_bit(3) & (!self.used.q.val().get_bit(2) | (!self.used.q.val().get_bit(1) & !self.used.q.val().get_bit(0))));
        self.l_le.next = self.l_le.val().replace_bit(2, !self.used.q.val().get_bit(3) & (!self.used.q.val().get_bit(2) | !self.used.q.val().get_bit(1)));
        self.l_le.next = self.l_le.val().replace_bit(3, !self.used.q.val().get_bit(3) & ((!self.used.q.val().get_bit(2) | !self.used.q.val().get_bit(1)) | !self.used.q.val().get_bit(0)));
        self.l_le.next = self.l_le.val().replace_bit(4, !self.used.q.val().get_bit(3));
        self.l_le.next = self.l_le.val().replace_bit(5, !self.used.q.val().get_bit(3) | ((!self.used.q.val().get_bit(2) & !self.used.q.val().get_bit(1)) & !self.used.q.val().get_bit(0)));
        self.l_le.next = self.l_le.val().replace_bit(6, !self.used.q.val().get_bit(3) | (!self.used.q.val().get_bit(2) & !self.used.q.val().get_bit(1)));
        self.l_le.next = self.l_le.val().replace_bit(7, !self.used.q.val().get_bit(3) | (!self.used.q.val().get_bit(2) & (!self.used.q.val().get_bit(1) | !self.used.q.val().get_bit(0))));
        self.l_le.next = self.l_le.val().replace_bit(8, !self.used.q.val().get_bit(3) | !self.used.q.val().get_bit(2));
        self.l_le.next = self.l_le.val().replace_bit(9, (!self.used.q.val().get_bit(3) | !self.used.q.val().get_bit(2)) | (!self.used.q.val().get_bit(1) & !self.used.q.val().get_bit(0)));
        self.l_le.next = self.l_le.val().replace_bit(10, (!self.used.q.val().get_bit(3) | !self.used.q.val().get_bit(2)) | !self.used.q.val().get_bit(1));
        self.l_th.next = self.l_le.val();
        if !(self.used.q.val().get_bit(5) & self.used.q.val().get_bit(4)) {
            self.l_th.next = 0x7FF.into();
        }
        if self.used.q.val().get_bit(6) {
            self.l_th.next = 0.into();
        }
        // Bit n of `l_fsff` (`l_feff`): a standard (extended) frame of n
        // data bytes fits, used <= 61 - n (59 - n), bit 10 - n (8 - n) of
        // `l_th`; bits 9..15 are 0 (n is at most 8).
        self.l_fsff.next = 0.into();
        self.l_feff.next = 0.into();
        self.l_fsff.next = self.l_fsff.val().replace_bit(0, self.l_th.val().get_bit(10));
        self.l_fsff.next = self.l_fsff.val().replace_bit(1, self.l_th.val().get_bit(9));
        self.l_fsff.next = self.l_fsff.val().replace_bit(2, self.l_th.val().get_bit(8));
        self.l_fsff.next = self.l_fsff.val().replace_bit(3, self.l_th.val().get_bit(7));
        self.l_fsff.next = self.l_fsff.val().replace_bit(4, self.l_th.val().get_bit(6));
        self.l_fsff.next = self.l_fsff.val().replace_bit(5, self.l_th.val().get_bit(5));
        self.l_fsff.next = self.l_fsff.val().replace_bit(6, self.l_th.val().get_bit(4));
        self.l_fsff.next = self.l_fsff.val().replace_bit(7, self.l_th.val().get_bit(3));
        self.l_fsff.next = self.l_fsff.val().replace_bit(8, self.l_th.val().get_bit(2));
        self.l_feff.next = self.l_feff.val().replace_bit(0, self.l_th.val().get_bit(8));
        self.l_feff.next = self.l_feff.val().replace_bit(1, self.l_th.val().get_bit(7));
        self.l_feff.next = self.l_feff.val().replace_bit(2, self.l_th.val().get_bit(6));
        self.l_feff.next = self.l_feff.val().replace_bit(3, self.l_th.val().get_bit(5));
        self.l_feff.next = self.l_feff.val().replace_bit(4, self.l_th.val().get_bit(4));
        self.l_feff.next = self.l_feff.val().replace_bit(5, self.l_th.val().get_bit(3));
        self.l_feff.next = self.l_feff.val().replace_bit(6, self.l_th.val().get_bit(2));
        self.l_feff.next = self.l_feff.val().replace_bit(7, self.l_th.val().get_bit(1));
        self.l_feff.next = self.l_feff.val().replace_bit(8, self.l_th.val().get_bit(0));
        // The data bytes carried by the received and by the own frame and
        // whether each fits: an offer selects the verdict (`l_sfits`), so
        // that the fit test is not behind the candidate frame's select.
        self.l_rn.next = self.rx_dlc.val();
        if self.rx_dlc.val().get_bit(3) {
            self.l_rn.next = 8.into();
        }
        if self.rx_rtr.val() {
            self.l_rn.next = 0.into();
        }
        self.l_on.next = self.own_dlc.val();
        if self.own_dlc.val().get_bit(3) {
            self.l_on.next = 8.into();
        }
        if self.own_rtr.val() {
            self.l_on.next = 0.into();
        }
        self.l_rfits.next = self.l_fsff.val().get_bit(self.l_rn.val().index());
        if self.rx_ide.val() {
            self.l_rfits.next = self.l_feff.val().get_bit(self.l_rn.val().index());
        }
        self.l_ofits.next = self.l_fsff.val().get_bit(self.l_on.val().index());
        if self.own_ide.val() {
            self.l_ofits.next = self.l_feff.val().get_bit(self.l_on.val().index());
        }
        self.l_sfits.next = self.l_rfits.val();
        if self.offer_own.val() {
            self.l_sfits.next = self.l_ofits.val();
        }

        // Length of the message at RBSA (for a release), from its FI byte.
        self.l_fi.next = self.cur_fi.q.val();
        if self.fetch_q.q.val() & (self.fetch_a.q.val() == self.rbsa_r.q.val()) {
            self.l_fi.next = self.ram.read_data.val();
        }
        self.cur_fi.d.next = self.l_fi.val();
        self.l_cur_n.next = self.l_fi.val().get_bits::<4>(0);
        if self.l_fi.val().get_bit(3) {
            self.l_cur_n.next = 8.into();
        }
        if self.l_fi.val().get_bit(6) {
            self.l_cur_n.next = 0.into();
        }
        self.l_cur_len.next = self.l_cur_n.val() + 3;
        if self.l_fi.val().get_bit(7) {
            self.l_cur_len.next = self.l_cur_n.val() + 5;
        }

        // RAM read port: the host, else the fetch of the FI at RBSA.
        self.ram.read_address.next = self.rbsa_r.q.val();
        self.fetch_q.d.next = true;
        if self.host_rd.val() {
            self.fetch_q.d.next = false;
            if self.host_win.val() {
                self.ram.read_address.next = self.rbsa_r.q.val() + self.host_idx.val();
            } else {
                self.ram.read_address.next = self.host_idx.val();
            }
        }
        self.fetch_a.d.next = self.rbsa_r.q.val();

        // Host writes (reset mode).
        if self.rbsa_we.val() {
            self.rbsa_r.d.next = self.wdata.val().get_bits::<6>(0);
            self.used.d.next = 0.into();
            self.rmc_r.d.next = 0.into();
        }
        if self.cdo.val() {
            self.dos_r.d.next = false;
        }
        self.ram.write_address.next = self.host_idx.val();
        self.ram.write_data.next = self.wdata.val();
        self.ram.write_enable.next = self.ram_we.val();

        // Writer.
        self.own_done.next = false;
        self.own_dropped.next = false;
        self.overrun.next = false;
        if self.wr_busy.q.val() {
            self.ram.write_address.next =
                (self.rbsa_r.q.val() + self.used.q.val().get_bits::<6>(0)) + bit_cast::<6, 4>(self.wr_idx.q.val());
            self.ram.write_data.next = self.l_wbyte.val();
            self.ram.write_enable.next = true;
            self.wr_idx.d.next = self.wr_idx.q.val() + 1;
            if self.l_wdone.val() {
                self.wr_busy.d.next = false;
                self.own_done.next = self.wr_src.q.val();
            }
        }
        // The filter's verdict on the own frame, taken on every clock on
        // which it sees the own frame (the writer idle, no received frame
        // offered); the own frame's offer uses the verdict of the clock
        // before, so that the filter is not between the core's `tx_done` and
        // the transmit control. The verdict is that of the offered frame:
        // the own frame is offered while its request is pending, and from
        // the clock the request is taken (TBS = 0) to its offer neither the
        // transmit buffer (locked) nor the filter's code, mask and mode
        // (reset mode only) change, and that is at least a frame's length
        // (no other offer and writer run can fill it).
        // (The candidate is the own frame then.) `l_acc` is the verdict on
        // the candidate frame, read on offers only: the own frame's taken
        // from `own_acc`, else the frame being written's, or the received
        // frame's.
        if !self.wr_busy.q.val() & !self.offer_rx.val() {
            self.own_acc.d.next = self.accept_own.val();
        }
        self.l_acc.next = self.accept.val();
        if self.wr_busy.q.val() {
            if self.wr_src.q.val() {
                self.l_acc.next = self.accept_own.val();
            }
        } else if self.offer_own.val() {
            self.l_acc.next = self.own_acc.q.val();
        }
        if self.offer_rx.val() | self.offer_own.val() {
            if self.l_acc.val() & self.l_sfits.val() & !self.wr_busy.q.val() {
                self.wr_busy.d.next = true;
                self.wr_src.d.next = self.offer_own.val();
                self.wr_idx.d.next = 0.into();
                self.wr_len.d.next = self.l_len.val();
            } else {
                if self.l_acc.val() {
                    self.dos_r.d.next = true;
                    self.overrun.next = !self.dos_r.q.val();
                }
            }
        }
        // (the else branch above for the own frame, written without the
        // filter's combinational verdict, which it does not depend on)
        self.own_dropped.next = self.offer_own.val()
            & !(self.own_acc.q.val() & self.l_ofits.val() & !self.wr_busy.q.val());
        // Pointers.
        if self.rrb.val() {
            self.rbsa_r.d.next = self.rbsa_r.q.val() + bit_cast::<6, 4>(self.l_cur_len.val());
        }
        if self.l_wdone.val() & !self.rrb.val() {
            self.rmc_r.d.next = self.rmc_r.q.val() + 1;
            self.used.d.next = self.used.q.val() + bit_cast::<7, 4>(self.wr_len.q.val());
        } else if self.rrb.val() & !self.l_wdone.val() {
            self.rmc_r.d.next = self.rmc_r.q.val() - 1;
            self.used.d.next = self.used.q.val() - bit_cast::<7, 4>(self.l_cur_len.val());
        } else if self.rrb.val() & self.l_wdone.val() {
            self.used.d.next =
                (self.used.q.val() + bit_cast::<7, 4>(self.wr_len.q.val())) - bit_cast::<7, 4>(self.l_cur_len.val());
        }
        if self.clear.val() {
            self.wr_busy.d.next = false;
            self.used.d.next = 0.into();
            self.rmc_r.d.next = 0.into();
        }
        if self.rst.val() {
            self.dos_r.d.next = false;
            self.rbsa_r.d.next = 0.into();
            self.used.d.next = 0.into();
            self.rmc_r.d.next = 0.into();
            self.wr_busy.d.next = false;
            self.ram.write_enable.next = false;
        }

        self.rx_n.next = self.l_rn.val();
        self.own_n.next = self.l_on.val();
        self.rdata.next = self.ram.read_data.val();
        self.rmc.next = self.rmc_r.q.val();
        self.rbsa.next = self.rbsa_r.q.val();
        self.dos.next = self.dos_r.q.val();
        self.busy.next = self.wr_busy.q.val();
        self.busy_own.next = self.wr_src.q.val();
    }
}

canstar_hdl::impl_clocked!(RxFifo);
