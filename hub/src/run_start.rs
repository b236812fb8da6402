//! How BT's dominant run began, for the first-flagger rule (hub.md §5.10, §5.12, §5.26).
//!
//! The first-flagger rule charges the dominant contenders of an error episode that the
//! frame monitor alone detected. Two beginnings of a dominant run make those contenders
//! nodes that reacted to something only some of them saw, and [`RunStart`] reports them on
//! `excused` until BT is recessive at a sample point again:
//!
//! - **a dominant stuff bit** (`stuff_dom`: the monitor reports a stuff bit after BT was
//!   recessive at the last sample, so its level must be dominant): nodes that saw one more
//!   recessive bit than the monitor start their error flags there (§5.10);
//! - **an early SOF from the peer's side** (§5.26): the monitor took a SOF whose edge came
//!   through a sublink while no port was dominant (`sub_lead`) for at least `min` clocks
//!   before the SOF's bit start, i.e. in Intermission bit 2 after this hub's sample point.
//!   Nodes that sample later took that bit for an overload condition and answer with
//!   overload flags. A SOF that the peer's node sent at the peer's bit start reaches this
//!   hub a clock or two before its own bit start, so `min` is 3 by default
//!   (`early_sof_clocks`; 0 = off). The count saturates at 3.
//!
//! Inputs are the hub's: `sample` and `bit_start` strobes, the monitor's `stuff` (with
//! `sample`) and decoded `sof`, the coupled bit `bt`. Reset (`reset` = 1, synchronous)
//! takes BT as recessive and clears the run.

use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct RunStart {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub sample: Signal<In, Bit>,
    pub bit_start: Signal<In, Bit>,
    /// With `sample`: the sampled bit is a stuff bit.
    pub stuff: Signal<In, Bit>,
    /// With `sample`: the sampled bit is a SOF.
    pub sof: Signal<In, Bit>,
    pub bt: Signal<In, Bit>,
    /// An enabled sublink and no enabled port is dominant.
    pub sub_lead: Signal<In, Bit>,
    /// With `sample`: a stuff bit after a recessive sample (its level must be dominant).
    pub stuff_dom: Signal<Out, Bit>,
    /// BT's dominant run began at a dominant stuff bit or at an early SOF from the peer's
    /// side (registered: valid from the clock after the sample that started the run).
    pub excused: Signal<Out, Bit>,
    bt_prev: DFF<Bit>,
    sl_cnt: DFF<Bits<2>>,
    sl_bs: DFF<Bit>,
    /// BT's dominant run since the last recessive sample began at one of the two starts.
    run: DFF<Bit>,
    on: Constant<Bit>,
    min: Constant<Bits<2>>,
}

impl RunStart {
    /// `min`: clocks of `sub_lead` before the SOF's bit start that make it early, 0..=3;
    /// 0 = the early-SOF excuse is off.
    pub fn new(min: u64) -> Self {
        assert!(min <= 3, "early_sof_clocks {min} is not in 0..=3");
        Self {
            clock: Default::default(),
            reset: Default::default(),
            sample: Default::default(),
            bit_start: Default::default(),
            stuff: Default::default(),
            sof: Default::default(),
            bt: Default::default(),
            sub_lead: Default::default(),
            stuff_dom: Default::default(),
            excused: Default::default(),
            bt_prev: Default::default(),
            sl_cnt: Default::default(),
            sl_bs: Default::default(),
            run: Default::default(),
            on: Constant::new(min > 0),
            min: Constant::new(min.into()),
        }
    }
}

impl Logic for RunStart {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, bt_prev, sl_cnt, sl_bs, run);
        // BT at the last sample
        if self.sample.val() {
            self.bt_prev.d.next = self.bt.val();
        }
        self.stuff_dom.next = self.stuff.val() & self.bt_prev.q.val();
        // clocks in which a sublink alone has been dominant (saturating), and whether
        // there were `min` of them before the last bit start
        if self.sub_lead.val() {
            if self.sl_cnt.q.val() != 3 {
                self.sl_cnt.d.next = self.sl_cnt.q.val() + 1;
            }
        } else {
            self.sl_cnt.d.next = 0.into();
        }
        if self.bit_start.val() {
            self.sl_bs.d.next = self.on.val() & (self.sl_cnt.q.val() >= self.min.val());
        }
        if self.sample.val() {
            if self.bt.val() {
                self.run.d.next = false;
            } else if self.stuff_dom.val() | (self.sof.val() & self.sl_bs.q.val()) {
                self.run.d.next = true;
            }
        }
        if self.reset.val() {
            self.bt_prev.d.next = true;
            self.run.d.next = false;
        }
        self.excused.next = self.run.q.val();
    }
}

canstar_hdl::impl_clocked!(RunStart);
