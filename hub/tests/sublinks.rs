//! Sublink judge units (hub.md §5.7, acceptance A4) with a modelled peer hub.
mod common;
use canstar_hub::frame_state::Field;
use canstar_hub::config::HubConfig;
use canstar_hub::{hub::HubCore, top::Hub};
use common::*;

fn traffic(frames: usize) -> Vec<Node> {
    let mut n: Vec<Node> = (0..3).map(|_| Node::default()).collect();
    for k in 0..frames {
        n[k % 3].queue.push_back(Frame::std(0x100 + 7 * k as u32, &[k as u8, 0x0f, 0xf0]));
    }
    n
}

fn recancentrate() -> HubConfig {
    HubConfig::default()
}

/// Runs the scenario, checks traffic completes and returns the net.
fn run<T: Dut>(sub: SublinkFn, frames: usize) -> Net<T> {
    let mut net = Net::<T>::new(&recancentrate(), traffic(frames));
    net.stim.sublink = sub;
    net.run_until_idle(60_000);
    let sent: usize = net.stim.nodes.iter().map(|n| n.sent).sum();
    assert_eq!(sent, frames, "all frames delivered");
    assert_eq!(net.isolated(), vec![false; 3], "no port isolated");
    net
}

fn healthy_peer_never_blamed<T: Dut>() {
    let net = run::<T>(mirror_peer(), 30);
    assert_eq!(net.sub_isolated(), vec![false, false]);
    assert_eq!(net.errors(), 0);
    assert!(net.max_sub_bic.iter().all(|&b| b == 0));
}

/// Replica rule: a stuck-at-recessive sublink is the one isolated (the baseline rule
/// would isolate its healthy, dominant replica). Node 1 is behind the peer (its uplink to
/// this hub silent, its level carried by the sublinks), so that in its frames the replicas
/// alone decide BT: where a port is dominant too, a disagreement is not recorded (hub.md
/// §5.18).
fn stuck_recessive_sublink_isolated_not_its_replica<T: Dut>() {
    for bad in [0usize, 1] {
        let frames = 12;
        let mut net = Net::<T>::new(&recancentrate(), traffic(frames));
        net.stim.up_faults[1] = Some(Box::new(|_, _, _| true));
        net.stim.sublink = Box::new(move |b, j, own, _| if j == bad && b > 50 { true } else { own.iter().all(|&p| p) });
        net.run_until_idle(60_000);
        let sent: usize = net.stim.nodes.iter().map(|n| n.sent).sum();
        assert_eq!(sent, frames, "all frames delivered");
        let mut expect = vec![false, false];
        expect[bad] = true;
        assert_eq!(net.sub_isolated(), expect);
        assert_eq!(net.errors(), 0, "a stuck-recessive replica does not disturb BT");
        assert!(net.hub.sub_rep()[bad] as u64 >= recancentrate().replica_limit);
        assert_eq!(net.isolated()[0] || net.isolated()[2], false, "no port with a node on it isolated");
    }
}

/// Stuck-at-dominant sublink: isolated (replica rule or dominant run), only that one.
fn stuck_dominant_sublink_isolated_alone<T: Dut>() {
    let start = 200;
    let mut net = Net::<T>::new(&recancentrate(), traffic(12));
    net.stim.sublink = Box::new(move |b, j, pins, _| if j == 1 && b >= start { false } else { pins.iter().all(|&p| p) });
    net.run(start);
    let mut at = None;
    for _ in 0..200 {
        net.step();
        if net.sub_isolated()[1] {
            at = Some(net.stim.bit);
            break;
        }
    }
    let at = at.expect("stuck-dominant sublink not isolated");
    let th = recancentrate().sub_dbc_threshold as usize;
    assert!(at - start <= th + 2, "isolated {} bits after the start (dominant run threshold {th})", at - start);
    net.run_until_idle(60_000);
    assert_eq!(net.sub_isolated(), vec![false, true]);
    assert_eq!(net.isolated(), vec![false; 3]);
    let sent: usize = net.stim.nodes.iter().map(|n| n.sent).sum();
    assert_eq!(sent, 12);
}

/// Dominant-run rule alone (one sublink, so no replica to compare with).
fn dominant_run_isolates_single_sublink<T: Dut>() {
    let cfg = HubConfig { sublinks: 1, ..Default::default() };
    let mut net = Net::<T>::new(&cfg, traffic(6));
    net.stim.sublink = Box::new(|b, _, pins, _| if (100..200).contains(&b) { false } else { pins.iter().all(|&p| p) });
    net.run(100);
    let mut at = None;
    for _ in 0..100 {
        net.step();
        if net.sub_isolated()[0] {
            at = Some(net.stim.bit);
            break;
        }
    }
    let at = at.expect("not isolated");
    // the run may have started up to 5 bits before the fault (dominant frame bits)
    let th = cfg.sub_dbc_threshold as usize;
    assert!((th - 6..=th + 2).contains(&(at - 100)), "isolated after {} bits", at - 100);
    assert!(net.hub.sub_dbc()[0] as usize >= th, "isolated by the dominant-run rule");
    // at most one first-flagger charge (hub.md §5.12): the stuck sublink was the dominant
    // contender when the monitor found the stuff error that its dominant run caused
    assert!(net.hub.sub_bic()[0] as usize <= 8, "sub bic {}", net.hub.sub_bic()[0]);
    assert_eq!(net.hub.sub_rep()[0] as usize, 0, "no replica rule with one sublink");
    net.run_until_idle(60_000);
    assert_eq!(net.isolated(), vec![false; 3]);
}

/// Bit flip (inversion) on one sublink: only that sublink is isolated.
fn inverted_sublink_isolated_alone<T: Dut>() {
    let net = run::<T>(Box::new(|b, j, pins, _| {
        let v = pins.iter().all(|&p| p);
        if j == 0 && b >= 150 {
            !v
        } else {
            v
        }
    }), 12);
    assert_eq!(net.sub_isolated(), vec![true, false]);
}

/// Unjustified dominant bits from the whole interlink (both replicas dominant in the
/// CRC delimiter of every frame): blamed +8 per episode, isolated at the sublink
/// threshold (9 episodes = 72 with the default threshold, hub.md §5.3), both replicas;
/// ports never blamed.
fn unjustified_dominant_on_interlink_isolates_both_at_sublink_threshold<T: Dut>() {
    let mut net = Net::<T>::new(&recancentrate(), traffic(40));
    net.stim.sublink = Box::new(|_, _, pins, t| {
        let (f, _) = t.classify(true);
        if f == Field::CrcDelim {
            false
        } else {
            pins.iter().all(|&p| p)
        }
    });
    let mut episodes_at_isolation = None;
    for _ in 0..60_000 {
        net.step();
        if net.sub_isolated().iter().any(|&x| x) && episodes_at_isolation.is_none() {
            episodes_at_isolation = Some(net.blames());
            break;
        }
    }
    assert_eq!(episodes_at_isolation, Some(recancentrate().sub_bic_threshold as usize));
    assert_eq!(net.sub_isolated(), vec![true, true]);
    assert_eq!(net.max_bic, vec![0, 0, 0], "ports not blamed");
    net.run_until_idle(60_000);
    assert_eq!(net.isolated(), vec![false; 3]);
    assert_eq!(net.stim.nodes.iter().map(|n| n.sent).sum::<usize>(), 40);
}

/// The peer turns one recessive data bit dominant in some frames (both replicas, as a
/// contender: the peer carries the transmitter's bits too). The transmitter sees a bit
/// error and flags: the hub starts its error episode there and does not blame the
/// transmitter's flag; no port is blamed.
fn transmitter_bit_error_from_peer_not_blamed_on_port<T: Dut>() {
    let mut flips = 0;
    let net = run::<T>(
        Box::new(move |_, j, pins, t| {
            let (f, pos) = t.classify(true);
            let v = pins.iter().all(|&p| p);
            if f == Field::Data && pos == 6 && v && flips < 6 {
                if j == 1 {
                    flips += 1;
                }
                return false;
            }
            v
        }),
        12,
    );
    assert!(net.errors() >= 1);
    assert_eq!(net.max_bic, vec![0, 0, 0], "no port blamed");
}

macro_rules! both {
    ($($name:ident),*) => {
        mod core_with_reference_tracker {
            $( #[test] fn $name() { super::$name::<super::HubCore>() } )*
        }
        mod hub_with_controller_monitor {
            $( #[test] fn $name() { super::$name::<super::Hub>() } )*
        }
    };
}

both!(transmitter_bit_error_from_peer_not_blamed_on_port, healthy_peer_never_blamed, stuck_recessive_sublink_isolated_not_its_replica, stuck_dominant_sublink_isolated_alone, dominant_run_isolates_single_sublink, inverted_sublink_isolated_alone, unjustified_dominant_on_interlink_isolates_both_at_sublink_threshold);
