//! The RTL hub as a kernel component: a dominant pulse on one uplink reaches every
//! downlink after the documented coupling latency.
use canstar_hub::config::HubConfig;
use canstar_sim::star::{HubPorts, LinkSpec};
use canstar_recan::rtl_hub::RtlHub;
use canstar_sim::Sim;

#[test]
fn rtl_hub_couples_an_uplink_to_every_downlink() {
    let cfg = HubConfig { sublinks: 0, ..HubConfig::default() };
    let mut sim = Sim::new(1);
    let ports = HubPorts::star_uniform(&mut sim, "h", 3, LinkSpec::default(), LinkSpec::default());
    let hub = RtlHub::new("h", &cfg);
    let period = hub_period(&cfg);
    let h = sim.add(hub, &ports.hub_inputs(), &ports.hub_outputs());
    sim.run_until(20 * period);
    for i in 0..3 {
        assert!(sim.value(ports.node_rx(i)), "downlink {i} recessive at idle");
    }
    let t0 = sim.now();
    sim.drive(ports.node_tx(1), false);
    sim.run_until_cond(t0 + 20 * period, |s| !s.value(ports.node_rx(0)));
    let dt = sim.now() - t0;
    assert!(!sim.value(ports.node_rx(2)));
    let clocks = dt.div_ceil(period);
    assert!(clocks as usize <= cfg.coupling_latency() + 1, "latency {clocks} clocks");
    assert!(sim.get(h).cycles() > 20);
    assert_eq!(sim.get(h).isolated(), vec![false; 3]);
}

fn hub_period(cfg: &HubConfig) -> u64 {
    (1e12 / cfg.clock_hz as f64).round() as u64
}
