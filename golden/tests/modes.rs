//! Host options (listen-only, self-test, single-shot, reset hold) and request status.

mod util;
use canstar_golden::{Config, FaultState, Field, GoldenBus, GoldenNode, ReqStatus, Role, RxOverride};
use util::*;

fn bus_with(cfgs: &[Config]) -> GoldenBus {
    let mut b = GoldenBus::with_nodes(cfgs.iter().map(|&c| GoldenNode::new(c)).collect());
    assert!(b.run_to_idle(20));
    b
}

/// Listen-only: receives and delivers, never drives `D` (no ACK), counters unchanged.
#[test]
fn listen_only_delivers_but_never_drives_dominant() {
    let lo = Config { listen_only: true, ..Default::default() };
    let mut b = bus_with(&[Config::default(), Config::default(), lo]);
    let f = std1(0x321);
    b.nodes[0].request(f.clone());
    b.nodes[2].request(std1(0x001)); // never sent by a listen-only node
    run_to_tx_ok(&mut b, 0, 300);
    assert!(b.run_to_idle(20));
    assert_eq!(delivered(&b, 2, 0), vec![f.clone()]);
    assert!(b.history[2].iter().all(|o| o.drove));
    // Alone with the transmitter: no ACK from the listen-only node.
    let mut b = bus_with(&[Config::default(), lo]);
    b.nodes[0].request(f);
    let o = b.run_until(300, |o| o[0].has("ACK_ERR")).unwrap();
    assert_eq!(o[0].tec, 8);
    b.run(30);
    assert_eq!((b.nodes[1].tec(), b.nodes[1].rec()), (0, 0));
}

/// Self-test: a lone node completes its frame without acknowledgement.
#[test]
fn self_test_needs_no_ack() {
    let mut b = bus_with(&[Config { self_test: true, ..Default::default() }]);
    b.nodes[0].request(std1(0x55));
    run_to_tx_ok(&mut b, 0, 300);
    assert_eq!(b.nodes[0].tec(), 0);
    assert_eq!(b.nodes[0].req_status(), ReqStatus::Done);
    assert!(!b.nodes[0].pending());
}

/// Single-shot: an ACK error ends the request (status error), no retry.
#[test]
fn single_shot_no_retry_after_error() {
    let mut b = bus_with(&[Config { single_shot: true, ..Default::default() }]);
    b.nodes[0].request(std1(0x55));
    b.run_until(300, |o| o[0].has("ACK_ERR")).unwrap();
    b.run(300);
    assert_eq!(count(&b, 0, 0, "SOF"), 1);
    assert_eq!(b.nodes[0].tec(), 8);
    assert_eq!(b.nodes[0].req_status(), ReqStatus::Error);
}

/// Automatic retry after a lost arbitration; withdraw during an attempt lets it finish and
/// stops retries; REQ records: pending -> transmitting -> pending (lost) -> transmitting -> done.
#[test]
fn retry_after_arbitration_loss_and_withdraw_semantics() {
    let mut b = idle_bus(2);
    b.nodes[0].request(std1(0x200));
    b.nodes[1].request(std1(0x100));
    run_to_tx_ok(&mut b, 1, 300);
    run_to_tx_ok(&mut b, 0, 300);
    let reqs: Vec<ReqStatus> = b.history[0].iter().flat_map(|o| o.req.iter().copied()).collect();
    assert_eq!(reqs, vec![ReqStatus::Pending, ReqStatus::Transmitting, ReqStatus::Pending, ReqStatus::Transmitting, ReqStatus::Done]);
    // withdraw during an attempt that will fail (no ACK: N2 stuck recessive)
    b.overrides[1] = RxOverride::StuckRecessive;
    b.nodes[0].request(std1(0x300));
    b.run(5);
    b.nodes[0].withdraw();
    let s = b.bit;
    b.run(400);
    assert_eq!(count(&b, 0, s, "ACK_ERR"), 1, "the running attempt finishes, no retry");
    assert_eq!(b.nodes[0].req_status(), ReqStatus::Error);
}

/// Holding reset: FIELD Reset, TX recessive, counters cleared; release -> integration.
#[test]
fn hold_reset_then_release_integrates() {
    let mut b = idle_bus(2);
    b.overrides[1] = RxOverride::StuckRecessive;
    b.nodes[0].request(std1(0x55));
    b.run_until(300, |o| o[0].has("ACK_ERR")).unwrap();
    assert_eq!(b.nodes[0].tec(), 8);
    b.nodes[0].hold_reset(true);
    let r = b.force(0, RxOverride::None, 5);
    assert!(r.iter().all(|o| o[0].label.field == Field::Reset && o[0].drove && o[0].tec == 0));
    assert_eq!(b.nodes[0].label().pos, 6);
    b.nodes[0].hold_reset(false);
    assert!(b.nodes[0].integrating());
    b.run(11);
    assert_eq!(b.nodes[0].label().field, Field::BusIdle);
    assert_eq!(b.nodes[0].state(), FaultState::ErrorActive);
    assert!(!b.nodes[0].pending(), "reset drops the request");
}

/// hs_en (can-protocol.md §3.3): set in idle-type states, from Intermission 3 and through an own SOF,
/// cleared once the SOF has been sampled.
#[test]
fn hs_en_follows_section_3_3() {
    let mut b = GoldenBus::new(2);
    assert!(b.nodes[0].hs_en(), "Wait_For_Bus_Idle");
    assert!(b.run_to_idle(20));
    assert!(b.nodes[0].hs_en(), "Bus_Idle");
    b.nodes[0].request(std1(0x55));
    b.step();
    assert_eq!(b.nodes[0].label().field, Field::StartOfFrame);
    assert!(b.nodes[0].hs_en(), "own SOF not yet sampled");
    b.step();
    assert!(!b.nodes[0].hs_en() && !b.nodes[1].hs_en(), "SOF sampled");
    assert!(b.run_to(0, Role::Tx, Field::Intermission, 2, false, 200));
    assert!(!b.nodes[0].hs_en());
    b.step();
    assert!(b.nodes[0].hs_en(), "from the sample point of Intermission 2 on");
}
