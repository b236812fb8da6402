//! [`TxControl`]: the transmit commands of CMR and the transmission state
//! behind TBS, TCS and TI (see "Commands" and "Self-reception" in the
//! module documentation of [`super`]).
//!
//! TR or SRR (`cmd` with `tr`/`srr`, operating mode) starts a transmission
//! when TBS = 1 and the node is not sleeping; with AT in the same write it
//! is single shot, and TCS goes to 0 (data sheet, status register, note on
//! TCS: it stays 0 until a transmission succeeds). AT alone while a transmission is pending aborts it: at
//! once if it has not started, else the core ends it after the frame. A
//! transmission ends (TBS = 1 again, `ti`) on success (TCS = 1), on a
//! failure of a single-shot or aborted transmission (TCS = 0), or, for a
//! self reception request, when the own frame has been copied into the
//! FIFO or dropped there (`own_done`, `own_dropped`). Entering reset mode
//! cancels a pending transmission without TI.
//!
//! State: `pend` (a transmission is pending: TBS = 0), `single` (single
//! shot), `srr` (self reception request), `abrt` (an abort was requested),
//! `lb` (the own frame was sent and is being copied into the FIFO), `tcs_n`
//! (!TCS). A hardware reset clears `pend`, `lb`, `abrt` and `tcs_n`.

use rust_hdl::prelude::*;

#[derive(LogicBlock, Default)]
pub struct TxControl {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    pub opm: Signal<In, Bit>,
    pub sleep: Signal<In, Bit>,
    pub enter_rm: Signal<In, Bit>,
    /// A write of CMR, with its TR, AT and SRR bits.
    pub cmd: Signal<In, Bit>,
    pub tr: Signal<In, Bit>,
    pub at: Signal<In, Bit>,
    pub srr: Signal<In, Bit>,
    /// The core: success, arbitration lost, error (as transmitter), the
    /// request as the protocol sees it, a frame of its own in progress.
    pub tx_done: Signal<In, Bit>,
    pub arb_lost: Signal<In, Bit>,
    pub error: Signal<In, Bit>,
    pub err_tx: Signal<In, Bit>,
    pub tx_rqst: Signal<In, Bit>,
    pub txact: Signal<In, Bit>,
    /// The FIFO stored / dropped the own frame (self reception).
    pub own_done: Signal<In, Bit>,
    pub own_dropped: Signal<In, Bit>,

    pub pending: Signal<Out, Bit>,
    pub single_shot: Signal<Out, Bit>,
    /// The core's request and abort.
    pub req: Signal<Out, Bit>,
    pub abort: Signal<Out, Bit>,
    pub tcs: Signal<Out, Bit>,
    /// The own frame of a self reception request was sent: offer it to the FIFO.
    pub own_offer: Signal<Out, Bit>,
    /// TBS returns to 1 (TI).
    pub ti: Signal<Out, Bit>,

    pend: DFF<Bit>,
    single: DFF<Bit>,
    srr_r: DFF<Bit>,
    abrt: DFF<Bit>,
    lb: DFF<Bit>,
    tcs_n: DFF<Bit>,

    l_txok: Signal<Local, Bit>,
    l_fail: Signal<Local, Bit>,
    l_rel: Signal<Local, Bit>,
}

impl Logic for TxControl {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, pend, single, srr_r, abrt, lb, tcs_n);
        self.l_txok.next = self.pend.q.val() & self.tx_done.val();
        self.abort.next = false;
        if self.cmd.val() & self.opm.val() {
            if (self.tr.val() | self.srr.val()) & !self.pend.q.val() & !self.sleep.val() {
                self.pend.d.next = true;
                self.single.d.next = self.at.val();
                self.srr_r.d.next = self.srr.val();
                self.abrt.d.next = false;
                // the data sheet's note on TCS: cleared by the request
                self.tcs_n.d.next = true;
            } else if self.at.val() & self.pend.q.val() & !self.lb.q.val() {
                self.abort.next = true;
                self.abrt.d.next = true;
            }
        }

        // Progress of the pending transmission.
        self.l_fail.next = self.pend.q.val()
            & !self.lb.q.val()
            & (self.single.q.val() | self.abrt.q.val())
            & (self.arb_lost.val() | (self.error.val() & self.err_tx.val()));
        if self.pend.q.val()
            & self.abrt.q.val()
            & !self.lb.q.val()
            & !self.tx_rqst.val()
            & !self.txact.val()
            & !self.l_txok.val()
        {
            // aborted before it started
            self.l_fail.next = true;
        }
        self.l_rel.next = false;
        if self.l_txok.val() {
            self.tcs_n.d.next = false;
            if self.srr_r.q.val() {
                self.lb.d.next = true;
            } else {
                self.l_rel.next = true;
            }
        } else if self.l_fail.val() {
            self.tcs_n.d.next = true;
            self.l_rel.next = true;
        }
        if self.own_done.val() | self.own_dropped.val() {
            self.l_rel.next = true;
            self.lb.d.next = false;
        }
        if self.l_rel.val() {
            self.pend.d.next = false;
        }
        if self.enter_rm.val() {
            self.pend.d.next = false;
            self.lb.d.next = false;
            self.abrt.d.next = false;
        }
        if self.rst.val() {
            self.pend.d.next = false;
            self.lb.d.next = false;
            self.abrt.d.next = false;
            self.tcs_n.d.next = false;
        }

        self.pending.next = self.pend.q.val();
        self.single_shot.next = self.single.q.val();
        self.req.next = self.pend.q.val() & !self.lb.q.val() & self.opm.val();
        self.tcs.next = !self.tcs_n.q.val();
        self.own_offer.next = self.l_txok.val() & self.srr_r.q.val() & self.opm.val();
        self.ti.next = self.l_rel.val() & !self.enter_rm.val();
    }
}

canstar_hdl::impl_clocked!(TxControl);
