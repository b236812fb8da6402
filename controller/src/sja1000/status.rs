//! [`Status`]: the status register SR, the error counters as the host
//! sees them (RXERR, TXERR), the error and bus status (ES, BS,
//! error-passive) with their interrupts (EI, EPI), the bus-off hold and the
//! counter load of reset mode (see "Error counters", "Bus-off" and "TS/RS"
//! in the module documentation of [`super`]).
//!
//! SR: RBS, DOS, TBS and TCS come from the FIFO and the transmission
//! control; RS and TS are both 1 while the core waits for bus idle (reset,
//! integration, bus-off), otherwise RS = receiving and TS = transmitting a
//! frame (Start_Of_Frame to the end of error/overload frames), from the
//! core's FIELD (codes in `Constant` fields from [`crate::fsm::Field`]) and
//! role. Bit positions come from the register table.
//!
//! Reset mode proper (`opm` low, not the bus-off hold) holds the core in
//! reset with its counters loaded every clock (`cnt_load`) from their own
//! values or from a host write of TXERR/RXERR; ES, BS and error-passive are
//! frozen then. A bus-off of the core (outside reset mode) sets RM
//! (`busoff`) without resetting the core (`boff`, the bus-off hold); the
//! hold ends when the core leaves bus-off or with a TXERR write. While
//! bus-off TXERR reads 127 − completed recovery runs and RXERR 0; a loaded
//! TEC of 256 reads 255.
//!
//! State: `boff` (the bus-off hold); `core_bs` (the core was bus-off on the
//! last clock outside reset mode proper); `es_q`, `bs_q`, `pas_q` (ES, BS
//! and error-passive as last seen, for the EI/EPI edges). All reset by
//! `rst`.

use super::regs;
use crate::fsm::Field;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct Status {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    pub opm: Signal<In, Bit>,
    /// The core's state (2 = bus-off), counters, completed recovery runs
    /// and timing rejection.
    pub state: Signal<In, Bits<2>>,
    pub tec: Signal<In, Bits<9>>,
    pub rec: Signal<In, Bits<8>>,
    pub runs: Signal<In, Bits<8>>,
    pub cfg_err: Signal<In, Bit>,
    /// The error warning limit.
    pub ewl: Signal<In, Bits<8>>,
    /// Host writes of RXERR / TXERR (reset mode) with their data.
    pub wr_rxerr: Signal<In, Bit>,
    pub wr_txerr: Signal<In, Bit>,
    pub wdata: Signal<In, Bits<8>>,
    /// For SR: a message in the FIFO, data overrun, TBS, TCS; the core's
    /// FIELD and role.
    pub rbs: Signal<In, Bit>,
    pub dos: Signal<In, Bit>,
    pub tbs: Signal<In, Bit>,
    pub tcs: Signal<In, Bit>,
    pub field: Signal<In, Bits<5>>,
    pub role: Signal<In, Bit>,

    /// SR as read.
    pub sr: Signal<Out, Bits<8>>,
    /// The core transmits a frame (Start_Of_Frame .. End_Of_Frame); the bus
    /// is idle (Bus_Idle).
    pub txact: Signal<Out, Bit>,
    pub idle: Signal<Out, Bit>,
    pub rxerr: Signal<Out, Bits<8>>,
    pub txerr: Signal<Out, Bits<8>>,
    pub es: Signal<Out, Bit>,
    pub bs: Signal<Out, Bit>,
    pub ei: Signal<Out, Bit>,
    pub epi: Signal<Out, Bit>,
    /// The core went bus-off: enter reset mode.
    pub busoff: Signal<Out, Bit>,
    pub hold: Signal<Out, Bit>,
    /// The core's counter load.
    pub cnt_load: Signal<Out, Bit>,
    pub tec_in: Signal<Out, Bits<9>>,
    pub rec_in: Signal<Out, Bits<8>>,

    boff: DFF<Bit>,
    core_bs: DFF<Bit>,
    es_q: DFF<Bit>,
    bs_q: DFF<Bit>,
    pas_q: DFF<Bit>,

    l_frz: Signal<Local, Bit>,
    l_cbsr: Signal<Local, Bit>,
    l_tecv: Signal<Local, Bits<8>>,
    l_recv: Signal<Local, Bits<8>>,
    l_pas: Signal<Local, Bit>,
    l_cload: Signal<Local, Bit>,
    l_wait: Signal<Local, Bit>,
    l_busy: Signal<Local, Bit>,
    l_sr: Signal<Local, Bits<8>>,
    f_idle: Constant<Bits<5>>,
    /// FIELD classes as one bit per code (`field_set`): waiting for bus
    /// idle (Reset, WaitIdle, BusOff), busy (Start_Of_Frame and later),
    /// the frame fields (Start_Of_Frame ..= End_Of_Frame).
    m_wait: Constant<Bits<32>>,
    m_busy: Constant<Bits<32>>,
    m_frame: Constant<Bits<32>>,
    sr_rbs: Constant<Bits<3>>,
    sr_dos: Constant<Bits<3>>,
    sr_tbs: Constant<Bits<3>>,
    sr_tcs: Constant<Bits<3>>,
    sr_rs: Constant<Bits<3>>,
    sr_ts: Constant<Bits<3>>,
    sr_es: Constant<Bits<3>>,
    sr_bs: Constant<Bits<3>>,
}

fn f5(f: Field) -> Constant<Bits<5>> {
    Constant::new(f.code().into())
}

/// The FIELD codes of `fields` as one bit per code: a class is then one
/// bit select of the 5-bit code (a LUT), where comparisons with constants
/// map to carry chains.
fn field_set(fields: impl Iterator<Item = Field>) -> Constant<Bits<32>> {
    Constant::new(fields.fold(0u64, |m, f| m | (1 << f.code())).into())
}

fn p3(mask: u8) -> Constant<Bits<3>> {
    Constant::new((regs::pos(mask) as u64).into())
}

impl Default for Status {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            rst: Default::default(),
            opm: Default::default(),
            state: Default::default(),
            tec: Default::default(),
            rec: Default::default(),
            runs: Default::default(),
            cfg_err: Default::default(),
            ewl: Default::default(),
            wr_rxerr: Default::default(),
            wr_txerr: Default::default(),
            wdata: Default::default(),
            rbs: Default::default(),
            dos: Default::default(),
            tbs: Default::default(),
            tcs: Default::default(),
            field: Default::default(),
            role: Default::default(),
            sr: Default::default(),
            txact: Default::default(),
            idle: Default::default(),
            rxerr: Default::default(),
            txerr: Default::default(),
            es: Default::default(),
            bs: Default::default(),
            ei: Default::default(),
            epi: Default::default(),
            busoff: Default::default(),
            hold: Default::default(),
            cnt_load: Default::default(),
            tec_in: Default::default(),
            rec_in: Default::default(),
            boff: Default::default(),
            core_bs: Default::default(),
            es_q: Default::default(),
            bs_q: Default::default(),
            pas_q: Default::default(),
            l_frz: Default::default(),
            l_cbsr: Default::default(),
            l_tecv: Default::default(),
            l_recv: Default::default(),
            l_pas: Default::default(),
            l_cload: Default::default(),
            l_wait: Default::default(),
            l_busy: Default::default(),
            l_sr: Default::default(),
            f_idle: f5(Field::Idle),
            m_wait: field_set([Field::Reset, Field::WaitIdle, Field::BusOff].into_iter()),
            m_busy: field_set(Field::ALL.into_iter().filter(|f| f.code() >= Field::Sof.code())),
            m_frame: field_set(
                Field::ALL.into_iter().filter(|f| (Field::Sof.code()..=Field::Eof.code()).contains(&f.code())),
            ),
            sr_rbs: p3(regs::SR_RBS),
            sr_dos: p3(regs::SR_DOS),
            sr_tbs: p3(regs::SR_TBS),
            sr_tcs: p3(regs::SR_TCS),
            sr_rs: p3(regs::SR_RS),
            sr_ts: p3(regs::SR_TS),
            sr_es: p3(regs::SR_ES),
            sr_bs: p3(regs::SR_BS),
        }
    }
}

impl Logic for Status {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, boff, core_bs, es_q, bs_q, pas_q);
        self.l_frz.next = !self.opm.val() & !self.boff.q.val();
        // the core's state code 2: bus-off
        self.l_cbsr.next = self.state.val() == 2;
        self.l_tecv.next = self.tec.val().get_bits::<8>(0);
        if self.tec.val() >= 256 {
            self.l_tecv.next = 255.into();
        }
        self.l_recv.next = self.rec.val();
        if self.l_cbsr.val() & !self.l_frz.val() {
            self.l_tecv.next = 127 - self.runs.val();
            self.l_recv.next = 0.into();
        }
        self.bs.next = self.l_cbsr.val();
        self.es.next = self.l_cbsr.val() | (self.l_tecv.val() >= self.ewl.val()) | (self.l_recv.val() >= self.ewl.val());
        self.l_pas.next = !self.l_cbsr.val() & ((self.l_tecv.val() >= 128) | (self.l_recv.val() >= 128));
        if self.l_frz.val() {
            self.bs.next = self.bs_q.q.val();
            self.es.next = self.es_q.q.val();
            self.l_pas.next = self.pas_q.q.val();
        }
        self.core_bs.d.next = self.l_cbsr.val() & !self.l_frz.val();
        self.es_q.d.next = self.es.val();
        self.bs_q.d.next = self.bs.val();
        self.pas_q.d.next = self.l_pas.val();

        // Counter load: every clock in reset mode (the core holds its own
        // values, or takes a host write) and while the timing is rejected.
        self.l_cload.next = self.l_frz.val() | self.cfg_err.val();
        self.tec_in.next = self.tec.val();
        self.rec_in.next = self.rec.val();
        if self.wr_rxerr.val() & self.l_frz.val() {
            // (no effect while bus-off)
            self.l_cload.next = true;
            self.rec_in.next = self.wdata.val();
        }
        if self.wr_txerr.val() {
            // 255: CPU-driven bus-off when reset mode is left
            self.l_cload.next = true;
            self.tec_in.next = bit_cast::<9, 8>(self.wdata.val());
            if self.wdata.val() == 255 {
                self.tec_in.next = 256.into();
            }
            if self.boff.q.val() {
                // ends the bus-off hold: the core restarts from the
                // written value (integration of 11 recessive bits)
                self.boff.d.next = false;
                self.rec_in.next = 0.into();
                if self.wdata.val() != 255 {
                    self.bs_q.d.next = false;
                }
            }
        }

        // Status changes and bus-off.
        self.ei.next = (self.es.val() != self.es_q.q.val()) | (self.bs.val() != self.bs_q.q.val());
        self.epi.next = (self.l_pas.val() & !self.pas_q.q.val())
            | (!self.l_pas.val() & self.pas_q.q.val() & !self.bs.val());
        self.busoff.next = self.l_cbsr.val() & !self.l_frz.val() & !self.core_bs.q.val();
        if self.busoff.val() {
            // reset mode, core kept in its bus-off state
            self.boff.d.next = true;
            self.ei.next = true;
        }
        if !self.l_cbsr.val() & self.core_bs.q.val() {
            self.boff.d.next = false;
        }
        if self.rst.val() {
            self.boff.d.next = false;
            self.core_bs.d.next = false;
            self.es_q.d.next = false;
            self.bs_q.d.next = false;
            self.pas_q.d.next = false;
        }

        // The core's activity and SR.
        self.l_wait.next = self.m_wait.val().get_bit(self.field.val().index());
        self.l_busy.next = self.m_busy.val().get_bit(self.field.val().index());
        self.txact.next = self.role.val() & self.m_frame.val().get_bit(self.field.val().index());
        self.idle.next = self.field.val() == self.f_idle.val();
        self.l_sr.next = 0.into();
        self.l_sr.next = self.l_sr.val().replace_bit(self.sr_rbs.val().index(), self.rbs.val());
        self.l_sr.next = self.l_sr.val().replace_bit(self.sr_dos.val().index(), self.dos.val());
        self.l_sr.next = self.l_sr.val().replace_bit(self.sr_tbs.val().index(), self.tbs.val());
        self.l_sr.next = self.l_sr.val().replace_bit(self.sr_tcs.val().index(), self.tcs.val());
        self.l_sr.next = self
            .l_sr
            .val()
            .replace_bit(self.sr_rs.val().index(), self.l_wait.val() | (self.l_busy.val() & !self.role.val()));
        self.l_sr.next = self
            .l_sr
            .val()
            .replace_bit(self.sr_ts.val().index(), self.l_wait.val() | (self.l_busy.val() & self.role.val()));
        self.l_sr.next = self.l_sr.val().replace_bit(self.sr_es.val().index(), self.es.val());
        self.l_sr.next = self.l_sr.val().replace_bit(self.sr_bs.val().index(), self.bs.val());
        self.sr.next = self.l_sr.val();

        self.rxerr.next = self.l_recv.val();
        self.txerr.next = self.l_tecv.val();
        self.hold.next = self.boff.q.val();
        self.cnt_load.next = self.l_cload.val() & !self.rst.val();
    }
}

canstar_hdl::impl_clocked!(Status);
