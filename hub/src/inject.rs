//! Fault-injection controller (H8, the reference's `faultInjectionModule`).
//!
//! Which point (uplink, downlink or outgoing sublink), which fault (stuck-at-recessive,
//! stuck-at-dominant, bit flip) and which start field are generation-time choices
//! ([`crate::config::FaultInjection`]); the hub applies the fault code through the
//! coupler's fault hooks while `active` is 1. This block only decides *when*:
//!
//! - `button` (the `inject_fault` input, 1 = pressed) is registered and edge detected;
//!   no debouncing (simulation).
//! - Idle, first press: armed. Armed: at a `sample` whose frame field equals
//!   `start_field` the fault starts (`active` = 1). A press while armed disarms.
//! - Active, second press: stopping. The fault stays on until the sample of the last
//!   EOF bit (`eof_last`), so that stopping never creates a half frame, then idle.
//! - Reset returns to idle.

// `#[hdl_gen]` has no match guards, so nested `if`s stay.
#![allow(clippy::collapsible_match)]

use rust_hdl::prelude::*;

#[derive(Copy, Clone, Debug, PartialEq, LogicState)]
pub enum InjState {
    Idle,
    Armed,
    Active,
    Stopping,
}

#[derive(LogicBlock)]
pub struct Injector {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub button: Signal<In, Bit>,
    pub sample: Signal<In, Bit>,
    pub field: Signal<In, Bits<4>>,
    pub eof_last: Signal<In, Bit>,
    pub active: Signal<Out, Bit>,
    pub armed: Signal<Out, Bit>,
    start_field: Constant<Bits<4>>,
    state: DFF<InjState>,
    btn_prev: DFF<Bit>,
    btn_r: DFF<Bit>,
    press: Signal<Local, Bit>,
}

impl Injector {
    /// An injector that starts the fault at a bit of field code `start_field`
    /// (see [`crate::frame_state::Field`]).
    pub fn new(start_field: u64) -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            button: Default::default(),
            sample: Default::default(),
            field: Default::default(),
            eof_last: Default::default(),
            active: Default::default(),
            armed: Default::default(),
            start_field: Constant::new(start_field.into()),
            state: Default::default(),
            btn_prev: Default::default(),
            btn_r: Default::default(),
            press: Default::default(),
        }
    }
}

impl Logic for Injector {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, state, btn_prev, btn_r);
        self.btn_r.d.next = self.button.val();
        self.btn_prev.d.next = self.btn_r.q.val();
        self.press.next = self.btn_r.q.val() & !self.btn_prev.q.val();
        match self.state.q.val() {
            InjState::Idle => {
                if self.press.val() {
                    self.state.d.next = InjState::Armed;
                }
            }
            InjState::Armed => {
                if self.press.val() {
                    self.state.d.next = InjState::Idle;
                } else if self.sample.val() & (self.field.val() == self.start_field.val()) {
                    self.state.d.next = InjState::Active;
                }
            }
            InjState::Active => {
                if self.press.val() {
                    self.state.d.next = InjState::Stopping;
                }
            }
            InjState::Stopping => {
                if self.sample.val() & self.eof_last.val() {
                    self.state.d.next = InjState::Idle;
                }
            }
            _ => {}
        }
        if self.reset.val() {
            self.state.d.next = InjState::Idle;
            self.btn_r.d.next = false;
            self.btn_prev.d.next = false;
        }
        self.active.next = (self.state.q.val() == InjState::Active) | (self.state.q.val() == InjState::Stopping);
        self.armed.next = self.state.q.val() == InjState::Armed;
    }
}

canstar_hdl::impl_clocked!(Injector);
