//! Icarus co-simulation of every committed generated top level (the files in
//! `verilog-out/` exactly as committed, not a fresh emission) against the Rust
//! model built with the default configuration, every output compared every
//! cycle. `canstar generate --check` separately proves the committed files are
//! what the default configuration generates.
use canstar_hdl::{btl, crc15, flow, stuff, sync};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::path::Path;

const CYCLES: usize = 30_000;

fn committed(rel: &str) -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("verilog-out").join(rel))
        .unwrap_or_else(|e| panic!("verilog-out/{rel}: {e}"))
}

/// A level that changes at random moments (about every `mean` cycles).
fn wander(rng: &mut ChaCha8Rng, v: bool, mean: u32) -> bool {
    if rng.gen_ratio(1, mean) { !v } else { v }
}

fn run<B: canstar_hdl::drive::Clocked>(uut: &mut B, file: &str, top: &str, mut stim: impl FnMut(&mut B, &mut ChaCha8Rng, usize)) {
    canstar_hdl::drive::init(uut);
    // The co-simulation test bench instantiates module `top`: name the
    // committed module so, and leave out the board/vector wrapper around it
    // (wrappers are checked by lint and synthesis in generated_verilog.rs).
    let v = committed(file);
    let stem = Path::new(file).file_stem().unwrap().to_string_lossy().into_owned();
    let mut v = v.replace(&format!("module {top}("), "module top(");
    for wrapper in [stem.clone(), format!("{stem}_board")] {
        if wrapper != top {
            if let Some(i) = v.find(&format!("\nmodule {wrapper}(")) {
                v.truncate(i + 1);
            }
        }
    }
    let v = v.as_str();
    let r = flow::cosim_with_verilog(uut, v, top, CYCLES, 7, &mut stim).unwrap_or_else(|e| panic!("{file} ({top}): {e}"));
    assert_eq!(r.cycles, CYCLES);
}

#[test]
#[ignore = "needs iverilog: run scripts/test-all.sh"]
fn committed_blocks_cosimulate() {
    run(&mut sync::Synchroniser::new(2), "blocks/canstar_synchroniser.v", "canstar_synchroniser", |u, r, c| {
        u.reset.next = c < 3 || r.gen_ratio(1, 5000);
        u.d.next = wander(r, u.d.val(), 4);
    });
    run(&mut sync::EdgeDetector::default(), "blocks/canstar_edge_detector.v", "canstar_edge_detector", |u, r, c| {
        u.reset.next = c < 3 || r.gen_ratio(1, 5000);
        u.d.next = wander(r, u.d.val(), 5);
    });
    run(&mut crc15::Crc15::default(), "blocks/canstar_crc15.v", "canstar_crc15", |u, r, c| {
        u.reset.next = c < 3 || r.gen_ratio(1, 5000);
        u.clear.next = r.gen_ratio(1, 200);
        u.en.next = r.gen_bool(0.5);
        u.din.next = r.gen();
    });
    run(&mut stuff::BitStuffer::default(), "blocks/canstar_bit_stuffer.v", "canstar_bit_stuffer", |u, r, c| {
        u.reset.next = c < 3 || r.gen_ratio(1, 5000);
        u.en.next = r.gen_bool(0.3);
        u.data.next = wander(r, u.data.val(), 6);
        u.active.next = !r.gen_ratio(1, 300);
    });
    run(&mut stuff::BitDestuffer::default(), "blocks/canstar_bit_destuffer.v", "canstar_bit_destuffer", |u, r, c| {
        u.reset.next = c < 3 || r.gen_ratio(1, 5000);
        u.en.next = r.gen_bool(0.3);
        u.din.next = wander(r, u.din.val(), 6);
        u.active.next = !r.gen_ratio(1, 300);
    });
    run(&mut btl::BitTiming::default(), "blocks/canstar_bit_timing.v", "canstar_bit_timing", |u, r, c| {
        u.reset.next = c < 3 || r.gen_ratio(1, 20_000);
        if c % 7_000 == 0 {
            let cfg = btl::BtlConfig::from_fields(r.gen_range(1..4), r.gen_range(1..5), r.gen_range(2..6), r.gen_range(0..6), r.gen_range(1..3), r.gen_bool(0.2));
            u.set_config(&cfg);
        }
        u.rx.next = wander(r, u.rx.val(), 40);
        u.drive.next = wander(r, u.drive.val(), 60);
        u.hs_en.next = !r.gen_ratio(1, 50);
    });
}

#[test]
#[ignore = "needs iverilog: run scripts/test-all.sh"]
fn committed_controller_core_cosimulates() {
    // Loopback with self-test: the core transmits its own requests, with
    // occasional disturbed bits that cause errors and error flags.
    let mut uut = canstar_controller::core::CanCore::with_sync_depth(2);
    let (mut done, mut errors, mut dist) = (0, 0, 0u32);
    run(&mut uut, "controller/canstar_can_core.v", "canstar_can_core", |u, r, c| {
        done += u.tx_done.val() as u32;
        errors += u.error.val() as u32;
        u.reset.next = c < 5;
        u.brp.next = 1.into();
        u.prop.next = 2.into();
        u.ph1.next = 3.into();
        u.ph2.next = 3.into();
        u.sjw.next = 1.into();
        u.self_test.next = true;
        // a disturbance of about one bit time now and then
        if dist == 0 && r.gen_ratio(1, 3_000) {
            dist = 24;
        }
        dist = dist.saturating_sub(1);
        u.rx.next = u.tx.val() ^ (dist > 0);
        if r.gen_ratio(1, 400) {
            u.tx_req.next = true;
            u.tx_ide.next = r.gen();
            u.tx_rtr.next = r.gen_ratio(1, 5);
            u.tx_id.next = (r.gen::<u32>() as u64 & 0x1FFF_FFFF).into();
            u.tx_dlc.next = (r.gen_range(0..16u64)).into();
            u.tx_data.next = r.gen::<u64>().into();
        } else if r.gen_ratio(1, 50) {
            u.tx_req.next = false;
        }
    });
    // the stimulus exercised frames and errors, not only idle
    assert!(done >= 5 && errors >= 1, "{done} frames sent, {errors} errors");
}

#[test]
#[ignore = "needs iverilog: run scripts/test-all.sh"]
fn committed_sja1000_cosimulates() {
    // Wishbone cycles with random addresses and data (mode, command, timing,
    // TX buffer writes; reads of every register), CAN loopback.
    // the committed file is generated with the default configuration's power-up BTR values
    let (btr0, btr1) = canstar::config::btr(&canstar::config::Config::default().bit_timing);
    let mut uut = canstar_controller::sja1000::Sja1000::with_reset_timing(btr0, btr1);
    run(&mut uut, "controller/canstar_sja1000.v", "canstar_sja1000", |u, r, c| {
        u.rst.next = c < 5;
        u.rx.next = u.tx.val() ^ r.gen_ratio(1, 5_000);
        if u.wb_ack.val() || !u.wb_cyc.val() {
            let go = r.gen_ratio(1, 8);
            u.wb_cyc.next = go;
            u.wb_stb.next = go;
            u.wb_we.next = r.gen_bool(0.4);
            let adr: u64 = if r.gen_bool(0.5) { r.gen_range(0..32) } else { r.gen_range(0..128) };
            u.wb_adr.next = adr.into();
            let dat: u64 = match adr {
                0 => r.gen_range(0..16) & !0x1 | (r.gen_ratio(1, 20) as u64), // mostly operating mode
                1 => 1 << r.gen_range(0..5),                                   // one command at a time
                _ => r.gen_range(0..256),
            };
            u.wb_dat_w.next = dat.into();
        }
    });
}

#[test]
#[ignore = "needs iverilog: run scripts/test-all.sh"]
fn committed_slcan_cosimulates() {
    // The host opens the channel at the power-up rate (S6) and sends a frame,
    // F and V at the committed 115200 baud (139 clocks per bit); the CAN bus
    // is the adapter's own TX (no ACK: error frames and retransmissions) with
    // rare disturbances.
    let config = canstar::config::Config::default();
    let p = config.slcan.params().unwrap();
    let mut uut = canstar_controller::slcan::SlcanTop::new(&p).with_rec_rule(config.controller.rec_rule);
    let cpb = p.clocks_per_bit as usize;
    let mut levels = vec![true; 10];
    for b in b"O\rt1232AABB\rF\rV\r" {
        levels.extend(std::iter::repeat(false).take(cpb));
        for k in 0..8 {
            levels.extend(std::iter::repeat(b >> k & 1 == 1).take(cpb));
        }
        levels.extend(std::iter::repeat(true).take(cpb));
    }
    assert!(levels.len() < CYCLES);
    let (mut replies, mut dominant) = (0, 0);
    run(&mut uut, "controller/canstar_slcan.v", "canstar_slcan", |u, r, c| {
        replies += (!u.uart_tx.val()) as usize;
        dominant += (!u.tx.val()) as usize;
        u.rst.next = c < 5;
        u.uart_rx.next = *levels.get(c).unwrap_or(&true);
        u.rx.next = u.tx.val() ^ r.gen_ratio(1, 20_000);
    });
    assert!(replies > 0, "the adapter never answered");
    assert!(dominant > 0, "the frame never reached the CAN pin");
}

#[test]
#[ignore = "needs iverilog: run scripts/test-all.sh"]
fn committed_hubs_cosimulate() {
    for (file, top, cfg) in [
        ("hub/canstar_hub.v", "canstar_hub_core", canstar_hub::config::HubConfig::default()),
        ("hub/canstar_cancentrate.v", "canstar_cancentrate_core", canstar_hub::config::HubConfig { sublinks: 0, ..Default::default() }),
    ] {
        let mut uut = canstar_hub::top::Hub::new(&cfg);
        let mut blamed = 0;
        // Mostly recessive uplinks with dominant bursts of bit length (16
        // clocks) and occasional long dominant runs, so that frames start,
        // errors are flagged and ports get blamed and isolated.
        run(&mut uut, file, top, |u, r, c| {
            blamed += u.isolated.iter().filter(|s| s.val()).count();
            u.rst_n.next = c >= 5;
            u.inject_fault.next = r.gen_ratio(1, 20_000);
            for (i, p) in u.rx.iter_mut().chain(u.reh_rx.iter_mut()).enumerate() {
                if c % 16 == 0 {
                    let v = if (c / 4096 + i) % 5 == 0 { r.gen_bool(0.3) } else { !r.gen_ratio(1, 12) };
                    p.next = v;
                }
            }
        });
        assert!(blamed > 0, "{file}: the stimulus never made the hub isolate a port");
    }
}
