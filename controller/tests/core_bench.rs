//! Simulation throughput of CanCore driven directly (no bus kernel): clock
//! cycles per second and settle passes per cycle (every pass evaluates
//! every block and compares every signal, so the cost of a cycle is about
//! passes × signals). A benchmark, not a test of speed: it prints figures
//! and only checks that the core did something.
use canstar_controller::core::CanCore;
use rust_hdl::prelude::*;
use std::time::Instant;

fn settle<B: Block>(u: &mut B, passes: &mut u64) {
    loop {
        u.update_all();
        *passes += 1;
        if !u.has_changed() {
            break;
        }
        assert!(*passes < u64::MAX / 2);
    }
}

#[test]
#[ignore = "benchmark: cargo test --release -p canstar-controller --test core_bench bench_print -- --ignored --nocapture"]
fn bench_print() {
    let mut u = CanCore::new();
    u.connect_all();
    u.clock.next = Clock::from(false);
    let mut passes = 0u64;
    settle(&mut u, &mut passes);
    // 13 clocks per bit (TQ = 1 clock; SYNC 1, PROP 4, PH1 4, PH2 4); the
    // bus: the core's own TX wired-AND with a pseudo-random other node.
    let (cycles, mut x, mut frames) = (200_000u64, 12345u32, 0u64);
    passes = 0;
    let t = Instant::now();
    for c in 0..cycles {
        u.reset.next = c < 3;
        u.brp.next = 0.into();
        u.prop.next = 3.into();
        u.ph1.next = 3.into();
        u.ph2.next = 3.into();
        u.sjw.next = 0.into();
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        if c % 8 == 0 {
            u.rx.next = (x & 3 != 0) & u.tx.val();
        }
        u.tx_req.next = (c / 5000) % 2 == 1;
        u.tx_id.next = ((x >> 3) as u64 & 0x7FF).into();
        u.tx_dlc.next = 3.into();
        settle(&mut u, &mut passes);
        u.clock.next = Clock::from(true);
        settle(&mut u, &mut passes);
        u.clock.next = Clock::from(false);
        settle(&mut u, &mut passes);
        frames += (u.error.val() || u.tx_done.val() || u.rx_valid.val()) as u64;
    }
    let s = t.elapsed().as_secs_f64();
    println!(
        "CanCore: {cycles} cycles in {s:.2} s: {:.0} cycles/s, {:.2} settle passes per cycle, {:.2} us per pass",
        cycles as f64 / s,
        passes as f64 / cycles as f64,
        s * 1e6 / passes as f64
    );
    assert!(frames > 0, "the core saw no event");
}
