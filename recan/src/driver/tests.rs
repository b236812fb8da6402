//! Driver unit tests: reports injected into controllers that are never clocked.

use super::*;
use crate::spec::CtrlSpec;
use canstar_sim::ClockSpec;

const BIT: u64 = 1_085_000;
/// Later than any report at `t` is seen, and than a routine's K after it.
const AFTER: u64 = 10_000_000 + 5 * BIT;

fn ctrls() -> [Ctrl; 2] {
    let s = CtrlSpec::default();
    ["A", "B"].map(|n| Ctrl::new(n, &s, ClockSpec::new(33_920)))
}

/// Step `d` once its reports at `t` are seen and again once its routines' K has
/// passed, returning what it noticed.
fn step_after(d: &mut Driver, t: u64, c: &mut [Ctrl; 2]) -> Vec<Notice> {
    let [a, b] = c;
    let mut n = d.step(t + AFTER, &mut [a, b]);
    n.extend(d.step(t + AFTER + 20 * BIT, &mut [a, b]));
    n
}

fn delivered(n: &[Notice]) -> Vec<Frame> {
    n.iter().filter_map(|n| if let Notice::Deliver(f) = n { Some(f.clone()) } else { None }).collect()
}

/// The driver as a copy by B that never reached A leaves it (`copy_to_other_star`,
/// then success when B reported the copy sent): tx controller A, `copied` = (f, B).
fn after_unreceived_copy(f: &Frame) -> (Driver, [Ctrl; 2]) {
    let mut d = Driver::new(0, &DriverSpec::default(), BIT, 0, false);
    d.copied = Some((f.clone(), 1));
    (d, ctrls())
}

#[test]
fn the_nodes_own_frame_equal_to_an_earlier_copy_is_not_taken_for_the_copy() {
    let f = Frame::std(0x10, &[1]);
    let (mut d, mut c) = after_unreceived_copy(&f);
    // eight frames later the application sends the same frame; A sends it and B,
    // on the other star, receives it
    let [a, b] = &mut c;
    assert!(d.tx_request(f.clone(), 0, &mut [a, b]));
    let t = 500 * BIT;
    c[0].report(t, CtrlEvent::TxDone(f.clone()));
    c[1].report(t, CtrlEvent::Rx(f.clone()));
    let n = step_after(&mut d, t, &mut c);
    assert!(n.iter().any(|n| matches!(n, Notice::TxSuccess(_))), "{n:?}");
    assert!(delivered(&n).is_empty(), "{n:?}");
    assert!(!d.frame_managed, "B's reception of the node's own frame must clear FrameManaged");
    // so a frame of another node that only A receives is delivered, not swallowed
    let g = Frame::std(0x20, &[2]);
    let t = 700 * BIT;
    c[0].report(t, CtrlEvent::Rx(g.clone()));
    let n = step_after(&mut d, t, &mut c);
    assert_eq!(delivered(&n), vec![g]);
}

#[test]
fn the_copy_received_by_the_tx_controller_is_ignored_once() {
    let f = Frame::std(0x10, &[1]);
    let (mut d, mut c) = after_unreceived_copy(&f);
    // A receives B's copy: not delivered, FrameManaged untouched
    c[0].report(100 * BIT, CtrlEvent::Rx(f.clone()));
    let n = step_after(&mut d, 100 * BIT, &mut c);
    assert!(delivered(&n).is_empty() && !d.frame_managed, "{n:?}");
    assert_eq!(d.copied, None);
    // a frame equal to it later (another node's, by its identifier) is delivered
    let t = 300 * BIT;
    c[0].report(t, CtrlEvent::Rx(f.clone()));
    c[1].report(t, CtrlEvent::Rx(f.clone()));
    let n = step_after(&mut d, t, &mut c);
    assert_eq!(delivered(&n), vec![f]);
}

/// hub.md §5.30: A reports frame u sent, B never sees it, and u is reported sent on the
/// omission rule; then A is quarantined (its timer) with the next frame p unsent. B
/// sends u first, then p; the application hears of one success, p's.
#[test]
fn the_omission_rule_frame_is_sent_again_when_the_tx_controller_is_quarantined() {
    let (u, p) = (Frame::std(0x10, &[3]), Frame::std(0x10, &[4]));
    for resend in [true, false] {
        let spec = DriverSpec { resend_unconfirmed: resend, ..DriverSpec::default() };
        let mut d = Driver::new(0, &spec, BIT, 0, false);
        let mut c = ctrls();
        d.msg_tx_omi = spec.max_inconsists;
        let [a, b] = &mut c;
        assert!(d.tx_request(u.clone(), 0, &mut [a, b]));
        c[0].report(100 * BIT, CtrlEvent::TxDone(u.clone()));
        let n = step_after(&mut d, 100 * BIT, &mut c);
        assert!(matches!(n[..], [Notice::TxSuccess(_)]), "{n:?}");
        let [a, b] = &mut c;
        assert!(d.tx_request(p.clone(), 200 * BIT, &mut [a, b]));
        let [a, b] = &mut c;
        let n = d.step(200 * BIT + d.timeout_ps, &mut [a, b]);
        assert!(!d.active[0] && d.tx == Some(1), "{n:?}");
        if !resend {
            assert!(n.contains(&Notice::Rerequest) && c[1].pending() == Some(&p), "{n:?}");
            continue;
        }
        assert!(n.contains(&Notice::Resend) && c[1].pending() == Some(&u), "{n:?}");
        let t = 3000 * BIT;
        c[1].report(t, CtrlEvent::TxDone(u.clone()));
        let n = step_after(&mut d, t, &mut c);
        assert!(!n.iter().any(|n| matches!(n, Notice::TxSuccess(_))), "u's success is not the application's: {n:?}");
        assert_eq!(c[1].pending(), Some(&p));
        let t = 3200 * BIT;
        c[1].report(t, CtrlEvent::TxDone(p.clone()));
        let n = step_after(&mut d, t, &mut c);
        assert!(matches!(n[..], [Notice::TxSuccess(_)]), "{n:?}");
        assert_eq!(d.pending, None);
    }
}

/// As above, but A reported a transmit error in p's EOF before its quarantine: receivers may
/// have taken p, and u after p would be a counter going back; only p goes on B.
#[test]
fn no_frame_is_sent_again_after_a_transmit_error_past_the_crc() {
    let (u, p) = (Frame::std(0x10, &[3]), Frame::std(0x10, &[4]));
    for (field, again) in [(Field::Eof, false), (Field::AckSlot, false), (Field::Crc, true), (Field::Ident, true)] {
        let mut d = Driver::new(0, &DriverSpec::default(), BIT, 0, false);
        let mut c = ctrls();
        d.msg_tx_omi = d.spec.max_inconsists;
        let [a, b] = &mut c;
        assert!(d.tx_request(u.clone(), 0, &mut [a, b]));
        c[0].report(100 * BIT, CtrlEvent::TxDone(u.clone()));
        step_after(&mut d, 100 * BIT, &mut c);
        let [a, b] = &mut c;
        assert!(d.tx_request(p.clone(), 200 * BIT, &mut [a, b]));
        c[0].report(300 * BIT, CtrlEvent::Error { tx: true, field });
        step_after(&mut d, 300 * BIT, &mut c);
        let [a, b] = &mut c;
        let n = d.step(200 * BIT + d.timeout_ps, &mut [a, b]);
        assert_eq!(n.contains(&Notice::Resend), again, "{field:?}: {n:?}");
        assert_eq!(c[1].pending(), Some(if again { &u } else { &p }), "{field:?}");
    }
}

#[test]
fn requesting_the_copied_frame_again_forgets_the_copy() {
    let f = Frame::std(0x10, &[1]);
    let (mut d, mut c) = after_unreceived_copy(&f);
    let [a, b] = &mut c;
    assert!(d.tx_request(Frame::std(0x10, &[2]), 0, &mut [a, b]));
    assert!(d.copied.is_some(), "another frame leaves the copy");
    d.pending = None;
    let [a, b] = &mut c;
    assert!(d.tx_request(f, 0, &mut [a, b]));
    assert_eq!(d.copied, None);
}
