//! Lock-step checker (can-protocol.md §19): the RTL and its golden model agree on clean and
//! disturbed traffic, and a corrupted golden model is caught.
use canstar_controller::frame::Frame;
use canstar_sim::bus::{Bus, NodeDelays};
use canstar_verify::lockstep::LockstepNode;
use canstar_verify::node::NodeConfig;
use canstar_sim::{ClockSpec, Handle, FaultMode, Sim};

fn two(ppm: f64, delay: u64) -> (Sim, Bus, Handle<LockstepNode>, Handle<LockstepNode>) {
    let mut sim = Sim::new(5);
    let bus = Bus::uniform(&mut sim, "bus", 2, NodeDelays::symmetric(delay, delay));
    let a = sim.add(LockstepNode::new(NodeConfig::named("n1"), ClockSpec::new(100_000)), &[bus.nodes[0].rx], &[bus.nodes[0].tx]);
    let b = sim.add(
        LockstepNode::new(NodeConfig::named("n2"), ClockSpec::new(100_000).with_ppm(ppm).with_phase(41_000)),
        &[bus.nodes[1].rx],
        &[bus.nodes[1].tx],
    );
    (sim, bus, a, b)
}

#[test]
fn clean_exchange_stays_in_lock_step() {
    let (mut sim, _bus, a, b) = two(1000.0, 15_000);
    let frames = [Frame::std(0x123, &[1, 2, 3]), Frame::data(true, 0x1abc_def0 & 0x1fff_ffff, 12, &[9; 8]), Frame::remote(false, 0x7ff, 3)];
    for f in &frames {
        sim.get_mut(a).node.request(f.clone());
        sim.get_mut(b).node.request(Frame::std(f.id & 0x7ff ^ 0x400, &[0x55]));
    }
    let ok = sim.run_until_cond(100_000_000_000, |s| {
        s.get(a).divergence().is_some() || s.get(b).divergence().is_some() || (!s.get(a).node.pending() && !s.get(b).node.pending())
    });
    assert!(ok);
    sim.run_for(30_000_000);
    for h in [a, b] {
        let n = sim.get(h);
        assert!(n.divergence().is_none(), "{}", n.divergence().unwrap());
        assert!(n.armed());
        assert!(n.warnings().is_empty(), "diagnostic differences: {:?}", n.warnings());
        let st = n.stats();
        assert!(st.bits > 300, "{st:?}");
        assert_eq!(st.frames, 3, "{st:?}");
    }
    assert_eq!(sim.get(b).node.received(), frames);
}

#[test]
fn disturbed_receive_paths_stay_in_lock_step() {
    let (mut sim, bus, a, b) = two(-500.0, 0);
    sim.run_for(20_000_000);
    for k in 0..6u64 {
        sim.get_mut(a).node.request(Frame::std(0x100 + k as u32, &[k as u8; 4]));
        let t = sim.now();
        // a few stuck and inverted windows on both receive paths
        bus.schedule_interference(&mut sim, (k % 2) as usize, t + 30_000_000 + k * 3_100_000, FaultMode::StuckDominant);
        bus.schedule_interference(&mut sim, (k % 2) as usize, t + 30_000_000 + k * 3_100_000 + 700_000 * (k + 1), FaultMode::None);
        sim.add_flip_window(bus.nodes[1 - (k % 2) as usize].rx, t + 45_000_000 + k * 1_700_000, t + 45_000_000 + k * 1_700_000 + 900_000);
        sim.run_for(150_000_000);
    }
    let ok = sim.run_until_cond(sim.now() + 2_000_000_000, |s| !s.get(a).node.pending());
    assert!(ok);
    for h in [a, b] {
        let n = sim.get(h);
        assert!(n.divergence().is_none(), "{}", n.divergence().unwrap());
    }
    assert!(sim.get(a).node.errors() + sim.get(b).node.errors() > 0, "the disturbances caused no error");
}

#[test]
fn a_corrupted_golden_counter_is_reported() {
    let (mut sim, _bus, a, _b) = two(0.0, 0);
    sim.get_mut(a).inject_tec_fault = Some(8);
    sim.get_mut(a).node.request(Frame::std(0x42, &[1]));
    sim.run_for(300_000_000);
    let d = sim.get(a).divergence().expect("divergence expected").clone();
    assert_eq!(d.signal, "tec");
    assert_eq!((d.dut.as_str(), d.golden.as_str()), ("0", "8"));
    assert!(!d.golden_trace.is_empty() && !d.dut_trace.is_empty());
    let text = d.to_string();
    assert!(text.contains("node n1") && text.contains("tec"), "{text}");
}

#[test]
fn a_wrong_rx_latency_shows_as_a_timing_divergence() {
    let (mut sim, _bus, a, b) = two(0.0, 0);
    sim.get_mut(b).skew_golden_rx(3);
    sim.get_mut(a).node.request(Frame::std(0x42, &[1]));
    sim.run_for(300_000_000);
    assert!(sim.get(a).divergence().is_none());
    let d = sim.get(b).divergence().expect("divergence expected");
    assert!(["sample", "busmon", "tx"].contains(&d.signal.as_str()), "{d}");
}

#[test]
fn bus_off_and_recovery_stay_in_lock_step() {
    let mut sim = Sim::new(11);
    let bus = Bus::uniform(&mut sim, "bus", 3, NodeDelays::symmetric(5_000, 5_000));
    let mut hs = vec![];
    for i in 0..3 {
        let mut n = LockstepNode::new(NodeConfig::named(&format!("n{i}")), ClockSpec::new(100_000).with_ppm(300.0 * i as f64).with_phase(13_000 * i as u64));
        n.record_steps();
        hs.push(sim.add(n, &[bus.nodes[i].rx], &[bus.nodes[i].tx]));
    }
    sim.run_for(30_000_000);
    // n0 deaf while it transmits: bit errors until bus-off
    bus.set_interference(&mut sim, 0, FaultMode::StuckRecessive);
    sim.get_mut(hs[0]).node.request(Frame::std(0x2aa, &[0xde, 0xad]));
    sim.get_mut(hs[1]).node.request(Frame::ext(0x1555_5555, &[1, 2, 3]));
    sim.run_for(900_000_000);
    bus.set_interference(&mut sim, 0, FaultMode::None);
    let ok = sim.run_until_cond(sim.now() + 5_000_000_000, |s| hs.iter().all(|h| !s.get(*h).node.pending()));
    assert!(ok, "frames not sent after recovery");
    sim.run_for(30_000_000);
    for h in &hs {
        let n = sim.get(*h);
        assert!(n.divergence().is_none(), "{}", n.divergence().unwrap());
    }
    let n0 = sim.get(hs[0]);
    assert!(n0.steps().iter().any(|(_, o)| o.state == canstar_golden::FaultState::BusOff), "n0 never went bus-off");
    assert!(n0.steps().iter().any(|(_, o)| o.has("RECOVERED")));
    assert_eq!(sim.get(hs[2]).node.received().len(), 2);
}
