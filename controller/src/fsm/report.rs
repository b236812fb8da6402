//! [`EventReport`]: the event word and the error/arbitration report
//! registers behind the host strobes of [`super::CanFsm`].
//!
//! Each event of a processed bit arrives on its own input (`ev_*`, named
//! after the `EV_*` constants); this block is the one place that assembles
//! them into the event word, at the `EV_*` positions (held in `Constant`
//! fields initialised from the constants, since `#[hdl_gen]` cannot read
//! Rust constants). The word is registered on `sample` for one clock
//! (`events`); the host strobes `tx_done`, `arb_lost`, `error` (with the
//! `ERRK_*` mask `err_kind`) and `rx_valid` are bits of it.
//!
//! State: `evr` (the event word of the last processed bit: written on
//! every `sample`, 0 on other clocks and on `reset`); `arbpos_r` (position
//! of the last lost arbitration, written when it is lost); `errf_r`,
//! `errp_r`, `errtx_r` (FIELD code, POSITION and role at the last detected
//! error, written when an error flag starts). The last four are not reset.

use super::{
    EV_ACK_ERR, EV_AEF, EV_ARB_LOST, EV_BIT, EV_BITS, EV_BIT_ERR, EV_CRC_ERR, EV_DAF, EV_EXC1, EV_EXC2, EV_FORM_ERR,
    EV_INTEGRATED, EV_OLF, EV_OVL, EV_PEF, EV_RECOVERED, EV_RUN, EV_RX_OK, EV_SOF, EV_STUFF_ERR, EV_TX_OK,
};
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct EventReport {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub sample: Signal<In, Bit>,
    pub ev_sof: Signal<In, Bit>,
    pub ev_arb_lost: Signal<In, Bit>,
    pub ev_bit_err: Signal<In, Bit>,
    pub ev_stuff_err: Signal<In, Bit>,
    pub ev_crc_err: Signal<In, Bit>,
    pub ev_form_err: Signal<In, Bit>,
    pub ev_ack_err: Signal<In, Bit>,
    pub ev_aef: Signal<In, Bit>,
    pub ev_pef: Signal<In, Bit>,
    pub ev_olf: Signal<In, Bit>,
    pub ev_ovl: Signal<In, Bit>,
    pub ev_daf: Signal<In, Bit>,
    pub ev_tx_ok: Signal<In, Bit>,
    pub ev_rx_ok: Signal<In, Bit>,
    pub ev_exc1: Signal<In, Bit>,
    pub ev_exc2: Signal<In, Bit>,
    pub ev_run: Signal<In, Bit>,
    pub ev_recovered: Signal<In, Bit>,
    pub ev_integrated: Signal<In, Bit>,
    /// An error flag starts: capture `code`, `pos` and `tx_role`.
    pub err_now: Signal<In, Bit>,
    pub code: Signal<In, Bits<5>>,
    pub pos: Signal<In, Bits<8>>,
    pub tx_role: Signal<In, Bit>,
    /// Arbitration position of this bit (captured with `ev_arb_lost`).
    pub arb_pos: Signal<In, Bits<6>>,

    pub events: Signal<Out, Bits<EV_BITS>>,
    pub tx_done: Signal<Out, Bit>,
    pub arb_lost: Signal<Out, Bit>,
    pub arb_lost_pos: Signal<Out, Bits<6>>,
    pub error: Signal<Out, Bit>,
    pub err_kind: Signal<Out, Bits<5>>,
    pub err_field: Signal<Out, Bits<5>>,
    pub err_pos: Signal<Out, Bits<8>>,
    pub err_tx: Signal<Out, Bit>,
    pub rx_valid: Signal<Out, Bit>,

    evr: DFF<Bits<EV_BITS>>,
    arbpos_r: DFF<Bits<6>>,
    errf_r: DFF<Bits<5>>,
    errp_r: DFF<Bits<8>>,
    errtx_r: DFF<Bit>,

    // Bit positions of the event word (the EV_* constants).
    k_sof: Constant<Bits<5>>,
    k_arb_lost: Constant<Bits<5>>,
    k_bit_err: Constant<Bits<5>>,
    k_stuff_err: Constant<Bits<5>>,
    k_crc_err: Constant<Bits<5>>,
    k_form_err: Constant<Bits<5>>,
    k_ack_err: Constant<Bits<5>>,
    k_aef: Constant<Bits<5>>,
    k_pef: Constant<Bits<5>>,
    k_olf: Constant<Bits<5>>,
    k_ovl: Constant<Bits<5>>,
    k_daf: Constant<Bits<5>>,
    k_tx_ok: Constant<Bits<5>>,
    k_rx_ok: Constant<Bits<5>>,
    k_exc1: Constant<Bits<5>>,
    k_exc2: Constant<Bits<5>>,
    k_run: Constant<Bits<5>>,
    k_recovered: Constant<Bits<5>>,
    k_integrated: Constant<Bits<5>>,
    k_bit: Constant<Bits<5>>,

    l_ev: Signal<Local, Bits<EV_BITS>>,
}

fn k(i: usize) -> Constant<Bits<5>> {
    Constant::new((i as u64).into())
}

impl Default for EventReport {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            sample: Default::default(),
            ev_sof: Default::default(),
            ev_arb_lost: Default::default(),
            ev_bit_err: Default::default(),
            ev_stuff_err: Default::default(),
            ev_crc_err: Default::default(),
            ev_form_err: Default::default(),
            ev_ack_err: Default::default(),
            ev_aef: Default::default(),
            ev_pef: Default::default(),
            ev_olf: Default::default(),
            ev_ovl: Default::default(),
            ev_daf: Default::default(),
            ev_tx_ok: Default::default(),
            ev_rx_ok: Default::default(),
            ev_exc1: Default::default(),
            ev_exc2: Default::default(),
            ev_run: Default::default(),
            ev_recovered: Default::default(),
            ev_integrated: Default::default(),
            err_now: Default::default(),
            code: Default::default(),
            pos: Default::default(),
            tx_role: Default::default(),
            arb_pos: Default::default(),
            events: Default::default(),
            tx_done: Default::default(),
            arb_lost: Default::default(),
            arb_lost_pos: Default::default(),
            error: Default::default(),
            err_kind: Default::default(),
            err_field: Default::default(),
            err_pos: Default::default(),
            err_tx: Default::default(),
            rx_valid: Default::default(),
            evr: Default::default(),
            arbpos_r: Default::default(),
            errf_r: Default::default(),
            errp_r: Default::default(),
            errtx_r: Default::default(),
            k_sof: k(EV_SOF),
            k_arb_lost: k(EV_ARB_LOST),
            k_bit_err: k(EV_BIT_ERR),
            k_stuff_err: k(EV_STUFF_ERR),
            k_crc_err: k(EV_CRC_ERR),
            k_form_err: k(EV_FORM_ERR),
            k_ack_err: k(EV_ACK_ERR),
            k_aef: k(EV_AEF),
            k_pef: k(EV_PEF),
            k_olf: k(EV_OLF),
            k_ovl: k(EV_OVL),
            k_daf: k(EV_DAF),
            k_tx_ok: k(EV_TX_OK),
            k_rx_ok: k(EV_RX_OK),
            k_exc1: k(EV_EXC1),
            k_exc2: k(EV_EXC2),
            k_run: k(EV_RUN),
            k_recovered: k(EV_RECOVERED),
            k_integrated: k(EV_INTEGRATED),
            k_bit: k(EV_BIT),
            l_ev: Default::default(),
        }
    }
}

impl Logic for EventReport {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, evr, arbpos_r, errf_r, errp_r, errtx_r);
        self.evr.d.next = 0.into();
        self.l_ev.next = 0.into();
        if self.sample.val() {
            // The event word: every event at its EV_* position.
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_sof.val().index(), self.ev_sof.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_arb_lost.val().index(), self.ev_arb_lost.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_bit_err.val().index(), self.ev_bit_err.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_stuff_err.val().index(), self.ev_stuff_err.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_crc_err.val().index(), self.ev_crc_err.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_form_err.val().index(), self.ev_form_err.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_ack_err.val().index(), self.ev_ack_err.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_aef.val().index(), self.ev_aef.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_pef.val().index(), self.ev_pef.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_olf.val().index(), self.ev_olf.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_ovl.val().index(), self.ev_ovl.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_daf.val().index(), self.ev_daf.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_tx_ok.val().index(), self.ev_tx_ok.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_rx_ok.val().index(), self.ev_rx_ok.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_exc1.val().index(), self.ev_exc1.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_exc2.val().index(), self.ev_exc2.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_run.val().index(), self.ev_run.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_recovered.val().index(), self.ev_recovered.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_integrated.val().index(), self.ev_integrated.val());
            self.l_ev.next = self.l_ev.val().replace_bit(self.k_bit.val().index(), true);
            self.evr.d.next = self.l_ev.val();
            if self.ev_arb_lost.val() {
                self.arbpos_r.d.next = self.arb_pos.val();
            }
            if self.err_now.val() {
                self.errf_r.d.next = self.code.val();
                self.errp_r.d.next = self.pos.val();
                self.errtx_r.d.next = self.tx_role.val();
            }
        }
        if self.reset.val() {
            self.evr.d.next = 0.into();
        }

        // The error kinds are consecutive in the word, in ERRK_* order.
        self.err_kind.next = self.evr.q.val().get_bits::<5>(self.k_bit_err.val().index());
        self.events.next = self.evr.q.val();
        self.tx_done.next = self.evr.q.val().get_bit(self.k_tx_ok.val().index());
        self.arb_lost.next = self.evr.q.val().get_bit(self.k_arb_lost.val().index());
        self.arb_lost_pos.next = self.arbpos_r.q.val();
        self.error.next = self.err_kind.val().any();
        self.err_field.next = self.errf_r.q.val();
        self.err_pos.next = self.errp_r.q.val();
        self.err_tx.next = self.errtx_r.q.val();
        self.rx_valid.next = self.evr.q.val().get_bit(self.k_rx_ok.val().index());
    }
}

canstar_hdl::impl_clocked!(EventReport);

#[cfg(test)]
mod tests {
    use super::super::{ERRK_ACK, ERRK_BIT, ERRK_CRC, ERRK_FORM, ERRK_STUFF};
    use super::*;
    use canstar_hdl::drive;

    #[test]
    fn each_event_lands_at_its_ev_position_for_one_clock() {
        let mut u = EventReport::default();
        drive::init(&mut u);
        type Input = fn(&mut EventReport) -> &mut Signal<In, Bit>;
        let inputs: [(Input, usize); 19] = [
            (|u| &mut u.ev_sof, EV_SOF),
            (|u| &mut u.ev_arb_lost, EV_ARB_LOST),
            (|u| &mut u.ev_bit_err, EV_BIT_ERR),
            (|u| &mut u.ev_stuff_err, EV_STUFF_ERR),
            (|u| &mut u.ev_crc_err, EV_CRC_ERR),
            (|u| &mut u.ev_form_err, EV_FORM_ERR),
            (|u| &mut u.ev_ack_err, EV_ACK_ERR),
            (|u| &mut u.ev_aef, EV_AEF),
            (|u| &mut u.ev_pef, EV_PEF),
            (|u| &mut u.ev_olf, EV_OLF),
            (|u| &mut u.ev_ovl, EV_OVL),
            (|u| &mut u.ev_daf, EV_DAF),
            (|u| &mut u.ev_tx_ok, EV_TX_OK),
            (|u| &mut u.ev_rx_ok, EV_RX_OK),
            (|u| &mut u.ev_exc1, EV_EXC1),
            (|u| &mut u.ev_exc2, EV_EXC2),
            (|u| &mut u.ev_run, EV_RUN),
            (|u| &mut u.ev_recovered, EV_RECOVERED),
            (|u| &mut u.ev_integrated, EV_INTEGRATED),
        ];
        for (input, pos) in inputs {
            input(&mut u).next = true;
            u.sample.next = true;
            drive::cycle(&mut u);
            input(&mut u).next = false;
            u.sample.next = false;
            let ev = u.events.val().index() as u64;
            assert_eq!(ev, (1 << pos) | (1 << EV_BIT), "EV bit {pos}");
            assert_eq!(u.tx_done.val(), pos == EV_TX_OK);
            assert_eq!(u.rx_valid.val(), pos == EV_RX_OK);
            assert_eq!(u.arb_lost.val(), pos == EV_ARB_LOST);
            let kinds = [(EV_BIT_ERR, ERRK_BIT), (EV_STUFF_ERR, ERRK_STUFF), (EV_CRC_ERR, ERRK_CRC), (EV_FORM_ERR, ERRK_FORM), (EV_ACK_ERR, ERRK_ACK)];
            let kind = kinds.iter().find(|k| k.0 == pos).map_or(0, |k| 1 << k.1);
            assert_eq!(u.err_kind.val().index(), kind);
            assert_eq!(u.error.val(), kind != 0);
            drive::cycle(&mut u);
            assert_eq!(u.events.val().index(), 0, "one clock only");
        }
    }

    #[test]
    fn error_and_arbitration_reports_are_captured_and_held() {
        let mut u = EventReport::default();
        drive::init(&mut u);
        u.sample.next = true;
        u.err_now.next = true;
        u.code.next = 17.into();
        u.pos.next = 6.into();
        u.tx_role.next = true;
        u.ev_arb_lost.next = true;
        u.arb_pos.next = 13.into();
        drive::cycle(&mut u);
        u.sample.next = false;
        u.err_now.next = false;
        u.ev_arb_lost.next = false;
        u.code.next = 3.into();
        u.arb_pos.next = 1.into();
        drive::cycle(&mut u);
        drive::cycle(&mut u);
        assert_eq!((u.err_field.val().index(), u.err_pos.val().index(), u.err_tx.val()), (17, 6, true));
        assert_eq!(u.arb_lost_pos.val().index(), 13);
    }
}
