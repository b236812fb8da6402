use canstar_sim::*;
use canstar_sim::star::*;
fn main() {
    let mut sim = Sim::new(9);
    sim.keep_history(u64::MAX);
    let up = LinkSpec { d_dom: 3_000, d_rec: 4_000 };
    let down = LinkSpec::symmetric(2_000);
    let star = HubPorts::star_uniform(&mut sim, "hub", 3, up, down);
    let hub_clk = ClockSpec::new(10_000).with_phase(500);
    sim.add(AndHub::new("hub", hub_clk, 3, 0), &star.hub_inputs(), &star.hub_outputs());
    sim.run_until(57_000); sim.drive(star.node_tx(0), false);
    sim.run_until(87_000); sim.drive(star.node_tx(0), true);
    sim.run_until(200_000);
    for (n, net) in [("tx0", star.node_tx(0)), ("up0", star.uplinks[0].output), ("down0in", star.downlinks[0].input), ("rx0", star.node_rx(0))] {
        let mut last = true;
        for t in 0..200_000 { let v = sim.value_at(net, t); if v != last { println!("{n} {t} {v}"); last = v; } }
    }
}
