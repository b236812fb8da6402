//! The ISO 16845 lower tester on the controller RTL (`canstar_verify::iso`):
//! each capability of GitHub issue #17 item 1 shown on the IUT, with
//! assertions that fail when the capability does not work.

use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;
use canstar_hdl::timing::BtlConfig;
use canstar_verify::iso::*;
use canstar_verify::node::NodeConfig;

const T: BtlConfig = BtlConfig::T10_6_4;
const CLK: u64 = 100_000;

fn iut() -> NodeConfig {
    NodeConfig::named("iut")
}

/// 0x078 = 0000 1111 000: a recessive stuff bit after Identifier 4, a
/// dominant one after Identifier 8.
fn stuffy() -> Frame {
    Frame::std(0x078, &[0x5A])
}

#[test]
fn a_frame_from_the_lt_is_received_and_acknowledged() {
    let mut lb = LtBench::new(vec![iut()]);
    lb.begin_step("rx");
    let f = Frame::std(0x123, &[1, 2, 3]);
    let mut p = Plan::frame(T, &f, BuildOptions::default());
    p.push_recessive(3);
    lb.play_and_run(&p);
    lb.run_idle(20).unwrap();
    let r = lb.end_step();
    r.check_expects().unwrap();
    let ack = p.find(Field::AckSlot, 1, false).unwrap();
    assert_eq!(r.bus_at(0, ack), Some(false), "the bus is dominant in the ACK slot");
    assert_eq!(r.iut_tx_at(0, ack - 1), Some(true), "no dominant in the CRC delimiter");
    assert_eq!(r.iut_tx_at(0, ack + 1), Some(true), "no dominant in the ACK delimiter");
    assert_eq!(lb.b.node(0).received(), vec![f]);
    assert_eq!(r.iut_events(EV_RX_OK).len(), 1);
    assert!(r.iut().iter().all(|b| !b.has(EV_AEF)), "no error flag:{}", r.dump(0));
    // the per-TQ bus string starts with the SOF's 10 dominant TQ
    assert!(r.bus_string().starts_with("0000000000"), "{}", &r.bus_string()[..40]);
    // an expectation that does not hold is reported
    let mut wrong = r.clone();
    wrong.plays[0].plan.expect(ack + 1, false, "made-up");
    assert!(wrong.check_expects().unwrap_err().contains("made-up"));
}

/// Bit `x` recessive followed by a dominant bit, in the data field.
fn rd_edge_in_data(p: &Plan) -> usize {
    (0..p.bits.len() - 1)
        .find(|&i| p.bits[i].level && !p.bits[i + 1].level && p.bits[i].label.is_some_and(|l| l.field == Field::Data && !l.stuff) && p.bits[i + 1].label.is_some_and(|l| !l.stuff))
        .unwrap()
}

/// Time between the IUT's sample points of plan bits `x` and `x + 1` (ps).
fn sample_gap(r: &StepRecord, p: &Plan, x: usize) -> u64 {
    let lab = |i: usize| p.bits[i].label.unwrap();
    let find = |l: Label| r.iut().iter().position(|b| b.field == l.field && b.pos == l.pos && b.stuff == l.stuff).unwrap();
    let (a, b) = (find(lab(x)), find(lab(x + 1)));
    assert_eq!(b, a + 1, "consecutive bits");
    r.iut()[b].t - r.iut()[a].t
}

#[test]
fn a_lengthened_or_shortened_bit_resynchronises_the_iut_by_min_k_sjw() {
    // T10/6/2: SJW 2 < PH1 and PH2, so the limit shows
    let cfg = iut().timing(1, 1, 4, 2);
    let t = cfg.timing;
    let f = Frame::std(0x2A5, &[0x3C, 0xA5]);
    for (k, longer) in [(0, true), (1, true), (2, true), (3, true), (4, true), (1, false), (2, false), (3, false), (4, false)] {
        let mut lb = LtBench::new(vec![cfg.clone()]);
        lb.begin_step("resync");
        let mut p = Plan::frame(t, &f, BuildOptions::default());
        let x = rd_edge_in_data(&p);
        if longer {
            p.lengthen(x, k);
        } else {
            p.shorten(x, k);
        }
        p.push_recessive(3);
        lb.play_and_run(&p);
        lb.run_idle(20).unwrap();
        let r = lb.end_step();
        let gap = sample_gap(&r, &p, x) / CLK;
        let m = k.min(t.sjw) as u64;
        let want = if longer { 10 + m } else { 10 - m };
        assert_eq!(gap, want, "bit {x} {} by {k} TQ: sample points {gap} TQ apart, expected {want}", if longer { "lengthened" } else { "shortened" });
        assert_eq!(lb.b.node(0).received(), vec![f.clone()], "k {k}");
    }
}

/// The IUT transmits `f`; the LT disturbs Identifier bit `pos` (dominant)
/// with a recessive glitch of `w` TQ at `q` TQ, and acknowledges.
fn tx_glitch(q: u32, w: u32) -> (StepRecord, LtBench) {
    let mut lb = LtBench::new(vec![iut()]);
    lb.begin_step("tx glitch");
    let f = stuffy();
    lb.b.node_mut(0).request(f);
    lb.wait(Trigger::at(Field::Ident, 2), 30).unwrap();
    let mut p = Plan::raw(T, &[true]);
    p.glitch(At::tq(0, q), Span::Tq(w), true);
    lb.play_and_run(&p);
    if lb.wait(Trigger::at(Field::AckSlot, 1), 120).is_ok() {
        lb.play_and_run(&Plan::raw(T, &[false]));
    }
    lb.run_idle(60).unwrap();
    lb.b.node_mut(0).withdraw();
    (lb.end_step(), lb)
}

#[test]
fn a_glitch_away_from_the_sample_point_is_ignored_one_over_it_is_a_bit_error() {
    let (r, lb) = tx_glitch(1, 3);
    assert!(r.iut_events(EV_BIT_ERR).is_empty(), "glitch in TQ 1..3:{}", r.dump(0));
    assert_eq!(lb.b.node(0).sent().len(), 1);
    assert_eq!(lb.b.tec(0), 0);
    let (r, lb) = tx_glitch(7, 2);
    assert!(r.iut_events(EV_BIT_ERR).is_empty(), "glitch in TQ 7..8 (after the sample point):{}", r.dump(0));
    assert_eq!(lb.b.node(0).sent().len(), 1);
    let (r, lb) = tx_glitch(5, 2);
    let e = r.iut_events(EV_BIT_ERR);
    assert_eq!(e.len(), 1, "glitch over the sample point:{}", r.dump(0));
    assert_eq!((e[0].field, e[0].pos), (Field::Ident, 2));
    assert!(e[0].has(EV_AEF) || r.iut_events(EV_AEF).len() == 1);
    assert_eq!(lb.b.node(0).sent().len(), 1, "the retransmission succeeds");
    assert_eq!(lb.b.tec(0), 7, "+8 for the bit error, -1 for the successful retransmission");
    // one-clock glitches at every clock of the bit: exactly one clock is the
    // instant the IUT samples, the last clock of TQ SP-1
    let mut hits = vec![];
    for c in 0..T.ntq() {
        let mut lb = LtBench::new(vec![iut()]);
        lb.begin_step("1-clock glitch");
        lb.b.node_mut(0).request(stuffy());
        lb.wait(Trigger::at(Field::Ident, 2), 30).unwrap();
        let mut p = Plan::raw(T, &[true]);
        p.glitch(At { bit: 0, tq: 0, clocks: c }, Span::Clocks(1), true);
        lb.play_and_run(&p);
        lb.b.node_mut(0).withdraw();
        lb.run_bits(3);
        if !lb.end_step().iut_events(EV_BIT_ERR).is_empty() {
            hits.push(c);
        }
    }
    assert_eq!(hits, vec![T.sp() - 1], "clocks whose glitch the IUT samples");
}

/// The LT sends [`stuffy`] with a recessive glitch of `w` TQ at `q` TQ in
/// the dominant stuff bit after Identifier 8, to the IUT as receiver.
fn rx_glitch(q: u32, w: u32, cut: bool) -> (StepRecord, LtBench, Plan) {
    let mut lb = LtBench::new(vec![iut()]);
    lb.begin_step("rx glitch");
    let f = stuffy();
    let mut p = Plan::frame(T, &f, BuildOptions::default());
    let s = p.find(Field::Ident, 8, true).unwrap();
    assert!(!p.bits[s].level);
    p.glitch(At::tq(s, q), Span::Tq(w), true);
    if cut {
        // the LT stops after the stuff bit: no dominant bit disturbs the IUT's flag
        p.truncate(s + 1).push_recessive(25);
    } else {
        p.push_recessive(3);
    }
    lb.play_and_run(&p);
    lb.run_idle(40).unwrap();
    (lb.end_step(), lb, p)
}

#[test]
fn a_glitch_in_a_receivers_stuff_bit_is_a_stuff_error_only_over_the_sample_point() {
    let (r, lb, _) = rx_glitch(1, 2, false);
    assert!(r.iut_events(EV_STUFF_ERR).is_empty(), "{}", r.dump(0));
    assert_eq!(lb.b.node(0).received(), vec![stuffy()]);
    let (r, lb, p) = rx_glitch(5, 2, true);
    let e = r.iut_events(EV_STUFF_ERR);
    assert_eq!(e.len(), 1, "{}", r.dump(0));
    assert_eq!((e[0].field, e[0].pos, e[0].stuff), (Field::Ident, 8, true));
    assert!(lb.b.node(0).received().is_empty());
    assert_eq!(lb.b.rec(0), 1);
    // the active error flag starts in the bit after the stuff bit
    let s = p.find(Field::Ident, 8, true).unwrap();
    assert_eq!(r.iut_tx_at(0, s), Some(true), "a receiver drives R in the stuff bit");
    for k in 1..=6 {
        assert_eq!(r.iut_tx_at(0, s + k), Some(false), "active error flag bit {k}");
    }
    assert_eq!(r.iut_tx_at(0, s + 7), Some(true), "the flag has 6 bits");
}

#[test]
fn a_receive_path_disturbance_changes_only_that_node() {
    // N2 error-passive (TEC 128), so that its flag does not show on the bus
    let mut lb = LtBench::new(vec![iut(), NodeConfig::named("n2")]);
    lb.begin_step("rx path");
    lb.preset(1, 128, 0);
    assert_eq!(lb.b.state(1), 1);
    let f = stuffy();
    let mut p = Plan::frame(T, &f, BuildOptions::default());
    let s = p.find(Field::Ident, 8, true).unwrap();
    p.disturb(Disturbance { at: At::tq(s, 0), span: Span::Bits(1), action: Action::Force(true), target: Target::Node(1) });
    p.push_recessive(3);
    lb.play_and_run(&p);
    lb.run_idle(40).unwrap();
    let r = lb.end_step();
    let at = |node: usize| *r.bits[node].iter().find(|b| b.field == Field::Ident && b.pos == 8 && b.stuff).unwrap();
    let (a, b) = (at(0), at(1));
    assert!(!a.level && !a.has(EV_STUFF_ERR), "IUT: {a}");
    assert!(b.level && b.has(EV_STUFF_ERR) && b.has(EV_PEF), "N2: {b}");
    assert_eq!(lb.b.node(0).received(), vec![f]);
    assert!(lb.b.node(1).received().is_empty());
    assert_eq!((lb.b.rec(0), lb.b.rec(1)), (0, 1));
    r.check_expects().unwrap();
}

#[test]
fn a_bus_disturbance_changes_every_node_and_overrides_the_wired_and() {
    let mut lb = LtBench::new(vec![iut(), NodeConfig::named("n2")]);
    lb.begin_step("bus");
    let f = stuffy();
    let mut p = Plan::frame(T, &f, BuildOptions::default());
    let s = p.find(Field::Ident, 8, true).unwrap();
    p.disturb(Disturbance { at: At::tq(s, 0), span: Span::Bits(1), action: Action::Force(true), target: Target::Bus });
    p.truncate(s + 1).push_recessive(25);
    lb.play_and_run(&p);
    lb.run_idle(40).unwrap();
    let r = lb.end_step();
    for node in 0..2 {
        let b = *r.bits[node].iter().find(|b| b.field == Field::Ident && b.pos == 8 && b.stuff).unwrap();
        assert!(b.level && b.has(EV_STUFF_ERR), "N{}: {b}", node + 1);
    }
    let mid = r.plan_time(0, p.sample_clock(s));
    let c = r.at(mid).unwrap();
    assert!(!c.wired && c.bus && c.iut_rx && !c.lt_tx, "wired AND dominant, every node reads recessive: {c:?}");
    assert_eq!((lb.b.rec(0), lb.b.rec(1)), (1, 1));
}

fn two_frames() -> (Plan, usize) {
    let mut p = Plan::frame(T, &Frame::std(0x111, &[1]), BuildOptions::default());
    p.push_recessive(3);
    let second = p.push_frame(&Frame::std(0x222, &[2]), BuildOptions::default());
    p.push_recessive(3);
    (p, second)
}

#[test]
fn occurrences_count_from_the_step_start() {
    let mut lb = LtBench::new(vec![iut()]);
    lb.begin_step("before");
    let (p, _) = two_frames();
    lb.play_and_run(&p);
    lb.run_idle(20).unwrap();
    lb.end_step();
    lb.begin_step("counted");
    let (p, second) = two_frames();
    let k = lb.play(&p);
    let t = lb.wait(Trigger::at(Field::Ident, 1).nth(2), 200).unwrap();
    let t_second = lb.wait(Trigger::at(Field::Dlc, 1).nth(2), 200).unwrap();
    lb.run_plan();
    let r = lb.end_step();
    assert_eq!(t, r.bit_start(k, second + 1), "Identifier 1 of the second frame of this step");
    let dlc = second + p.bits[second..].iter().position(|b| b.label.is_some_and(|l| l.field == Field::Dlc)).unwrap();
    assert_eq!(t_second, r.bit_start(k, dlc));
    // a TQ offset moves the trigger by that many TQ
    lb.begin_step("offset");
    let (p, second) = two_frames();
    let k = lb.play(&p);
    let t = lb.wait(Trigger::at(Field::Ident, 1).nth(2).tq(7), 200).unwrap();
    lb.run_plan();
    let r = lb.end_step();
    assert_eq!(t, r.bit_start(k, second + 1) + 7 * CLK);
}

#[test]
fn triggers_at_bus_off_recovery_reset_and_wait_for_bus_idle() {
    let mut lb = LtBench::new(vec![iut()]);
    lb.begin_step("bus-off");
    lb.preset(0, 255, 0);
    lb.b.node_mut(0).request(stuffy());
    lb.wait(Trigger::at(Field::Ident, 1), 30).unwrap();
    let mut p = Plan::raw(T, &[true]);
    p.disturb(Disturbance { at: At::tq(0, 0), span: Span::Bits(1), action: Action::Force(true), target: Target::Bus });
    // wait while the plan plays: Bus_Off 1 begins before the plan's bit ends
    lb.play(&p);
    let t_off = lb.wait(Trigger::at(Field::BusOff, 1), 5).unwrap();
    lb.b.node_mut(0).withdraw();
    assert_eq!(lb.b.state(0), 2, "bus-off when the trigger fires");
    assert!(lb.b.tec(0) > 255);
    let t_run1 = lb.wait(Trigger::recovery(1, 11), 20).unwrap();
    assert_eq!((t_run1 - t_off) / lb.b.bit_ps, 10, "bit 11 of the first run");
    let t_last = lb.wait(Trigger::recovery(128, 11), 128 * 11 + 5).unwrap();
    assert_eq!((t_last - t_off) / lb.b.bit_ps, 128 * 11 - 1);
    assert_eq!(lb.b.runs(0), 127);
    lb.run_bits(2);
    assert_eq!((lb.b.state(0), lb.b.tec(0), lb.b.node(0).field()), (0, 0, Field::Idle));
    let r = lb.end_step();
    assert_eq!(r.iut_events(EV_BIT_ERR).len(), 1);
    assert_eq!(r.iut_events(EV_RECOVERED).len(), 1);
    // the step reset, then Reset and Wait_For_Bus_Idle triggers
    lb.begin_step("reset");
    lb.preset(0, 20, 30);
    lb.reset_iut();
    let t_reset = lb.wait(Trigger::reset(), 2).unwrap();
    lb.run_until_time(t_reset);
    assert_eq!(lb.b.node(0).field(), Field::Reset);
    let t_w = lb.wait(Trigger::at(Field::WaitIdle, 5), 20).unwrap();
    assert!(t_w > t_reset);
    assert_eq!((lb.b.tec(0), lb.b.rec(0)), (0, 0), "counters cleared by the reset");
    lb.run_until(20, |s| s.b.node(0).field() == Field::Idle).unwrap();
    let r = lb.end_step();
    assert_eq!(r.iut_events(EV_INTEGRATED).len(), 1);
}

#[test]
fn a_counter_preset_shows_in_the_counters_and_the_error_state() {
    let mut lb = LtBench::new(vec![iut()]);
    lb.begin_step("preset");
    lb.preset(0, 100, 50);
    assert_eq!((lb.b.tec(0), lb.b.rec(0), lb.b.state(0)), (100, 50, 0));
    lb.preset(0, 128, 5);
    assert_eq!((lb.b.tec(0), lb.b.rec(0), lb.b.state(0)), (128, 5, 1));
    lb.preset(0, 3, 127);
    assert_eq!((lb.b.tec(0), lb.b.rec(0), lb.b.state(0)), (3, 127, 0));
    // counting goes on from the preset values: a stuff error as receiver
    let mut p = Plan::frame(T, &stuffy(), BuildOptions::default());
    let s = p.find(Field::Ident, 8, true).unwrap();
    p.set_level(s, true).truncate(s + 1).push_recessive(25);
    lb.play_and_run(&p);
    lb.run_idle(40).unwrap();
    assert_eq!((lb.b.tec(0), lb.b.rec(0), lb.b.state(0)), (3, 128, 1), "REC 127 + 1: error-passive");
}

#[test]
fn a_step_writes_its_vcd_on_request() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("step.vcd");
    let mut lb = LtBench::new(vec![iut()]);
    lb.vcd_next_step(&path);
    lb.begin_step("vcd");
    let mut p = Plan::frame(T, &Frame::std(0x7F0, &[]), BuildOptions::default());
    p.push_recessive(3);
    lb.play_and_run(&p);
    lb.end_step();
    assert!(lb.vcd_errors.is_empty(), "{:?}", lb.vcd_errors);
    let v = std::fs::read_to_string(&path).unwrap();
    assert!(v.contains("$enddefinitions"), "a VCD header");
    assert!(v.lines().any(|l| l.contains("$scope") && l.split_whitespace().any(|w| w == "lt")), "the LT's nets (scope bus.lt) are in the VCD");
    let changes = v.lines().filter(|l| l.starts_with('#')).count();
    assert!(changes > 100, "{changes} time stamps");
}

#[test]
fn the_lt_answers_the_iuts_frame_and_checks_every_bit_of_it() {
    let mut lb = LtBench::new(vec![iut()]);
    lb.begin_step("tx");
    let f = Frame::std(0x35A, &[0xC3, 0x00, 0x7E]);
    lb.b.node_mut(0).request(f.clone());
    lb.wait(Trigger::at(Field::Sof, 1), 30).unwrap();
    let p = Plan::answer(T, &f, BuildOptions::default(), 3);
    lb.play_and_run(&p);
    lb.run_idle(20).unwrap();
    let r = lb.end_step();
    r.check_expects().unwrap();
    assert_eq!(r.iut_events(EV_TX_OK).len(), 1);
    assert_eq!(lb.b.tec(0), 0);
    // the check reads the IUT's TX: another frame's bits do not match it
    let other = Plan::answer(T, &Frame::std(0x35B, &[0xC3, 0x00, 0x7E]), BuildOptions::default(), 3);
    let mut wrong = r.clone();
    wrong.plays[0].plan = other;
    assert!(wrong.check_expects().is_err());
    // without the LT's ACK the IUT sees an ACK error
    let mut lb = LtBench::new(vec![iut()]);
    lb.begin_step("tx no ack");
    lb.b.node_mut(0).request(f.clone());
    lb.wait(Trigger::at(Field::Sof, 1), 30).unwrap();
    let mut p = Plan::answer(T, &f, BuildOptions::default(), 3);
    let ack = p.find(Field::AckSlot, 1, false).unwrap();
    p.set_level(ack, true).truncate(ack + 1).push_recessive(20);
    lb.b.node_mut(0).withdraw(); // this attempt finishes, no retry
    lb.play_and_run(&p);
    lb.run_idle(40).unwrap();
    let r = lb.end_step();
    let e = r.iut_events(EV_ACK_ERR);
    assert_eq!(e.len(), 1, "{}", r.dump(0));
    assert_eq!(lb.b.tec(0), 8);
}

#[test]
fn a_trigger_at_the_second_error_flag_of_the_step() {
    // stuff error at the dominant stuff bit after Identifier 8; a bus-wide
    // recessive bit in the 3rd bit of the IUT's flag is a bit error that
    // restarts the flag: the second Active_Error_Flag of the step
    let mut lb = LtBench::new(vec![iut()]);
    lb.begin_step("2nd flag");
    let mut p = Plan::frame(T, &stuffy(), BuildOptions::default());
    let s = p.find(Field::Ident, 8, true).unwrap();
    p.set_level(s, true).truncate(s + 1).push_recessive(30);
    p.disturb(Disturbance { at: At::tq(s + 3, 0), span: Span::Bits(1), action: Action::Force(true), target: Target::Bus });
    let k = lb.play(&p);
    let t1 = lb.wait(Trigger::at(Field::ActFlag, 1), 40).unwrap();
    let t2 = lb.wait(Trigger::at(Field::ActFlag, 1).nth(2).tq(2), 40).unwrap();
    lb.run_plan();
    lb.run_idle(40).unwrap();
    let r = lb.end_step();
    assert_eq!(t1, r.bit_start(k, s + 1), "the first flag starts after the stuff bit");
    assert_eq!(t2, r.bit_start(k, s + 4) + 2 * CLK, "the second flag starts after the disturbed flag bit, + 2 TQ");
    assert_eq!(r.iut_events(EV_AEF).len(), 2, "{}", r.dump(0));
    assert_eq!(lb.b.rec(0), 1 + 8, "stuff error +1, bit error in the flag +8");
}
