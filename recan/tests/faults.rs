//! Faults beyond the published scenarios (recancentrate.md §6): controller crash
//! (caught by the transmission timer), a stuck sublink, a whole faulty hub, a
//! bit-flipping uplink.
use canstar_recan::{
    run, CtrlRef, Dir, FaultKind, FaultSpec, FaultTarget, Isolated, NetworkSpec, RunResult, RunSpec, StartField,
};

fn go(faults: Vec<FaultSpec>, frames: u32, edit: impl FnOnce(&mut NetworkSpec)) -> RunResult {
    let mut net = NetworkSpec::fast();
    edit(&mut net);
    let mut spec = RunSpec::new(net, 7, frames);
    spec.faults = faults;
    spec.quiet_frames = Some(5);
    spec.trace = true;
    let r = run(&spec);
    eprintln!(
        "fault {:?} at {:?}; isolated {:?}; quarantined {:?} {:?}; tx {:?}; retx {} rereq {}; worst healthy {}; delivered {:?}; failures {:?}",
        r.fault_resolved, r.fault_start_ps, r.isolated, r.quarantined, r.quarantine_reasons, r.tx_ctrl, r.max_retransmissions,
        r.rerequests, r.worst_healthy_tec_rec, r.delivered_per_node, r.failures
    );
    if !r.ok {
        for l in &r.trace {
            eprintln!("{l}");
        }
    }
    r
}

#[test]
fn crashed_tx_controller_is_caught_by_the_transmission_timer() {
    let crash = FaultSpec::new(
        FaultTarget::Crash { node: 1, ctrl: CtrlRef::Tx },
        FaultKind::Sar,
        FaultSpec::at_field(StartField::Data, 2),
    );
    // a shorter timer than the prototype's 2.2 ms keeps the test short
    let r = go(vec![crash], 30, |n| n.driver.tx_timeout_ticks = 0x2000);
    assert!(r.ok, "{:?}", r.failures);
    assert_eq!(r.quarantined.len(), 1);
    assert_eq!((r.quarantined[0].0, r.quarantined[0].1), (1, 0));
    assert_eq!(r.quarantine_reasons, vec!["timer".to_string()]);
    assert_eq!(r.tx_ctrl[1], Some(1));
    assert_eq!(r.rerequests, 1, "the frame the crashed controller never sent is requested on B");
    assert!(r.isolated.is_empty());
}

#[test]
fn stuck_dominant_sublink_is_isolated_by_the_receiving_hub_only() {
    let f = FaultSpec::new(
        FaultTarget::Sublink { interlink: 0, from_hub: 0 },
        FaultKind::Sad,
        FaultSpec::at_field(StartField::Crc, 2),
    );
    let r = go(vec![f], 20, |_| {});
    assert!(r.ok, "{:?}", r.failures);
    let iso: Vec<Isolated> = r.isolated.iter().map(|i| i.what).collect();
    assert_eq!(iso, vec![Isolated::Sublink { hub: 1, sublink: 0 }]);
    assert!(r.quarantined.is_empty());
    assert!(r.worst_healthy_tec_rec < 96);
}

#[test]
fn hub_with_stuck_dominant_output_is_cut_off_and_nodes_continue_on_the_other_hub() {
    let f = FaultSpec::new(FaultTarget::Hub { hub: 1 }, FaultKind::Sad, FaultSpec::at_field(StartField::Data, 2));
    let r = go(vec![f], 25, |_| {});
    let iso: Vec<Isolated> = r.isolated.iter().map(|i| i.what).collect();
    assert!(iso.contains(&Isolated::Sublink { hub: 0, sublink: 0 }) && iso.contains(&Isolated::Sublink { hub: 0, sublink: 1 }), "{iso:?}");
    assert!(!iso.iter().any(|i| matches!(i, Isolated::Port { hub: 0, .. })), "hub 0 isolates none of its ports: {iso:?}");
    // every B controller (on hub 1) sees a stuck bus and is quarantined; A stays tx
    let mut q: Vec<(usize, usize)> = r.quarantined.iter().map(|&(n, c, _)| (n, c)).collect();
    q.sort();
    assert_eq!(q, vec![(0, 1), (1, 1), (2, 1)]);
    assert_eq!(r.tx_ctrl, vec![Some(0), Some(0), Some(0)]);
    assert!(r.lost.is_empty(), "{:?}", r.lost);
    assert!(r.ok, "{:?}", r.failures);
    assert!(r.delivered >= 7, "{:?}", r.delivered_per_node);
}

#[test]
fn bit_flipping_receiver_uplink_is_isolated_before_any_healthy_controller_reaches_96() {
    // one flipped bit every 23 bit times on the receiver's controller A uplink
    let f = FaultSpec::new(
        FaultTarget::Link { node: 2, ctrl: CtrlRef::A, dir: Dir::Up },
        FaultKind::BitFlip { every_bits: 23.0, width_ns: 1085.0, offset_ns: 0.0 },
        FaultSpec::at_field(StartField::Ident, 2),
    );
    let r = go(vec![f], 40, |_| {});
    assert!(r.ok, "{:?}", r.failures);
    let iso: Vec<Isolated> = r.isolated.iter().map(|i| i.what).collect();
    assert_eq!(iso, vec![Isolated::Port { hub: 0, port: 2 }]);
    assert!(r.worst_healthy_tec_rec < 96, "{}", r.worst_healthy_tec_rec);
}

#[test]
fn broken_interlink_costs_no_frame_while_the_other_interlink_works() {
    let f = FaultSpec::new(FaultTarget::Interlink { interlink: 1 }, FaultKind::Sar, FaultSpec::at_field(StartField::Dlc, 2));
    let r = go(vec![f], 10, |_| {});
    assert!(r.ok, "{:?}", r.failures);
    // the hubs may isolate the dead interlink's sublinks, nothing else
    assert!(
        r.isolated.iter().all(|i| matches!(i.what, Isolated::Sublink { sublink: 1, .. })),
        "{:?}",
        r.isolated
    );
    assert!(r.quarantined.is_empty());
    assert_eq!(r.healthy_errors_after_fault, 0);
    assert_eq!(r.max_retransmissions, 0);
}
