//! The shared RTL blocks: compiled model against rust-hdl on seeded random stimulus,
//! every output every cycle, every atom at checkpoints.

use canstar_hdl::{btl, crc15, drive::Clocked, stuff, sync};
use canstar_models::generated as g;
use canstar_models::lockstep::{Lockstep, RandomInputs};
use canstar_rtlc::rt::{Block, Model};

fn run<H: Clocked, M: Model>(
    hdl: H,
    make: fn(&dyn Block) -> Result<M, canstar_rtlc::Error>,
    set: fn(&mut H, &[u128]),
    get: fn(&H, &mut [u128]),
    cycles: u64,
    seed: u64,
    prob: impl Fn(&str) -> f64,
) {
    let mut l = Lockstep::new(hdl, make, set, get).unwrap_or_else(|m| panic!("{m}"));
    let mut stim = RandomInputs::new(&l.model, seed, prob);
    for c in 0..cycles {
        l.step(stim.draw()).unwrap_or_else(|m| panic!("{m}"));
        if c % 100_000 == 99_999 {
            l.compare_all().unwrap_or_else(|m| panic!("{m}"));
        }
    }
    let n = l.compare_all().unwrap_or_else(|m| panic!("{m}"));
    assert!(n > 5);
}

fn reset_rare(name: &str) -> f64 {
    if name == "reset" {
        0.001
    } else {
        0.3
    }
}

#[test]
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn synchroniser_both_depths() {
    for depth in [1, 2] {
        run(sync::Synchroniser::new(depth), g::synchroniser::Synchroniser::from_instance, g::synchroniser::hdl_set_inputs, g::synchroniser::hdl_outputs, 500_000, depth as u64, reset_rare);
    }
}

#[test]
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn edge_detector() {
    run(sync::EdgeDetector::default(), g::edge_detector::EdgeDetector::from_instance, g::edge_detector::hdl_set_inputs, g::edge_detector::hdl_outputs, 1_000_000, 3, reset_rare);
}

#[test]
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn crc15() {
    run(crc15::Crc15::default(), g::crc15::Crc15::from_instance, g::crc15::hdl_set_inputs, g::crc15::hdl_outputs, 1_000_000, 4, |n| if n == "clear" || n == "reset" { 0.002 } else { 0.4 });
}

#[test]
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn stuffer_and_destuffer() {
    run(stuff::BitStuffer::default(), g::bit_stuffer::BitStuffer::from_instance, g::bit_stuffer::hdl_set_inputs, g::bit_stuffer::hdl_outputs, 1_000_000, 5, reset_rare);
    run(stuff::BitDestuffer::default(), g::bit_destuffer::BitDestuffer::from_instance, g::bit_destuffer::hdl_set_inputs, g::bit_destuffer::hdl_outputs, 1_000_000, 6, reset_rare);
}

#[test]
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn bit_timing() {
    // timing fields change rarely (also to invalid values), RX at random
    let prob = |n: &str| match n {
        "reset" => 0.0005,
        "rx" => 0.05,
        "brp" | "prop" | "ph1" | "ph2" | "sjw" | "triple" => 0.00005,
        _ => 0.02,
    };
    let mut b = btl::BitTiming::default();
    b.set_config(&btl::BtlConfig::from_fields(1, 1, 3, 3, 2, false));
    run(b, g::bit_timing::BitTiming::from_instance, g::bit_timing::hdl_set_inputs, g::bit_timing::hdl_outputs, 1_000_000, 7, prob);
}

/// The operator-semantics design (`canstar_models::semantics`), all inputs random.
#[test]
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn operator_semantics() {
    use canstar_models::semantics::Ops;
    run(Ops::default(), g::semantics::Ops::from_instance, g::semantics::hdl_set_inputs, g::semantics::hdl_outputs, 300_000, 8, |_| 0.5);
}
