//! The hubs: compiled model against rust-hdl, every output every cycle, every atom
//! at checkpoints.
//!
//! - `Hub` (with its frame monitor) in a ReCANcentrate network: hub A runs in both
//!   engines, hub B (compiled only) is its interlinked replica; three CAN nodes
//!   (compiled `CanCore` models with hosts sending frames) on each hub's ports.
//!   Ports and interlinks get faults now and then (stuck dominant, stuck recessive,
//!   bit flipping), so the judges blame, isolate, count and the error flag fires.
//! - The same for CANcentrate (M = 0) and one interlink (M = 1).
//! - `HubCore` on random stimulus.

mod common;

use canstar_hub::config::{FaultInjection, FaultPoint, HubConfig, InjectionKind};
use canstar_hub::{hub::HubCore, top::Hub};
use canstar_models::generated as g;
use canstar_models::lockstep::{Lockstep, RandomInputs};
use canstar_rtlc::rt::Model;
use common::hubnet::HubNet;
use common::Ports;

/// Run hub A (rust-hdl and model in lock-step) in a network for `cycles` clocks.
/// Returns (frames received by the nodes, clocks with a port isolated).
fn network<M: Model>(a: &mut Lockstep<Hub, M>, m: usize, cycles: u64, seed: u64) -> (u64, u64) {
    let mut net = HubNet::new(Ports::of(&a.model), m, seed);
    for c in 0..cycles {
        let v = net.inputs(a.outputs()).to_vec();
        a.step(&v).unwrap_or_else(|e| panic!("hub: {e}"));
        net.advance(a.outputs());
        if c % 100_000 == 99_999 {
            a.compare_all().unwrap_or_else(|e| panic!("hub: {e}"));
        }
    }
    a.compare_all().unwrap_or_else(|e| panic!("hub: {e}"));
    (net.frames, net.isolated)
}

fn start<M: Model>(cfg: &HubConfig, make: fn(&dyn canstar_rtlc::rt::Block) -> Result<M, canstar_rtlc::Error>, set: fn(&mut Hub, &[u128]), get: fn(&Hub, &mut [u128])) -> Lockstep<Hub, M> {
    Lockstep::new(Hub::new(cfg), make, set, get).unwrap_or_else(|e| panic!("{e}"))
}

/// The reference ReCANcentrate hub (N = 3, M = 2), 1 M clocks.
#[test]
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn recancentrate_network() {
    let cfg = HubConfig::default();
    let mut a = start(&cfg, g::hub_n3_m2::HubN3M2::from_instance, g::hub_n3_m2::hdl_set_inputs, g::hub_n3_m2::hdl_outputs);
    let (frames, isolated) = network(&mut a, 2, 1_000_000, 31);
    assert!(frames > 500, "{frames} frames");
    assert!(isolated > 1000, "{isolated} clocks with a port isolated");
}

/// CANcentrate (M = 0) with reintegration, synchroniser depth 2 and a fault-injection
/// hook (all runtime constants of the same model shape).
#[test]
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn cancentrate_network_with_runtime_constants() {
    let cfg = HubConfig {
        sublinks: 0,
        sync_depth: 2,
        reintegration: Some(3),
        bic_threshold: 4,
        fault_injection: Some(FaultInjection { point: FaultPoint::Downlink(1), kind: InjectionKind::BitFlip, start_field: 6 }),
        ..HubConfig::default()
    };
    let mut a = start(&cfg, g::hub_n3_m0::HubN3M0::from_instance, g::hub_n3_m0::hdl_set_inputs, g::hub_n3_m0::hdl_outputs);
    let (frames, _) = network(&mut a, 0, 300_000, 32);
    assert!(frames > 100, "{frames} frames");
}

/// One interlink (M = 1), 300 000 clocks.
#[test]
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn one_interlink_network() {
    let cfg = HubConfig { sublinks: 1, ..HubConfig::default() };
    let mut a = start(&cfg, g::hub_n3_m1::HubN3M1::from_instance, g::hub_n3_m1::hdl_set_inputs, g::hub_n3_m1::hdl_outputs);
    let (frames, _) = network(&mut a, 1, 300_000, 33);
    assert!(frames > 100, "{frames} frames");
}

/// `HubCore` of every committed shape on random stimulus (the monitor inputs too):
/// 1 M clocks of the reference shape, 150 000 of the others.
#[test]
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn hub_core_random() {
    fn run<M: Model>(cfg: HubConfig, make: fn(&dyn canstar_rtlc::rt::Block) -> Result<M, canstar_rtlc::Error>, set: fn(&mut HubCore, &[u128]), get: fn(&HubCore, &mut [u128]), cycles: u64, seed: u64) {
        let mut l = Lockstep::new(HubCore::new(&cfg), make, set, get).unwrap_or_else(|e| panic!("{e}"));
        let prob = |n: &str| match n {
            "rst_n" => 0.0005,
            "mon_sample" | "mon_bit_start" => 0.2,
            "inject_fault" => 0.001,
            _ if n.starts_with("rx") || n.starts_with("reh_rx") => 0.05,
            _ => 0.05,
        };
        let mut stim = RandomInputs::new(&l.model, seed, prob);
        for _ in 0..cycles {
            let v = stim.draw().to_vec();
            l.step(&v).unwrap_or_else(|e| panic!("{e}"));
        }
        l.compare_all().unwrap_or_else(|e| panic!("{e}"));
    }
    let with_hook = |m| HubConfig {
        sublinks: m,
        fault_injection: Some(FaultInjection { point: FaultPoint::Uplink(0), kind: InjectionKind::StuckDominant, start_field: 3 }),
        ..HubConfig::default()
    };
    run(with_hook(2), g::hub_core_n3_m2::HubCoreN3M2::from_instance, g::hub_core_n3_m2::hdl_set_inputs, g::hub_core_n3_m2::hdl_outputs, 1_000_000, 41);
    run(with_hook(0), g::hub_core_n3_m0::HubCoreN3M0::from_instance, g::hub_core_n3_m0::hdl_set_inputs, g::hub_core_n3_m0::hdl_outputs, 150_000, 42);
    run(HubConfig { sublinks: 1, ..HubConfig::default() }, g::hub_core_n3_m1::HubCoreN3M1::from_instance, g::hub_core_n3_m1::hdl_set_inputs, g::hub_core_n3_m1::hdl_outputs, 150_000, 43);
}
