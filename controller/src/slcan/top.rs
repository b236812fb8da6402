//! [`SlcanTop`]: the USB-to-CAN adapter: UART receiver → character queue →
//! [`Engine`] (parser, sequencer, line transmitter) → UART transmitter, and
//! the engine's Wishbone master on a [`Sja1000`] whose `rx`/`tx` are the
//! CAN pins. The SJA1000's interrupt output is not used (the engine polls
//! SR); it has no state of its own beyond its sub-blocks.
//!
//! Ports: `clock`, `rst` (synchronous, active high: resets every
//! sub-block; the channel is closed after it), `uart_rx` (from the host,
//! asynchronous), `uart_tx` (to the host, registered, 1 when idle), `rx`
//! (CAN bus level, asynchronous), `tx` (CAN, registered, 1 = recessive).
//! Generation-time parameters: [`SlcanParams`] (UART divider, `Sn` table).

use super::engine::Engine;
use super::infifo::InFifo;
use super::uart::{UartRx, UartTx};
use super::SlcanParams;
use crate::sja1000::Sja1000;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct SlcanTop {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    pub uart_rx: Signal<In, Bit>,
    pub uart_tx: Signal<Out, Bit>,
    pub rx: Signal<In, Bit>,
    pub tx: Signal<Out, Bit>,

    urx: UartRx,
    utx: UartTx,
    queue: InFifo,
    engine: Engine,
    can: Sja1000,
}

impl SlcanTop {
    pub fn new(p: &SlcanParams) -> Self {
        let (b0, b1) = p.default_btr();
        Self {
            clock: Default::default(),
            rst: Default::default(),
            uart_rx: Default::default(),
            uart_tx: Default::default(),
            rx: Default::default(),
            tx: Default::default(),
            urx: UartRx::new(p.clocks_per_bit),
            utx: UartTx::new(p.clocks_per_bit),
            queue: Default::default(),
            engine: Engine::new(p),
            can: Sja1000::with_reset_timing(b0, b1),
        }
    }

    /// The REC rule at a receiver's dominant last EOF bit of the SJA1000's
    /// core ([`Sja1000::with_rec_rule`]).
    pub fn with_rec_rule(mut self, rule: crate::core::RecRule) -> Self {
        self.can = std::mem::take(&mut self.can).with_rec_rule(rule);
        self
    }

    /// The SJA1000 inside (read-only, for tests).
    pub fn sja1000(&self) -> &Sja1000 {
        &self.can
    }
}

impl Default for SlcanTop {
    fn default() -> Self {
        Self::new(&SlcanParams::default())
    }
}

impl Logic for SlcanTop {
    #[hdl_gen]
    fn update(&mut self) {
        self.urx.clock.next = self.clock.val();
        self.urx.rst.next = self.rst.val();
        self.urx.rxd.next = self.uart_rx.val();

        self.queue.clock.next = self.clock.val();
        self.queue.rst.next = self.rst.val();
        self.queue.push.next = self.urx.valid.val();
        self.queue.wdata.next = self.urx.data.val();
        self.queue.lose.next = self.urx.ferr.val();
        self.queue.pop.next = self.engine.c_pop.val();

        self.engine.clock.next = self.clock.val();
        self.engine.rst.next = self.rst.val();
        self.engine.c_valid.next = self.queue.valid.val();
        self.engine.c_data.next = self.queue.rdata.val();
        self.engine.tx_busy.next = self.utx.busy.val();
        self.engine.wb_dat_r.next = self.can.wb_dat_r.val();
        self.engine.wb_ack.next = self.can.wb_ack.val();

        self.utx.clock.next = self.clock.val();
        self.utx.rst.next = self.rst.val();
        self.utx.start.next = self.engine.tx_start.val();
        self.utx.data.next = self.engine.tx_data.val();

        self.can.clock.next = self.clock.val();
        self.can.rst.next = self.rst.val();
        self.can.wb_cyc.next = self.engine.wb_cyc.val();
        self.can.wb_stb.next = self.engine.wb_cyc.val();
        self.can.wb_we.next = self.engine.wb_we.val();
        self.can.wb_adr.next = self.engine.wb_adr.val();
        self.can.wb_dat_w.next = self.engine.wb_dat_w.val();
        self.can.rx.next = self.rx.val();

        self.uart_tx.next = self.utx.txd.val();
        self.tx.next = self.can.tx.val();
    }
}

canstar_hdl::impl_clocked!(SlcanTop);
