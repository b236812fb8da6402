//! VCD output, bounded memory over long runs, the benchmark.

use canstar_sim::bench::{bench, bench_default, edge_counter_node, BenchConfig, PatternNode};
use canstar_sim::bus::{Bus, NodeDelays};
use canstar_sim::star::{AndHub, HubPorts, LinkSpec};
use canstar_sim::{ClockSpec, FaultMode, Sim};

/// A bus with three EdgeCounter nodes driven by pseudo-random patterns, a
/// star with the stand-in hub, random phases from the seed.
fn build(seed: u64) -> (Sim, Bus) {
    let mut sim = Sim::new(seed);
    let bus = Bus::uniform(&mut sim, "bus", 3, NodeDelays { tx_dom: 30_000, tx_rec: 45_000, rx_dom: 20_000, rx_rec: 20_000 });
    for (i, n) in bus.nodes.iter().enumerate() {
        let clk = sim.random_phase_clock(25_000, 40.0 * i as f64 - 40.0);
        sim.add(PatternNode::new(edge_counter_node(i, clk), 8, 7 + i as u32), &[n.rx], &[n.tx]);
    }
    let star = HubPorts::star_uniform(&mut sim, "star", 2, LinkSpec::symmetric(5_000), LinkSpec::symmetric(5_000));
    let hclk = sim.random_phase_clock(10_000, 0.0);
    sim.add(AndHub::new("hub", hclk, 2, 0), &star.hub_inputs(), &star.hub_outputs());
    sim.drive(star.node_tx(0), true);
    (sim, bus)
}

fn run_with_vcd(seed: u64, file: &std::path::Path, filter: Option<&[&str]>) -> String {
    let (mut sim, bus) = build(seed);
    sim.start_vcd_file(file, filter).unwrap();
    sim.run_until(3_000_000);
    bus.set_interference(&mut sim, 2, FaultMode::Invert);
    sim.run_until(6_000_000);
    sim.finish_vcd().unwrap();
    std::fs::read_to_string(file).unwrap()
}

#[test]
fn vcd_has_instance_scopes_and_wires_and_is_deterministic() {
    let dir = tempfile::tempdir().unwrap();
    let a = run_with_vcd(42, &dir.path().join("a.vcd"), None);
    let b = run_with_vcd(42, &dir.path().join("b.vcd"), None);
    assert_eq!(a, b, "same seed, same VCD");
    let c = run_with_vcd(43, &dir.path().join("c.vcd"), None);
    assert_ne!(a, c, "another seed gives other phases");

    assert!(a.contains("$timescale 1 ps $end"));
    for scope in ["sim", "node0", "node1", "node2", "sync0", "cnt", "bus", "star", "p0", "up", "down"] {
        assert!(a.contains(&format!("$scope module {scope} $end")), "scope {scope}");
    }
    for var in [" 8 ", " 1 "] {
        assert!(a.contains(&format!("$var wire{var}")));
    }
    for name in ["edges", "level", "rx", "tx", "tx_at_bus", "rx_path", "clock", "out", "in", "delayed"] {
        assert!(a.contains(&format!(" {name} $end")), "var {name}");
    }
    // parse it: node1's edge counter changes over time, the bus level toggles
    let mut p = vcd::Parser::new(std::io::BufReader::new(a.as_bytes()));
    let h = p.parse_header().unwrap();
    let edges = h.find_var(&["sim", "node1", "edges"]).unwrap().code;
    let level = h.find_var(&["sim", "bus", "level"]).unwrap().code;
    let rx2 = h.find_var(&["sim", "bus", "node2", "rx"]).unwrap().code;
    let (mut n_edges, mut n_level, mut n_rx2, mut last_t) = (0, 0, 0, 0);
    for cmd in p {
        match cmd.unwrap() {
            vcd::Command::Timestamp(t) => {
                assert!(t >= last_t, "timestamps increase");
                last_t = t;
            }
            vcd::Command::ChangeVector(i, _) if i == edges => n_edges += 1,
            vcd::Command::ChangeScalar(i, _) if i == level => n_level += 1,
            vcd::Command::ChangeScalar(i, _) if i == rx2 => n_rx2 += 1,
            _ => {}
        }
    }
    assert!(n_edges > 5 && n_level > 5 && n_rx2 > 5, "{n_edges} {n_level} {n_rx2}");
    assert!(last_t <= 6_000_000 && last_t > 5_000_000);
}

#[test]
fn vcd_filter_selects_signals_by_hierarchical_name() {
    let dir = tempfile::tempdir().unwrap();
    let v = run_with_vcd(1, &dir.path().join("f.vcd"), Some(&["bus.level", "node1.cnt", "star.p1*"]));
    let mut p = vcd::Parser::new(std::io::BufReader::new(v.as_bytes()));
    let h = p.parse_header().unwrap();
    assert!(h.find_var(&["sim", "bus", "level"]).is_some());
    assert!(h.find_var(&["sim", "node1", "cnt", "q"]).is_some());
    assert!(h.find_var(&["sim", "node1", "cnt", "d"]).is_some());
    assert!(h.find_var(&["sim", "star", "p1", "up", "out"]).is_some());
    assert!(h.find_var(&["sim", "node1", "edges"]).is_none());
    assert!(h.find_var(&["sim", "node0", "cnt", "q"]).is_none());
    assert!(h.find_var(&["sim", "bus", "node0", "rx"]).is_none());
    assert!(h.find_var(&["sim", "star", "p0", "up", "out"]).is_none());
    assert!(!v.contains("$scope module node0 $end"), "no empty scopes");
}

#[test]
fn pruning_keeps_memory_bounded_over_a_long_run() {
    let (mut sim, bus) = build(5);
    let horizon = sim.horizon();
    assert_eq!(horizon, 45_000 + 20_000);
    let mut max_events = 0;
    let mut level_changes = 0u64;
    let mut last_level = true;
    // 40 ms of simulated time at 40 MHz: 1.6 M cycles per node
    for k in 1..=400u64 {
        sim.run_until(k * 100_000_000);
        max_events = max_events.max(sim.stored_events());
        let l = sim.value(bus.level);
        level_changes += (l != last_level) as u64;
        last_level = l;
    }
    assert!(sim.total_cycles() > 3 * 1_500_000);
    assert!(level_changes > 10);
    // patterns change at most every 8 cycles = 200 ns: within horizon + 1 us
    // of kept history there are at most a few dozen transitions per net
    assert!(max_events < 200, "stored events {max_events}");
    assert!(sim.history_start() > 39_000_000_000);
    // without pruning history grows with the run
    let (mut sim2, _) = build(5);
    sim2.keep_history(u64::MAX);
    sim2.run_until(100_000_000);
    assert!(sim2.stored_events() > 10 * max_events, "{} vs {}", sim2.stored_events(), max_events);
}

#[test]
#[should_panic(expected = "before the kept history")]
fn looking_back_past_the_kept_history_panics() {
    let (mut sim, bus) = build(5);
    sim.run_until(100_000_000);
    let _ = sim.value_at(bus.level, 1_000);
}

#[test]
fn bench_reports_cycle_counts() {
    let cfg = BenchConfig { single_cycles: 20_000, bus_nodes: 4, bus_cycles_per_node: 5_000, ..Default::default() };
    let r = bench_default(&cfg);
    assert_eq!(r.single_cycles, 20_000); // one node, ppm 0: exactly the cycles asked for
    assert!(r.bus_cycles >= 4 * 4_990 && r.bus_cycles <= 4 * 5_010, "{}", r.bus_cycles);
    assert!(r.single_cycles_per_sec > 0.0 && r.bus_cycles_per_sec > 0.0);
    assert_eq!(r.bus_nodes, 4);
    println!("{r}");
    // generic over the factory: a plain-Rust node works too
    let r2 = bench(&cfg, |_, clk| Reader { clk, zeros: 0 });
    assert_eq!(r2.single_cycles, 20_000);
}

/// A plain-Rust node: counts dominant samples of its RX.
struct Reader {
    clk: ClockSpec,
    zeros: u64,
}
impl canstar_sim::Component for Reader {
    fn name(&self) -> &str {
        "reader"
    }
    fn clock(&self) -> ClockSpec {
        self.clk
    }
    fn tick(&mut self, io: &mut canstar_sim::Io<'_>) {
        self.zeros += !io.input(0) as u64;
    }
}

/// Not a test of speed: prints the benchmark (run with --ignored --nocapture).
#[test]
#[ignore = "benchmark: cargo test --release -p canstar-sim --test vcd_prune_bench bench_print -- --ignored --nocapture"]
fn bench_print() {
    println!("{}", bench_default(&BenchConfig::default()));
}
