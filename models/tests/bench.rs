//! Throughput of the compiled models against rust-hdl direct drive on the same
//! stimulus (benchmarks: they print figures and assert only that the engines agree):
//!
//! `cargo test --release -p canstar-models --test bench -- --ignored --nocapture --exact bench_print`
//!
//! Workloads (recorded from a compiled-model run of the closed loop, then replayed
//! into each engine, so every engine gets exactly the same inputs):
//! - CanCore: 2, 3, 6 nodes on a wired-AND bus sending frames back to back;
//! - SJA1000: controller 0 of two on a bus with register-level hosts (`common/sjanet.rs`);
//! - Hub (N = 3, M = 2, with its monitor): hub A of a ReCANcentrate network
//!   (`common/hubnet.rs`).
//!
//! `bench_print_verilator_files` writes the same workloads (`common/stim.rs` format), the
//! port adapters and the expected output hashes for `models/verilator/run.sh`, which
//! measures Verilator on them. Rates are per second of this thread's CPU time.

mod common;

use canstar_controller::core::CanCore;
use canstar_hdl::drive;
use canstar_models::generated as g;
use canstar_rtlc::rt::Model;
use common::stim::{self, Stim};
use common::Ports;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Back-to-back frames for one CanCore: request again as soon as one is sent.
fn core_inputs(p: &Ports, v: &mut [u128], rng: &mut ChaCha8Rng, done: bool, cycle: u64) {
    if cycle == 0 {
        v[p.i("ph1")] = 3;
        v[p.i("ph2")] = 3;
        v[p.i("sjw")] = 3;
        v[p.i("reset")] = 1;
        v[p.i("rx")] = 1;
    }
    if cycle == 3 {
        v[p.i("reset")] = 0;
    }
    let req = p.i("tx_req");
    if done {
        v[req] = 0;
    } else if v[req] == 0 {
        v[req] = 1;
        v[p.i("tx_ide")] = rng.gen_bool(0.3) as u128;
        v[p.i("tx_id")] = rng.gen::<u32>() as u128 & 0x1fff_ffff;
        v[p.i("tx_dlc")] = rng.gen_range(0..9);
        v[p.i("tx_data")] = rng.gen::<u64>() as u128;
    }
}

/// `n` CanCore nodes on a bus, one stream per node.
fn record_can(n: usize, cycles: u64) -> Stim {
    let p = Ports::of(&g::can_core::CanCore::new());
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let mut ms: Vec<g::can_core::CanCore> = (0..n).map(|_| g::can_core::CanCore::new()).collect();
    let mut vs = vec![vec![0u128; p.ins.len()]; n];
    let mut st = Stim::new(n, p.ins.len());
    for c in 0..cycles {
        let bus = ms.iter().all(|m| m.tx);
        for k in 0..n {
            core_inputs(&p, &mut vs[k], &mut rng, ms[k].tx_done, c);
            vs[k][p.i("rx")] = bus as u128;
            ms[k].set_inputs(&vs[k]);
            ms[k].cycle();
            st.push(k, &vs[k]);
        }
        st.next();
    }
    st
}

/// SJA1000 power-up BTR0/BTR1 of the committed Verilog (`configs/default.toml`).
const SJA_BTR: (u8, u8) = (0x00, 0x14);

/// Controller 0 of two SJA1000s on a bus with hosts.
fn record_sja(cycles: u64) -> Stim {
    let mut ms = [g::sja1000::Sja1000::new(), g::sja1000::Sja1000::new()];
    let b = canstar_controller::sja1000::Sja1000::with_reset_timing(SJA_BTR.0, SJA_BTR.1);
    for m in ms.iter_mut() {
        m.load(&b).unwrap();
    }
    let mut net = common::sjanet::SjaNet::new(&ms[0], 2, 21);
    let n_out = ms[0].info().outputs.len();
    let mut outs = vec![vec![0u128; n_out]; 2];
    let mut st = Stim::new(1, ms[0].info().inputs.len());
    for _ in 0..cycles {
        for k in 0..2 {
            let v = net.inputs(k, &outs[k]).to_vec();
            ms[k].set_inputs(&v);
            ms[k].cycle();
            ms[k].outputs(&mut outs[k]);
            if k == 0 {
                st.push(0, &v);
            }
        }
        let tx = net.ix.tx;
        net.advance(outs.iter().map(|o| o[tx] != 0));
        st.next();
    }
    st
}

/// Hub A (N = 3, M = 2) in a ReCANcentrate network.
fn record_hub(cycles: u64) -> Stim {
    let mut a = g::hub_n3_m2::HubN3M2::new();
    let mut net = common::hubnet::HubNet::new(Ports::of(&a), 2, 31);
    let mut out = vec![0u128; a.info().outputs.len()];
    let mut st = Stim::new(1, a.info().inputs.len());
    for _ in 0..cycles {
        let v = net.inputs(&out).to_vec();
        a.set_inputs(&v);
        a.cycle();
        a.outputs(&mut out);
        net.advance(&out);
        st.push(0, &v);
        st.next();
    }
    st
}

/// Replay into compiled models: (cycles per CPU second per stream, output hash).
fn replay_model<M: Model>(fresh: impl Fn() -> M, st: &Stim, hash: bool) -> (f64, u64) {
    let (secs, h) = stim::replay_model(fresh, st, hash);
    ((st.cycles * st.streams as u64) as f64 / secs, h)
}

/// Replay into rust-hdl instances: (cycles per CPU second per stream, output hash).
fn replay_hdl<H: drive::Clocked>(fresh: impl Fn() -> H, set: fn(&mut H, &[u128]), get: fn(&H, &mut [u128]), n_out: usize, st: &Stim) -> (f64, u64) {
    let (secs, h) = stim::replay_hdl(fresh, set, get, n_out, st);
    ((st.cycles * st.streams as u64) as f64 / secs, h)
}

fn head(st: &Stim, cycles: u64) -> Stim {
    st.head(cycles)
}

fn line(what: &str, unit: &str, hdl: f64, model: f64) {
    println!("{what:<34} rust-hdl {hdl:>9.0} {unit}/s   compiled {model:>11.0} {unit}/s   {:>5.0}x", model / hdl);
}

#[test]
#[ignore]
fn bench_print() {
    println!("compiled models (canstar-rtlc) against rust-hdl direct drive, same recorded stimulus, per CPU second");
    for n in [2, 3, 6] {
        let st = record_can(n, 1_000_000);
        let short = head(&st, 30_000);
        let n_out = g::can_core::CanCore::new().info().outputs.len();
        let (h, hh) = replay_hdl(CanCore::new, g::can_core::hdl_set_inputs, g::can_core::hdl_outputs, n_out, &short);
        let (_, mh) = replay_model(g::can_core::CanCore::new, &short, true);
        assert_eq!(hh, mh, "the engines disagree");
        let (m, _) = replay_model(g::can_core::CanCore::new, &st, false);
        line(&format!("CanCore, {n} nodes on a bus"), "node-cycles", h, m);
    }
    let st = record_sja(2_000_000);
    let short = head(&st, 50_000);
    let sja = || canstar_controller::sja1000::Sja1000::with_reset_timing(SJA_BTR.0, SJA_BTR.1);
    let fresh = || {
        let mut m = g::sja1000::Sja1000::new();
        m.load(&sja()).unwrap();
        m
    };
    let (h, hh) = replay_hdl(sja, g::sja1000::hdl_set_inputs, g::sja1000::hdl_outputs, fresh().info().outputs.len(), &short);
    assert_eq!(hh, replay_model(fresh, &short, true).1, "the engines disagree");
    line("SJA1000 top, host traffic", "cycles", h, replay_model(fresh, &st, false).0);
    let st = record_hub(2_000_000);
    let short = head(&st, 30_000);
    let cfg = canstar_hub::config::HubConfig::default();
    let n_out = g::hub_n3_m2::HubN3M2::new().info().outputs.len();
    let (h, hh) = replay_hdl(|| canstar_hub::top::Hub::new(&cfg), g::hub_n3_m2::hdl_set_inputs, g::hub_n3_m2::hdl_outputs, n_out, &short);
    assert_eq!(hh, replay_model(g::hub_n3_m2::HubN3M2::new, &short, true).1, "the engines disagree");
    line("Hub N=3 M=2 (with monitor)", "cycles", h, replay_model(g::hub_n3_m2::HubN3M2::new, &st, false).0);
}

fn ports_h(m: &dyn Model) -> String {
    stim::verilator_ports_h(m)
}

/// Write the Verilator workloads: `<dir>/<design>/{stim.bin, ports.h, expect.txt}`.
#[test]
#[ignore]
fn bench_print_verilator_files() {
    let dir = std::path::PathBuf::from(std::env::var("CANSTAR_BENCH_DIR").unwrap_or_else(|_| concat!(env!("CARGO_MANIFEST_DIR"), "/../target/verilator-bench").into()));
    let header = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../verilog-out/controller/canstar_sja1000.v")).unwrap();
    assert!(header.lines().next().unwrap().contains("BTR0/BTR1 after reset 0x00/0x14"), "SJA_BTR is not the committed Verilog's");
    let sja_fresh = || {
        let mut m = g::sja1000::Sja1000::new();
        m.load(&canstar_controller::sja1000::Sja1000::with_reset_timing(SJA_BTR.0, SJA_BTR.1)).unwrap();
        m
    };
    type Work = (&'static str, Stim, Box<dyn Fn() -> (f64, u64)>, String);
    let work: Vec<Work> = {
        let can3 = record_can(3, 1_000_000);
        let sja = record_sja(2_000_000);
        let hub = record_hub(2_000_000);
        let (c2, s2, h2) = (can3.clone(), sja.clone(), hub.clone());
        vec![
            ("can_core", can3, Box::new(move || replay_model(g::can_core::CanCore::new, &c2, true)), ports_h(&g::can_core::CanCore::new())),
            ("sja1000", sja, Box::new(move || replay_model(sja_fresh, &s2, true)), ports_h(&g::sja1000::Sja1000::new())),
            ("hub", hub, Box::new(move || replay_model(g::hub_n3_m2::HubN3M2::new, &h2, true)), ports_h(&g::hub_n3_m2::HubN3M2::new())),
        ]
    };
    for (name, st, run, ports) in work {
        let d = dir.join(name);
        std::fs::create_dir_all(&d).unwrap();
        st.save(&d.join("stim.bin")).unwrap();
        std::fs::write(d.join("ports.h"), ports).unwrap();
        let (rate, hash) = run();
        std::fs::write(d.join("expect.txt"), format!("{hash:016x}\n")).unwrap();
        println!("{name}: {} streams x {} cycles, compiled {rate:.0} cycles/s per stream, output hash {hash:016x}", st.streams, st.cycles);
    }
}


/// Long compiled-model replays for a profiler (`perf record` on the test binary).
#[test]
#[ignore]
fn diag_profile() {
    let which = std::env::var("CANSTAR_PROFILE").unwrap_or_default();
    if which == "hub" {
        let st = record_hub(1_000_000);
        for _ in 0..5 {
            replay_model(g::hub_n3_m2::HubN3M2::new, &st, false);
        }
    } else if which == "can" {
        let st = record_can(3, 1_000_000);
        for _ in 0..5 {
            replay_model(g::can_core::CanCore::new, &st, false);
        }
    } else if which == "sja" {
        let st = record_sja(1_000_000);
        for _ in 0..5 {
            replay_model(g::sja1000::Sja1000::new, &st, false);
        }
    }
}
