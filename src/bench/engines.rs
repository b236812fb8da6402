//! `canstar bench`: rust-hdl, the compiled models and Verilator side by side on the
//! same recorded workloads, and the kernel (`canstar_sim::Sim`, closed loop with nets,
//! delays, host and driver models) running the same systems on the compiled models.
//!
//! Workloads, recorded from a kernel run on the compiled models and replayed into
//! every engine (so every engine gets exactly the same inputs, clock by clock):
//! - CanCore, N = 2, 3, 6 nodes on a wired-AND bus (10 MHz, 1 Mbit/s, no delays),
//!   every node with a full transmit queue;
//! - the hub alone (N = 3, M = 2, frame monitor included): hub 0 of the reference
//!   network's run;
//! - the reference network (`NetworkSpec::default()`: 2 hubs, 6 controllers, their
//!   clocks, phases and link delays): the 6 controller and 2 hub streams.
//!
//! Rates are clock cycles (summed over the instances) per second of this thread's CPU
//! time. Verilator's harness checks that its outputs hash to the compiled model's.

use super::verilator::Harness;
use anyhow::Result;
use canstar_controller::frame::Frame;
use canstar_hub::config::HubConfig;
use canstar_models::core_sim;
use canstar_models::generated::{can_core, hub_n3_m2};
use canstar_models::hub_sim;
use canstar_models::stim::{cpu, replay_hdl, replay_model, Stim};
use canstar_models::Model;
use canstar_recan::{NetworkSpec, RunSpec};
use canstar_sim::bus::{Bus, NodeDelays};
use canstar_sim::{ClockSpec, Sim};
use canstar_verify::node::{CanNode, NodeConfig};
use rand::{Rng, SeedableRng};

/// One workload's figures (cycles per CPU second; `None`/`Err`: not measured, and why).
pub struct Row {
    pub name: String,
    pub hdl: f64,
    pub compiled: f64,
    pub verilator: Result<f64, String>,
    pub kernel: Option<f64>,
}

/// Options of the engine benchmark.
pub struct Options {
    /// Clock cycles per node of the CanCore bus workloads.
    pub core_cycles: u64,
    /// Simulated time of the reference network run (ps).
    pub network_ps: u64,
    /// Cycles per stream replayed into rust-hdl (its rate is taken on this head).
    pub hdl_cycles: u64,
    /// Measure Verilator (if installed).
    pub verilator: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options { core_cycles: 400_000, network_ps: 20_000_000_000, hdl_cycles: 20_000, verilator: true }
    }
}

/// N CanNodes (compiled) on a bus with full queues for `cycles` clocks: the recorded
/// inputs of every core when `record`, and the kernel's rate (node-cycles per CPU-s).
fn can_bus(n: usize, cycles: u64, record: bool) -> (Option<Stim>, f64, usize) {
    let mut sim = Sim::new(1);
    let bus = Bus::uniform(&mut sim, "bus", n, NodeDelays::symmetric(0, 0));
    let clock = ClockSpec::new(100_000);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(n as u64);
    let mut hs = vec![];
    for i in 0..n {
        let mut node = CanNode::new(NodeConfig::named(&format!("n{i}")), clock);
        if record {
            node.core.start_recording();
        }
        // more frames than the run can send (a frame is at most ~160 bits = 1600 clocks)
        for _ in 0..cycles / 1000 + 4 {
            let dlc = rng.gen_range(0..=8usize);
            let data: Vec<u8> = (0..dlc).map(|_| rng.gen()).collect();
            node.request(if rng.gen_bool(0.3) { Frame::ext(rng.gen_range(0..1 << 29), &data) } else { Frame::std(rng.gen_range(0..1 << 11), &data) });
        }
        hs.push(sim.add(node, &[bus.nodes[i].rx], &[bus.nodes[i].tx]));
    }
    let t = cpu();
    sim.run_until(clock.period_ps * cycles - 1);
    let dt = cpu() - t;
    let node_cycles: u64 = hs.iter().map(|&h| sim.get(h).cycles()).sum();
    let depth = sim.get(hs[0]).core.sync_depth();
    let st = record.then(|| Stim::merge(&hs.iter().map(|&h| sim.get_mut(h).core.take_recording().unwrap()).collect::<Vec<_>>()));
    (st, node_cycles as f64 / dt, depth)
}

/// The hub's recorded input words as a stimulus in the model's port order.
fn hub_stim(words: &[canstar_recan::rtl_hub::HubInputWord], n: usize, m: usize) -> Stim {
    let mut st = Stim::new(1, 2 + n + m);
    for &w in words {
        let v: Vec<u128> = (0..2 + n + m).map(|i| ((w >> i) & 1) as u128).collect();
        st.push(0, &v);
        st.next();
    }
    st
}

fn rate(st: &Stim, secs: f64) -> f64 {
    (st.cycles * st.streams as u64) as f64 / secs
}

/// Verilator CPU seconds on `st`, or why not.
fn verilator(on: bool, name: &str, verilog: impl FnOnce() -> String, model: &dyn Model, st: &Stim, expect: u64) -> Result<f64, String> {
    if !on {
        return Err("not requested".into());
    }
    Harness::build(name, &verilog(), model)?.replay(st, expect)
}

fn core_verilog(depth: usize) -> String {
    canstar_hdl::flow::emit(&core_sim::fresh_hdl(depth, Default::default()))
}

/// Replays of CanCore streams: (rust-hdl, compiled, Verilator) rates.
fn core_engines(st: &Stim, depth: usize, o: &Options, name: &str) -> (f64, f64, Result<f64, String>) {
    let fresh = || can_core::CanCore::from_instance(&core_sim::fresh_hdl(depth, Default::default())).expect("committed CanCore model");
    let short = st.head(o.hdl_cycles);
    let n_out = fresh().info().outputs.len();
    let (th, hh) = replay_hdl(|| canstar_controller::core::CanCore::with_sync_depth(depth), can_core::hdl_set_inputs, can_core::hdl_outputs, n_out, &short);
    let (_, mh) = replay_model(fresh, &short, true);
    assert_eq!(hh, mh, "rust-hdl and the compiled model disagree on {name}");
    let (tm, hash) = replay_model(fresh, st, true);
    let (tm2, _) = replay_model(fresh, st, false);
    let v = verilator(o.verilator, "can_core", || core_verilog(depth), &fresh(), st, hash);
    (rate(&short, th), rate(st, tm.min(tm2)), v.map(|s| rate(st, s)))
}

/// Replays of hub streams: (rust-hdl, compiled, Verilator) rates.
fn hub_engines(st: &Stim, cfg: &HubConfig, o: &Options) -> (f64, f64, Result<f64, String>) {
    let fresh = || hub_n3_m2::HubN3M2::from_instance(&hub_sim::fresh_hdl(cfg)).expect("committed N3M2 hub model");
    let short = st.head(o.hdl_cycles);
    let n_out = fresh().info().outputs.len();
    let hdl_fresh = || {
        let mut h = canstar_hub::top::Hub::new(cfg);
        for r in h.rx.iter_mut().chain(h.reh_rx.iter_mut()) {
            r.next = true;
        }
        h.rst_n.next = false;
        h
    };
    let (th, hh) = replay_hdl(hdl_fresh, hub_n3_m2::hdl_set_inputs, hub_n3_m2::hdl_outputs, n_out, &short);
    let (_, mh) = replay_model(fresh, &short, true);
    assert_eq!(hh, mh, "rust-hdl and the compiled model disagree on the hub");
    let (tm, hash) = replay_model(fresh, st, true);
    let (tm2, _) = replay_model(fresh, st, false);
    let v = verilator(o.verilator, "hub_n3_m2", || canstar_hdl::flow::emit(&hub_sim::fresh_hdl(cfg)), &fresh(), st, hash);
    (rate(&short, th), rate(st, tm.min(tm2)), v.map(|s| rate(st, s)))
}

/// Run every workload and return the rows (printing progress to stderr).
pub fn measure(o: &Options) -> Vec<Row> {
    let mut rows = vec![];
    for n in [2, 3, 6] {
        eprintln!("CanCore x {n}: recording {} clocks per node ...", o.core_cycles);
        let (st, _, depth) = can_bus(n, o.core_cycles, true);
        let st = st.unwrap();
        let (_, kernel, _) = can_bus(n, o.core_cycles, false);
        let (hdl, compiled, verilator) = core_engines(&st, depth, o, "the CanCore bus");
        rows.push(Row { name: format!("CanCore, {n} nodes on a bus"), hdl, compiled, verilator, kernel: Some(kernel) });
    }
    eprintln!("reference network: recording {:.1} ms ...", o.network_ps as f64 / 1e9);
    let spec = {
        let mut s = RunSpec::new(NetworkSpec::default(), 1, 0);
        s.max_time_ps = Some(o.network_ps);
        s
    };
    let mut ctrl_st = vec![];
    let mut hub_words = vec![];
    let mut depth = 0;
    canstar_recan::run_inspect(
        &spec,
        &mut |sim, net| {
            for p in &net.ctrls {
                for &h in p {
                    sim.get_mut(h).core.start_recording();
                }
            }
            for &h in &net.hubs {
                sim.get_mut(h).start_recording();
            }
        },
        &mut |sim, net| {
            for p in &net.ctrls {
                for &h in p {
                    depth = sim.get(h).core.sync_depth();
                    ctrl_st.push(sim.get_mut(h).core.take_recording().unwrap());
                }
            }
            for &h in &net.hubs {
                hub_words.push(sim.get_mut(h).take_recording());
            }
        },
    );
    let t = cpu();
    let r = canstar_recan::run(&spec);
    let kernel_net = r.sim_cycles as f64 / (cpu() - t);
    let cfg = spec.network.hub.clone();
    let (n, m) = (cfg.ports, cfg.sublinks);
    let hub0 = hub_stim(&hub_words[0], n, m);
    let (hh, hm, hv) = hub_engines(&hub0, &cfg, o);
    rows.push(Row { name: format!("Hub N={n} M={m} alone, recorded traffic"), hdl: hh, compiled: hm, verilator: hv, kernel: None });
    // the network: both hubs' and the six controllers' streams
    let ctrls = Stim::merge(&ctrl_st);
    let hubs = {
        let parts: Vec<Stim> = hub_words.iter().map(|w| hub_stim(w, n, m)).collect();
        Stim::merge(&parts)
    };
    let (ch, cm, cv) = core_engines(&ctrls, depth, o, "the network's controllers");
    let (hh, hm, hv) = hub_engines(&hubs, &cfg, o);
    let (cc, hc) = ((ctrls.cycles * ctrls.streams as u64) as f64, (hubs.cycles * hubs.streams as u64) as f64);
    let combine = |a: f64, b: f64| (cc + hc) / (cc / a + hc / b);
    rows.push(Row {
        name: "Reference network (2 hubs, 6 ctrls)".into(),
        hdl: combine(ch, hh),
        compiled: combine(cm, hm),
        verilator: cv.and_then(|c| hv.map(|h| combine(c, h))),
        kernel: Some(kernel_net),
    });
    rows
}

fn si(x: f64) -> String {
    if x >= 1e6 {
        format!("{:.2} M", x / 1e6)
    } else {
        format!("{:.0} k", x / 1e3)
    }
}

/// The table (Markdown, as README quotes it).
pub fn table(rows: &[Row]) -> String {
    let mut s = String::from("| workload (cycles per CPU-s) | rust-hdl | compiled | Verilator | compiled / Verilator | kernel (compiled, closed loop) |\n|---|---:|---:|---:|---:|---:|\n");
    for r in rows {
        let (v, ratio) = match &r.verilator {
            Ok(v) => (si(*v), format!("{:.2}x", r.compiled / v)),
            Err(e) => (format!("— ({e})"), "—".into()),
        };
        s += &format!(
            "| {} | {} | {} | {} | {} | {} |\n",
            r.name,
            si(r.hdl),
            si(r.compiled),
            v,
            ratio,
            r.kernel.map(si).unwrap_or_else(|| "—".into())
        );
    }
    s
}
