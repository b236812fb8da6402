//! Shared helpers of the block tests: imports, random bit strings, a software
//! destuffer, the co-simulation length.
#![allow(dead_code, unused_imports)]

pub use canstar_hdl::crc15::{crc15_bits, crc15_bytes, Crc15};
pub use canstar_hdl::drive;
pub use canstar_hdl::flow;
pub use canstar_hdl::stuff::{stuff_bits, BitDestuffer, BitStuffer};
pub use canstar_hdl::sync::{EdgeDetector, Synchroniser};
pub use proptest::prelude::*;
pub use rand::{Rng, SeedableRng};
pub use rand_chacha::ChaCha8Rng;

pub const FLOW_CYCLES: usize = 100_000;

// ---------------------------------------------------------------- helpers

/// A bit string made of runs of equal bits, each 1..=max_run long (so that
/// runs of 5 and more, which trigger stuffing, are common).
pub fn runs(rng: &mut ChaCha8Rng, n: usize, max_run: usize) -> Vec<bool> {
    let mut v = Vec::with_capacity(n);
    let mut level = rng.gen::<bool>();
    while v.len() < n {
        let len = rng.gen_range(1..=max_run);
        for _ in 0..len.min(n - v.len()) {
            v.push(level);
        }
        level = !level;
    }
    v
}

pub fn bytes_to_bits(bytes: &[u8]) -> Vec<bool> {
    bytes.iter().flat_map(|b| (0..8).rev().map(move |i| (b >> i) & 1 == 1)).collect()
}

/// Software destuffing by the window rule (independent of the counter
/// formulation of the RTL): bit i is a stuff error when bits i-5..=i are
/// equal, a stuff bit when bits i-5..i are equal and bit i differs.
/// Returns the data bits and the stuff-bit positions, or the error position.
pub fn destuff_sw(stream: &[bool]) -> Result<(Vec<bool>, Vec<usize>), usize> {
    let mut data = vec![];
    let mut stuff = vec![];
    for i in 0..stream.len() {
        if i >= 5 && stream[i - 5..i].iter().all(|&b| b == stream[i - 1]) {
            if stream[i] == stream[i - 1] {
                return Err(i);
            }
            stuff.push(i);
        } else {
            data.push(stream[i]);
        }
    }
    Ok((data, stuff))
}

pub fn max_run(bits: &[bool]) -> usize {
    let (mut best, mut cur) = (0, 0);
    for i in 0..bits.len() {
        cur = if i > 0 && bits[i] == bits[i - 1] { cur + 1 } else { 1 };
        best = best.max(cur);
    }
    best
}
