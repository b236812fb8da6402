//! [`Sja1000`]: the top of the register block: the Wishbone slave with the
//! address decoding and the read multiplexer, the status register, the
//! stored registers OCR, EWL and CDR, and the composition of [`CanCore`]
//! with the sub-blocks (behaviour: see the module documentation of
//! [`super`]).
//!
//! Addresses, write masks, reset values and bit positions come from
//! [`super::regs`] through `Constant` fields. Every sub-block input is
//! assigned once per evaluation (from a working value or a register), so
//! glitches inside this block's `always @(*)` never reach a sub-block in an
//! event-driven simulator.
//!
//! State: `ack` (the Wishbone acknowledge: a request was seen on the last
//! clock); `rdat`, `ramsel` (read data, or take the FIFO RAM's read data;
//! written on a read); `txram`, `txsel`, `ffsel`, `amr_def` (a block-RAM
//! copy of the transmit buffer and of ACR0..3/AMR0..3, written with them,
//! from which the host reads them: `txsel` on the acknowledge clock of such
//! a read, when `wb_dat_r` is the RAM's read data, or 0xFF (`ffsel`) for an
//! AMR byte not written since the hardware reset (`amr_def`, one bit per
//! AMR byte; the filter's AMR flip-flops are 0xFF then), and `rdat` takes
//! it, so that they read as the flip-flops would); `ocr`, `ewl`, `cdr` (stored registers, written in
//! the modes of the register table). `rst` clears `ack`, sets `amr_def` and
//! loads the table's reset values into `ocr`, `ewl` and `cdr`.
//!
//! Length: this file is about 650 lines and `update` about 350, over the
//! project's limits, because `update` is the one `#[hdl_gen]` body that
//! wires the core to ten sub-blocks and decodes every register address; the
//! decodes themselves live in the sub-blocks, and what is left is one
//! assignment per connection.

use super::capture::ErrorCapture;
use super::status::Status;
use super::fifo::RxFifo;
use super::filter::AcceptanceFilter;
use super::irq::Interrupts;
use super::mode::ModeControl;
use super::regs::{self, Reg};
use super::timing::BusTiming;
use super::txbuf::TxBuffer;
use super::txctl::TxControl;
use crate::core::CanCore;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct Sja1000 {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    pub wb_cyc: Signal<In, Bit>,
    pub wb_stb: Signal<In, Bit>,
    pub wb_we: Signal<In, Bit>,
    pub wb_adr: Signal<In, Bits<8>>,
    pub wb_dat_w: Signal<In, Bits<8>>,
    pub wb_dat_r: Signal<Out, Bits<8>>,
    pub wb_ack: Signal<Out, Bit>,
    pub rx: Signal<In, Bit>,
    pub tx: Signal<Out, Bit>,
    pub int_n: Signal<Out, Bit>,

    core: CanCore,
    timing: BusTiming,
    txbuf: TxBuffer,
    filter: AcceptanceFilter,
    fifo: RxFifo,
    capture: ErrorCapture,
    txctl: TxControl,
    status: Status,
    mode: ModeControl,
    irq: Interrupts,

    /// A copy of the transmit buffer (0..12) and of ACR0..3, AMR0..3
    /// (16..23) for host reads, written with them.
    txram: RAM<Bits<8>, 5>,
    ack: DFF<Bit>,
    rdat: DFF<Bits<8>>,
    ramsel: DFF<Bit>,
    txsel: DFF<Bit>,
    ffsel: DFF<Bit>,
    amr_def: DFF<Bits<4>>,
    ocr: DFF<Bits<8>>,
    ewl: DFF<Bits<8>>,
    cdr: DFF<Bits<8>>,

    // ---- the register map (from regs) as Constant fields ----
    a_mod: Constant<Bits<7>>,
    a_cmr: Constant<Bits<7>>,
    a_sr: Constant<Bits<7>>,
    a_ir: Constant<Bits<7>>,
    a_ier: Constant<Bits<7>>,
    a_btr0: Constant<Bits<7>>,
    a_btr1: Constant<Bits<7>>,
    a_ocr: Constant<Bits<7>>,
    a_alc: Constant<Bits<7>>,
    a_ecc: Constant<Bits<7>>,
    a_ewl: Constant<Bits<7>>,
    a_rxerr: Constant<Bits<7>>,
    a_txerr: Constant<Bits<7>>,
    a_acc: Constant<Bits<7>>,
    a_acc_end: Constant<Bits<7>>,
    a_win: Constant<Bits<7>>,
    a_win_end: Constant<Bits<7>>,
    a_rmc: Constant<Bits<7>>,
    a_rbsa: Constant<Bits<7>>,
    a_cdr: Constant<Bits<7>>,
    a_ram: Constant<Bits<7>>,
    a_ram_end: Constant<Bits<7>>,
    a_txb: Constant<Bits<7>>,
    a_txb_end: Constant<Bits<7>>,
    wm_cdr_op: Constant<Bits<8>>,
    wm_cdr_rm: Constant<Bits<8>>,
    rv_ewl: Constant<Bits<8>>,
    rv_ocr: Constant<Bits<8>>,
    rv_cdr: Constant<Bits<8>>,
    cmd_tr: Constant<Bits<3>>,
    cmd_at: Constant<Bits<3>>,
    cmd_rrb: Constant<Bits<3>>,
    cmd_cdo: Constant<Bits<3>>,
    cmd_srr: Constant<Bits<3>>,

    // ---- working values ----
    l_req: Signal<Local, Bit>,
    l_wr: Signal<Local, Bit>,
    l_rd: Signal<Local, Bit>,
    l_a: Signal<Local, Bits<7>>,
    l_d: Signal<Local, Bits<8>>,
    l_rm: Signal<Local, Bit>,
    l_win: Signal<Local, Bit>,
    l_ram_a: Signal<Local, Bit>,
    l_off: Signal<Local, Bits<7>>,
    l_txb_a: Signal<Local, Bit>,
    l_acc_a: Signal<Local, Bit>,
    l_racc: Signal<Local, Bit>,
    l_ra: Signal<Local, Bits<5>>,
    l_rram: Signal<Local, Bits<8>>,
    l_ramrd: Signal<Local, Bit>,
    l_rdv: Signal<Local, Bits<8>>,
    l_cdrm: Signal<Local, Bits<8>>,
    l_rrb: Signal<Local, Bit>,
    l_cdo: Signal<Local, Bit>,
    l_cmd: Signal<Local, Bit>,
    l_we_mod: Signal<Local, Bit>,
    l_we_ier: Signal<Local, Bit>,
    l_we_rxerr: Signal<Local, Bit>,
    l_we_txerr: Signal<Local, Bit>,
    l_we_btr0: Signal<Local, Bit>,
    l_we_btr1: Signal<Local, Bit>,
    l_we_acc: Signal<Local, Bit>,
    l_we_rbsa: Signal<Local, Bit>,
    l_we_txb: Signal<Local, Bit>,
    // interrupt events (IR bits)
}

fn a7(v: u8) -> Constant<Bits<7>> {
    Constant::new((v as u64).into())
}
fn b8(v: u8) -> Constant<Bits<8>> {
    Constant::new((v as u64).into())
}
fn p3(mask: u8) -> Constant<Bits<3>> {
    Constant::new((regs::pos(mask) as u64).into())
}
fn wmask(r: Reg, reset_mode: bool) -> Constant<Bits<8>> {
    b8(r.access(reset_mode).map_or(0, |a| a.wmask))
}

impl Sja1000 {
    fn build(btr0: u8, btr1: u8) -> Self {
        use regs::*;
        Self {
            clock: Default::default(),
            rst: Default::default(),
            wb_cyc: Default::default(),
            wb_stb: Default::default(),
            wb_we: Default::default(),
            wb_adr: Default::default(),
            wb_dat_w: Default::default(),
            wb_dat_r: Default::default(),
            wb_ack: Default::default(),
            rx: Default::default(),
            tx: Default::default(),
            int_n: Default::default(),
            core: CanCore::new(),
            timing: BusTiming::new(btr0, btr1),
            txbuf: Default::default(),
            filter: Default::default(),
            fifo: Default::default(),
            capture: Default::default(),
            txctl: Default::default(),
            status: Default::default(),
            mode: Default::default(),
            irq: Default::default(),
            // zero-initialised, as the buffer's flip-flops
            txram: (0..32).map(|_| Bits::<8>::from(0u64)).into(),
            ack: Default::default(),
            rdat: Default::default(),
            ramsel: Default::default(),
            txsel: Default::default(),
            ffsel: Default::default(),
            amr_def: Default::default(),
            ocr: Default::default(),
            ewl: Default::default(),
            cdr: Default::default(),
            a_mod: a7(MOD.addr),
            a_cmr: a7(CMR.addr),
            a_sr: a7(SR.addr),
            a_ir: a7(IR.addr),
            a_ier: a7(IER.addr),
            a_btr0: a7(BTR0.addr),
            a_btr1: a7(BTR1.addr),
            a_ocr: a7(OCR.addr),
            a_alc: a7(ALC.addr),
            a_ecc: a7(ECC.addr),
            a_ewl: a7(EWL.addr),
            a_rxerr: a7(RXERR.addr),
            a_txerr: a7(TXERR.addr),
            a_acc: a7(ACR.addr),
            a_acc_end: a7(AMR.last()),
            a_win: a7(RXBUF.addr),
            a_win_end: a7(RXBUF.last()),
            a_rmc: a7(RMC.addr),
            a_rbsa: a7(RBSA.addr),
            a_cdr: a7(CDR.addr),
            a_ram: a7(RXFIFO.addr),
            a_ram_end: a7(RXFIFO.last()),
            a_txb: a7(TXB.addr),
            a_txb_end: a7(TXB.last()),
            wm_cdr_op: wmask(CDR, false),
            wm_cdr_rm: wmask(CDR, true),
            rv_ewl: b8(EWL.reset.unwrap()),
            rv_ocr: b8(OCR.reset.unwrap()),
            rv_cdr: b8(CDR.reset.unwrap()),
            cmd_tr: p3(CMD_TR),
            cmd_at: p3(CMD_AT),
            cmd_rrb: p3(CMD_RRB),
            cmd_cdo: p3(CMD_CDO),
            cmd_srr: p3(CMD_SRR),
            l_req: Default::default(),
            l_wr: Default::default(),
            l_rd: Default::default(),
            l_a: Default::default(),
            l_d: Default::default(),
            l_rm: Default::default(),
            l_win: Default::default(),
            l_ram_a: Default::default(),
            l_off: Default::default(),
            l_txb_a: Default::default(),
            l_acc_a: Default::default(),
            l_racc: Default::default(),
            l_ra: Default::default(),
            l_rram: Default::default(),
            l_ramrd: Default::default(),
            l_rdv: Default::default(),
            l_cdrm: Default::default(),
            l_rrb: Default::default(),
            l_cdo: Default::default(),
            l_cmd: Default::default(),
            l_we_mod: Default::default(),
            l_we_ier: Default::default(),
            l_we_rxerr: Default::default(),
            l_we_txerr: Default::default(),
            l_we_btr0: Default::default(),
            l_we_btr1: Default::default(),
            l_we_acc: Default::default(),
            l_we_rbsa: Default::default(),
            l_we_txb: Default::default(),
        }
    }

    /// A new register block (hold `rst` high for a clock to initialise it).
    /// A hardware reset clears BTR0 and BTR1.
    pub fn new() -> Self {
        Self::build(0, 0)
    }

    /// As [`Sja1000::new`], with the values a hardware reset loads into BTR0
    /// and BTR1 (a real SJA1000 leaves them undefined), so that the
    /// controller runs at a chosen bit rate from power-up.
    pub fn with_reset_timing(btr0: u8, btr1: u8) -> Self {
        Self::build(btr0, btr1)
    }

    /// The same register block around a core with the REC rule `rule` for a
    /// dominant End_Of_Frame bit 7 (C13; ISO by default).
    pub fn with_rec_rule(mut self, rule: crate::core::RecRule) -> Self {
        self.core = std::mem::take(&mut self.core).with_rec_rule(rule);
        self
    }

    /// The wrapped CAN core (read-only, for tests and debugging: e.g. its
    /// `dbg_sample` strobe and `state`).
    pub fn core(&self) -> &CanCore {
        &self.core
    }
}

impl Default for Sja1000 {
    fn default() -> Self {
        Self::new()
    }
}

impl Logic for Sja1000 {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, ack, rdat, ramsel, txsel, ffsel, amr_def, ocr, ewl, cdr);
        self.txram.read_clock.next = self.clock.val();
        self.txram.write_clock.next = self.clock.val();

        // ---- Wishbone decode (address bit 7 ignored) ----
        self.l_req.next = self.wb_cyc.val() & self.wb_stb.val() & !self.ack.q.val();
        self.l_wr.next = self.l_req.val() & self.wb_we.val();
        self.l_rd.next = self.l_req.val() & !self.wb_we.val();
        self.l_a.next = self.wb_adr.val().get_bits::<7>(0);
        self.l_d.next = self.wb_dat_w.val();
        self.l_rm.next = !self.mode.opm.val();
        self.l_win.next = (self.l_a.val() >= self.a_win.val()) & (self.l_a.val() <= self.a_win_end.val());
        self.l_acc_a.next = (self.l_a.val() >= self.a_acc.val()) & (self.l_a.val() <= self.a_acc_end.val());
        self.l_ram_a.next = (self.l_a.val() >= self.a_ram.val()) & (self.l_a.val() <= self.a_ram_end.val());
        self.l_txb_a.next = (self.l_a.val() >= self.a_txb.val()) & (self.l_a.val() <= self.a_txb_end.val());
        // offset in the receive window or in the FIFO RAM
        self.l_off.next = self.l_a.val() - self.a_ram.val();
        if self.l_win.val() {
            self.l_off.next = self.l_a.val() - self.a_win.val();
        }

        // ---- Defaults ----
        self.ack.d.next = self.l_req.val();
        self.l_rrb.next = false;
        self.l_cdo.next = false;
        self.l_cmd.next = false;
        self.l_we_mod.next = false;
        self.l_we_ier.next = false;
        self.l_we_btr0.next = false;
        self.l_we_btr1.next = false;
        self.l_we_rxerr.next = false;
        self.l_we_txerr.next = false;
        self.l_we_acc.next = false;
        self.l_we_rbsa.next = false;

        // ---- Read data ----
        self.l_ramrd.next = false;
        self.l_rdv.next = 0.into();
        if self.l_a.val() == self.a_mod.val() {
            self.l_rdv.next = self.mode.rdata.val();
        }
        if self.l_a.val() == self.a_sr.val() {
            self.l_rdv.next = self.status.sr.val();
        }
        if self.l_a.val() == self.a_ir.val() {
            self.l_rdv.next = self.irq.ir.val();
        }
        if self.l_a.val() == self.a_ier.val() {
            self.l_rdv.next = self.irq.ier.val();
        }
        if self.l_a.val() == self.a_btr0.val() {
            self.l_rdv.next = self.timing.btr0.val();
        }
        if self.l_a.val() == self.a_btr1.val() {
            self.l_rdv.next = self.timing.btr1.val();
        }
        if self.l_a.val() == self.a_ocr.val() {
            self.l_rdv.next = self.ocr.q.val();
        }
        if self.l_a.val() == self.a_alc.val() {
            self.l_rdv.next = bit_cast::<8, 5>(self.capture.alc.val());
        }
        if self.l_a.val() == self.a_ecc.val() {
            self.l_rdv.next = self.capture.ecc.val();
        }
        if self.l_a.val() == self.a_ewl.val() {
            self.l_rdv.next = self.ewl.q.val();
        }
        if self.l_a.val() == self.a_rxerr.val() {
            self.l_rdv.next = self.status.rxerr.val();
        }
        if self.l_a.val() == self.a_txerr.val() {
            self.l_rdv.next = self.status.txerr.val();
        }
        // (ACR/AMR in reset mode: from the RAM copy, below)
        if !self.l_rm.val() & self.l_win.val() {
            self.l_ramrd.next = true;
        }
        if self.l_a.val() == self.a_rmc.val() {
            self.l_rdv.next = bit_cast::<8, 5>(self.fifo.rmc.val());
        }
        if self.l_a.val() == self.a_rbsa.val() {
            self.l_rdv.next = bit_cast::<8, 6>(self.fifo.rbsa.val());
        }
        if self.l_a.val() == self.a_cdr.val() {
            self.l_rdv.next = self.cdr.q.val();
        }
        if self.l_ram_a.val() {
            self.l_ramrd.next = true;
        }
        // The transmit buffer and ACR/AMR are read from their RAM copy: the
        // byte arrives on the acknowledge clock (`txsel`; `ffsel`: an AMR
        // byte not written since the hardware reset, 0xFF) and is kept in
        // `rdat` from then on.
        self.l_racc.next = self.l_rm.val() & self.l_acc_a.val();
        self.l_ra.next = bit_cast::<5, 4>(self.l_a.val().get_bits::<4>(0));
        self.l_ra.next = self.l_ra.val().replace_bit(4, self.l_racc.val());
        self.l_rram.next = self.txram.read_data.val();
        if self.ffsel.q.val() {
            self.l_rram.next = 0xFF.into();
        }
        self.txsel.d.next = false;
        if self.txsel.q.val() {
            self.rdat.d.next = self.l_rram.val();
        }
        if self.l_rd.val() {
            self.rdat.d.next = self.l_rdv.val();
            self.ramsel.d.next = self.l_ramrd.val();
            self.txsel.d.next = self.l_txb_a.val() | self.l_racc.val();
            self.ffsel.d.next = self.l_racc.val()
                & self.l_a.val().get_bit(2)
                & self.amr_def.q.val().get_bit(self.l_a.val().get_bits::<2>(0).index());
        }

        // ---- Writes ----
        self.l_cdrm.next = self.wm_cdr_op.val();
        if self.l_rm.val() {
            self.l_cdrm.next = self.wm_cdr_rm.val();
        }
        if self.l_wr.val() {
            self.l_we_mod.next = self.l_a.val() == self.a_mod.val();
            if self.l_a.val() == self.a_cmr.val() {
                self.l_cmd.next = true;
                self.l_rrb.next = self.l_d.val().get_bit(self.cmd_rrb.val().index()) & (self.fifo.rmc.val() != 0);
                self.l_cdo.next = self.l_d.val().get_bit(self.cmd_cdo.val().index());
            }
            self.l_we_ier.next = self.l_a.val() == self.a_ier.val();
            if self.l_a.val() == self.a_cdr.val() {
                // the writable bits of the mode; bit 4 (not in either mask) reads 0
                self.cdr.d.next = ((self.cdr.q.val() & !self.l_cdrm.val()) | (self.l_d.val() & self.l_cdrm.val()))
                    & (self.wm_cdr_op.val() | self.wm_cdr_rm.val());
            }
            if self.l_rm.val() {
                self.l_we_btr0.next = self.l_a.val() == self.a_btr0.val();
                self.l_we_btr1.next = self.l_a.val() == self.a_btr1.val();
                if self.l_a.val() == self.a_ocr.val() {
                    self.ocr.d.next = self.l_d.val();
                }
                if self.l_a.val() == self.a_ewl.val() {
                    self.ewl.d.next = self.l_d.val();
                }
                self.l_we_rxerr.next = self.l_a.val() == self.a_rxerr.val();
                self.l_we_txerr.next = self.l_a.val() == self.a_txerr.val();
                self.l_we_acc.next = self.l_acc_a.val();
                self.l_we_rbsa.next = self.l_a.val() == self.a_rbsa.val();
            }
        }
        // The transmit buffer: the window in operating mode (TBS = 1), 0x60.. in reset mode.
        self.l_we_txb.next = self.l_wr.val()
            & ((self.mode.opm.val() & self.l_win.val() & !self.txctl.pending.val())
                | (self.l_rm.val() & self.l_txb_a.val()));

        // AMR bytes read 0xFF from a hardware reset until written
        if self.l_we_acc.val() & self.l_a.val().get_bit(2) {
            self.amr_def.d.next = self
                .amr_def
                .q
                .val()
                .replace_bit(self.l_a.val().get_bits::<2>(0).index(), false);
        }

        // ---- Hardware reset ----
        if self.rst.val() {
            self.amr_def.d.next = 0xF.into();
            self.ack.d.next = false;
            self.ocr.d.next = self.rv_ocr.val();
            self.ewl.d.next = self.rv_ewl.val();
            self.cdr.d.next = self.rv_cdr.val();
        }

        // ---- Sub-blocks (each input assigned once) ----
        self.core.clock.next = self.clock.val();
        self.core.reset.next = self.rst.val() | (!self.mode.opm.val() & !self.status.hold.val());
        self.core.rx.next = self.rx.val();
        self.core.brp.next = self.timing.brp.val();
        self.core.prop.next = self.timing.prop.val();
        self.core.ph1.next = self.timing.ph1.val();
        self.core.ph2.next = self.timing.ph2.val();
        self.core.sjw.next = self.timing.sjw.val();
        self.core.triple.next = self.timing.triple.val();
        self.core.listen_only.next = self.mode.lom.val();
        self.core.self_test.next = self.mode.stm.val();
        self.core.single_shot.next = self.txctl.single_shot.val();
        self.core.host_recovery.next = true;
        self.core.recover.next = self.mode.recover.val();
        self.core.tx_req.next = self.txctl.req.val();
        self.core.tx_ide.next = self.txbuf.ide.val();
        self.core.tx_rtr.next = self.txbuf.rtr.val();
        self.core.tx_id.next = self.txbuf.id.val();
        self.core.tx_dlc.next = self.txbuf.dlc.val();
        self.core.tx_data.next = self.txbuf.data.val();
        self.core.tx_abort.next = self.txctl.abort.val();
        self.core.cnt_load.next = self.status.cnt_load.val();
        self.core.tec_in.next = self.status.tec_in.val();
        self.core.rec_in.next = self.status.rec_in.val();

        self.timing.clock.next = self.clock.val();
        self.timing.rst.next = self.rst.val();
        self.timing.we0.next = self.l_we_btr0.val();
        self.timing.we1.next = self.l_we_btr1.val();
        self.timing.wdata.next = self.l_d.val();

        self.txbuf.clock.next = self.clock.val();
        self.txbuf.we.next = self.l_we_txb.val();
        self.txbuf.idx.next = self.l_a.val().get_bits::<4>(0);
        self.txbuf.wdata.next = self.l_d.val();
        // (entry 15 is never written: between reads the read register holds
        // 0, which a model built from a running instance starts from)
        self.txram.read_address.next = 15.into();
        if self.l_rd.val() & (self.l_txb_a.val() | self.l_racc.val()) {
            self.txram.read_address.next = self.l_ra.val();
        }
        self.txram.write_address.next = self.l_ra.val();
        self.txram.write_data.next = self.l_d.val();
        self.txram.write_enable.next = self.l_we_txb.val() | self.l_we_acc.val();

        self.txctl.clock.next = self.clock.val();
        self.txctl.rst.next = self.rst.val();
        self.txctl.opm.next = self.mode.opm.val();
        self.txctl.sleep.next = self.mode.sleep.val();
        self.txctl.enter_rm.next = self.mode.enter_rm.val();
        self.txctl.cmd.next = self.l_cmd.val();
        self.txctl.tr.next = self.l_d.val().get_bit(self.cmd_tr.val().index());
        self.txctl.at.next = self.l_d.val().get_bit(self.cmd_at.val().index());
        self.txctl.srr.next = self.l_d.val().get_bit(self.cmd_srr.val().index());
        self.txctl.tx_done.next = self.core.tx_done.val();
        self.txctl.arb_lost.next = self.core.arb_lost.val();
        self.txctl.error.next = self.core.error.val();
        self.txctl.err_tx.next = self.core.err_tx.val();
        self.txctl.tx_rqst.next = self.core.dbg_tx_rqst.val();
        self.txctl.txact.next = self.status.txact.val();
        self.txctl.own_done.next = self.fifo.own_done.val();
        self.txctl.own_dropped.next = self.fifo.own_dropped.val();

        self.status.clock.next = self.clock.val();
        self.status.rst.next = self.rst.val();
        self.status.opm.next = self.mode.opm.val();
        self.status.state.next = self.core.state.val();
        self.status.tec.next = self.core.tec.val();
        self.status.rec.next = self.core.rec.val();
        self.status.runs.next = self.core.dbg_runs.val();
        self.status.cfg_err.next = self.core.cfg_err.val();
        self.status.ewl.next = self.ewl.q.val();
        self.status.wr_rxerr.next = self.l_we_rxerr.val();
        self.status.wr_txerr.next = self.l_we_txerr.val();
        self.status.wdata.next = self.l_d.val();
        self.status.rbs.next = self.fifo.rmc.val() != 0;
        self.status.dos.next = self.fifo.dos.val();
        self.status.tbs.next = !self.txctl.pending.val();
        self.status.tcs.next = self.txctl.tcs.val();
        self.status.field.next = self.core.dbg_field.val();
        self.status.role.next = self.core.dbg_role.val();

        self.filter.clock.next = self.clock.val();
        self.filter.rst.next = self.rst.val();
        self.filter.we.next = self.l_we_acc.val();
        self.filter.idx.next = self.l_a.val().get_bits::<3>(0);
        self.filter.wdata.next = self.l_d.val();
        self.filter.single.next = self.mode.afm.val();
        self.filter.ide.next = self.core.rx_ide.val();
        self.filter.rtr.next = self.core.rx_rtr.val();
        self.filter.id.next = self.core.rx_id.val();
        self.filter.n.next = self.fifo.rx_n.val();
        self.filter.d01.next = self.core.rx_data.val().get_bits::<16>(48);
        self.filter.own_ide.next = self.txbuf.ide.val();
        self.filter.own_rtr.next = self.txbuf.rtr.val();
        self.filter.own_id.next = self.txbuf.id.val();
        self.filter.own_n.next = self.fifo.own_n.val();
        self.filter.own_d01.next = self.txbuf.data.val().get_bits::<16>(48);

        self.fifo.clock.next = self.clock.val();
        self.fifo.rst.next = self.rst.val();
        self.fifo.clear.next = self.mode.enter_rm.val();
        self.fifo.offer_rx.next = self.core.rx_valid.val() & self.mode.opm.val();
        self.fifo.offer_own.next = self.txctl.own_offer.val();
        self.fifo.rx_ide.next = self.core.rx_ide.val();
        self.fifo.rx_rtr.next = self.core.rx_rtr.val();
        self.fifo.rx_id.next = self.core.rx_id.val();
        self.fifo.rx_dlc.next = self.core.rx_dlc.val();
        self.fifo.rx_data.next = self.core.rx_data.val();
        self.fifo.own_ide.next = self.txbuf.ide.val();
        self.fifo.own_rtr.next = self.txbuf.rtr.val();
        self.fifo.own_id.next = self.txbuf.id.val();
        self.fifo.own_dlc.next = self.txbuf.dlc.val();
        self.fifo.own_data.next = self.txbuf.data.val();
        self.fifo.accept.next = self.filter.accept.val();
        self.fifo.accept_own.next = self.filter.accept_own.val();
        self.fifo.rrb.next = self.l_rrb.val();
        self.fifo.cdo.next = self.l_cdo.val();
        self.fifo.rbsa_we.next = self.l_we_rbsa.val();
        self.fifo.ram_we.next = self.l_wr.val() & self.l_rm.val() & self.l_ram_a.val();
        self.fifo.wdata.next = self.l_d.val();
        self.fifo.host_rd.next = self.l_rd.val() & self.l_ramrd.val();
        self.fifo.host_win.next = self.l_win.val();
        self.fifo.host_idx.next = self.l_off.val().get_bits::<6>(0);

        self.mode.clock.next = self.clock.val();
        self.mode.rst.next = self.rst.val();
        self.mode.wr.next = self.l_we_mod.val();
        self.mode.wdata.next = self.l_d.val();
        self.mode.may_sleep.next =
            (self.irq.ir.val() == 0) & self.status.idle.val() & !self.txctl.pending.val();
        self.mode.bus_dom.next = self.core.dbg_sample.val() & !self.core.dbg_busmon.val();
        self.mode.busoff.next = self.status.busoff.val();
        self.mode.hold.next = self.status.hold.val();

        self.irq.clock.next = self.clock.val();
        self.irq.rst.next = self.rst.val();
        self.irq.wr_ier.next = self.l_we_ier.val();
        self.irq.wdata.next = self.l_d.val();
        self.irq.rd_ir.next = self.l_rd.val() & (self.l_a.val() == self.a_ir.val());
        self.irq.rbs.next = self.fifo.rmc.val() != 0;
        self.irq.ti.next = self.txctl.ti.val();
        self.irq.ei.next = self.status.ei.val();
        self.irq.doi.next = self.fifo.overrun.val();
        self.irq.wui.next = self.mode.wui.val();
        self.irq.epi.next = self.status.epi.val();
        self.irq.ali.next = self.core.arb_lost.val();
        self.irq.bei.next = self.core.error.val();

        self.capture.clock.next = self.clock.val();
        self.capture.rst.next = self.rst.val();
        self.capture.arb_lost.next = self.core.arb_lost.val();
        self.capture.arb_lost_pos.next = self.core.arb_lost_pos.val();
        self.capture.error.next = self.core.error.val();
        self.capture.err_kind.next = self.core.err_kind.val();
        self.capture.err_field.next = self.core.err_field.val();
        self.capture.err_pos.next = self.core.err_pos.val();
        self.capture.err_tx.next = self.core.err_tx.val();
        self.capture.field.next = self.core.dbg_field.val();
        self.capture.rd_alc.next = self.l_rd.val() & (self.l_a.val() == self.a_alc.val());
        self.capture.rd_ecc.next = self.l_rd.val() & (self.l_a.val() == self.a_ecc.val());

        // ---- Outputs ----
        self.tx.next = self.core.tx.val();
        self.wb_ack.next = self.ack.q.val();
        self.wb_dat_r.next = self.rdat.q.val();
        if self.ramsel.q.val() {
            self.wb_dat_r.next = self.fifo.rdata.val();
        }
        if self.txsel.q.val() {
            self.wb_dat_r.next = self.l_rram.val();
        }
        self.int_n.next = self.irq.int_n.val();
    }
}

canstar_hdl::impl_clocked!(Sja1000);
