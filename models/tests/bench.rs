//! Throughput of the compiled models against rust-hdl direct drive on the same
//! stimulus (a benchmark: it prints figures and asserts only that both engines end
//! with the same outputs):
//! `cargo test --release -p canstar-models --test bench -- --ignored --nocapture bench_print`
//!
//! - CanCore: 2, 3, 6 nodes on a wired-AND bus sending frames back to back (each
//!   engine runs the closed loop; the traffic is the same because the engines agree).
//! - SJA1000: two controllers with register-level hosts (`common/sjanet.rs`); the
//!   inputs of controller 0 recorded from a model run, replayed into each engine.
//! - Hub (N = 3, M = 2, with its monitor) and HubCore: the inputs of hub A in a
//!   ReCANcentrate network (`common/hubnet.rs`) recorded from a model run, replayed.
//!
//! Inputs go in as whole vectors (`Model::set_inputs`, the generated `hdl_set_inputs`).
//! Rates are per second of this thread's CPU time.

mod common;

/// CPU time of this thread (the machine is shared: wall time would count other
/// processes' time slices).
struct Instant(f64);

impl Instant {
    fn now() -> Instant {
        let mut t = libc::timespec { tv_sec: 0, tv_nsec: 0 };
        // SAFETY: clock_gettime writes the timespec it is given.
        unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
        Instant(t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9)
    }
    fn elapsed(&self) -> Elapsed {
        Elapsed(Instant::now().0 - self.0)
    }
}

struct Elapsed(f64);

impl Elapsed {
    fn as_secs_f64(&self) -> f64 {
        self.0
    }
}

use canstar_controller::core::CanCore;
use canstar_hdl::drive;
use canstar_models::generated as g;
use canstar_rtlc::rt::Model;
use common::Ports;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Back-to-back frames for one CanCore: request again as soon as one is sent.
fn core_inputs(p: &Ports, v: &mut [u128], rng: &mut ChaCha8Rng, done: bool, cycle: u64) {
    if cycle == 0 {
        v[p.i("ph1")] = 3;
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

/// `n` CanCore nodes on a bus: node-cycles per second of (rust-hdl, compiled), frames.
fn can_bus(n: usize, model_cycles: u64, hdl_cycles: u64) -> (f64, f64, u64) {
    let p = Ports::of(&g::can_core::CanCore::new());
    let (o_tx, o_done, o_rxv, i_rx) = (p.o("tx"), p.o("tx_done"), p.o("rx_valid"), p.i("rx"));
    let run = |cycles: u64, hdl: bool| -> (f64, u64, Vec<Vec<u128>>) {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let mut ms: Vec<g::can_core::CanCore> = (0..n).map(|_| g::can_core::CanCore::new()).collect();
        let mut hs: Vec<Box<CanCore>> = (0..if hdl { n } else { 0 })
            .map(|_| {
                let mut c = Box::new(CanCore::new());
                drive::init(&mut *c);
                c
            })
            .collect();
        let mut vs = vec![vec![0u128; p.ins.len()]; n];
        let mut outs = vec![vec![0u128; p.outs.len()]; n];
        for o in outs.iter_mut() {
            o[o_tx] = 1;
        }
        let mut frames = 0;
        let t = Instant::now();
        for c in 0..cycles {
            let bus = outs.iter().all(|o| o[o_tx] != 0);
            for k in 0..n {
                core_inputs(&p, &mut vs[k], &mut rng, outs[k][o_done] != 0, c);
                vs[k][i_rx] = bus as u128;
                if hdl {
                    g::can_core::hdl_set_inputs(&mut hs[k], &vs[k]);
                    drive::cycle(&mut *hs[k]);
                    g::can_core::hdl_outputs(&hs[k], &mut outs[k]);
                } else {
                    ms[k].set_inputs(&vs[k]);
                    ms[k].cycle();
                    ms[k].outputs(&mut outs[k]);
                }
                frames += outs[k][o_rxv] as u64;
            }
        }
        ((cycles * n as u64) as f64 / t.elapsed().as_secs_f64(), frames, outs)
    };
    let (hdl_rate, _, hdl_outs) = run(hdl_cycles, true);
    let (_, _, check) = run(hdl_cycles, false);
    assert_eq!(hdl_outs, check, "the engines disagree");
    let (model_rate, frames, _) = run(model_cycles, false);
    (hdl_rate, model_rate, frames)
}

/// Replay recorded inputs into a model and a rust-hdl instance: cycles per second of
/// (rust-hdl, compiled). The outputs after the rust-hdl part must agree.
fn replay<M: Model, H: drive::Clocked>(mut m: M, mut h: H, set: fn(&mut H, &[u128]), get: fn(&H, &mut [u128]), rec: &[Vec<u128>], hdl_n: usize) -> (f64, f64) {
    drive::init(&mut h);
    let t = Instant::now();
    for v in &rec[..hdl_n] {
        set(&mut h, v);
        drive::cycle(&mut h);
    }
    let hdl_rate = hdl_n as f64 / t.elapsed().as_secs_f64();
    let mut a = vec![0u128; m.info().outputs.len()];
    get(&h, &mut a);
    let mut b = a.clone();
    let t = Instant::now();
    for (k, v) in rec.iter().enumerate() {
        m.set_inputs(v);
        m.cycle();
        if k + 1 == hdl_n {
            m.outputs(&mut b);
        }
    }
    let model_rate = rec.len() as f64 / t.elapsed().as_secs_f64();
    assert_eq!(a, b, "the engines disagree");
    (hdl_rate, model_rate)
}

/// Inputs of SJA1000 controller 0 of two on a bus with hosts, from a model run.
fn record_sja(cycles: u64) -> Vec<Vec<u128>> {
    let mut ms = [g::sja1000::Sja1000::new(), g::sja1000::Sja1000::new()];
    let mut net = common::sjanet::SjaNet::new(&ms[0], 2, 21);
    let n_out = ms[0].info().outputs.len();
    let mut outs = vec![vec![0u128; n_out]; 2];
    let mut rec = vec![];
    for _ in 0..cycles {
        for k in 0..2 {
            let v = net.inputs(k, &outs[k]).to_vec();
            ms[k].set_inputs(&v);
            ms[k].cycle();
            ms[k].outputs(&mut outs[k]);
            if k == 0 {
                rec.push(v);
            }
        }
        let tx = net.ix.tx;
        net.advance(outs.iter().map(|o| o[tx] != 0));
    }
    rec
}

/// Inputs of hub A (N = 3, M = 2) in a ReCANcentrate network, from a model run.
fn record_hub(cycles: u64) -> Vec<Vec<u128>> {
    let mut a = g::hub_n3_m2::HubN3M2::new();
    let mut net = common::hubnet::HubNet::new(Ports::of(&a), 2, 31);
    let mut out = vec![0u128; a.info().outputs.len()];
    let mut rec = vec![];
    for _ in 0..cycles {
        let v = net.inputs(&out).to_vec();
        a.set_inputs(&v);
        a.cycle();
        a.outputs(&mut out);
        net.advance(&out);
        rec.push(v);
    }
    rec
}

#[test]
#[ignore]
fn bench_print() {
    println!("compiled models (canstar-rtlc) against rust-hdl direct drive, same stimulus, cycles/s");
    for n in [2, 3, 6] {
        let (h, m, frames) = can_bus(n, 3_000_000, 100_000);
        println!("CanCore, {n} nodes on a bus:   rust-hdl {h:>9.0} node-cycles/s   compiled {m:>11.0} node-cycles/s   {:>5.0}x  ({frames} frames)", m / h);
    }
    let rec = record_sja(2_000_000);
    let (h, m) = replay(g::sja1000::Sja1000::new(), canstar_controller::sja1000::Sja1000::new(), g::sja1000::hdl_set_inputs, g::sja1000::hdl_outputs, &rec, 100_000);
    println!("SJA1000 top, host traffic:    rust-hdl {h:>9.0} cycles/s        compiled {m:>11.0} cycles/s        {:>5.0}x", m / h);
    let rec = record_hub(2_000_000);
    let cfg = canstar_hub::hub::HubConfig::default();
    let (h, m) = replay(g::hub_n3_m2::HubN3M2::new(), canstar_hub::hub::Hub::new(&cfg), g::hub_n3_m2::hdl_set_inputs, g::hub_n3_m2::hdl_outputs, &rec, 50_000);
    println!("Hub N3 M2 (with monitor):     rust-hdl {h:>9.0} cycles/s        compiled {m:>11.0} cycles/s        {:>5.0}x", m / h);
}
