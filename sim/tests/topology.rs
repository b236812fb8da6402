//! Nodes exchanging levels over a bus and over star networks.

mod common;

use canstar_sim::bench::{edge_counter_node, EdgeCounter, PatternNode};
use canstar_sim::bus::{Bus, NodeDelays};
use canstar_sim::star::{AndHub, HubPorts, LinkSpec, PortSpec, TwoHubs};
use canstar_sim::{ClockSpec, HdlComponent, FaultMode, Sim};
use common::Scripted;

/// Index of the first edge of `c` strictly after `t` (by brute force).
fn first_edge_after(c: &ClockSpec, t: u64) -> u64 {
    (0..).find(|&n| c.edge_time(n) > t).unwrap()
}

#[test]
fn two_nodes_with_different_clocks_exchange_levels_with_exact_delays() {
    let mut sim = Sim::new(3);
    sim.keep_history(u64::MAX);
    let ca = ClockSpec::new(25_000).with_ppm(120.0).with_phase(1_234);
    let cb = ClockSpec::new(31_250).with_ppm(-80.0).with_phase(17_001);
    let da = NodeDelays { tx_dom: 40_000, tx_rec: 55_000, rx_dom: 20_000, rx_rec: 21_000 };
    let db = NodeDelays { tx_dom: 35_000, tx_rec: 36_000, rx_dom: 12_345, rx_rec: 54_321 };
    let bus = Bus::build(&mut sim, "bus", &[("a", da), ("b", db)]);
    // a: dominant at edge 10, recessive at edge 50; b: dominant at edge 100, recessive at edge 130
    let a = sim.add(Scripted::new("a", ca, &[(10, false), (50, true)]), &[bus.nodes[0].rx], &[bus.nodes[0].tx]);
    let b = sim.add(Scripted::new("b", cb, &[(100, false), (130, true)]), &[bus.nodes[1].rx], &[bus.nodes[1].tx]);
    sim.run_until(10_000_000);

    // a's dominant reaches b's RX at tA(10) + tx_dom(a) + rx_dom(b)
    let a_dom = ca.edge_time(10) + da.tx_dom + db.rx_dom;
    let a_rec = ca.edge_time(50) + da.tx_rec + db.rx_rec;
    let sb = &sim.get(b).samples;
    let first_dom = first_edge_after(&cb, a_dom) as usize;
    let first_rec = first_edge_after(&cb, a_rec) as usize;
    assert!(sb[first_dom - 1].1 && !sb[first_dom].1, "b samples dominant from the first edge after {a_dom}");
    assert!(sb[first_dom..first_rec].iter().all(|s| !s.1));
    assert!(sb[first_rec].1);
    assert!(sim.value_at(bus.nodes[1].rx, a_dom - 1));
    assert!(!sim.value_at(bus.nodes[1].rx, a_dom));
    assert!(!sim.value_at(bus.nodes[1].rx, a_rec - 1));
    assert!(sim.value_at(bus.nodes[1].rx, a_rec));

    // and back: b's dominant reaches a
    let b_dom = cb.edge_time(100) + db.tx_dom + da.rx_dom;
    let b_rec = cb.edge_time(130) + db.tx_rec + da.rx_rec;
    let sa = &sim.get(a).samples;
    let n0 = first_edge_after(&ca, b_dom) as usize;
    let n1 = first_edge_after(&ca, b_rec) as usize;
    assert!(sa[n0 - 1].1 && !sa[n0].1);
    assert!(sa[n0..n1].iter().all(|s| !s.1) && sa[n1].1);
    // a also sees its own frame (tx_dom(a) + rx_dom(a))
    let own = first_edge_after(&ca, ca.edge_time(10) + da.tx_dom + da.rx_dom) as usize;
    assert!(sa[own - 1].1 && !sa[own].1);
}

#[test]
fn hdl_component_on_a_bus_sees_the_other_nodes_edges() {
    let mut sim = Sim::new(5);
    sim.keep_history(u64::MAX);
    let bus = Bus::uniform(&mut sim, "bus", 2, NodeDelays::symmetric(10_000, 5_000));
    let clk = ClockSpec::new(25_000);
    let talker = sim.add(
        PatternNode::new(edge_counter_node(0, clk), 10, 99),
        &[bus.nodes[0].rx],
        &[bus.nodes[0].tx],
    );
    let listener = sim.add(edge_counter_node(1, clk.with_ppm(50.0)), &[bus.nodes[1].rx], &[]);
    sim.run_until(25_000 * 2_000);
    // count the bus edges the listener's RX saw (before the last two cycles of synchroniser latency)
    let t_end = sim.now() - 3 * 25_000;
    // (levels last at least 10 cycles: sampling every ns finds every edge)
    let edges = (1..t_end / 1_000)
        .filter(|&k| sim.value_at(bus.nodes[1].rx, k * 1_000) != sim.value_at(bus.nodes[1].rx, (k - 1) * 1_000))
        .count();
    let counted = sim.get(listener).block.edges.val().index() as usize;
    assert!(edges > 20, "pattern must toggle");
    assert!((counted as i64 - (edges % 256) as i64).abs() <= 1, "counted {counted}, edges {edges}");
    let _: &PatternNode<HdlComponent<EdgeCounter>> = sim.get(talker);
}

/// Star with the stand-in hub: every node receives the AND of all uplinks,
/// one hub cycle later, through its downlink.
#[test]
fn star_with_and_hub() {
    let mut sim = Sim::new(9);
    sim.keep_history(u64::MAX);
    let up = LinkSpec { d_dom: 3_000, d_rec: 4_000 };
    let down = LinkSpec::symmetric(2_000);
    let star = HubPorts::star_uniform(&mut sim, "hub", 3, up, down);
    let hub_clk = ClockSpec::new(10_000).with_phase(500);
    sim.add(AndHub::new("hub", hub_clk, 3, 0), &star.hub_inputs(), &star.hub_outputs());
    let node_clk = ClockSpec::new(10_000).with_phase(7_000);
    let mut nodes = Vec::new();
    let scripts: [&[(u64, bool)]; 3] = [&[(5, false), (8, true)], &[(20, false), (21, true)], &[]];
    for (i, script) in scripts.iter().enumerate() {
        nodes.push(sim.add(Scripted::new(&format!("n{i}"), node_clk, script), &[star.node_rx(i)], &[star.node_tx(i)]));
    }
    sim.run_until(1_000_000);
    // node 0 dominant from edge 5 (t = 57_000) to edge 8 (87_000):
    // uplink out dominant [60_000, 91_000); hub edges at 500 + 10_000 k see it
    // from 60_500 to 90_500 and recessive again at 100_500; downlinks add 2_000
    for i in 0..3 {
        let rx = star.node_rx(i);
        assert!(sim.value_at(rx, 62_499));
        assert!(!sim.value_at(rx, 62_500), "node {i}: hub edge 60_500 + downlink 2_000");
        assert!(!sim.value_at(rx, 102_499));
        assert!(sim.value_at(rx, 102_500));
    }
    // node 1's one-bit pulse at 207_000..217_000: uplink [210_000, 221_000),
    // hub edges 210_500 and 220_500 see it, rx [212_500, 232_500)
    let rx2 = star.node_rx(2);
    let dom: Vec<u64> = (200_000..240_000).filter(|&t| !sim.value_at(rx2, t)).collect();
    assert_eq!((dom[0], *dom.last().unwrap() + 1, dom.len() as u64), (212_500, 232_500, 20_000));
    // node 2 samples (edges at 7_000 + 10_000 k) see the dominant period
    let s2 = &sim.get(nodes[2]).samples;
    let dom_edges: Vec<u64> = s2.iter().filter(|s| !s.1).map(|s| s.0).collect();
    assert_eq!(dom_edges, vec![67_000, 77_000, 87_000, 97_000, 217_000, 227_000]);
}

#[test]
fn star_link_faults_reach_everybody_through_the_hub() {
    let mut sim = Sim::new(9);
    let star = HubPorts::star_uniform(&mut sim, "hub", 2, LinkSpec::symmetric(100), LinkSpec::symmetric(100));
    sim.add(AndHub::new("hub", ClockSpec::new(1_000), 2, 0), &star.hub_inputs(), &star.hub_outputs());
    sim.run_until(10_000);
    assert!(sim.value(star.node_rx(0)) && sim.value(star.node_rx(1)));
    // uplink 0 stuck dominant: both downlinks dominant after a hub cycle
    star.uplinks[0].set_fault(&mut sim, FaultMode::StuckDominant);
    sim.run_until(12_000);
    assert!(!sim.value(star.node_rx(0)) && !sim.value(star.node_rx(1)));
    // downlink 1 stuck recessive hides it from node 1 only
    star.downlinks[1].set_fault(&mut sim, FaultMode::StuckRecessive);
    sim.run_until(13_000);
    assert!(!sim.value(star.node_rx(0)) && sim.value(star.node_rx(1)));
    // back to normal at scheduled times; bit flip on downlink 0 during a window
    star.uplinks[0].schedule_fault(&mut sim, 20_000, FaultMode::None);
    star.downlinks[1].schedule_fault(&mut sim, 20_000, FaultMode::None);
    star.downlinks[0].add_flip_window(&mut sim, 30_000, 30_500);
    sim.run_until(29_999);
    assert!(sim.value(star.node_rx(0)) && sim.value(star.node_rx(1)));
    sim.run_until(30_000);
    assert!(!sim.value(star.node_rx(0)) && sim.value(star.node_rx(1)));
    sim.run_until(30_500);
    assert!(sim.value(star.node_rx(0)));
    // BitFlip mode
    star.downlinks[1].set_fault(&mut sim, FaultMode::Invert);
    assert!(!sim.value(star.node_rx(1)));
}

#[test]
fn two_hubs_joined_by_interlinks() {
    let mut sim = Sim::new(2);
    sim.keep_history(200_000);
    let port = PortSpec { up: LinkSpec::symmetric(1_000), down: LinkSpec::symmetric(1_000) };
    let net = TwoHubs::uniform(&mut sim, "rc", 3, 2, port, LinkSpec::symmetric(5_000));
    assert_eq!(net.hubs[0].sub_out, net.hubs[1].sub_in);
    assert_eq!(net.hubs[1].sub_out, net.hubs[0].sub_in);
    let clk = ClockSpec::new(10_000);
    for (k, h) in net.hubs.iter().enumerate() {
        assert_eq!(h.hub_inputs().len(), 5);
        assert_eq!(h.hub_outputs().len(), 5);
        sim.add(AndHub::new(&format!("hub{k}"), clk.with_phase(k as u64 * 3_000), 3, 2), &h.hub_inputs(), &h.hub_outputs());
    }
    // a controller on hub 0 port 1 sends a dominant level from t = 100_000
    let tx = net.hubs[0].node_tx(1);
    sim.run_until(100_000);
    sim.drive(tx, false);
    sim.run_until(200_000);
    // everybody on both hubs receives it
    for h in &net.hubs {
        for i in 0..3 {
            assert!(!sim.value(h.node_rx(i)), "{} port {i}", h.name);
        }
    }
    // hub 0: uplink out at 101_000, hub edge 110_000, downlink at 111_000
    let rx00 = net.hubs[0].node_rx(0);
    assert!(sim.value_at(rx00, 110_999) && !sim.value_at(rx00, 111_000));
    // hub 1: sublink in at 110_000 + 5_000 = 115_000, hub 1 edge 123_000, downlink 124_000
    let rx10 = net.hubs[1].node_rx(0);
    assert!(sim.value_at(rx10, 123_999) && !sim.value_at(rx10, 124_000));
    // both interlinks broken: hub 1 no longer hears hub 0
    for l in &net.hubs[0].sub_out {
        l.set_fault(&mut sim, FaultMode::StuckRecessive);
    }
    sim.run_until(300_000);
    assert!(!sim.value(rx00));
    assert!(sim.value(rx10));
    // hub 1's own contribution does not echo back: the stand-in sends only ANDC on sublinks
    sim.drive(tx, true);
    sim.run_until(400_000);
    assert!(sim.value(rx00) && sim.value(rx10));
}

#[test]
fn run_until_cond_stops_at_the_first_matching_edge() {
    let mut sim = Sim::new(0);
    let bus = Bus::uniform(&mut sim, "bus", 2, NodeDelays::symmetric(1_000, 1_000));
    let clk = ClockSpec::new(10_000);
    sim.add(Scripted::new("a", clk, &[(7, false)]), &[bus.nodes[0].rx], &[bus.nodes[0].tx]);
    let b = sim.add(Scripted::new("b", clk.with_phase(5_000), &[]), &[bus.nodes[1].rx], &[]);
    let rx = bus.nodes[1].rx;
    let hit = sim.run_until_cond(1_000_000, |s| !s.value(rx));
    assert!(hit);
    // dominant written at 70_000 reaches b's RX at 72_000; the condition is
    // checked after every step, the first step after 72_000 is b's edge at 75_000
    assert_eq!(sim.now(), 75_000);
    assert_eq!(sim.get(b).samples.last().unwrap(), &(75_000, false));
    // a deadline in the past: no step at all
    assert!(!sim.run_until_cond(50_000, |_| false));
    assert_eq!(sim.now(), 75_000);
    let mut sim2 = Sim::new(0);
    sim2.add(Scripted::new("c", clk, &[]), &[], &[]);
    assert!(!sim2.run_until_cond(95_000, |_| false));
    assert_eq!(sim2.now(), 90_000);
}
