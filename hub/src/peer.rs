//! The peer guard's estimate of the peer hub's sublink counters (hub.md §5.20).
//!
//! The peer charges its sublinks for the error episodes that this hub charges to its
//! ports, and takes one count off every `sub_bic_decay` good frames. [`PeerEstimate`]
//! follows that count in `bic` units: `inc` (the largest charge step of a port in the last
//! clock, in blames, 0..=3) adds `8 x inc`, saturating at 255; otherwise a good frame
//! (`frame_ok`, registered here so that it stays in step with the units' registered
//! steps) counts towards the decay. `high` is 1 while the guard is on and the estimate is
//! at least its limit (`8 x peer_guard`). Reset (`reset` = 1, synchronous) clears it.

use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct PeerEstimate {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    /// The largest charge step of a port in the last clock (blames, 0 = none).
    pub inc: Signal<In, Bits<2>>,
    /// A good frame ended at this clock's sample.
    pub frame_ok: Signal<In, Bit>,
    /// The estimate is at the guard's limit (and the guard is on).
    pub high: Signal<Out, Bit>,
    /// The estimate (`bic` units), for tests and debugging.
    pub est: Signal<Out, Bits<8>>,
    pest_r: DFF<Bits<8>>,
    pdc_r: DFF<Bits<3>>,
    fok_r: DFF<Bit>,
    pstep: Signal<Local, Bits<8>>,
    on: Constant<Bit>,
    lim: Constant<Bits<8>>,
    decay: Constant<Bits<3>>,
}

impl PeerEstimate {
    /// `on`: the guard is enabled (a peer exists and `peer_guard > 0`); `limit`: the
    /// estimate at which `high` rises (`bic` units, at most 255); `decay`: good frames per
    /// count taken off (1..=7).
    pub fn new(on: bool, limit: u64, decay: u64) -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            inc: Default::default(),
            frame_ok: Default::default(),
            high: Default::default(),
            est: Default::default(),
            pest_r: Default::default(),
            pdc_r: Default::default(),
            fok_r: Default::default(),
            pstep: Default::default(),
            on: Constant::new(on),
            lim: Constant::new(limit.into()),
            decay: Constant::new(decay.into()),
        }
    }
}

impl Logic for PeerEstimate {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, pest_r, pdc_r, fok_r);
        self.fok_r.d.next = self.frame_ok.val();
        // (8 per blame, at most 3 blames: saturating below 232)
        if self.inc.val() == 3 {
            self.pstep.next = 24.into();
        } else if self.inc.val() == 2 {
            self.pstep.next = 16.into();
        } else {
            self.pstep.next = 8.into();
        }
        if self.inc.val() != 0 {
            if self.pest_r.q.val() > 231 {
                self.pest_r.d.next = 255.into();
            } else {
                self.pest_r.d.next = self.pest_r.q.val() + self.pstep.val();
            }
        } else if self.fok_r.q.val() & (self.pest_r.q.val() != 0) {
            if (self.pdc_r.q.val() + 1) >= self.decay.val() {
                self.pdc_r.d.next = 0.into();
                self.pest_r.d.next = self.pest_r.q.val() - 1;
            } else {
                self.pdc_r.d.next = self.pdc_r.q.val() + 1;
            }
        }
        if self.reset.val() {
            self.pest_r.d.next = 0.into();
            self.pdc_r.d.next = 0.into();
            self.fok_r.d.next = false;
        }
        self.high.next = self.on.val() & (self.pest_r.q.val() >= self.lim.val());
        self.est.next = self.pest_r.q.val();
    }
}

canstar_hdl::impl_clocked!(PeerEstimate);
