//! CAN bit stuffing: after 5 consecutive equal bits in the stuffed area (SOF
//! through the last CRC bit, including a stuff bit that follows it), one bit
//! of the opposite level is inserted. A stuff bit counts as the first bit of
//! the next run, so the run counter is simply the length of the current run of
//! equal levels (at most 5 in a correct stream).
//!
//! Both blocks work on strobes: `en` marks the clock at which one bit is
//! taken (sampled for the destuffer, sent for the stuffer). `active` says
//! whether that bit lies in the stuffed area; at an `en` with `active` low the
//! run counter is cleared, so the first active bit (SOF) starts a new run of 1.
//!
//! # [`BitDestuffer`]
//!
//! | port    | dir | meaning |
//! |---------|-----|---------|
//! | `clock` | in  | system clock |
//! | `reset` | in  | synchronous, active high: run cleared |
//! | `en`    | in  | strobe: one bit was sampled this clock |
//! | `din`   | in  | its level (not `bit`: a SystemVerilog keyword) |
//! | `active`| in  | this bit is in the stuffed area (low: clear the run at `en`) |
//! | `stuff_bit`  | out | combinational, `en & active` qualified: this bit follows 5 equal bits and has the opposite level: drop it |
//! | `stuff_error`| out | combinational, `en & active` qualified: this bit is the 6th equal bit |
//! | `next_is_stuff` | out | from registers: 5 equal bits seen, the next active bit is a stuff bit |
//! | `stuff_level`   | out | from registers: the level that stuff bit must have (complement of the run); meaningful when `next_is_stuff` |
//!
//! After a stuff error the run counter stays at 5 (every further equal bit is
//! a stuff error again, an opposite bit is taken as a stuff bit); the
//! controller aborts the frame anyway.
//!
//! The controller keeps `active` high for the bit after the last CRC bit
//! when `next_is_stuff` is set: that bit is the final stuff bit, part of the
//! stuffed area.
//!
//! # [`BitStuffer`]
//!
//! | port    | dir | meaning |
//! |---------|-----|---------|
//! | `clock` | in  | system clock |
//! | `reset` | in  | synchronous, active high: run cleared |
//! | `en`    | in  | strobe: advance, the current `out` has been sent |
//! | `data`  | in  | the next data bit the frame logic wants to send |
//! | `active`| in  | stuffing enabled for the current bit (low: clear the run at `en`) |
//! | `out`   | out | combinational: the bit to send now: `data`, or after 5 equal bits (with `active`) the complement of the run |
//! | `is_stuff` | out | combinational: `out` is a stuff bit; the frame logic must not consume `data` at this `en` |
//! | `stuff_pending` | out | from registers: 5 equal bits sent, the next active bit is a stuff bit (extra output, independent of `active`) |
//!
//! The frame logic keeps `active` high until the stuff bit that may follow
//! the last CRC bit has been sent (`stuff_pending` tells it one is due).
//!
//! # Software
//!
//! [`stuff_bits`] stuffs a whole bit string the same way (oracle for tests and
//! frame builders).

use rust_hdl::prelude::*;

/// Receive-side run counter: flags stuff bits to drop and stuff errors.
#[derive(LogicBlock, Default)]
pub struct BitDestuffer {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub en: Signal<In, Bit>,
    pub din: Signal<In, Bit>,
    pub active: Signal<In, Bit>,
    /// This bit is a stuff bit (drop it). Valid on the `en` clock.
    pub stuff_bit: Signal<Out, Bit>,
    /// This bit is the 6th equal bit. Valid on the `en` clock.
    pub stuff_error: Signal<Out, Bit>,
    /// The next active bit is a stuff bit.
    pub next_is_stuff: Signal<Out, Bit>,
    /// The level that stuff bit must have.
    pub stuff_level: Signal<Out, Bit>,
    /// Length of the current run (0: no run yet).
    cnt: DFF<Bits<3>>,
    /// Level of the current run.
    lvl: DFF<Bit>,
    at5: Signal<Local, Bit>,
    same: Signal<Local, Bit>,
    take: Signal<Local, Bit>,
}

impl Logic for BitDestuffer {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, cnt, lvl);
        self.at5.next = self.cnt.q.val() == 5;
        self.same.next = (self.cnt.q.val() != 0) & (self.din.val() == self.lvl.q.val());
        self.take.next = self.en.val() & self.active.val();
        self.next_is_stuff.next = self.at5.val();
        self.stuff_level.next = !self.lvl.q.val();
        self.stuff_bit.next = self.take.val() & self.at5.val() & (!self.same.val());
        self.stuff_error.next = self.take.val() & self.at5.val() & self.same.val();
        if self.en.val() {
            if self.active.val() {
                if self.same.val() {
                    if !self.at5.val() {
                        self.cnt.d.next = self.cnt.q.val() + 1;
                    }
                } else {
                    self.cnt.d.next = 1.into();
                    self.lvl.d.next = self.din.val();
                }
            } else {
                self.cnt.d.next = 0.into();
            }
        }
        if self.reset.val() {
            self.cnt.d.next = 0.into();
            self.lvl.d.next = false;
        }
    }
}

crate::impl_clocked!(BitDestuffer);

/// Transmit-side stuffer: inserts the complement after 5 equal bits.
#[derive(LogicBlock, Default)]
pub struct BitStuffer {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub en: Signal<In, Bit>,
    pub data: Signal<In, Bit>,
    pub active: Signal<In, Bit>,
    /// The bit to send now.
    pub out: Signal<Out, Bit>,
    /// `out` is a stuff bit (do not consume `data` at this `en`).
    pub is_stuff: Signal<Out, Bit>,
    /// 5 equal bits sent: the next active bit is a stuff bit.
    pub stuff_pending: Signal<Out, Bit>,
    /// Length of the current run of sent bits (0: no run yet).
    cnt: DFF<Bits<3>>,
    /// Level of the current run.
    lvl: DFF<Bit>,
    at5: Signal<Local, Bit>,
    stf: Signal<Local, Bit>,
    o: Signal<Local, Bit>,
}

impl Logic for BitStuffer {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, cnt, lvl);
        self.at5.next = self.cnt.q.val() == 5;
        self.stf.next = self.active.val() & self.at5.val();
        self.o.next = self.data.val();
        if self.stf.val() {
            self.o.next = !self.lvl.q.val();
        }
        self.out.next = self.o.val();
        self.is_stuff.next = self.stf.val();
        self.stuff_pending.next = self.at5.val();
        if self.en.val() {
            if self.active.val() {
                if (self.cnt.q.val() != 0) & (self.o.val() == self.lvl.q.val()) {
                    self.cnt.d.next = self.cnt.q.val() + 1;
                } else {
                    self.cnt.d.next = 1.into();
                    self.lvl.d.next = self.o.val();
                }
            } else {
                self.cnt.d.next = 0.into();
            }
        }
        if self.reset.val() {
            self.cnt.d.next = 0.into();
            self.lvl.d.next = false;
        }
    }
}

crate::impl_clocked!(BitStuffer);

/// Stuff a bit string: after every run of 5 equal bits (stuff bits count as
/// the first bit of the next run) insert the opposite level, including after
/// the last bit, as CAN does after the CRC sequence.
pub fn stuff_bits(bits: &[bool]) -> Vec<bool> {
    let mut out = Vec::with_capacity(bits.len() + bits.len() / 4 + 1);
    let mut run = 0usize;
    let mut level = false;
    let mut push = |b: bool, out: &mut Vec<bool>| {
        if run > 0 && b == level {
            run += 1;
        } else {
            level = b;
            run = 1;
        }
        out.push(b);
        run == 5
    };
    for &b in bits {
        if push(b, &mut out) {
            let s = !b;
            push(s, &mut out);
        }
    }
    out
}
