//! The conformance bench itself: the WAIT_FOR forcing instant, the records
//! and the scripted transmitter.
use canstar_controller::core::CanCore;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::{Field, EV_SOF};
use canstar_verify::conformance::*;
use canstar_sim::FaultMode;

/// The override is set `L_rx − 1` clocks before N1's TX edge of the target
/// bit: the tick of that TX edge still reads the previous bit's last TQ, so
/// the override is first read in the target bit's SYNC_SEG (the btl cases
/// b–f check the TQ alignment through sample points).
#[test]
fn forcing_starts_l_rx_minus_1_clocks_before_the_target_bit_on_tx() {
    let mut b = Bench::new(vec![cfg()], false, None);
    // Identifier 3 dominant, 4 recessive: N1's TX rises at the start of ID 4.
    let f = Frame::std(0x0F0, &[]);
    b.node_mut(0).request(f);
    b.wait_for(0, Field::Ident, 4, false, 100).unwrap();
    let t_force = b.recs(0).last().unwrap().t + b.ph2_rest_ps(0);
    let txn = b.bus.nodes[0].tx;
    let mut last = b.sim.value(txn);
    let mut edge = None;
    for _ in 0..40 {
        b.step();
        let v = b.sim.value(txn);
        if v != last && edge.is_none() {
            edge = Some(b.sim.now());
        }
        last = v;
    }
    let l_rx = CanCore::l_rx(canstar_controller::core::SYNC_DEPTH) as u64;
    assert_eq!(edge.unwrap() - t_force, (l_rx - 1) * CLOCK_PS);
}

#[test]
fn forced_bit_is_recorded_at_the_target() {
    let mut b = Bench::new(vec![cfg()], false, None);
    b.node_mut(0).request(Frame::std(0x0F0, &[]));
    let m = b.force_at(&[0], Field::Ident, 4, false, FaultMode::StuckDominant, 1).unwrap();
    let r = b.rec_at(0, m).unwrap();
    assert_eq!((r.field, r.pos, r.level, r.drove), (Field::Ident, 4, false, true), "{r}");
}

#[test]
fn scripted_frame_with_recessive_r0_is_received() {
    let mut b = Bench::new(vec![cfg()], true, None);
    let f = Frame::std(0x123, &[0xA5]);
    let h = b.script.unwrap();
    b.sim.get_mut(h).send(script_bits(&f, BuildOptions { r0: true, ..Default::default() }));
    b.run_bits(5);
    b.run_idle(200).unwrap();
    assert_eq!(b.node(0).received(), vec![f]);
    assert_eq!(b.count(0, 0, EV_SOF), 1);
}

#[test]
fn cli_prints_one_line_per_program_and_the_total() {
    let mut out = Vec::new();
    let (p, f) = run_cli(Some("txarb"), None, &mut out).unwrap();
    let s = String::from_utf8(out).unwrap();
    assert_eq!((p, f), (20, 0), "{s}");
    assert_eq!(s.lines().last().unwrap(), "20 passed, 0 failed");
    assert!(s.lines().next().unwrap().starts_with("txarb"));
}
