//! Error-flag generator (`efgTxSignal` of the reference, H6).
//!
//! On `trigger` (a one-clock strobe at a sample point: the frame monitor detected a
//! stuff, CRC or form error, or a judge unit blamed a port) the generator waits for the
//! next `bit_start` strobe (start of the next bit) and then drives `efg` dominant (0) for
//! exactly 6 bit times (until the 7th `bit_start`). It never sends overload flags.
//! A trigger while a flag is pending or being sent is ignored (one flag per episode).
//!
//! `busy` is 1 from the clock after the trigger until the flag ends: the hub treats
//! that time as error phase, so the judges do not blame the error flags that the
//! nodes send in answer to the hub's flag before the frame monitor itself enters its
//! error phase. `active` is 1 while the flag is driven (H9 status).
//! Reset (`reset` = 1, synchronous) stops any flag.

use rust_hdl::prelude::*;

/// Length of the hub's error flag in bits.
pub const EFG_FLAG_BITS: u64 = 6;

#[derive(LogicBlock, Default)]
pub struct ErrorFlagGen {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub trigger: Signal<In, Bit>,
    pub bit_start: Signal<In, Bit>,
    pub efg: Signal<Out, Bit>,
    pub busy: Signal<Out, Bit>,
    pub active: Signal<Out, Bit>,
    pending: DFF<Bit>,
    driving: DFF<Bit>,
    cnt: DFF<Bits<3>>,
}

impl Logic for ErrorFlagGen {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, pending, driving, cnt);
        if self.bit_start.val() {
            if self.pending.q.val() {
                self.pending.d.next = false;
                self.driving.d.next = true;
                self.cnt.d.next = 0.into();
            } else if self.driving.q.val() {
                if self.cnt.q.val() == 5 {
                    self.driving.d.next = false;
                } else {
                    self.cnt.d.next = self.cnt.q.val() + 1;
                }
            }
        }
        if self.trigger.val() & !self.pending.q.val() & !self.driving.q.val() {
            self.pending.d.next = true;
        }
        if self.reset.val() {
            self.pending.d.next = false;
            self.driving.d.next = false;
            self.cnt.d.next = 0.into();
        }
        self.efg.next = !self.driving.q.val();
        self.active.next = self.driving.q.val();
        self.busy.next = self.pending.q.val() | self.driving.q.val();
    }
}

canstar_hdl::impl_clocked!(ErrorFlagGen);
