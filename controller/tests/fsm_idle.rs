//! The idle program (conformance-tests.md §9) on the bit-level harness:
//! integration, bus idle, bus-off and recovery of a single node.
mod common;
use canstar_controller::frame::Frame;
use canstar_controller::fsm::*;
use common::*;

fn pos(b: &Bus) -> u64 {
    b.nodes[0].pos.val().index() as u64
}

#[test]
fn idle_program() {
    let (d, r) = (Ovr::StuckD, Ovr::StuckR);
    let mut b = Bus::new(1);
    // idle_1: D at Wait_For_Bus_Idle 9: the count restarts
    b.force_at(0, Field::WaitIdle, 9, d, 1);
    assert_eq!((b.field(0), pos(&b)), (Field::WaitIdle, 1));
    // idle_2: D at Wait_For_Bus_Idle 11: restarts again; 11 R -> Bus_Idle
    b.force_at(0, Field::WaitIdle, 11, d, 1);
    assert_eq!((b.field(0), pos(&b)), (Field::WaitIdle, 1));
    b.run(10);
    assert_eq!(b.field(0), Field::WaitIdle);
    b.step();
    assert_eq!((b.field(0), b.state(0)), (Field::Idle, 0));
    // idle_3: D at Bus_Idle 2: SOF, receiver, stuff error at the 6th bit after it
    b.force_at(0, Field::Idle, 2, d, 1);
    assert!(b.last(0).has(EV_SOF));
    let s = b.bit;
    b.run_until(10, |b| b.nodes[0].error.val());
    let x = b.last(0).clone();
    assert!(x.has(EV_STUFF_ERR) && x.has(EV_AEF) && x.stuff && x.bit == s + 5, "{x:?}");
    assert_eq!(b.rec(0), 1);
    // idle_4: request; D at Intermission 3: taken as SOF, N1 transmits from Identifier 1
    b.request(0, &Frame::std(0x1F0, &[0x42])); // ID 2 dominant (idle_6)
    b.force_at(0, Field::Inter, 3, d, 1);
    assert!(b.last(0).has(EV_SOF));
    assert!(b.nodes[0].role.val());
    assert_eq!((b.field(0), pos(&b)), (Field::Ident, 1));
    // idle_5: no ACK: ACK_ERR, AEF, +8; R while sending AEFs until TEC >= 128
    b.run_until(200, |b| b.nodes[0].error.val());
    assert!(b.last(0).has(EV_ACK_ERR) && b.last(0).has(EV_AEF));
    assert_eq!(b.tec(0), 8);
    b.step();
    b.ovr[0] = r;
    b.run_until(100, |b| b.tec(0) >= 128);
    b.ovr[0] = Ovr::None;
    assert_eq!(b.tec(0), 128);
    assert!(b.last(0).has(EV_AEF), "the last flag is still active");
    b.run_until(100, |b| b.field(0) == Field::Sof);
    let susp = b.log[0].iter().rev().take(30).filter(|x| x.field == Field::Suspend).count();
    assert_eq!(susp, 8, "suspend before the retry");
    // the retries end in ACK errors with passive flags and exception 1
    b.run_until(200, |b| b.nodes[0].error.val());
    assert!(b.last(0).has(EV_ACK_ERR) && b.last(0).has(EV_PEF));
    b.run_until(30, |b| b.field(0) == Field::ErrDel);
    assert_eq!(b.tec(0), 128);
    // idle_6: R at Identifier 2 (dominant): BIT_ERR, PEF, +8
    b.force_at(0, Field::Ident, 2, r, 1);
    assert!(b.last(0).has(EV_BIT_ERR) && b.last(0).has(EV_PEF));
    assert_eq!(b.tec(0), 136);
    // idle_7: R held: every SOF is a bit error, +8 each, until bus-off
    b.ovr[0] = r;
    let mut last = b.tec(0);
    b.run_until(5000, |b| {
        b.state(0) == 2 || {
            let t = b.tec(0);
            assert!(t == last || t == last + 8, "tec {last} -> {t}");
            last = t;
            false
        }
    });
    assert_eq!(b.tec(0), 256);
    assert!(b.log[0].iter().rev().take(40).filter(|x| x.has(EV_BIT_ERR)).all(|x| x.field == Field::Sof));
    // idle_8: withdraw, release: runs of 11 R are counted
    b.withdraw(0);
    b.ovr[0] = Ovr::None;
    b.step();
    assert_eq!(b.field(0), Field::BusOff);
    let runs = |b: &Bus| b.nodes[0].runs.val().index();
    // idle_9: D at run bit 9: restarts
    b.force_at(0, Field::BusOff, 9, d, 1);
    assert_eq!((runs(&b), pos(&b)), (0, 1));
    // idle_10: D at run bit 11: restarts, not complete
    b.force_at(0, Field::BusOff, 11, d, 1);
    assert_eq!((runs(&b), pos(&b)), (0, 1));
    // idle_11: one run completes, D at bit 1 of the next: completed stays 1
    b.run(11);
    assert_eq!(runs(&b), 1);
    b.force_at(0, Field::BusOff, 1, d, 1);
    assert_eq!(runs(&b), 1);
    // idle_12: D at bit 10 of the run after 126 more completed runs
    b.run(126 * 11);
    assert_eq!(runs(&b), 127);
    b.force_at(0, Field::BusOff, 10, d, 1);
    assert_eq!((runs(&b), b.state(0)), (127, 2));
    b.run(10);
    assert_eq!(b.state(0), 2);
    b.step();
    assert!(b.last(0).has(EV_RECOVERED));
    assert_eq!((b.field(0), b.tec(0), b.rec(0), b.state(0)), (Field::Idle, 0, 0, 0));
    // idle_13: D at Bus_Idle 12: SOF, receiver, stuff error, REC 1
    b.force_at(0, Field::Idle, 12, d, 1);
    assert!(b.last(0).has(EV_SOF));
    b.run_until(10, |b| b.nodes[0].error.val());
    assert!(b.last(0).has(EV_STUFF_ERR) && b.last(0).has(EV_AEF));
    assert_eq!(b.rec(0), 1);
}
