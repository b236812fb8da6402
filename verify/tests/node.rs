//! The RTL controller as a kernel component: nodes on a bus with delays and
//! drifting clocks exchange frames.
use canstar_controller::frame::Frame;
use canstar_sim::bus::{Bus, NodeDelays};
use canstar_verify::node::{CanNode, HostEvent, NodeConfig};
use canstar_sim::{ClockSpec, FaultMode, Sim};

fn two_nodes(ppm: f64, delay_ps: u64) -> (Sim, Bus, canstar_sim::Handle<CanNode>, canstar_sim::Handle<CanNode>) {
    let mut sim = Sim::new(3);
    let bus = Bus::uniform(&mut sim, "bus", 2, NodeDelays::symmetric(delay_ps, delay_ps));
    let a = sim.add(CanNode::new(NodeConfig::named("n1"), ClockSpec::new(100_000)), &[bus.nodes[0].rx], &[bus.nodes[0].tx]);
    let b = sim.add(
        CanNode::new(NodeConfig::named("n2"), ClockSpec::new(100_000).with_ppm(ppm).with_phase(37_000)),
        &[bus.nodes[1].rx],
        &[bus.nodes[1].tx],
    );
    (sim, bus, a, b)
}

#[test]
fn frames_of_every_kind_cross_a_bus_with_delays_and_drift() {
    let (mut sim, _bus, a, b) = two_nodes(1500.0, 20_000);
    let mut frames = vec![];
    for dlc in 0..16u8 {
        let n = dlc.min(8) as usize;
        let data: Vec<u8> = (0..n as u8).map(|i| i.wrapping_mul(37) ^ dlc).collect();
        frames.push(Frame::data(dlc % 2 == 1, if dlc % 2 == 1 { 0x1234567 + dlc as u32 } else { 0x100 + dlc as u32 }, dlc, &data));
        frames.push(Frame::remote(dlc % 3 == 0, 0x55 + dlc as u32, dlc));
    }
    for f in &frames {
        sim.get_mut(a).request(f.clone());
    }
    let done = sim.run_until_cond(200_000_000_000, |s| s.get(a).sent().len() == frames.len());
    assert!(done, "only {} of {} frames sent", sim.get(a).sent().len(), frames.len());
    sim.run_for(20_000_000);
    assert_eq!(sim.get(a).sent(), frames);
    assert_eq!(sim.get(b).received(), frames);
    assert_eq!((sim.get(a).tec(), sim.get(a).rec(), sim.get(b).tec(), sim.get(b).rec()), (0, 0, 0, 0));
    assert_eq!(sim.get(a).errors() + sim.get(b).errors(), 0);
}

#[test]
fn receive_interference_causes_errors_only_where_applied() {
    let (mut sim, bus, a, b) = two_nodes(0.0, 0);
    // Let both integrate, then make n2 deaf (stuck recessive): n1 gets no ACK.
    sim.run_for(30_000_000);
    bus.set_interference(&mut sim, 1, FaultMode::StuckRecessive);
    sim.get_mut(a).request(Frame::std(0x321, &[0xAA]));
    sim.run_for(200_000_000);
    let n1 = sim.get(a);
    assert!(n1.tec() >= 8, "ACK errors expected at n1, TEC {}", n1.tec());
    assert!(n1.log().iter().any(|(_, e)| matches!(e, HostEvent::Error { tx: true, .. })));
    // n2 saw an idle bus: no errors, nothing received.
    assert_eq!(sim.get(b).errors(), 0);
    assert!(sim.get(b).received().is_empty());
    // Remove the interference: the retry succeeds and n2 receives it once.
    bus.set_interference(&mut sim, 1, FaultMode::None);
    let ok = sim.run_until_cond(sim.now() + 200_000_000, |s| !s.get(a).sent().is_empty());
    assert!(ok);
    sim.run_for(20_000_000);
    assert_eq!(sim.get(b).received(), vec![Frame::std(0x321, &[0xAA])]);
}
