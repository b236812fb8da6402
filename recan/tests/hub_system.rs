//! The RTL hub (`canstar_hub::top::Hub` as `RtlHub`) with real CAN controllers
//! (`CanNode`) in the simulation kernel: hub.md acceptance A1 (fault-free traffic is
//! never blamed), A3 (faulty uplinks isolated in time), A4 (two coupled hubs) and H2
//! (coupling latency measured on the pins).
#![allow(clippy::needless_range_loop)]
mod hub_util;
use canstar_controller::frame::Frame;
#[allow(unused_imports)]
use canstar_sim::FaultMode;
use canstar_verify::node::{ErrorKind, HostEvent};
use hub_util::*;

#[test]
fn fault_free_full_load_one_hub() {
    let cfg = hub_cfg(3, 0);
    let mut st = Star::new(&cfg, &[0.0, 0.0, 0.0], 1);
    let nodes = st.nodes.clone();
    let sent = load(&mut st.sim, &nodes, 4, 11);
    let t0 = std::time::Instant::now();
    assert!(st.run_until_drained(4000));
    eprintln!("wall {:?} sim {} bits", t0.elapsed(), st.sim.now() / BIT);
    for j in 0..3 {
        assert_eq!(st.node(j).errors(), 0, "node {j} errors {:?}", st.node(j).log());
        for k in 0..3 {
            if k != j {
                assert!(received_in_order(st.node(j), &sent[k]), "node {j} missed frames of {k}");
            }
        }
    }
    assert_never_blamed(st.rtl(), "one hub");
    assert_eq!(st.rtl().stats.frames_ok, 12);
    assert!(arb_losses(&st.sim, &st.nodes) > 3, "arbitration among the nodes");
    assert_frame_mix(&sent);
}

/// Compare the two hubs' downlink levels at every sample point of hub 0's frame
/// monitor with hub 1's sample nearest in time (within half a bit). Returns the
/// number of compared samples and the first disagreement.
fn compare_downlinks(d: &Dual) -> (usize, Option<(u64, bool, bool)>) {
    // bits sampled while a monitor is idle are not synchronised to any edge (the first
    // SOF reaches the two hubs one hub crossing apart): compared from SOF to intermission
    let idle = canstar_hub::frame_state::Field::Idle.code() as u8;
    let s0 = d.rtl(0).samples();
    let s1 = d.rtl(1).samples();
    let mut j = 0;
    let mut n = 0;
    for &(t, v, f) in s0 {
        while j + 1 < s1.len() && s1[j + 1].0 <= t {
            j += 1;
        }
        let cand = [j, (j + 1).min(s1.len().saturating_sub(1))];
        let best = cand.iter().copied().filter(|&k| k < s1.len()).min_by_key(|&k| s1[k].0.abs_diff(t));
        if let Some(k) = best {
            if s1[k].0.abs_diff(t) < BIT / 2 && f != idle && s1[k].2 != idle {
                n += 1;
                if s1[k].1 != v {
                    return (n, Some((t, v, s1[k].1)));
                }
            }
        }
    }
    (n, None)
}

fn dual_fault_free(seed: u64, ppm: &[f64]) -> (Dual, Vec<Vec<Frame>>) {
    dual_fault_free_cfg(&hub_cfg(3, 2), seed, ppm, 4)
}

fn dual_fault_free_cfg(cfg: &canstar_hub::config::HubConfig, seed: u64, ppm: &[f64], frames: usize) -> (Dual, Vec<Vec<Frame>>) {
    let cfg = cfg.clone();
    let mut d = Dual::new(&cfg, ppm, seed);
    d.rtl_mut(0).record_samples();
    d.rtl_mut(1).record_samples();
    // node 0 and node 2 transmit through hub 0, node 1 through hub 1
    let tx = vec![d.a[0], d.b[1], d.a[2]];
    let sent = load(&mut d.sim, &tx, frames, seed + 100);
    let t0 = std::time::Instant::now();
    assert!(d.run_until_drained(4000), "queues drained");
    eprintln!("wall {:?} sim {} bits", t0.elapsed(), d.sim.now() / BIT);
    for h in 0..2 {
        for k in 0..3 {
            let c = d.ctrl(h, k);
            assert_eq!(c.errors(), 0, "ctrl {h}/{k} errors {:?}", c.log());
            for (m, s) in sent.iter().enumerate() {
                let own_tx = (m == 0 && h == 0 && k == 0) || (m == 1 && h == 1 && k == 1) || (m == 2 && h == 0 && k == 2);
                if !own_tx {
                    assert!(received_in_order(c, s), "ctrl {h}/{k} missed frames of node {m}");
                }
            }
        }
        assert_never_blamed(d.rtl(h), &format!("hub {h}"));
    }
    let (n, bad) = compare_downlinks(&d);
    assert!(bad.is_none(), "downlinks differ at a sample point: {bad:?}");
    assert!(n > 500, "compared {n} samples");
    assert!(arb_losses(&d.sim, &tx) > 2, "arbitration across the hubs");
    (d, sent)
}

#[test]
fn two_hubs_fault_free_full_load() {
    let (_, sent) = dual_fault_free(2, &[0.0, 0.0, 0.0]);
    assert_frame_mix(&sent);
}

/// H2 in the kernel: clocks from a dominant edge on an uplink pin (the hub's input net)
/// to the downlink pins of the same hub and, across the interlink, of the other hub.
/// Returns (best, worst) same-hub and worst other-hub latency in hub clock periods,
/// rounded up, over 8 phases of the uplink edge within a clock period.
fn measure_latency(sync_depth: usize) -> (u64, u64, u64) {
    use canstar_sim::star::{LinkSpec, TwoHubs};
    use canstar_recan::rtl_hub::RtlHub;
    use canstar_sim::{ClockSpec, Sim};
    let cfg = canstar_hub::config::HubConfig { sync_depth, ..hub_cfg(3, 2) };
    let (mut worst_same, mut worst_other, mut best_same) = (0, 0, u64::MAX);
    for phase in 0..8u64 {
        let mut sim = Sim::new(phase);
        let z = LinkSpec::default();
        let ports = vec![canstar_sim::star::PortSpec { up: z, down: z }; 3];
        let net = TwoHubs::build(&mut sim, "r", [&ports, &ports], &[(z, z), (z, z)]);
        // both hubs on the same clock, so the interlink latency is measured in clocks
        let clk = ClockSpec::new(HUB_PERIOD);
        sim.add(RtlHub::with_clock("h0", &cfg, clk), &net.hubs[0].hub_inputs(), &net.hubs[0].hub_outputs());
        sim.add(RtlHub::with_clock("h1", &cfg, clk), &net.hubs[1].hub_inputs(), &net.hubs[1].hub_outputs());
        sim.run_until(40 * HUB_PERIOD + phase * HUB_PERIOD / 8 + 1);
        let t0 = sim.now();
        sim.run_for(0);
        let tdrive = 40 * HUB_PERIOD + phase * HUB_PERIOD / 8 + 1;
        assert!(t0 <= tdrive);
        sim.drive(net.hubs[0].node_tx(0), false);
        let down0 = net.hubs[0].downlinks[1].input;
        let down1 = net.hubs[1].downlinks[2].input;
        assert!(sim.run_until_cond(tdrive + 20 * HUB_PERIOD, |s| !s.value(down0)));
        let same = (sim.now() - tdrive).div_ceil(HUB_PERIOD);
        assert!(sim.run_until_cond(tdrive + 20 * HUB_PERIOD, |s| !s.value(down1)));
        let other = (sim.now() - tdrive).div_ceil(HUB_PERIOD);
        worst_same = worst_same.max(same);
        best_same = best_same.min(same);
        worst_other = worst_other.max(other);
    }
    (best_same, worst_same, worst_other)
}

#[test]
fn coupling_latency_in_the_kernel() {
    for depth in [1usize, 2] {
        let (best, same, other) = measure_latency(depth);
        eprintln!("sync depth {depth}: uplink pin -> own downlink {best}..{same} clocks, -> other hub's downlink {other} clocks");
        let lat = canstar_hub::config::HubConfig { sync_depth: depth, ..Default::default() }.coupling_latency() as u64;
        // an edge between two clock edges is seen at the next one: pin to pin takes
        // (lat - 1, lat] clock periods, rounded up: lat; across the interlink twice that
        assert_eq!((best, same, other), (lat, lat, 2 * lat), "depth {depth}");
    }
}

/// A1: a late joiner (a node reset in the middle of full-load traffic integrates
/// again and sends), and a node that starts late; never blamed.
#[test]
fn late_joiner_one_hub() {
    let cfg = hub_cfg(3, 0);
    let mut st = Star::new(&cfg, &[0.0, 0.0, 0.0], 6);
    let nodes = st.nodes.clone();
    let sent = load(&mut st.sim, &nodes[..2], 8, 66);
    // node 2 starts late, and is reset twice in the middle of frames
    st.node_mut(2).hard_reset();
    st.sim.run_for(137 * BIT);
    st.node_mut(2).hard_reset();
    st.node_mut(2).request(Frame::std(0x7f2, &[2]));
    st.sim.run_for(251 * BIT + BIT / 3);
    st.node_mut(2).hard_reset();
    st.node_mut(2).request(Frame::ext(0x1abcdef2, &[2, 2]));
    assert!(st.run_until_drained(4000));
    assert!(st.node(2).sent().contains(&Frame::ext(0x1abcdef2, &[2, 2])), "late joiner sent");
    for j in 0..2 {
        assert!(received_in_order(st.node(j), &st.node(2).sent()), "node {j} got the late joiner's frames");
        let k = 1 - j;
        assert!(received_in_order(st.node(j), &sent[k]));
    }
    assert_never_blamed(st.rtl(), "late joiner");
}

/// A1: node oscillators at the tolerance limit of the bit timing (±6250 ppm), one hub
/// and two hubs (sync depth 1, the default).
#[test]
fn clock_tolerance_limit_one_hub() {
    let tol = tolerance_ppm();
    assert!((tol - 6250.0).abs() < 1.0);
    let cfg = hub_cfg(3, 0);
    let mut st = Star::new(&cfg, &[tol, -tol, 0.0], 7);
    let nodes = st.nodes.clone();
    let sent = load(&mut st.sim, &nodes, 5, 77);
    assert!(st.run_until_drained(4000));
    for j in 0..3 {
        assert_eq!(st.node(j).errors(), 0, "node {j} errors {:?}", st.node(j).log());
        for k in 0..3 {
            if k != j {
                assert!(received_in_order(st.node(j), &sent[k]));
            }
        }
    }
    assert_never_blamed(st.rtl(), "clock tolerance");
}

#[test]
fn two_hubs_clock_tolerance_limit() {
    let tol = tolerance_ppm();
    dual_fault_free_cfg(&hub_cfg(3, 2), 5, &[tol, -tol, 0.0], 5);
    dual_fault_free_cfg(&hub_cfg(3, 2), 6, &[-tol, tol, tol], 4);
}

#[test]
#[ignore = "diagnostic: shows that sync depth 2 fails at the tolerance limit with two hubs"]
fn diag_probe_tolerance() {
    let tol = tolerance_ppm();
    eprintln!("tolerance {tol} ppm");
    for depth in [2usize, 1] {
        for (seed, ppm) in [(5u64, [tol, -tol, 0.0]), (6, [-tol, tol, tol]), (7, [tol, -tol, -tol])] {
            let cfg = canstar_hub::config::HubConfig { sync_depth: depth, ..hub_cfg(3, 2) };
            let r = std::panic::catch_unwind(|| { dual_fault_free_cfg(&cfg, seed, &ppm, 6); });
            eprintln!("depth {depth} seed {seed} ppm {ppm:?}: {}", if r.is_ok() { "ok" } else { "FAIL" });
        }
    }
}

/// A1: identical frames from two nodes at the same time, on top of random full load.
#[test]
fn identical_identifiers_one_hub() {
    let cfg = hub_cfg(3, 0);
    let mut st = Star::new(&cfg, &[0.0, 0.0, 0.0], 3);
    let same = Frame::std(0x0a5, &[1, 2, 3]);
    let same_ext = Frame::remote(true, 0x1234567, 2);
    for k in 0..2 {
        st.node_mut(k).request(same.clone());
        st.node_mut(k).request(same_ext.clone());
    }
    let nodes = st.nodes.clone();
    let _ = load(&mut st.sim, &nodes, 2, 33);
    assert!(st.run_until_drained(3000));
    for j in 0..3 {
        assert_eq!(st.node(j).errors(), 0, "node {j} errors {:?}", st.node(j).log());
    }
    // both senders report success; the third node receives each identical frame once
    for k in 0..2 {
        assert!(st.node(k).sent().contains(&same) && st.node(k).sent().contains(&same_ext));
    }
    let rx2 = st.node(2).received();
    assert_eq!(rx2.iter().filter(|f| **f == same).count(), 1);
    assert_eq!(rx2.iter().filter(|f| **f == same_ext).count(), 1);
    assert_never_blamed(st.rtl(), "identical identifiers");
}

/// A1: a node made error-passive beforehand (the host loads TEC 160, as `canstar soak
/// --events` does), then full load with the error-passive transmitter (passive error flags,
/// suspend transmission): never blamed.
#[test]
fn error_passive_node_one_hub() {
    let cfg = hub_cfg(3, 0);
    let mut st = Star::new(&cfg, &[0.0, 0.0, 0.0], 4);
    let nodes = st.nodes.clone();
    let x = st.nodes[0];
    // (after the controller's reset: a load during reset is ignored)
    st.sim.run_for(20 * BIT);
    st.sim.get_mut(x).load_counters(160, 0);
    st.sim.run_for(BIT);
    assert_eq!(st.node(0).state(), 1, "node 0 error-passive, tec {}", st.node(0).tec());
    st.node_mut(0).withdraw();
    st.sim.run_for(200 * BIT);
    let sent = load(&mut st.sim, &nodes, 4, 44);
    assert!(st.run_until_drained(6000));
    assert_eq!(st.node(0).state(), 1, "node 0 stayed error-passive");
    for j in 0..3 {
        for k in 0..3 {
            if k != j {
                assert!(received_in_order(st.node(j), &sent[k]), "node {j} missed frames of {k}");
            }
        }
    }
    eprintln!("tec {} rec {:?}", st.node(0).tec(), (st.node(1).rec(), st.node(2).rec()));
    assert_never_blamed(st.rtl(), "error-passive node");
}

/// hub.md §5.12: a transmitter whose downlink flips one bit of its data field sees a bit
/// error that nobody else sees and sends its error flag; the monitor detects the stuff error
/// with no blame before it, and the first-flagger rule charges the transmitter's port, 8 per
/// episode, until it is isolated at `bic 48/48` (6 episodes). The receivers are never charged.
#[test]
fn transmitter_with_flipping_downlink_isolated_by_first_flagger() {
    use canstar_controller::fsm::Field as F;
    let cfg = hub_cfg(3, 0);
    let mut st = Star::new(&cfg, &[0.0, 0.0, 0.0], 4);
    let x = st.nodes[0];
    let down0 = st.ports.downlinks[0];
    for i in 0..40 {
        st.sim.get_mut(x).request(Frame::std(0x100 + i, &[0x55, i as u8, 0xaa]));
    }
    let mut flips = 0;
    while st.rtl().stats.isolated_at[0].is_none() && flips < 20 {
        assert!(flip_bit_at(&mut st.sim, x, down0, F::Data, 9, 400, |n| canstar_controller::view::CoreView::dbg_role(&n.core)));
        flips += 1;
        st.sim.run_for(20 * BIT);
    }
    let s = &st.rtl().stats;
    assert_eq!(flips, 6, "isolated after {flips} flips: {s:?}");
    assert_eq!(s.isolated_by[0].as_deref(), Some("bic 48/48"));
    assert_eq!(&s.max_bic[1..], &[0, 0], "receivers charged: {s:?}");
    assert!(s.isolated_at[1..].iter().all(|i| i.is_none()));
}

/// A1: a dominant last EOF bit at one receiver (a short inversion of its downlink)
/// makes it send an overload flag; everyone follows with overload frames; the hub
/// blames nobody. With the dominant bit on an uplink (the hub and every node see it) the
/// transmitter takes it for a form error and sends the frame again, and the hub charges
/// that port once per dominant last EOF bit (hub.md §5.19), nobody else, and isolates
/// nothing.
#[test]
fn overload_frames_one_hub() {
    use canstar_controller::fsm::Field as F;
    for on_uplink in [false, true] {
        let cfg = hub_cfg(3, 0);
        let mut st = Star::new(&cfg, &[0.0, 0.0, 0.0], 5);
        let nodes = st.nodes.clone();
        let sent = load(&mut st.sim, &nodes[..2], 6, 55);
        let n2 = st.nodes[2];
        let link = if on_uplink { st.ports.uplinks[2] } else { st.ports.downlinks[2] };
        // on the uplink a whole bit time (a sub-bit pulse on an uplink is a glitch,
        // hub.md §5.8, and three of them isolate the port: a legal overload flag is never
        // that short)
        for _ in 0..3 {
            if on_uplink {
                // the uplink forced dominant for one bit time (an inversion would cut the
                // node's own overload flag into glitches)
                let deadline = st.sim.now() + 400 * BIT;
                assert!(st.sim.run_until_cond(deadline, |s| s.get(n2).field() == F::Eof && s.get(n2).pos() == 7));
                let t = st.sim.now();
                link.schedule_fault(&mut st.sim, t + BIT / 2, FaultMode::StuckDominant);
                link.schedule_fault(&mut st.sim, t + BIT * 3 / 2, FaultMode::None);
            } else {
                assert!(flip_bit_at(&mut st.sim, n2, link, F::Eof, 7, 400, |_| true));
            }
            st.sim.run_for(40 * BIT);
        }
        assert!(st.run_until_drained(3000));
        for j in 0..3 {
            // a transmitter takes a dominant last EOF bit on BT as a form error (and
            // retransmits; receivers already accepted the frame): legal, expected only
            // when the dominant bit reached BT (uplink case)
            let bad = st.node(j).log().iter().filter(|(_, e)| match e {
                HostEvent::Error { kinds, field, pos, tx } => {
                    !(on_uplink && *tx && *kinds == vec![ErrorKind::Form] && *field == canstar_controller::fsm::Field::Eof && *pos == 7)
                }
                _ => false,
            }).count();
            assert_eq!(bad, 0, "node {j} errors {:?}", st.node(j).log());
            for k in 0..2 {
                if k != j {
                    assert!(received_in_order(st.node(j), &sent[k]), "node {j} missed frames of {k}");
                }
            }
        }
        eprintln!("uplink {on_uplink}: stats {:?}", st.rtl().stats);
        assert!(st.rtl().stats.overload_bits >= 3 * 7, "overload frames happened");
        if on_uplink {
            let s = &st.rtl().stats;
            assert_eq!(s.blames, 3, "overload via uplink: {s:?}");
            assert!(s.max_bic[2] > 0 && s.max_bic[..2].iter().chain(&s.max_sub_bic).all(|&b| b == 0), "{s:?}");
            assert!(s.isolated_at.iter().all(|x| x.is_none()), "{s:?}");
        } else {
            assert_never_blamed(st.rtl(), "overload via downlink");
        }
    }
}

// ---------------------------------------------------------------- A3: faulty ports

fn faulty_star(cfg: &canstar_hub::config::HubConfig, seed: u64, frames: usize) -> (Star, Vec<Vec<Frame>>) {
    let mut st = Star::new(cfg, &[0.0, 0.0, 0.0], seed);
    let nodes = st.nodes.clone();
    let sent = load(&mut st.sim, &nodes, frames, seed + 1000);
    (st, sent)
}

/// A3: a stuck-at-dominant uplink, started in the middle of full-load traffic, is
/// isolated within DBC threshold + 2 bits; then the others communicate again.
#[test]
fn stuck_dominant_uplink_isolated_in_time() {
    let cfg = hub_cfg(3, 0);
    for (seed, start_bits) in [(21u64, 300u64), (22, 417), (23, 733)] {
        let (mut st, sent) = faulty_star(&cfg, seed, 12);
        let t_f = start_bits * BIT + BIT / 7 * (seed % 7);
        st.ports.uplinks[1].schedule_fault(&mut st.sim, t_f, FaultMode::StuckDominant);
        st.sim.run_until(t_f + 40 * BIT);
        let iso = st.rtl().stats.isolated_at[1].expect("port 1 isolated");
        let bits = (iso - t_f) as f64 / BIT as f64;
        eprintln!("stuck dominant from {start_bits} bits: isolated after {bits:.2} bits");
        assert!(bits <= (cfg.dbc_threshold + 2) as f64, "isolated after {bits} bits");
        assert_eq!(st.rtl().isolated(), vec![false, true, false]);
        // the others go on and deliver all their frames
        st.node_mut(1).withdraw();
        let (tec, rec) = run_tracking(&mut st.sim, &[st.nodes[0], st.nodes[2]], 300 * BIT);
        assert!(st.run_until_drained(5000), "healthy nodes drained their queues");
        assert!(received_in_order(st.node(0), &sent[2]) && received_in_order(st.node(2), &sent[0]));
        assert!(tec < 96 && rec < 96, "healthy tec {tec} rec {rec}");
        assert_eq!(st.rtl().isolated(), vec![false, true, false]);
    }
}

/// A3: a node whose downlink is stuck recessive keeps restarting its error flag; its
/// uplink is isolated within one error episode (the dominant-run rule).
#[test]
fn stuck_recessive_downlink_node_isolated() {
    let cfg = hub_cfg(3, 0);
    let (mut st, _) = faulty_star(&cfg, 24, 10);
    let t_f = 250 * BIT;
    st.ports.downlinks[2].schedule_fault(&mut st.sim, t_f, FaultMode::StuckRecessive);
    let (tec, rec) = run_tracking(&mut st.sim, &[st.nodes[0], st.nodes[1]], 600 * BIT);
    let iso = st.rtl().stats.isolated_at[2].expect("port 2 isolated");
    let s = &st.rtl().stats;
    eprintln!("stuck recessive downlink: isolated {:.1} bits after the fault, blames {}, max dbc {:?}, healthy tec {tec} rec {rec}", (iso - t_f) as f64 / BIT as f64, s.blames, s.max_dbc);
    assert_eq!(st.rtl().isolated(), vec![false, false, true]);
    assert!(tec < 96 && rec < 96);
    // one error episode: at most two error flags of the hub between fault and isolation
    assert!(st.node(0).errors() <= 3, "{:?}", st.node(0).log());
}

fn bit_flipping_uplink(cfg: &canstar_hub::config::HubConfig, seed: u64, every_bits: u64, count: usize, budget_bits: u64) -> (Star, f64, u32, u32) {
    let (mut st, _) = faulty_star(cfg, seed, 400);
    let t_f = 200 * BIT;
    // half-bit inversions at a fixed period unrelated to the frame length
    st.sim.add_flip_pattern(st.ports.uplinks[0].output, t_f, BIT / 2, every_bits * BIT + BIT / 3, count);
    let healthy = [st.nodes[1], st.nodes[2]];
    let mut worst = (0, 0);
    let step = 500 * BIT;
    while st.sim.now() < t_f + budget_bits * BIT && st.rtl().stats.isolated_at[0].is_none() {
        let (t, r) = run_tracking(&mut st.sim, &healthy, step);
        worst = (worst.0.max(t), worst.1.max(r));
    }
    let iso = st.rtl().stats.isolated_at[0].map(|t| (t - t_f) as f64 / BIT as f64).unwrap_or(f64::INFINITY);
    (st, iso, worst.0, worst.1)
}

/// A3: a bit-flipping uplink (one half-bit inversion every 23 bits) is isolated by the
/// decaying BIC before any healthy controller's TEC or REC reaches 96.
#[test]
fn bit_flipping_uplink_isolated_before_96() {
    let cfg = hub_cfg(3, 0);
    let (st, iso, tec, rec) = bit_flipping_uplink(&cfg, 25, 23, 2000, 20_000);
    let s = &st.rtl().stats;
    eprintln!("flips every 23 bits: isolated after {iso:.0} bits, blames {}, max bic {:?}, healthy tec {tec} rec {rec}", s.blames, s.max_bic);
    assert!(iso.is_finite());
    assert_eq!(st.rtl().isolated(), vec![true, false, false]);
    assert!(tec < 96 && rec < 96, "healthy tec {tec} rec {rec}");
}

/// A3 "any rate": a rarely flipping uplink (one inversion every 1201 bits, about one
/// per 10 frames: the decaying BIC never passes 8) is isolated by the lifetime counter
/// (threshold lowered to 4 to keep the test short), healthy TEC/REC stay below 96.
#[test]
fn slow_bit_flipping_uplink_isolated_by_lifetime_counter() {
    let cfg = canstar_hub::config::HubConfig { life_threshold: 4, ..hub_cfg(3, 0) };
    let (st, iso, tec, rec) = bit_flipping_uplink(&cfg, 26, 1201, 40, 40_000);
    let s = &st.rtl().stats;
    eprintln!("flips every 1201 bits: isolated after {iso:.0} bits, blames {}, max bic {:?}, healthy tec {tec} rec {rec}", s.blames, s.max_bic);
    assert!(iso.is_finite(), "isolated");
    assert!(s.max_bic[0] <= 16, "the decaying counter alone would not isolate: {:?}", s.max_bic);
    assert_eq!(st.rtl().isolated(), vec![true, false, false]);
    assert!(tec < 96 && rec < 96);
    // without the lifetime counter (threshold at its maximum) the glitch counter (§5.8)
    // isolates the same uplink: each half-bit inversion is a glitch, and one per 1201
    // bits comes faster than one per 16 good frames decays
    let cfg = canstar_hub::config::HubConfig { life_threshold: 127, ..hub_cfg(3, 0) };
    let (st, iso, _, _) = bit_flipping_uplink(&cfg, 26, 1201, 40, 9_000);
    let s = &st.rtl().stats;
    assert!(iso.is_finite(), "isolated by the glitch counter: {s:?}");
    assert!(s.max_bic[0] <= 16 && s.glitch_log.len() >= 3, "{s:?}");
    // with neither (glitch limit at its maximum, 4 inversions) it is not isolated
    let cfg = canstar_hub::config::HubConfig { life_threshold: 127, glitch_limit: 7, ..hub_cfg(3, 0) };
    let (st, iso, _, _) = bit_flipping_uplink(&cfg, 26, 1201, 40, 5_000);
    assert!(iso.is_infinite(), "decay alone isolates after {iso} bits? {:?}", st.rtl().stats);
}

/// §5.5: a port that never acknowledges (uplink stuck recessive) is reported silent
/// and not isolated; the others keep communicating.
#[test]
fn never_acknowledging_port_silent_not_isolated() {
    let cfg = hub_cfg(3, 0);
    let mut st = Star::new(&cfg, &[0.0, 0.0, 0.0], 27);
    st.ports.uplinks[2].set_fault(&mut st.sim, FaultMode::StuckRecessive);
    let nodes = st.nodes.clone();
    let sent = load(&mut st.sim, &nodes[..2], 6, 2700);
    assert!(st.run_until_drained(3000));
    assert!(st.rtl().stats.silent_at[2].is_some(), "{:?}", st.rtl().stats);
    assert_eq!(st.rtl().silent(), vec![false, false, true]);
    assert_eq!(st.rtl().isolated(), vec![false; 3]);
    assert_eq!(st.rtl().stats.blames, 0);
    assert!(received_in_order(st.node(0), &sent[1]) && received_in_order(st.node(1), &sent[0]));
}

/// §5.6: with reintegration (W = 4), a port isolated for a transient stuck-dominant
/// fault is re-enabled after 4 good frames once the fault is gone, and sends again.
#[test]
fn reintegration_after_transient_fault() {
    let cfg = canstar_hub::config::HubConfig { reintegration: Some(4), ..hub_cfg(3, 0) };
    let (mut st, _) = faulty_star(&cfg, 28, 30);
    let t_f = 300 * BIT;
    st.ports.uplinks[1].schedule_fault(&mut st.sim, t_f, FaultMode::StuckDominant);
    st.ports.uplinks[1].schedule_fault(&mut st.sim, t_f + 60 * BIT, FaultMode::None);
    st.sim.run_until(t_f);
    // node 1 stops sending (a transmitter on an isolated port sees bit errors on every
    // frame and ends bus-off, not acknowledging, so it could not be reintegrated); it
    // keeps receiving and acknowledging
    st.node_mut(1).withdraw();
    st.sim.run_until(t_f + 60 * BIT);
    assert!(st.rtl().isolated()[1], "isolated during the fault");
    let sent_before = st.node(1).sent().len();
    assert!(st.sim.run_until_cond(t_f + 2000 * BIT, |s| !s.get(st.hub).isolated()[1]), "reintegrated");
    let back = st.sim.now();
    eprintln!("reintegrated {:.0} bits after the fault ended", (back - t_f - 60 * BIT) as f64 / BIT as f64);
    for i in 0..3 {
        st.node_mut(1).request(Frame::std(0x001 + i, &[i as u8]));
    }
    st.sim.run_for(800 * BIT);
    assert!(st.node(1).sent().len() >= sent_before + 3, "node 1 sends again");
    assert_eq!(st.rtl().isolated(), vec![false; 3]);
}

// ---------------------------------------------------------------- A4: two hubs

/// A two-hub network under full load (nodes 0 and 2 transmit via hub 0, node 1 via
/// hub 1) with one fault applied at `t_f`; returns the network after `bits` bits.
fn dual_with_fault(seed: u64, bits: u64, fault: impl FnOnce(&mut Dual, u64)) -> (Dual, Vec<Vec<Frame>>, u64) {
    let cfg = hub_cfg(3, 2);
    let mut d = Dual::new(&cfg, &[0.0, 0.0, 0.0], seed);
    let tx = vec![d.a[0], d.b[1], d.a[2]];
    let sent = load(&mut d.sim, &tx, 60, seed + 500);
    let t_f = 250 * BIT;
    fault(&mut d, t_f);
    d.sim.run_until(t_f + bits * BIT);
    (d, sent, t_f)
}

fn assert_no_isolation_except(d: &Dual, ports: [Vec<bool>; 2], subs: [Vec<bool>; 2]) {
    for h in 0..2 {
        assert_eq!(d.rtl(h).isolated(), ports[h], "hub {h} ports, stats {:?}", d.rtl(h).stats);
        assert_eq!(d.rtl(h).sub_isolated(), subs[h], "hub {h} sublinks, stats {:?}", d.rtl(h).stats);
    }
}

/// Traffic goes on after the fault: every controller sees new frames (received, or
/// sent by itself: under full load the node with the lowest identifiers may win every
/// slot for a while and then receives nothing).
fn assert_traffic_goes_on(d: &mut Dual) {
    let seen = |d: &Dual| -> Vec<usize> { d.all().iter().map(|&h| d.sim.get(h).received().len() + d.sim.get(h).sent().len()).collect() };
    let before = seen(d);
    d.sim.run_for(600 * BIT);
    let after = seen(d);
    for (k, (b, a)) in before.iter().zip(&after).enumerate() {
        assert!(a > b, "controller {k} sees frames after the fault: {before:?} -> {after:?}");
    }
}

/// A4: sublink 0 from hub 0 to hub 1 stuck recessive: hub 1 isolates that sublink
/// (replica rule), nothing else is isolated.
#[test]
fn two_hubs_sublink_stuck_recessive() {
    let (mut d, _, t_f) = dual_with_fault(31, 800, |d, t| d.net.hubs[0].sub_out[0].schedule_fault(&mut d.sim, t, FaultMode::StuckRecessive));
    let at = d.rtl(1).stats.sub_isolated_at[0].expect("isolated");
    eprintln!("stuck recessive sublink: isolated after {:.0} bits", (at - t_f) as f64 / BIT as f64);
    // the replica rule's charges (`max_sub_rep`, reported by `canstar soak`): the faulty
    // replica reached the limit, the healthy one and hub 0's sublinks were never charged
    assert!(d.rtl(1).stats.max_sub_rep[0] >= hub_cfg(3, 2).replica_limit, "{:?}", d.rtl(1).stats.max_sub_rep);
    assert_eq!(d.rtl(1).stats.max_sub_rep[1], 0);
    assert_eq!(d.rtl(0).stats.max_sub_rep, vec![0, 0]);
    assert_no_isolation_except(&d, [vec![false; 3], vec![false; 3]], [vec![false, false], vec![true, false]]);
    assert_traffic_goes_on(&mut d);
}

/// A4: sublink 0 from hub 0 to hub 1 stuck dominant: hub 1 isolates it (dominant
/// run), hub 0 isolates nothing.
#[test]
fn two_hubs_sublink_stuck_dominant() {
    let (mut d, _, t_f) = dual_with_fault(32, 300, |d, t| d.net.hubs[0].sub_out[0].schedule_fault(&mut d.sim, t, FaultMode::StuckDominant));
    let at = d.rtl(1).stats.sub_isolated_at[0].expect("isolated");
    let bits = (at - t_f) as f64 / BIT as f64;
    eprintln!("stuck dominant sublink: isolated after {bits:.1} bits");
    assert!(bits <= (hub_cfg(3, 2).sub_dbc_threshold + 2) as f64);
    assert_no_isolation_except(&d, [vec![false; 3], vec![false; 3]], [vec![false, false], vec![true, false]]);
    assert_traffic_goes_on(&mut d);
}

/// A4: bit flips on sublink 0 from hub 1 to hub 0 (a half-bit inversion every 29 bits):
/// hub 0 isolates only that sublink.
#[test]
fn two_hubs_sublink_bit_flips() {
    let (mut d, _, t_f) = dual_with_fault(33, 3000, |d, t| {
        let out = d.net.hubs[1].sub_out[0].output;
        d.sim.add_flip_pattern(out, t, BIT / 2, 29 * BIT + BIT / 5, 200);
    });
    let at = d.rtl(0).stats.sub_isolated_at[0].expect("isolated");
    eprintln!("bit-flipping sublink: isolated after {:.0} bits, hub 0 stats {:?}", (at - t_f) as f64 / BIT as f64, d.rtl(0).stats);
    assert_no_isolation_except(&d, [vec![false; 3], vec![false; 3]], [vec![true, false], vec![false, false]]);
    assert_traffic_goes_on(&mut d);
}

/// A4: a faulty node port (stuck-dominant uplink of node 1's controller on hub 0): only
/// that port is isolated, no sublink on either hub, and the downlinks of both hubs agree.
#[test]
fn two_hubs_faulty_port_isolates_only_the_port() {
    for (seed, kind) in [(34u64, FaultMode::StuckDominant), (35, FaultMode::Invert)] {
        let (mut d, _, t_f) = dual_with_fault(seed, 1500, |d, t| {
            d.rtl_mut(0).record_samples();
            d.rtl_mut(1).record_samples();
            if kind == FaultMode::Invert {
                let out = d.net.hubs[0].uplinks[1].output;
                d.sim.add_flip_pattern(out, t, BIT / 2, 23 * BIT + BIT / 3, 200);
            } else {
                d.net.hubs[0].uplinks[1].schedule_fault(&mut d.sim, t, kind);
            }
        });
        let at = d.rtl(0).stats.isolated_at[1].expect("isolated");
        eprintln!("{kind:?} on port 1 of hub 0: isolated after {:.1} bits", (at - t_f) as f64 / BIT as f64);
        assert_no_isolation_except(&d, [vec![false, true, false], vec![false; 3]], [vec![false, false], vec![false, false]]);
        if kind == FaultMode::StuckDominant {
            // (a half-bit inversion at an arbitrary phase can end between the two hubs'
            // sample points, which lie one hub crossing apart: then the hubs legitimately
            // sample different levels, so the comparison is made for the stable fault)
            let (n, bad) = compare_downlinks(&d);
            assert!(bad.is_none() && n > 1000, "downlinks differ: {bad:?} after {n}");
        }
        assert_traffic_goes_on(&mut d);
    }
}

#[test]
#[ignore = "diagnostic"]
fn diag_collateral_blame() {
    let cfg = hub_cfg(3, 2);
    let mut d = Dual::new(&cfg, &[0.0, 0.0, 0.0], 41);
    let tx = vec![d.a[0], d.b[1], d.a[2]];
    let _ = load(&mut d.sim, &tx, 80, 4100);
    d.net.hubs[0].uplinks[2].schedule_fault(&mut d.sim, 600 * BIT, FaultMode::StuckDominant);
    d.sim.add_flip_pattern(d.net.hubs[0].uplinks[1].output, 1500 * BIT, BIT / 2, 23 * BIT + BIT / 3, 100);
    d.sim.run_until(4000 * BIT);
    for h in 0..2 {
        for b in &d.rtl(h).stats.blame_log {
            eprintln!("hub {h}: t {:.1} bits unit {} field {} pos {}", b.0 as f64 / BIT as f64, b.1, b.2, b.3);
        }
    }
    for (name, hd) in [("a0", d.a[0]), ("b1", d.b[1]), ("a1", d.a[1])] {
        for (t, e) in d.sim.get(hd).log() {
            let tb = *t as f64 / BIT as f64;
            if (2140.0..2240.0).contains(&tb) {
                eprintln!("{name} {tb:.1}: {e:?}");
            }
        }
        eprintln!("{name} tec {} rec {} state {}", d.sim.get(hd).tec(), d.sim.get(hd).rec(), d.sim.get(hd).state());
    }
}
