use canstar_hdl::drive;
use canstar_controller::core::CanCore;
use canstar_hub::hub::{Hub, HubConfig};
#[test]
#[ignore]
fn bench_parts() {
    let mut c = CanCore::with_sync_depth(1);
    drive::init(&mut c);
    c.brp.next = 3u64.into(); c.prop.next = 2u64.into(); c.ph1.next = 1u64.into();
    let n = 100_000;
    let t = std::time::Instant::now();
    for i in 0..n { c.reset.next = i < 4; c.rx.next = (i / 37) % 3 != 0; drive::cycle(&mut c); }
    let a = t.elapsed().as_secs_f64();
    let mut h = Hub::new(&HubConfig { sync_depth: 1, ..HubConfig::default() });
    for r in h.rx.iter_mut().chain(h.reh_rx.iter_mut()) { r.next = true; }
    drive::init(&mut h);
    let t = std::time::Instant::now();
    for i in 0..n { h.rst_n.next = i > 4; h.rx[0].next = (i / 37) % 3 != 0; drive::cycle(&mut h); }
    let b = t.elapsed().as_secs_f64();
    eprintln!("CanCore {:.2} us/cycle, Hub {:.2} us/cycle", a / n as f64 * 1e6, b / n as f64 * 1e6);
}

fn settle_count<B: rust_hdl::prelude::Block>(u: &mut B) -> usize {
    for i in 0..1000 { u.update_all(); if !u.has_changed() { return i + 1; } }
    1000
}
fn cyc<B: canstar_hdl::drive::Clocked>(u: &mut B, acc: &mut [usize; 3]) {
    acc[0] += settle_count(u);
    u.clock_input().next = rust_hdl::prelude::Clock::from(true);
    acc[1] += settle_count(u);
    u.clock_input().next = rust_hdl::prelude::Clock::from(false);
    acc[2] += settle_count(u);
}
#[test]
#[ignore]
fn settle_iters() {
    let mut c = CanCore::with_sync_depth(1);
    drive::init(&mut c);
    c.brp.next = 3u64.into(); c.prop.next = 2u64.into(); c.ph1.next = 1u64.into();
    let n = 20_000;
    let mut acc = [0usize; 3];
    for i in 0..n { c.reset.next = i < 4; c.rx.next = (i / 37) % 3 != 0; cyc(&mut c, &mut acc); }
    eprintln!("CanCore settle passes per cycle: {:?}", acc.map(|a| a as f64 / n as f64));
    let mut h = Hub::new(&HubConfig { sync_depth: 1, ..HubConfig::default() });
    for r in h.rx.iter_mut().chain(h.reh_rx.iter_mut()) { r.next = true; }
    drive::init(&mut h);
    let mut acc = [0usize; 3];
    for i in 0..n { h.rst_n.next = i > 4; h.rx[0].next = (i / 37) % 3 != 0; cyc(&mut h, &mut acc); }
    eprintln!("Hub settle passes per cycle: {:?}", acc.map(|a| a as f64 / n as f64));
}

#[test]
#[ignore]
fn field_probe() {
    use canstar_sim::recan::spec::Network;
    use canstar_sim::recan::NetworkSpec;
    use canstar_controller::frame::Frame;
    let mut sim = canstar_sim::Sim::new(1);
    let net = Network::build(&mut sim, &NetworkSpec::fast()).unwrap();
    sim.run_until(25_000_000);
    sim.get_mut(net.ctrls[0][0]).request(Frame::std(0xa0, &[3]));
    let mut last = String::new();
    let end = sim.now() + 80_000_000;
    while sim.now() < end {
        sim.step();
        let c = sim.get(net.ctrls[0][0]);
        let s = format!("{:?} {} role {}", c.field(), c.pos(), c.transmitting());
        if s != last { eprintln!("{:>8} {s}", sim.now() / 1000); last = s; }
    }
}

#[test]
#[ignore]
fn print_toml() {
    println!("{}", canstar_sim::recan::NetworkSpec::default().to_toml());
}
