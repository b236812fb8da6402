//! Bit timing logic (BTL): prescaler, bit segments, sampling, hard and
//! re-synchronisation, transmit points.
//!
//! [`BitTiming`] is the RTL; [`BtlModel`] is a pure-Rust transcription of the
//! normative counter model of can-protocol.md §2.3 (one call per time
//! quantum); [`BtlCycleModel`] wraps it with the prescaler, the configuration
//! latch and the register timing of the RTL so that it predicts every output
//! of [`BitTiming`] on every clock. The tests compare the RTL against it.
//!
//! # Port contract of [`BitTiming`]
//!
//! Inputs:
//! - `clock`; `reset`: synchronous, active high. On every clock with `reset`
//!   high the configuration inputs are latched, the bit counter is put at the
//!   start of a bit (`cnt` = 0, so the first TQ after reset is SYNC_SEG), the
//!   prescaler is cleared, `busmon` and `tx` become recessive and
//!   synchronisation is enabled. SP, NTQ and the validity of the
//!   configuration are computed from the latched fields, so they are fixed
//!   from the release of reset on.
//! - `brp` (BRP − 1, 7 bits), `prop` (PROP − 1, 4 bits), `ph1` (PH1 − 1,
//!   3 bits), `ph2` (PH2 − 1, 3 bits), `sjw` (SJW − 1, 2 bits), `triple`
//!   (triple sampling): the host fields of §2.2. SP = 1 + PROP + PH1,
//!   NTQ = SP + PH2. The prescaler (1..128) and PROP (1..16) are wider than
//!   §2.2's 1..32 and 1..8, and PH2 is a field (1..8, C2) where §2.2's
//!   Bosch-style interface derives it as max(PH1, 2), so that every SJA1000
//!   bus timing setting (TQ = 2·(BRP+1) clocks, TSEG1 up to 16 TQ, TSEG2 up
//!   to 8 TQ) can be expressed; NTQ is still limited to 8..25. Only SP, NTQ
//!   and SJW shape the behaviour: any PROP/PH1 split with the same sum
//!   behaves the same. The information processing time is IPT = min(PH2, 2)
//!   TQ (§2.5, C1): 1 TQ when PH2 = 1, which needs BRP ≥ 2 (see Latency).
//! - `rx`: the synchronised RX level (1 = recessive), looked at only on TQ
//!   ticks.
//! - `drive`: the level the bit-stream logic wants on TX from the next
//!   transmit point. Also selects between §3.4 and §3.5, and between the two
//!   rules of §3.3.
//! - `hs_en`: hard synchronisation enabled.
//!
//! `rx`, `drive` and `hs_en` are used combinationally on the tick clock (see
//! below): `drive` and `hs_en` must not depend combinationally on `tq` or
//! `bit_start`.
//!
//! Outputs:
//! - `cfg_err`: the latched configuration is invalid (NTQ outside 8..25,
//!   SJW > PH1, or PH2 = 1 with BRP = 1: an IPT of 1 clock). SJW may exceed
//!   PH2 (C22): an edge after the sample point is then always corrected in
//!   full by a restart.
//!   The block is then inert: `tx` recessive, no strobe, until a reset with
//!   a valid configuration. The block is also inert after power-up until its
//!   first reset (with `cfg_err` = 0).
//! - `tq`: high on the *tick clock*, one clock in every BRP (the clock on
//!   which the prescaler wraps, the BRP-th clock after the release of reset).
//!   On this clock the counter model takes one step with the `rx`, `drive`
//!   and `hs_en` present on this clock.
//! - `bit_start`: high on the tick clock of every transmit point (§2.5,
//!   including restarts and postponed transmit points). `tx` takes `drive`
//!   at the end of this clock and shows it from the next clock on. Because a
//!   restart depends on `rx`, `bit_start` is a combinational function of
//!   `rx`, `drive` and `hs_en` on the tick clock. A restart right after a
//!   normal bit end (edge in SYNC_SEG with hard sync) gives two transmit
//!   points one TQ apart; count bits with `sample`, not with `bit_start`.
//! - `tx`: registered pin; changes only on the clock after `bit_start`.
//! - `sample`: registered, high on the clock after the tick clock of a
//!   sample point. `busmon`: the last sampled level, registered, already the
//!   new value on the clock on which `sample` is high. With triple sampling
//!   the sampled level is the majority of `rx` on the last three tick clocks.
//! - `hard_sync`, `resync`: registered, high on the clock after a tick clock
//!   on which a synchronisation condition (§3.1) held with `hs_en` high or
//!   low respectively, whether or not it moved the bit (e.g. e = 0, or hard
//!   synchronisation while driving `D` before the sample point).
//!
//! # Latency
//!
//! If the tick clock is clock k, then `rx` of clock k is what the model step
//! sees; `sample`, `busmon`, `hard_sync`, `resync` and `tx` show the result
//! on clock k + 1; `bit_start` and `tq` are on clock k. So an `rx` edge that
//! arrives on a tick clock gives `hard_sync`/`resync` one clock later, and an
//! edge arriving between ticks waits for the next tick (up to BRP − 1 clocks
//! more). Busmon and TX both change [`L_RX`] = 1 clock after the tick whose
//! model step caused the change, so a golden model that applies each TQ step
//! at once sees the same instants when its RX is delayed by [`L_RX`] clocks
//! more than this block's `rx` input.
//!
//! The bit-stream logic latches on `sample` (clock ts + 1 for a sample
//! point on tick clock ts) and presents the new `drive` and `hs_en` from
//! clock ts + 2 on, so a transmit point needs its tick clock at ts + 2 or
//! later: [`IPT_CLOCKS`] = 2 clocks. With IPT = 2 TQ the earliest transmit
//! point is the tick clock ts + 2·BRP, on which the new `drive` has been
//! present for 2·BRP − 1 ≥ 1 clocks; with PH2 = 1 (IPT = 1 TQ, BRP ≥ 2 so
//! that one TQ is at least 2 clocks) it is ts + BRP ≥ ts + 2, the normal
//! end of the bit, on which `drive` has been present for BRP − 1 ≥ 1
//! clocks. The shortest legal case, BRP = 2 and PH2 = 1, uses exactly the 2
//! clocks (controller/tests/bit_timing_ph2.rs runs frames through it).
//! With BRP = 1, a sample point on tick clock k and the earliest transmit
//! point after it (§2.5 postponement, e.g. T10/8/1 with an edge in TQ 8):
//!
//! ```text
//! clock       k        k+1        k+2        k+3
//! tq          1        1          1          1
//! rx          sampled
//! sample      0        1          0          0
//! busmon      old      new        new        new
//! drive       old      old        new        new     (bit-stream logic latches at the end of k+1)
//! bit_start   0        0 (postp.) 1          0
//! tx          old      old        old        new
//! ```

use crate::impl_clocked;
pub use crate::btl_model::{BtlCycleModel, BtlEvents, BtlInputs, BtlModel, BtlPins};
pub use crate::timing::{BtlConfig, IPT, IPT_CLOCKS};
use rust_hdl::prelude::*;

/// Clocks from the tick clock on which `rx` is looked at to the clock on
/// which `busmon` and `tx` show the result of that TQ step.
pub const L_RX: usize = 1;

/// The bit timing logic RTL. See the module documentation for the port
/// contract and the timing.
#[derive(LogicBlock, Default)]
pub struct BitTiming {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub brp: Signal<In, Bits<7>>,
    pub prop: Signal<In, Bits<4>>,
    pub ph1: Signal<In, Bits<3>>,
    pub ph2: Signal<In, Bits<3>>,
    pub sjw: Signal<In, Bits<2>>,
    pub triple: Signal<In, Bit>,
    pub rx: Signal<In, Bit>,
    pub drive: Signal<In, Bit>,
    pub hs_en: Signal<In, Bit>,
    pub tq: Signal<Out, Bit>,
    pub sample: Signal<Out, Bit>,
    pub busmon: Signal<Out, Bit>,
    pub bit_start: Signal<Out, Bit>,
    pub tx: Signal<Out, Bit>,
    pub hard_sync: Signal<Out, Bit>,
    pub resync: Signal<Out, Bit>,
    pub cfg_err: Signal<Out, Bit>,
    // Configuration latched under reset.
    c_brp: DFF<Bits<7>>,
    c_sp: DFF<Bits<5>>,
    c_ntq: DFF<Bits<5>>,
    c_sjw: DFF<Bits<5>>,
    c_triple: DFF<Bit>,
    c_ipt1: DFF<Bit>,
    c_valid: DFF<Bit>,
    c_bad: DFF<Bit>,
    // Prescaler and counter model state. Levels that must be recessive at
    // power-up are stored inverted (DFFs power up at 0). The counter model
    // of §2.3 (`cnt`, sample point `spw`, bit end `nbw`) is kept as
    // distances, so that no step compares two counters: `lc` = min(cnt, SJW)
    // (the lengthening of an early edge; 0 exactly when cnt = 0), `rem` =
    // nbw − cnt (≥ 1: the phase error of a late edge, and the TQs to the end
    // of the bit), `tsp` = spw − cnt (the TQs to the sample point, looked at
    // only before it) and `late` = cnt ≥ spw (cnt + 1 > spw).
    c_sp1: DFF<Bits<5>>,
    c_ntq1: DFF<Bits<5>>,
    c_sjw1: DFF<Bits<5>>,
    // Bit i: SJW ≥ i + 1 (all 0 before the first reset, where `c_sjw` = 0).
    c_sjw_ge: DFF<Bits<4>>,
    pre: DFF<Bits<7>>,
    lc: DFF<Bits<3>>,
    rem: DFF<Bits<5>>,
    tsp: DFF<Bits<5>>,
    late: DFF<Bit>,
    busmon_n: DFF<Bit>,
    sync_dis: DFF<Bit>,
    since: DFF<Bits<2>>,
    pending: DFF<Bit>,
    tx_n: DFF<Bit>,
    h1_n: DFF<Bit>,
    h2_n: DFF<Bit>,
    sample_r: DFF<Bit>,
    hard_r: DFF<Bit>,
    resync_r: DFF<Bit>,
    // Combinational temporaries.
    in_sp: Signal<Local, Bits<6>>,
    in_ph2: Signal<Local, Bits<6>>,
    in_ntq: Signal<Local, Bits<6>>,
    in_sjw: Signal<Local, Bits<5>>,
    in_bad: Signal<Local, Bit>,
    tick: Signal<Local, Bit>,
    rs_ok: Signal<Local, Bit>,
    sync_cond: Signal<Local, Bit>,
    do_hard: Signal<Local, Bit>,
    do_resync: Signal<Local, Bit>,
    restart: Signal<Local, Bit>,
    shorten: Signal<Local, Bit>,
    lengthen: Signal<Local, Bit>,
    eob: Signal<Local, Bit>,
    smp: Signal<Local, Bit>,
    lc_inc: Signal<Local, Bits<3>>,
    rem_dec: Signal<Local, Bits<5>>,
    tsp_dec: Signal<Local, Bits<5>>,
    since_inc: Signal<Local, Bits<2>>,
    fire: Signal<Local, Bit>,
    sampled: Signal<Local, Bit>,
}

impl_clocked!(BitTiming);

impl Logic for BitTiming {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, c_brp, c_sp, c_ntq, c_sjw, c_triple, c_ipt1, c_valid, c_bad, c_sp1, c_ntq1, c_sjw1, c_sjw_ge, pre,
            lc, rem, tsp, late, busmon_n, sync_dis, since, pending, tx_n, h1_n, h2_n, sample_r, hard_r, resync_r
        );

        // Configuration from the input fields (value - 1 encoding).
        self.in_sp.next = (bit_cast::<6, 4>(self.prop.val()) + bit_cast::<6, 3>(self.ph1.val())) + 3;
        self.in_ph2.next = bit_cast::<6, 3>(self.ph2.val()) + 1;
        self.in_ntq.next = self.in_sp.val() + self.in_ph2.val();
        self.in_sjw.next = bit_cast::<5, 2>(self.sjw.val()) + 1;
        // NTQ 8..25, SJW <= PH1 (C22), PH2 = 1 TQ only with BRP >= 2 (IPT =
        // 1 TQ must still be 2 clocks).
        self.in_bad.next = (((self.in_ntq.val() < 8) | (self.in_ntq.val() > 25))
            | (bit_cast::<3, 2>(self.sjw.val()) > self.ph1.val()))
            | ((self.ph2.val() == 0) & (self.brp.val() == 0));

        // Prescaler tick.
        self.tick.next = (self.c_valid.q.val() & !self.reset.val()) & (self.pre.q.val() == self.c_brp.q.val());

        // Step 1 and 2: which side of the sample point (`late`), whether a
        // late edge is within SJW (phase error nbw − cnt = `rem`).
        // rem ≤ SJW without a comparator after `rem`: `c_sjw` is 0 (before
        // the first reset) or SJW = 1..4, and `c_sjw_ge` bit i is SJW ≥ i + 1,
        // so this is exactly `rem <= c_sjw` for every `rem` (unit test
        // `rs_ok_is_rem_le_sjw`).
        self.rs_ok.next = ((((self.rem.q.val() == 0)
            | ((self.rem.q.val() == 1) & self.c_sjw_ge.q.val().get_bit(0)))
            | ((self.rem.q.val() == 2) & self.c_sjw_ge.q.val().get_bit(1)))
            | ((self.rem.q.val() == 3) & self.c_sjw_ge.q.val().get_bit(2)))
            | ((self.rem.q.val() == 4) & self.c_sjw_ge.q.val().get_bit(3));
        if self.lc.q.val() == bit_cast::<3, 5>(self.c_sjw.q.val()) {
            self.lc_inc.next = self.lc.q.val();
        } else {
            self.lc_inc.next = self.lc.q.val() + 1;
        }
        self.rem_dec.next = self.rem.q.val() - 1;
        self.tsp_dec.next = self.tsp.q.val() - 1;

        // Step 3: synchronisation (rx dominant, busmon recessive, sync_en).
        // A restart puts cnt at 1; a late edge beyond SJW shortens the bit
        // by SJW (nbw − SJW); an early edge while transmitting recessive
        // with cnt > 0 lengthens it by min(cnt, SJW) (spw and nbw + lc).
        self.sync_cond.next = (!self.rx.val() & !self.busmon_n.q.val()) & !self.sync_dis.q.val();
        self.do_hard.next = self.sync_cond.val() & self.hs_en.val();
        self.do_resync.next = self.sync_cond.val() & !self.hs_en.val();
        self.restart.next = (self.do_hard.val() & (self.drive.val() | self.late.q.val()))
            | ((self.do_resync.val() & self.late.q.val()) & self.rs_ok.val());
        self.shorten.next = (self.do_resync.val() & self.late.q.val()) & !self.rs_ok.val();
        self.lengthen.next =
            ((self.do_resync.val() & !self.late.q.val()) & self.drive.val()) & self.lc.q.val().any();

        // Step 4: end of bit (cnt + 1 = nbw, or nbw − SJW when shortened; a
        // restart or a lengthened bit does not end here: NTQ ≥ 8, rem ≥ 2
        // before the sample point).
        self.eob.next = false;
        if !self.restart.val() {
            if self.shorten.val() {
                self.eob.next = self.rem.q.val() == self.c_sjw1.q.val();
            } else {
                self.eob.next = self.rem.q.val() == 1;
            }
        }

        // Step 5: sample point (cnt + 1 = spw, only before it, and only in
        // an unchanged bit: a lengthened bit moves it, a restart puts cnt at
        // 1 < SP).
        self.smp.next = (((self.tsp.q.val() == 1) & !self.late.q.val()) & !self.restart.val())
            & (!self.lengthen.val() & !self.eob.val());
        self.sampled.next = !self.rx.val();
        if self.c_triple.q.val() {
            // Majority, computed on the inverted (dominant = 1) levels.
            self.sampled.next = ((!self.rx.val() & self.h1_n.q.val()) | (!self.rx.val() & self.h2_n.q.val()))
                | (self.h1_n.q.val() & self.h2_n.q.val());
        }

        // §2.5: transmit point, postponed to sample point + IPT (2 TQ, or
        // 1 TQ when PH2 = 1: then every transmit point is at least one TQ,
        // so at least 2 clocks, after the sample point).
        self.since_inc.next = self.since.q.val() + 1;
        if self.since.q.val() == 2 {
            self.since_inc.next = 2.into();
        }
        self.fire.next = (self.restart.val() | self.eob.val() | self.pending.q.val())
            & ((self.since_inc.val() == 2) | self.c_ipt1.q.val());

        // Registers.
        if self.reset.val() {
            self.c_brp.d.next = self.brp.val();
            self.c_sp.d.next = self.in_sp.val().get_bits::<5>(0);
            self.c_ntq.d.next = self.in_ntq.val().get_bits::<5>(0);
            self.c_sjw.d.next = self.in_sjw.val();
            self.c_sp1.d.next = self.in_sp.val().get_bits::<5>(0) - 1;
            self.c_ntq1.d.next = self.in_ntq.val().get_bits::<5>(0) - 1;
            self.c_sjw1.d.next = self.in_sjw.val() + 1;
            self.c_sjw_ge.d.next = 1.into();
            if self.sjw.val() == 1 {
                self.c_sjw_ge.d.next = 3.into();
            }
            if self.sjw.val() == 2 {
                self.c_sjw_ge.d.next = 7.into();
            }
            if self.sjw.val() == 3 {
                self.c_sjw_ge.d.next = 15.into();
            }
            self.c_triple.d.next = self.triple.val();
            self.c_ipt1.d.next = self.ph2.val() == 0;
            self.c_bad.d.next = self.in_bad.val();
            self.c_valid.d.next = !self.in_bad.val();
            self.pre.d.next = 0.into();
            self.lc.d.next = 0.into();
            self.rem.d.next = self.in_ntq.val().get_bits::<5>(0);
            self.tsp.d.next = self.in_sp.val().get_bits::<5>(0);
            self.late.d.next = false;
            self.busmon_n.d.next = false;
            self.sync_dis.d.next = false;
            self.since.d.next = 2.into();
            self.pending.d.next = false;
            self.tx_n.d.next = false;
            self.h1_n.d.next = false;
            self.h2_n.d.next = false;
            self.sample_r.d.next = false;
            self.hard_r.d.next = false;
            self.resync_r.d.next = false;
        } else {
            self.sample_r.d.next = self.tick.val() & self.smp.val();
            self.hard_r.d.next = self.tick.val() & self.do_hard.val();
            self.resync_r.d.next = self.tick.val() & self.do_resync.val();
            if self.c_valid.q.val() {
                if self.tick.val() {
                    self.pre.d.next = 0.into();
                } else {
                    self.pre.d.next = self.pre.q.val() + 1;
                }
            }
            if self.tick.val() {
                if self.eob.val() {
                    self.lc.d.next = 0.into();
                    self.rem.d.next = self.c_ntq.q.val();
                    self.tsp.d.next = self.c_sp.q.val();
                    self.late.d.next = false;
                } else if self.restart.val() {
                    self.lc.d.next = 1.into();
                    self.rem.d.next = self.c_ntq1.q.val();
                    self.tsp.d.next = self.c_sp1.q.val();
                    self.late.d.next = false;
                } else if self.shorten.val() {
                    self.lc.d.next = self.lc_inc.val();
                    self.rem.d.next = self.rem.q.val() - self.c_sjw1.q.val();
                    self.tsp.d.next = self.tsp_dec.val();
                    self.late.d.next = true;
                } else if self.lengthen.val() {
                    self.lc.d.next = self.lc_inc.val();
                    self.rem.d.next = self.rem_dec.val() + bit_cast::<5, 3>(self.lc.q.val());
                    self.tsp.d.next = self.tsp_dec.val() + bit_cast::<5, 3>(self.lc.q.val());
                    self.late.d.next = false;
                } else {
                    self.lc.d.next = self.lc_inc.val();
                    self.rem.d.next = self.rem_dec.val();
                    self.tsp.d.next = self.tsp_dec.val();
                    self.late.d.next = self.late.q.val() | (self.tsp.q.val() == 1);
                }
                if self.smp.val() {
                    self.busmon_n.d.next = self.sampled.val();
                    self.sync_dis.d.next = false;
                    self.since.d.next = 0.into();
                } else {
                    self.since.d.next = self.since_inc.val();
                    if self.sync_cond.val() {
                        self.sync_dis.d.next = true;
                    }
                }
                self.pending.d.next = (self.restart.val() | self.eob.val() | self.pending.q.val()) & !self.fire.val();
                if self.fire.val() {
                    self.tx_n.d.next = !self.drive.val();
                }
                self.h1_n.d.next = !self.rx.val();
                self.h2_n.d.next = self.h1_n.q.val();
            }
        }

        // Outputs.
        self.tq.next = self.tick.val();
        self.sample.next = self.sample_r.q.val();
        self.busmon.next = !self.busmon_n.q.val();
        self.bit_start.next = self.tick.val() & self.fire.val();
        self.tx.next = !self.tx_n.q.val();
        self.hard_sync.next = self.hard_r.q.val();
        self.resync.next = self.resync_r.q.val();
        self.cfg_err.next = self.c_bad.q.val();
    }
}

impl BitTiming {
    /// Set the configuration inputs from `cfg` (takes effect under reset).
    pub fn set_config(&mut self, cfg: &BtlConfig) {
        let (brp, prop, ph1, ph2, sjw) = cfg.fields();
        self.brp.next = (brp as u64).into();
        self.prop.next = (prop as u64).into();
        self.ph1.next = (ph1 as u64).into();
        self.ph2.next = (ph2 as u64).into();
        self.sjw.next = (sjw as u64).into();
        self.triple.next = cfg.triple;
    }

    /// Set every input from `i`.
    pub fn set_inputs(&mut self, i: &BtlInputs) {
        self.reset.next = i.reset;
        self.brp.next = (i.brp as u64 & 127).into();
        self.prop.next = (i.prop as u64 & 15).into();
        self.ph1.next = (i.ph1 as u64 & 7).into();
        self.ph2.next = (i.ph2 as u64 & 7).into();
        self.sjw.next = (i.sjw as u64 & 3).into();
        self.triple.next = i.triple;
        self.rx.next = i.rx;
        self.drive.next = i.drive;
        self.hs_en.next = i.hs_en;
    }

    /// The current output values.
    pub fn pins(&self) -> BtlPins {
        BtlPins {
            tq: self.tq.val(),
            sample: self.sample.val(),
            busmon: self.busmon.val(),
            bit_start: self.bit_start.val(),
            tx: self.tx.val(),
            hard_sync: self.hard_sync.val(),
            resync: self.resync.val(),
            cfg_err: self.cfg_err.val(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drive::{cycle, init, settle};

    /// `rs_ok` (a late edge within SJW) is exactly the comparison
    /// `rem <= c_sjw` it replaces, for every `rem`, before the first reset
    /// (`c_sjw` = 0) and after a reset with each SJW.
    #[test]
    fn rs_ok_is_rem_le_sjw() {
        // None: never reset; Some(s): reset with the SJW field s (SJW − 1).
        for sjw in [None, Some(0u64), Some(1), Some(2), Some(3)] {
            let mut uut = BitTiming::default();
            init(&mut uut);
            if let Some(s) = sjw {
                // T = 1 + 3 + 3 + 3 TQ, SJW ≤ PH1 for every s.
                uut.brp.next = 1.into();
                uut.prop.next = 2.into();
                uut.ph1.next = 3.into();
                uut.ph2.next = 2.into();
                uut.sjw.next = s.into();
                uut.reset.next = true;
                cycle(&mut uut);
                uut.reset.next = false;
                settle(&mut uut);
                assert_eq!(uut.c_sjw.q.val().index() as u64, s + 1);
            } else {
                assert_eq!(uut.c_sjw.q.val().index(), 0);
            }
            for rem in 0..32u64 {
                uut.rem.q.next = rem.into();
                settle(&mut uut);
                let expected = uut.rem.q.val() <= uut.c_sjw.q.val();
                assert_eq!(uut.rs_ok.val(), expected, "sjw field {sjw:?}, rem {rem}");
            }
        }
    }
}
