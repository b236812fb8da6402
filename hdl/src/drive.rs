//! Direct drive of rust-hdl blocks.
//!
//! rust-hdl's own `Simulation` engine runs every testbench in a thread and
//! exchanges the design through channels, which makes it about 1000 times
//! slower than driving the design directly. Every canstar simulation, unit
//! test and co-simulation uses the functions here instead: set the inputs,
//! settle, raise the clock, settle, lower the clock, settle.

use rust_hdl::prelude::*;

/// Iterations allowed for combinational logic to settle after a change.
pub const MAX_SETTLE_ITERS: usize = 1000;

/// A block with one clock input, as every canstar RTL block has
/// (one clock per chip, clock enables for time quanta and sample points).
pub trait Clocked: Block {
    fn clock_input(&mut self) -> &mut Signal<In, Clock>;
}

/// Implement [`Clocked`] for a block whose clock input is the field `clock`.
#[macro_export]
macro_rules! impl_clocked {
    ($t:ty) => {
        impl $crate::drive::Clocked for $t {
            fn clock_input(&mut self) -> &mut rust_hdl::prelude::Signal<rust_hdl::prelude::In, rust_hdl::prelude::Clock> {
                &mut self.clock
            }
        }
    };
}

/// Propagate pending input changes until the design is stable.
///
/// Panics if the logic does not converge (a combinational loop).
#[inline]
pub fn settle<B: Block>(uut: &mut B) {
    if !simulate(uut, MAX_SETTLE_ITERS) {
        panic!("logic did not settle within {MAX_SETTLE_ITERS} iterations (combinational loop?)");
    }
}

/// Connect a freshly built block and settle it with the clock low.
pub fn init<B: Clocked>(uut: &mut B) {
    uut.connect_all();
    uut.clock_input().next = Clock::from(false);
    settle(uut);
}

/// One full clock cycle. Inputs set (through `.next`) before the call are
/// propagated first, then the rising edge is applied, then the falling edge.
/// After the call, outputs show the state after the rising edge.
#[inline]
pub fn cycle<B: Clocked>(uut: &mut B) {
    settle(uut);
    rising_edge(uut);
    falling_edge(uut);
}

/// Apply only the rising edge (inputs must already be settled).
#[inline]
pub fn rising_edge<B: Clocked>(uut: &mut B) {
    uut.clock_input().next = Clock::from(true);
    settle(uut);
}

/// Apply only the falling edge.
#[inline]
pub fn falling_edge<B: Clocked>(uut: &mut B) {
    uut.clock_input().next = Clock::from(false);
    settle(uut);
}
