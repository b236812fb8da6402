//! Input synchroniser and edge detector for the CAN receive line.
//!
//! # [`Synchroniser`]
//!
//! A chain of 1 or 2 flip-flops that brings the asynchronous `RX` pin into
//! the clock domain (2 stages for a real pin, 1 where a shorter loop delay
//! matters more than metastability, e.g. a simulated bus).
//!
//! | port    | dir | meaning |
//! |---------|-----|---------|
//! | `clock` | in  | the one system clock |
//! | `reset` | in  | synchronous, active high: every stage becomes 1 |
//! | `d`     | in  | the asynchronous input |
//! | `q`     | out | `d` delayed by [`Synchroniser::latency`] clocks |
//!
//! Power-up and reset value is 1, the recessive CAN level, so that a node
//! coming out of reset does not see a spurious dominant edge. Flip-flops power
//! up at 0 (in Rust and in the emitted Verilog alike), so every stage stores
//! the *inverted* level; `q` is 1 from cycle 0 in both.
//!
//! # [`EdgeDetector`]
//!
//! Compares `d` with its value of the previous clock (a register, 1 after
//! power-up and reset).
//!
//! | port    | dir | meaning |
//! |---------|-----|---------|
//! | `clock` | in  | system clock |
//! | `reset` | in  | synchronous, active high: the previous value becomes 1 |
//! | `d`     | in  | the (already synchronised) level |
//! | `fall`  | out | combinational: previous 1, `d` now 0 (recessive-to-dominant edge) |
//! | `rise`  | out | combinational: previous 0, `d` now 1 (dominant-to-recessive edge) |
//! | `prev`  | out | the registered previous value (extra output) |
//!
//! `fall` and `rise` are not masked by `reset`: they compare `d` with the
//! register whatever `reset` is.

use rust_hdl::prelude::*;

/// 1- or 2-stage input synchroniser, reset and power-up level 1.
#[derive(LogicBlock)]
pub struct Synchroniser {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub d: Signal<In, Bit>,
    pub q: Signal<Out, Bit>,
    /// true: 2 stages, false: 1 stage.
    two_stages: Constant<Bit>,
    /// First stage, inverted level.
    s1_n: DFF<Bit>,
    /// Second stage, inverted level (unused with 1 stage; synthesis removes it).
    s2_n: DFF<Bit>,
}

impl Synchroniser {
    /// A synchroniser of `depth` flip-flops. Panics unless `depth` is 1 or 2.
    pub fn new(depth: usize) -> Self {
        assert!(depth == 1 || depth == 2, "Synchroniser depth must be 1 or 2, got {depth}");
        Self {
            clock: Default::default(),
            reset: Default::default(),
            d: Default::default(),
            q: Default::default(),
            two_stages: Constant::new(depth == 2),
            s1_n: Default::default(),
            s2_n: Default::default(),
        }
    }

    /// Clocks from `d` to `q` (1 or 2).
    pub fn latency(&self) -> usize {
        if self.two_stages.val() {
            2
        } else {
            1
        }
    }
}

impl Default for Synchroniser {
    /// Two stages.
    fn default() -> Self {
        Self::new(2)
    }
}

impl Logic for Synchroniser {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, s1_n, s2_n);
        self.s1_n.d.next = !self.d.val();
        self.s2_n.d.next = self.s1_n.q.val();
        if self.reset.val() {
            self.s1_n.d.next = false;
            self.s2_n.d.next = false;
        }
        self.q.next = !self.s1_n.q.val();
        if self.two_stages.val() {
            self.q.next = !self.s2_n.q.val();
        }
    }
}

crate::impl_clocked!(Synchroniser);

/// Falling/rising edge detector against the registered previous value.
#[derive(LogicBlock, Default)]
pub struct EdgeDetector {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub d: Signal<In, Bit>,
    /// `d` went 1 -> 0 (recessive to dominant) this clock.
    pub fall: Signal<Out, Bit>,
    /// `d` went 0 -> 1 (dominant to recessive) this clock.
    pub rise: Signal<Out, Bit>,
    /// The registered previous value of `d` (1 after power-up and reset).
    pub prev: Signal<Out, Bit>,
    /// Previous value, inverted (so that power-up 0 means level 1).
    prev_n: DFF<Bit>,
}

impl Logic for EdgeDetector {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, prev_n);
        self.prev_n.d.next = !self.d.val();
        if self.reset.val() {
            self.prev_n.d.next = false;
        }
        self.prev.next = !self.prev_n.q.val();
        self.fall.next = (!self.prev_n.q.val()) & (!self.d.val());
        self.rise.next = self.prev_n.q.val() & self.d.val();
    }
}

crate::impl_clocked!(EdgeDetector);
