//! Clocks, delay lines, wired-AND, interference and link faults.

mod common;

use canstar_sim::bus::{Bus, NodeDelays};
use canstar_sim::star::{Link, LinkSpec};
use canstar_sim::{ClockSpec, FaultMode, NetId, Sim};
use common::Scripted;

/// Drive `net` (no component driver) with level changes at the given times.
fn drive_pattern(sim: &mut Sim, net: NetId, changes: &[(u64, bool)]) {
    for &(t, v) in changes {
        sim.run_until(t);
        sim.drive(net, v);
    }
}

/// Levels of `net` at each instant of `[from, to)`.
fn trace(sim: &Sim, net: NetId, from: u64, to: u64) -> Vec<bool> {
    (from..to).map(|t| sim.value_at(net, t)).collect()
}

/// Instants in `[from, to)` where `net` is dominant, as half-open intervals.
fn dominant_intervals(sim: &Sim, net: NetId, from: u64, to: u64) -> Vec<(u64, u64)> {
    let mut out = Vec::new();
    let mut start = None;
    for t in from..to {
        let d = !sim.value_at(net, t);
        match (d, start) {
            (true, None) => start = Some(t),
            (false, Some(s)) => {
                out.push((s, t));
                start = None
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        out.push((s, to));
    }
    out
}

#[test]
fn edge_times_with_ppm_offsets_are_exact() {
    let c = ClockSpec::new(25_000).with_ppm(100.0);
    assert_eq!(c.edge_time(0), 0);
    assert_eq!(c.edge_time(1), 25_002); // 25002.5 floored
    assert_eq!(c.edge_time(2), 50_005);
    assert_eq!(c.edge_time(10_000), 250_025_000);
    // 10^12 edges: exact integer arithmetic, no drift from accumulated floats
    assert_eq!(c.edge_time(1_000_000_000_000), 25_002_500_000_000_000);

    let c = ClockSpec::new(12_500).with_ppm(-37.5).with_phase(777);
    for n in [0u64, 1, 3, 999, 123_456, 98_765_432_101] {
        // t_n = phase + floor(n * 12500 * (1 - 37.5e-6)) = phase + floor(n * 12500 * 1999925 / 2000000)
        let expect = 777 + ((n as u128 * 12_500 * 1_999_925) / 2_000_000) as u64;
        assert_eq!(c.edge_time(n), expect, "edge {n}");
    }
    for t in [0u64, 776, 777, 778, 12_000, 13_276, 13_277, 1_000_000_007] {
        let n = c.first_edge_after(t);
        assert!(c.edge_time(n) > t);
        assert!(n == 0 || c.edge_time(n - 1) <= t);
    }
}

#[test]
fn components_tick_on_their_own_drifting_edges() {
    let mut sim = Sim::new(1);
    let fast = ClockSpec::new(1_000).with_ppm(500.0);
    let slow = ClockSpec::new(1_000).with_ppm(-500.0).with_phase(3);
    let a = sim.add(Scripted::new("a", fast, &[]), &[], &[]);
    let b = sim.add(Scripted::new("b", slow, &[]), &[], &[]);
    sim.run_until(2_000_000);
    let ta: Vec<u64> = sim.get(a).samples.iter().map(|s| s.0).collect();
    let tb: Vec<u64> = sim.get(b).samples.iter().map(|s| s.0).collect();
    for (n, &t) in ta.iter().enumerate() {
        assert_eq!(t, fast.edge_time(n as u64));
    }
    for (n, &t) in tb.iter().enumerate() {
        assert_eq!(t, slow.edge_time(n as u64));
    }
    // +500 ppm is slower: in 2 us of 1 ns clocks the two differ by ~2 edges
    assert_eq!(ta.len(), 2_000); // edges 0..=1999 (1999 * 1000.5 <= 2e6 < 2000 * 1000.5)
    assert_eq!(tb.len(), 2_001);
    assert_eq!(sim.now(), 2_000_000);
}

#[test]
fn clock_jitter_is_bounded_and_seeded() {
    let run = |seed: u64| {
        let mut sim = Sim::new(seed);
        let c = ClockSpec::new(10_000).with_ppm(25.0).with_jitter(300);
        let h = sim.add(Scripted::new("j", c, &[]), &[], &[]);
        let plain = sim.add(Scripted::new("p", ClockSpec::new(10_000), &[]), &[], &[]);
        sim.run_until(10_000_000);
        for (n, s) in sim.get(plain).samples.iter().enumerate() {
            assert_eq!(s.0, 10_000 * n as u64);
        }
        let t: Vec<u64> = sim.get(h).samples.iter().map(|s| s.0).collect();
        for (n, &x) in t.iter().enumerate() {
            let nominal = c.edge_time(n as u64);
            assert!(x >= nominal && x <= nominal + 300, "edge {n}: {x} vs {nominal}");
        }
        t
    };
    let a = run(1);
    assert_eq!(a, run(1));
    assert_ne!(a, run(2));
    let distinct: std::collections::BTreeSet<u64> =
        a.iter().enumerate().map(|(n, &x)| x - ClockSpec::new(10_000).with_ppm(25.0).edge_time(n as u64)).collect();
    assert!(distinct.len() > 100, "jitter varies from edge to edge");
}

#[test]
fn delay_line_symmetric_shifts_exactly() {
    let mut sim = Sim::new(0);
    let src = sim.driven("src", true);
    let d = sim.delay("d", src, 7, 7);
    drive_pattern(&mut sim, src, &[(10, false), (13, true), (20, false), (40, true)]);
    sim.run_until(100);
    assert_eq!(dominant_intervals(&sim, src, 0, 100), vec![(10, 13), (20, 40)]);
    assert_eq!(dominant_intervals(&sim, d, 0, 100), vec![(17, 20), (27, 47)]);
}

#[test]
fn delay_line_slow_recessive_stretches_dominant_and_swallows_short_recessive() {
    // dR >= dD: out = src(t-dD) & src(t-dR)
    let mut sim = Sim::new(0);
    let src = sim.driven("src", true);
    let d = sim.delay("d", src, 10, 30);
    drive_pattern(
        &mut sim,
        src,
        &[
            (100, false), // dominant pulse of 5
            (105, true),
            (200, false), // dominant, then a recessive glitch of 15 (swallowed)
            (300, true),
            (315, false),
            (400, true), // recessive pulse of 25 (survives as 5)
            (425, false),
            (500, true),
        ],
    );
    sim.run_until(1000);
    // the 5 ps dominant pulse is stretched to 25 ps (falling edge +10, rising edge +30)
    assert_eq!(dominant_intervals(&sim, d, 0, 1000), vec![(110, 135), (210, 430), (435, 530)]);
    // reference: recessive iff recessive over the whole window [t-30, t-10]
    for t in 30..1000 {
        let expect = (t - 30..=t - 10).all(|u| sim.value_at(src, u));
        assert_eq!(sim.value_at(d, t), expect, "t={t}");
    }
    // where the window holds at most one transition: out = src(t-dD) & src(t-dR)
    for t in (180..330).chain(380..560) {
        let expect = sim.value_at(src, t - 10) & sim.value_at(src, t - 30);
        assert_eq!(sim.value_at(d, t), expect, "t={t}");
    }
}

#[test]
fn delay_line_slow_dominant_swallows_short_dominant() {
    // dD > dR: out = src(t-dD) | src(t-dR)
    let mut sim = Sim::new(0);
    let src = sim.driven("src", true);
    let d = sim.delay("d", src, 30, 10);
    drive_pattern(
        &mut sim,
        src,
        &[(100, false), (115, true), (200, false), (250, true), (300, false), (303, true)],
    );
    sim.run_until(1000);
    // the 15 ps and 3 ps dominant pulses vanish, the 50 ps one shrinks to 30
    assert_eq!(dominant_intervals(&sim, d, 0, 1000), vec![(230, 260)]);
    for t in 30..1000 {
        let expect = (t - 30..=t - 10).any(|u| sim.value_at(src, u));
        assert_eq!(sim.value_at(d, t), expect, "t={t}");
    }
    for t in (80..150).chain(180..290) {
        let expect = sim.value_at(src, t - 30) | sim.value_at(src, t - 10);
        assert_eq!(sim.value_at(d, t), expect, "t={t}");
    }
}

#[test]
fn wired_and_is_dominant_if_any_input_is() {
    let mut sim = Sim::new(0);
    let a = sim.driven("a", true);
    let b = sim.driven("b", true);
    let c = sim.driven("c", true);
    let w = sim.wired_and("w", &[a, b, c]);
    for (t, pattern) in (0u64..8).map(|k| (10 + 10 * k, k)) {
        sim.run_until(t);
        sim.drive(a, pattern & 1 != 0);
        sim.drive(b, pattern & 2 != 0);
        sim.drive(c, pattern & 4 != 0);
        assert_eq!(sim.value(w), pattern == 7, "pattern {pattern}");
    }
}

/// A two-node bus; node 0's TX is driven by test code with `pattern`.
fn interference_bus(mode: FaultMode) -> (Sim, Bus) {
    let mut sim = Sim::new(0);
    let bus = Bus::uniform(&mut sim, "bus", 2, NodeDelays::symmetric(5, 3));
    bus.set_interference(&mut sim, 1, mode);
    (sim, bus)
}

#[test]
fn each_interference_mode_changes_only_that_node() {
    let pattern = [(100u64, false), (150, true), (200, false), (260, true)];
    let bus_dom = [(108u64, 158u64), (208, 268)];
    for mode in [FaultMode::None, FaultMode::Invert, FaultMode::StuckRecessive, FaultMode::StuckDominant] {
        let (mut sim, bus) = interference_bus(mode);
        drive_pattern(&mut sim, bus.nodes[0].tx, &pattern);
        sim.run_until(400);
        assert_eq!(dominant_intervals(&sim, bus.nodes[0].rx, 0, 400), bus_dom.to_vec(), "{mode:?}");
        let rx1 = dominant_intervals(&sim, bus.nodes[1].rx, 0, 400);
        let expect = match mode {
            FaultMode::None => bus_dom.to_vec(),
            FaultMode::Invert => vec![(0, 108), (158, 208), (268, 400)],
            FaultMode::StuckRecessive => vec![],
            FaultMode::StuckDominant => vec![(0, 400)],
        };
        assert_eq!(rx1, expect, "{mode:?}");
        // the bus itself is never affected
        assert_eq!(dominant_intervals(&sim, bus.level, 0, 400), vec![(105, 155), (205, 265)]);
    }
}

#[test]
fn interference_switches_at_scheduled_and_current_times() {
    let (mut sim, bus) = interference_bus(FaultMode::None);
    let rx1 = bus.nodes[1].rx;
    bus.schedule_interference(&mut sim, 1, 1000, FaultMode::StuckDominant);
    bus.schedule_interference(&mut sim, 1, 2000, FaultMode::Invert);
    sim.run_until(999);
    assert!(sim.value(rx1));
    sim.run_until(1000);
    assert!(!sim.value(rx1), "stuck dominant from t=1000 on");
    sim.run_until(1999);
    assert!(!sim.value(rx1));
    sim.run_until(2000);
    assert!(!sim.value(rx1), "inverted recessive bus");
    assert_eq!(sim.fault_mode_at(rx1, 2000), FaultMode::Invert);
    sim.run_until(2500);
    bus.set_interference(&mut sim, 1, FaultMode::StuckRecessive);
    assert!(sim.value(rx1));
    assert!(!sim.value_at(rx1, 2499), "the past is unchanged");
    assert!(sim.value(bus.nodes[0].rx));
}

#[test]
fn components_see_interference_changes_from_the_next_edge() {
    let mut sim = Sim::new(0);
    let bus = Bus::uniform(&mut sim, "bus", 1, NodeDelays::symmetric(0, 0));
    let h = sim.add(Scripted::new("n", ClockSpec::new(100), &[]), &[bus.nodes[0].rx], &[]);
    sim.run_until(300); // edges 0..=300
    bus.set_interference(&mut sim, 0, FaultMode::StuckDominant);
    bus.schedule_interference(&mut sim, 0, 550, FaultMode::None);
    sim.run_until(700);
    let s: Vec<(u64, bool)> = sim.get(h).samples.clone();
    let expect: Vec<(u64, bool)> =
        vec![(0, true), (100, true), (200, true), (300, true), (400, false), (500, false), (600, true), (700, true)];
    assert_eq!(s, expect);
}

#[test]
fn each_link_fault_mode() {
    for f in [FaultMode::None, FaultMode::Invert, FaultMode::StuckRecessive, FaultMode::StuckDominant] {
        let mut sim = Sim::new(0);
        let l = Link::build(&mut sim, "l", LinkSpec { d_dom: 10, d_rec: 20 });
        l.set_fault(&mut sim, f);
        drive_pattern(&mut sim, l.input, &[(100, false), (200, true)]);
        sim.run_until(400);
        let got = dominant_intervals(&sim, l.output, 0, 400);
        let expect = match f {
            FaultMode::None => vec![(110, 220)],
            FaultMode::Invert => vec![(0, 110), (220, 400)],
            FaultMode::StuckRecessive => vec![],
            FaultMode::StuckDominant => vec![(0, 400)],
        };
        assert_eq!(got, expect, "{f:?}");
        assert_eq!(dominant_intervals(&sim, l.delayed, 0, 400), vec![(110, 220)]);
    }
}

#[test]
fn link_fault_schedule_and_flip_windows() {
    let mut sim = Sim::new(0);
    let l = Link::build(&mut sim, "l", LinkSpec::symmetric(0));
    l.schedule_fault(&mut sim, 100, FaultMode::StuckDominant);
    l.schedule_fault(&mut sim, 200, FaultMode::None);
    l.add_flip_window(&mut sim, 300, 310);
    l.add_flip_window(&mut sim, 305, 320); // merges to [300, 320)
    sim.add_flip_pattern(l.output, 400, 5, 20, 3); // [400,405) [420,425) [440,445)
    sim.run_until(1000);
    assert_eq!(
        dominant_intervals(&sim, l.output, 0, 1000),
        vec![(100, 200), (300, 320), (400, 405), (420, 425), (440, 445)]
    );
    // a flip window on a dominant input produces recessive
    let mut sim = Sim::new(0);
    let l = Link::build(&mut sim, "l", LinkSpec::symmetric(0));
    sim.drive(l.input, false);
    l.add_flip_window(&mut sim, 50, 60);
    sim.run_until(100);
    assert_eq!(dominant_intervals(&sim, l.output, 0, 100), vec![(0, 50), (60, 100)]);
    assert_eq!(trace(&sim, l.output, 49, 51), vec![false, true]);
}

#[test]
fn fn_component_toggles_and_reads() {
    let mut sim = Sim::new(0);
    let a = sim.driven("a", true);
    let b = sim.delay("b", a, 250, 250);
    let mut level = true;
    let seen_ptr = std::rc::Rc::new(std::cell::RefCell::new(Vec::new()));
    let sp = seen_ptr.clone();
    sim.add(
        canstar_sim::FnComponent::new("toggler", ClockSpec::new(1_000), move |io| {
            sp.borrow_mut().push((io.now(), io.input(0)));
            level = !level;
            io.set_output(0, level);
        }),
        &[b],
        &[a],
    );
    sim.run_until(5_000);
    let seen = seen_ptr.borrow().clone();
    // a toggles at every edge (dominant at 0, 2000, 4000), b follows 250 ps later:
    // the edge at 1000 sees the dominant written at 0
    assert_eq!(seen, vec![(0, true), (1_000, false), (2_000, true), (3_000, false), (4_000, true), (5_000, false)]);
    assert_eq!(dominant_intervals(&sim, b, 0, 5_000), vec![(250, 1_250), (2_250, 3_250), (4_250, 5_000)]);
}
