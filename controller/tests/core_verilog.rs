//! The Verilog flow of CanCore: Verilator lint, Yosys synthesis and a
//! co-simulation of the emitted Verilog against the Rust model, on a bus
//! waveform of real frames (the dlc and stuffbit program frames first, then
//! random frames with disturbances), with the core's own TX wired-AND into
//! its RX, transmit requests, mode changes, resets and timing changes.
mod common;
use canstar_controller::core::CanCore;
use canstar_hdl::flow;
use common::core_bus::fields_timing;
use common::stim::{dlc_and_stuffbit_frames, random_frame, BusScript};
use rand::Rng;
use std::cell::Cell;
use std::rc::Rc;

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn core_verilog_flow() {
    let mut u = CanCore::new();
    // Phase 1: the dlc and stuffbit program frames, undisturbed, the core
    // only receiving. Phase 2: random frames, disturbances, own requests,
    // mode and timing changes.
    let mut script = BusScript::new(0.0);
    let prefix = dlc_and_stuffbit_frames();
    let n_prefix = prefix.len();
    script.push_idle(12); // integration
    script.push_frames_with(&prefix);
    let mut phase2 = false;
    // timings (value - 1): T10/6/4, T10/8/1, T25/17/1, T10/6/2, and an invalid one
    let timings = [(0u64, 0u64, 3u64, 3u64), (0, 4, 1, 0), (0, 7, 7, 0), (1, 0, 3, 1), (0, 0, 0, 0)];
    let mut bit_clocks = 10u32;
    let mut left = 0u32;
    let mut level = true;
    let mut req_timer = 0u32;
    let stats = Rc::new(Cell::new((0usize, 0usize, 0usize, 0usize)));
    let st = stats.clone();
    let cycles = 260_000;
    let (synth, cs) = flow::full_check(&mut u, "cancore", cycles, 5, move |u, rng, cycle| {
        // count what the model did in the last cycle
        let mut s = st.get();
        s.0 += u.rx_valid.val() as usize;
        s.1 += u.tx_done.val() as usize;
        s.2 += u.error.val() as usize;
        s.3 += u.arb_lost.val() as usize;
        st.set(s);
        if !phase2 && script.queued() == 0 {
            phase2 = true;
            script.disturb = 0.002;
            assert_eq!(s.0, n_prefix, "every dlc/stuffbit frame delivered at cycle {cycle}");
        }

        let reset = cycle < 3 || (phase2 && cycle % 37_000 == 0);
        u.reset.next = reset;
        if reset {
            let t = if cycle < 3 { timings[0] } else { timings[rng.gen_range(0..timings.len())] };
            let cfg = fields_timing(t, false);
            u.set_timing(&cfg);
            bit_clocks = cfg.ntq() * cfg.brp;
        }
        // While the core transmits a frame (SOF .. EOF), the scripted other
        // nodes pause and acknowledge it (almost always).
        let field = u.dbg_field.val().index();
        if u.dbg_role.val() && (4..=17).contains(&field) {
            left = 0;
            level = !(field == 15 && (cycle % 9_000) > 300);
        } else {
            if left == 0 {
                level = script.next_bit(rng);
                left = bit_clocks;
                // occasional phase error of the other nodes' bits
                if rng.gen_bool(0.03) {
                    left = (left as i32 + rng.gen_range(-2..=2)).max(1) as u32;
                }
            }
            left -= 1;
        }
        u.rx.next = level & u.tx.val();
        if req_timer == 0 && phase2 {
            req_timer = rng.gen_range(200..8_000);
            let want = rng.gen_bool(0.6);
            u.tx_req.next = want;
            if want {
                let f = random_frame(rng);
                u.tx_ide.next = f.ide;
                u.tx_rtr.next = f.rtr;
                u.tx_id.next = (f.id as u64).into();
                u.tx_dlc.next = (f.dlc as u64).into();
                u.tx_data.next = f.data_word().into();
            }
        }
        req_timer = req_timer.saturating_sub(1);
        u.single_shot.next = phase2 && cycle % 50_000 > 42_000;
        u.self_test.next = phase2 && cycle % 45_000 > 40_000;
        u.listen_only.next = phase2 && cycle % 70_000 > 66_000;
        u.host_recovery.next = phase2 && cycle % 60_000 > 52_000;
        u.triple.next = phase2 && cycle % 80_000 > 72_000;
        u.recover.next = phase2 && rng.gen_bool(0.0005);
        u.tx_abort.next = phase2 && rng.gen_bool(0.00005);
        (u.cnt_load.next, u.tec_in.next, u.rec_in.next) = (phase2 && cycle % 23_000 < 3, ((cycle * 37 % 512) as u64).into(), ((cycle * 11 % 256) as u64).into());
    })
    .expect("CanCore Verilog flow");
    assert_eq!(cs.cycles, cycles);
    assert!(synth.cells > 0);
    let (rxv, txd, err, arb) = stats.get();
    eprintln!("cosim: {rxv} frames received, {txd} sent, {err} errors, {arb} arbitration losses; {} cells", synth.cells);
    assert!(rxv >= 150 && txd >= 5 && err >= 20, "stimulus too weak: {rxv} {txd} {err} {arb}");
}

/// Size of the core on an iCE40 (printed; the assertion only checks that
/// synthesis succeeds and the design is not optimised away).
#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn core_ice40_size() {
    let mut u = CanCore::new();
    canstar_hdl::drive::init(&mut u);
    let v = flow::emit(&u);
    let r = flow::synth_check(&v, "top", flow::SynthTarget::Ice40).expect("synth_ice40");
    let lines: Vec<&str> = r.stat.lines().filter(|l| l.contains("SB_LUT4") || l.contains("SB_DFF") || l.contains("cells")).collect();
    eprintln!("CanCore on iCE40:\n{}", lines.join("\n"));
    assert!(r.cells > 500, "{}", r.stat);
}
