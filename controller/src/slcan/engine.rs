//! [`Engine`]: the slcan command sequencer. It takes host characters from
//! the queue into the [`LineParser`], executes each complete line by
//! driving the SJA1000 through its Wishbone port as a driver would, polls
//! SR for received frames while the channel is open, reads them from the
//! receive window, releases them (RRB) and hands every reply and frame line
//! to the [`LineTx`] (one line at a time).
//!
//! State: `st` (the sequencer state) and `ret` (where a Wishbone access
//! returns to); the Wishbone master `wcyc` (cyc = stb), `wwe`, `wadr`,
//! `wdat` and `rd` (the data read); `open`, `lom` (channel open, in
//! listen-only mode); `btr0`, `btr1` (written to the SJA1000 at `O`/`L`;
//! reset to the generation-time default, set by `Sn`/`sxxyy`); `k` (index
//! of a TX-buffer write or an RX-window read); `rk` (the reply kind: 0 OK,
//! 1 BEL, 2 `z`, 3 `Z`, 4 `F`, 5 `V`, 6 `N`, 7 a received frame); `srv`,
//! `flags` (SR and the status flags of `F`); `rximg` (the 13 bytes of the
//! receive window, FI in bits 103..96). The reply line for `rk` is composed
//! by [`Reply`].
//!
//! Commands (validity as described in [`super`]; BEL otherwise):
//! - `O`/`L` (closed): BTR0, BTR1, IER = BEIE|ALIE|EPIE|DOIE, MOD = 0 / LOM.
//! - `C`: MOD = RM (entering reset mode empties the RX FIFO).
//! - `t`/`T`/`r`/`R` (open, not listen-only): read SR until TBS = 1, at
//!   most `tx_wait` times ([`SlcanParams::tx_wait_polls`]: 20 ms of the
//!   nominal clock, longer than a frame at 10 kbit/s), so that a host that
//!   sends frames back to back (python-can, slcand) is not refused while
//!   the previous frame is on the bus; still busy → BEL (no ACK, bus-off,
//!   arbitration lost for that long). Received frames wait meanwhile (in
//!   the SJA1000's 64-byte FIFO). SR.BS = 1 (bus-off: the block is in reset
//!   mode, where 0x10.. are the acceptance registers) → BEL; the host
//!   closes and reopens (`C`, `O`) to start the recovery. Then the 13 bytes of the TX buffer (FI, identifier, data; unused bytes 0),
//!   then CMR = TR; reply `z\r` / `Z\r`. The reply means "queued", as on a
//!   Lawicel adapter, not "sent".
//! - `F`: read SR, read IR (the read clears DOI, EPI, ALI, BEI); if SR.DOS,
//!   CMR = CDO (clears it). Flags: bit 0 RX FIFO full (SR.DOS: a frame was
//!   dropped), bit 1 TX buffer busy (SR.TBS = 0), bit 2 error warning
//!   (SR.ES), bit 3 data overrun (SR.DOS or IR.DOI), bit 5 error passive
//!   (IR.EPI), bit 6 arbitration lost (IR.ALI), bit 7 bus error (IR.BEI).
//! - `Sn`, `sxxyy` (closed), `V`, `N`, empty line: no bus access. `sxxyy`
//!   with a setting the core refuses (TSEG1 = 0 or a bit under 8 TQ, see
//!   [`crate::sja1000::timing`]) answers BEL; other values are taken as
//!   given (an SJW the core limits, for instance).
//!
//! Between lines, while open, SR is read; RBS = 1 → the 13 window bytes
//! are read, CMR = RRB, and the frame line goes out. Host characters wait
//! in the queue meanwhile. A Wishbone access takes 3 clocks.

use super::linetx::LineTx;
use super::parse::LineParser;
use super::reply::Reply;
use super::SlcanParams;
use rust_hdl::prelude::*;

#[derive(Copy, Clone, Debug, PartialEq, Eq, LogicState)]
pub enum EState {
    Idle,
    Exec,
    WbWait,
    OpenBtr1,
    OpenIer,
    OpenMod,
    TxCheck,
    TxLoad,
    TxNext,
    FIr,
    FDone,
    PollChk,
    RxRead,
    RxNext,
    Reply,
}

#[derive(LogicBlock)]
pub struct Engine {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    /// The character queue.
    pub c_valid: Signal<In, Bit>,
    pub c_data: Signal<In, Bits<9>>,
    pub c_pop: Signal<Out, Bit>,
    /// The UART transmitter.
    pub tx_busy: Signal<In, Bit>,
    pub tx_start: Signal<Out, Bit>,
    pub tx_data: Signal<Out, Bits<8>>,
    /// Wishbone master to the SJA1000 (cyc = stb).
    pub wb_cyc: Signal<Out, Bit>,
    pub wb_we: Signal<Out, Bit>,
    pub wb_adr: Signal<Out, Bits<8>>,
    pub wb_dat_w: Signal<Out, Bits<8>>,
    pub wb_dat_r: Signal<In, Bits<8>>,
    pub wb_ack: Signal<In, Bit>,

    parser: LineParser,
    reply: Reply,
    out: LineTx,

    st: DFF<EState>,
    ret: DFF<EState>,
    wcyc: DFF<Bit>,
    wwe: DFF<Bit>,
    wadr: DFF<Bits<8>>,
    wdat: DFF<Bits<8>>,
    rd: DFF<Bits<8>>,
    open: DFF<Bit>,
    lom: DFF<Bit>,
    btr0: DFF<Bits<8>>,
    btr1: DFF<Bits<8>>,
    k: DFF<Bits<4>>,
    rk: DFF<Bits<3>>,
    srv: DFF<Bits<8>>,
    flags: DFF<Bits<8>>,
    rximg: DFF<Bits<104>>,
    wcnt: DFF<Bits<20>>,
    /// SR reads (4 clocks each) to wait for TBS before answering BEL.
    tx_wait: Constant<Bits<20>>,

    /// The `Sn` table: entry n in bits 16n+15..16n (BTR0 high byte), and
    /// which entries exist.
    tbl: Constant<Bits<160>>,
    tvalid: Constant<Bits<10>>,
    dbtr0: Constant<Bits<8>>,
    dbtr1: Constant<Bits<8>>,

    l_c: Signal<Local, Bits<8>>,
    l_cmd: Signal<Local, Bits<8>>,
    l_len: Signal<Local, Bits<5>>,
    l_ok1: Signal<Local, Bit>,
    l_std: Signal<Local, Bit>,
    l_ext: Signal<Local, Bit>,
    l_rtr: Signal<Local, Bit>,
    l_flen: Signal<Local, Bits<5>>,
    l_fok: Signal<Local, Bit>,
    l_ent: Signal<Local, Bits<16>>,
    l_fi: Signal<Local, Bits<8>>,
    l_timg: Signal<Local, Bits<104>>,
    l_fl: Signal<Local, Bits<8>>,
    l_take: Signal<Local, Bit>,
    l_sq: Signal<Local, Bits<5>>,
    l_load: Signal<Local, Bit>,
    l_tsh: Signal<Local, Bits<160>>,
    l_tv: Signal<Local, Bits<10>>,
    l_tbyte: Signal<Local, Bits<104>>,
}

impl Engine {
    pub fn new(p: &SlcanParams) -> Self {
        let mut tbl: u128 = 0;
        let mut hi: u64 = 0;
        let mut valid = 0u64;
        for (n, e) in p.table.iter().enumerate() {
            if let Some((b0, b1)) = e {
                let v = ((*b0 as u64) << 8) | *b1 as u64;
                if n < 8 {
                    tbl |= (v as u128) << (16 * n);
                } else {
                    hi |= v << (16 * (n - 8));
                }
                valid |= 1 << n;
            }
        }
        let tbits: Bits<160> = (bit_cast::<160, 32>(hi.into()) << 128) | bit_cast::<160, 128>(super::bits128(tbl));
        let (d0, d1) = p.default_btr();
        Self {
            clock: Default::default(),
            rst: Default::default(),
            c_valid: Default::default(),
            c_data: Default::default(),
            c_pop: Default::default(),
            tx_busy: Default::default(),
            tx_start: Default::default(),
            tx_data: Default::default(),
            wb_cyc: Default::default(),
            wb_we: Default::default(),
            wb_adr: Default::default(),
            wb_dat_w: Default::default(),
            wb_dat_r: Default::default(),
            wb_ack: Default::default(),
            parser: Default::default(),
            reply: Default::default(),
            out: Default::default(),
            st: Default::default(),
            ret: Default::default(),
            wcyc: Default::default(),
            wwe: Default::default(),
            wadr: Default::default(),
            wdat: Default::default(),
            rd: Default::default(),
            open: Default::default(),
            lom: Default::default(),
            btr0: Default::default(),
            btr1: Default::default(),
            k: Default::default(),
            rk: Default::default(),
            srv: Default::default(),
            flags: Default::default(),
            rximg: Default::default(),
            wcnt: Default::default(),
            tx_wait: Constant::new((p.tx_wait_polls as u64).into()),
            tbl: Constant::new(tbits),
            tvalid: Constant::new(valid.into()),
            dbtr0: Constant::new((d0 as u64).into()),
            dbtr1: Constant::new((d1 as u64).into()),
            l_c: Default::default(),
            l_cmd: Default::default(),
            l_len: Default::default(),
            l_ok1: Default::default(),
            l_std: Default::default(),
            l_ext: Default::default(),
            l_rtr: Default::default(),
            l_flen: Default::default(),
            l_fok: Default::default(),
            l_ent: Default::default(),
            l_fi: Default::default(),
            l_timg: Default::default(),
            l_fl: Default::default(),
            l_take: Default::default(),
            l_sq: Default::default(),
            l_load: Default::default(),
            l_tsh: Default::default(),
            l_tv: Default::default(),
            l_tbyte: Default::default(),
        }
    }
}

impl Logic for Engine {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, st, ret, wcyc, wwe, wadr, wdat, rd, open, lom, btr0, btr1, k, rk, srv, flags, rximg, wcnt);

        // ---- the parsed line ----
        self.l_c.next = self.c_data.val().get_bits::<8>(0);
        self.l_cmd.next = self.parser.cmd.val();
        self.l_len.next = self.parser.len.val();
        self.l_ok1.next = !self.parser.bad.val() & (self.l_len.val() == 1);
        self.l_std.next = (self.l_cmd.val() == 0x74) | (self.l_cmd.val() == 0x72);
        self.l_ext.next = (self.l_cmd.val() == 0x54) | (self.l_cmd.val() == 0x52);
        self.l_rtr.next = (self.l_cmd.val() == 0x72) | (self.l_cmd.val() == 0x52);
        // the length a frame command must have
        self.l_flen.next = 5.into();
        if self.l_ext.val() {
            self.l_flen.next = 10.into();
        }
        if !self.l_rtr.val() {
            self.l_flen.next = self.l_flen.val() + (bit_cast::<5, 4>(self.parser.dlc.val()) << 1);
        }
        self.l_fok.next = !self.parser.bad.val() & (self.parser.dlc.val() <= 8) & (self.l_len.val() == self.l_flen.val());
        if self.l_std.val() & (self.parser.acc.val() > 0x7FF) {
            self.l_fok.next = false;
        }
        if self.l_ext.val() & (self.parser.acc.val() > 0x1FFFFFFF) {
            self.l_fok.next = false;
        }
        self.l_ent.next = 0.into();
        self.l_tsh.next = 0.into();
        self.l_tv.next = self.tvalid.val() >> self.parser.dlc.val();
        if self.parser.dlc.val() <= 9 {
            self.l_tsh.next = self.tbl.val() >> (bit_cast::<8, 4>(self.parser.dlc.val()) << 4);
            self.l_ent.next = self.l_tsh.val().get_bits::<16>(0);
        }

        // TSEG1 + TSEG2 of sxxyy (1 + t1 + t2 >= 8 TQ: TSEG1 + TSEG2 >= 5)
        self.l_sq.next = bit_cast::<5, 4>(self.parser.acc.val().get_bits::<4>(0))
            + bit_cast::<5, 3>(self.parser.acc.val().get_bits::<3>(4));

        // ---- the TX buffer image: 13 bytes, FI in bits 103..96 ----
        self.l_fi.next = bit_cast::<8, 4>(self.parser.dlc.val());
        if self.l_rtr.val() {
            self.l_fi.next = bit_cast::<8, 4>(self.parser.dlc.val()) | 0x40;
        }
        if self.l_ext.val() {
            self.l_timg.next = (bit_cast::<104, 8>(self.l_fi.val() | 0x80) << 96)
                | (bit_cast::<104, 32>(self.parser.acc.val()) << 67)
                | bit_cast::<104, 64>(self.parser.data.val());
        } else {
            self.l_timg.next = (bit_cast::<104, 8>(self.l_fi.val()) << 96)
                | (bit_cast::<104, 32>(self.parser.acc.val()) << 85)
                | (bit_cast::<104, 64>(self.parser.data.val()) << 16);
        }

        self.l_tbyte.next = self.l_timg.val() << (bit_cast::<7, 4>(self.k.q.val()) << 3);

        // ---- defaults ----
        self.l_take.next = false;
        self.l_load.next = false;
        self.l_fl.next = 0.into();

        match self.st.q.val() {
            EState::Idle => {
                if self.c_valid.val() {
                    self.l_take.next = true;
                    if self.l_c.val() == 0x0D {
                        self.st.d.next = EState::Exec;
                    }
                } else if self.open.q.val() {
                    // poll SR
                    self.wcyc.d.next = true;
                    self.wwe.d.next = false;
                    self.wadr.d.next = 0x02.into();
                    self.st.d.next = EState::WbWait;
                    self.ret.d.next = EState::PollChk;
                }
            }
            EState::Exec => {
                self.wcnt.d.next = 0.into();
                self.rk.d.next = 1.into();
                self.st.d.next = EState::Reply;
                if self.l_len.val() == 0 {
                    if !self.parser.bad.val() {
                        self.rk.d.next = 0.into();
                    }
                } else if self.l_cmd.val() == 0x53 {
                    // Sn
                    if !self.parser.bad.val()
                        & (self.l_len.val() == 2)
                        & !self.open.q.val()
                        & (self.parser.dlc.val() <= 9)
                    {
                        if self.l_tv.val().get_bit(0) {
                            self.btr0.d.next = self.l_ent.val().get_bits::<8>(8);
                            self.btr1.d.next = self.l_ent.val().get_bits::<8>(0);
                            self.rk.d.next = 0.into();
                        }
                    }
                } else if self.l_cmd.val() == 0x73 {
                    // sxxyy
                    // the settings the core refuses (TSEG1 = 0, under 8 TQ) answer BEL
                    if !self.parser.bad.val()
                        & (self.l_len.val() == 5)
                        & !self.open.q.val()
                        & (self.parser.acc.val().get_bits::<4>(0) != 0)
                        & (self.l_sq.val() >= 5)
                    {
                        self.btr0.d.next = self.parser.acc.val().get_bits::<8>(8);
                        self.btr1.d.next = self.parser.acc.val().get_bits::<8>(0);
                        self.rk.d.next = 0.into();
                    }
                } else if (self.l_cmd.val() == 0x4F) | (self.l_cmd.val() == 0x4C) {
                    // O, L
                    if self.l_ok1.val() & !self.open.q.val() {
                        self.lom.d.next = self.l_cmd.val() == 0x4C;
                        self.wcyc.d.next = true;
                        self.wwe.d.next = true;
                        self.wadr.d.next = 0x06.into();
                        self.wdat.d.next = self.btr0.q.val();
                        self.st.d.next = EState::WbWait;
                        self.ret.d.next = EState::OpenBtr1;
                    }
                } else if self.l_cmd.val() == 0x43 {
                    // C
                    if self.l_ok1.val() {
                        self.open.d.next = false;
                        self.rk.d.next = 0.into();
                        self.wcyc.d.next = true;
                        self.wwe.d.next = true;
                        self.wadr.d.next = 0x00.into();
                        self.wdat.d.next = 0x01.into();
                        self.st.d.next = EState::WbWait;
                        self.ret.d.next = EState::Reply;
                    }
                } else if self.l_std.val() | self.l_ext.val() {
                    if self.l_fok.val() & self.open.q.val() & !self.lom.q.val() {
                        self.rk.d.next = 2.into();
                        if self.l_ext.val() {
                            self.rk.d.next = 3.into();
                        }
                        self.wcyc.d.next = true;
                        self.wwe.d.next = false;
                        self.wadr.d.next = 0x02.into();
                        self.st.d.next = EState::WbWait;
                        self.ret.d.next = EState::TxCheck;
                    }
                } else if self.l_cmd.val() == 0x46 {
                    // F
                    if self.l_ok1.val() {
                        self.wcyc.d.next = true;
                        self.wwe.d.next = false;
                        self.wadr.d.next = 0x02.into();
                        self.st.d.next = EState::WbWait;
                        self.ret.d.next = EState::FIr;
                    }
                } else if self.l_cmd.val() == 0x56 {
                    if self.l_ok1.val() {
                        self.rk.d.next = 5.into();
                    }
                } else if self.l_cmd.val() == 0x4E {
                    if self.l_ok1.val() {
                        self.rk.d.next = 6.into();
                    }
                }
            }
            EState::WbWait => {
                if self.wb_ack.val() {
                    self.wcyc.d.next = false;
                    self.rd.d.next = self.wb_dat_r.val();
                    self.st.d.next = self.ret.q.val();
                }
            }
            EState::OpenBtr1 => {
                self.wcyc.d.next = true;
                self.wwe.d.next = true;
                self.wadr.d.next = 0x07.into();
                self.wdat.d.next = self.btr1.q.val();
                self.st.d.next = EState::WbWait;
                self.ret.d.next = EState::OpenIer;
            }
            EState::OpenIer => {
                self.wcyc.d.next = true;
                self.wwe.d.next = true;
                self.wadr.d.next = 0x04.into();
                self.wdat.d.next = 0xE8.into();
                self.st.d.next = EState::WbWait;
                self.ret.d.next = EState::OpenMod;
            }
            EState::OpenMod => {
                self.wcyc.d.next = true;
                self.wwe.d.next = true;
                self.wadr.d.next = 0x00.into();
                self.wdat.d.next = 0x00.into();
                if self.lom.q.val() {
                    self.wdat.d.next = 0x02.into();
                }
                self.open.d.next = true;
                self.rk.d.next = 0.into();
                self.st.d.next = EState::WbWait;
                self.ret.d.next = EState::Reply;
            }
            EState::TxCheck => {
                if self.rd.q.val().get_bit(7) {
                    // bus-off: the SJA1000 is in reset mode, where 0x10.. are
                    // the acceptance registers; refuse
                    self.rk.d.next = 1.into();
                    self.st.d.next = EState::Reply;
                } else if (self.rd.q.val() & 0x04) == 0 {
                    // TBS = 0: wait for the TX buffer (read SR again), BEL
                    // when it stays busy
                    self.wcnt.d.next = self.wcnt.q.val() + 1;
                    if self.wcnt.q.val() == self.tx_wait.val() {
                        self.rk.d.next = 1.into();
                        self.st.d.next = EState::Reply;
                    } else {
                        self.wcyc.d.next = true;
                        self.wwe.d.next = false;
                        self.wadr.d.next = 0x02.into();
                        self.st.d.next = EState::WbWait;
                        self.ret.d.next = EState::TxCheck;
                    }
                } else {
                    self.k.d.next = 0.into();
                    self.st.d.next = EState::TxLoad;
                }
            }
            EState::TxLoad => {
                self.wcyc.d.next = true;
                self.wwe.d.next = true;
                self.wadr.d.next = bit_cast::<8, 4>(self.k.q.val()) + 0x10;
                self.wdat.d.next = self.l_tbyte.val().get_bits::<8>(96);
                self.st.d.next = EState::WbWait;
                self.ret.d.next = EState::TxNext;
            }
            EState::TxNext => {
                if self.k.q.val() == 12 {
                    // CMR = TR
                    self.wcyc.d.next = true;
                    self.wwe.d.next = true;
                    self.wadr.d.next = 0x01.into();
                    self.wdat.d.next = 0x01.into();
                    self.st.d.next = EState::WbWait;
                    self.ret.d.next = EState::Reply;
                } else {
                    self.k.d.next = self.k.q.val() + 1;
                    self.st.d.next = EState::TxLoad;
                }
            }
            EState::FIr => {
                self.srv.d.next = self.rd.q.val();
                self.wcyc.d.next = true;
                self.wwe.d.next = false;
                self.wadr.d.next = 0x03.into();
                self.st.d.next = EState::WbWait;
                self.ret.d.next = EState::FDone;
            }
            EState::FDone => {
                // rd = IR, srv = SR
                self.l_fl.next = self.rd.q.val() & 0xE0;
                if self.srv.q.val().get_bit(1) {
                    // DOS: RX FIFO full (a frame was dropped) and data overrun
                    self.l_fl.next = self.l_fl.val() | 0x09;
                }
                if self.rd.q.val().get_bit(3) {
                    self.l_fl.next = self.l_fl.val() | 0x08;
                }
                if !self.srv.q.val().get_bit(2) {
                    self.l_fl.next = self.l_fl.val() | 0x02;
                }
                if self.srv.q.val().get_bit(6) {
                    self.l_fl.next = self.l_fl.val() | 0x04;
                }
                self.flags.d.next = self.l_fl.val();
                self.rk.d.next = 4.into();
                self.st.d.next = EState::Reply;
                if self.srv.q.val().get_bit(1) {
                    // CMR = CDO
                    self.wcyc.d.next = true;
                    self.wwe.d.next = true;
                    self.wadr.d.next = 0x01.into();
                    self.wdat.d.next = 0x08.into();
                    self.st.d.next = EState::WbWait;
                    self.ret.d.next = EState::Reply;
                }
            }
            EState::PollChk => {
                self.st.d.next = EState::Idle;
                if self.rd.q.val().get_bit(0) {
                    self.k.d.next = 0.into();
                    self.st.d.next = EState::RxRead;
                }
            }
            EState::RxRead => {
                self.wcyc.d.next = true;
                self.wwe.d.next = false;
                self.wadr.d.next = bit_cast::<8, 4>(self.k.q.val()) + 0x10;
                self.st.d.next = EState::WbWait;
                self.ret.d.next = EState::RxNext;
            }
            EState::RxNext => {
                self.rximg.d.next = (self.rximg.q.val() << 8) | bit_cast::<104, 8>(self.rd.q.val());
                if self.k.q.val() == 12 {
                    // CMR = RRB
                    self.rk.d.next = 7.into();
                    self.wcyc.d.next = true;
                    self.wwe.d.next = true;
                    self.wadr.d.next = 0x01.into();
                    self.wdat.d.next = 0x04.into();
                    self.st.d.next = EState::WbWait;
                    self.ret.d.next = EState::Reply;
                } else {
                    self.k.d.next = self.k.q.val() + 1;
                    self.st.d.next = EState::RxRead;
                }
            }
            EState::Reply => {
                if !self.out.busy.val() {
                    self.l_load.next = true;
                    self.st.d.next = EState::Idle;
                }
            }
        }

        // ---- the reply line ----
        self.reply.rk.next = self.rk.q.val();
        self.reply.flags.next = self.flags.q.val();
        self.reply.rximg.next = self.rximg.q.val();
        self.out.l_pre.next = self.reply.pre.val();
        self.out.l_haspre.next = self.reply.haspre.val();
        self.out.l_nib.next = self.reply.nib.val();
        self.out.l_cnt.next = self.reply.cnt.val();
        self.out.l_cr.next = self.reply.cr.val();

        if self.rst.val() {
            self.st.d.next = EState::Idle;
            self.ret.d.next = EState::Idle;
            self.wcyc.d.next = false;
            self.wwe.d.next = false;
            self.wadr.d.next = 0.into();
            self.wdat.d.next = 0.into();
            self.rd.d.next = 0.into();
            self.open.d.next = false;
            self.lom.d.next = false;
            self.btr0.d.next = self.dbtr0.val();
            self.btr1.d.next = self.dbtr1.val();
            self.k.d.next = 0.into();
            self.rk.d.next = 0.into();
            self.srv.d.next = 0.into();
            self.flags.d.next = 0.into();
            self.rximg.d.next = 0.into();
            self.wcnt.d.next = 0.into();
        }

        // ---- sub-blocks and outputs: each assigned once per evaluation, so
        // that no glitch of this block reaches another in an event-driven
        // simulator (a zero-delay loop with the line transmitter otherwise) ----
        self.parser.take.next = self.l_take.val();
        self.c_pop.next = self.l_take.val();
        self.out.load.next = self.l_load.val();
        self.parser.clock.next = self.clock.val();
        self.parser.rst.next = self.rst.val();
        self.parser.ch.next = self.c_data.val();
        self.out.clock.next = self.clock.val();
        self.out.rst.next = self.rst.val();
        self.out.tx_busy.next = self.tx_busy.val();
        self.tx_start.next = self.out.tx_start.val();
        self.tx_data.next = self.out.tx_data.val();

        self.wb_cyc.next = self.wcyc.q.val();
        self.wb_we.next = self.wwe.q.val();
        self.wb_adr.next = self.wadr.q.val();
        self.wb_dat_w.next = self.wdat.q.val();
    }
}

canstar_hdl::impl_clocked!(Engine);
