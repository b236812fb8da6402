//! The whole conformance suite with every node in lock step with its own
//! golden model (can-protocol.md §19, issue #4): one test per program, each
//! asserting that no node diverged, that the checkers actually compared
//! sample points, that labels and event words agree (no §19.7 warning), and
//! that the program's own steps still pass.
use canstar_verify::conformance::{run_program_with, RunOptions};

fn lockstep(program: &str) {
    let run = run_program_with(program, &RunOptions { vcd_dir: None, lockstep: true, ..Default::default() }).expect("no such program");
    let divs: Vec<String> = run.log.divergences.iter().map(|d| d.to_string()).collect();
    assert!(divs.is_empty(), "{program}: {} lock-step divergence(s):\n{}", divs.len(), divs.join("\n"));
    assert!(run.log.checked_bits > 100, "{program}: only {} sample points compared", run.log.checked_bits);
    // §19.7 diagnostics: the bit labels (FIELD/POSITION/stuff/role) and the
    // event words of RTL and golden model agree at every sample point too.
    assert!(run.log.warnings.is_empty(), "{program}: checker warnings:\n{}", run.log.warnings.join("\n"));
    let failed: Vec<String> = run.results.iter().filter(|r| !r.pass).map(|r| format!("{}: {}", r.name, r.msg)).collect();
    assert!(failed.is_empty(), "{program}: steps failed in lock-step mode:\n{}", failed.join("\n"));
}

macro_rules! lockstep_tests {
    ($($name:ident),*) => { $( #[test] fn $name() { lockstep(stringify!($name)); } )* };
}

lockstep_tests!(baudrate, biterror, btl, crc, dlc, emlcount, extd_id, formerr, idle, overload, stuffbit, stufferr, txarb);

/// Regression (found by the lock-step suite): after the release of reset the
/// golden model is in Wait_For_Bus_Idle, where hard synchronisation is
/// enabled; the checker used to present the reset value (disabled) until the
/// first golden sample point, so an edge early in the first bit with a phase
/// error beyond SJW was resynchronised by the golden bit timing and hard
/// synchronised by the DUT. The start-up pulse of the conformance bench hits
/// exactly such an instant. Every offset of a dominant pulse after reset must
/// stay in lock step.
#[test]
fn dominant_pulse_at_every_offset_after_reset_stays_in_lock_step() {
    use canstar_sim::bus::{Bus, NodeDelays};
    use canstar_verify::lockstep::LockstepNode;
    use canstar_verify::node::NodeConfig;
    use canstar_sim::{ClockSpec, FaultMode, Sim};
    for k in 0..30u64 {
        let mut sim = Sim::new(5);
        let bus = Bus::uniform(&mut sim, "bus", 1, NodeDelays::symmetric(0, 0));
        let a = sim.add(LockstepNode::new(NodeConfig::named("n1"), ClockSpec::new(100_000)), &[bus.nodes[0].rx], &[bus.nodes[0].tx]);
        for c in 0..400u64 {
            if c == k {
                bus.set_interference(&mut sim, 0, FaultMode::StuckDominant);
            }
            if c == k + 10 {
                bus.set_interference(&mut sim, 0, FaultMode::None);
            }
            sim.step();
        }
        let l = sim.get(a);
        assert!(l.armed(), "offset {k}: checker not armed");
        assert!(l.divergence().is_none(), "offset {k}: {}", l.divergence().unwrap());
    }
}

/// Regression: a hardware reset clears the DUT's counters at once; the golden
/// counters must be shown cleared on the same clock (they used to stay at
/// their last shown value until the next golden sample point).
#[test]
fn hardware_reset_with_counters_set_stays_in_lock_step() {
    use canstar_verify::conformance::{cfg, Bench};
    use canstar_sim::FaultMode;
    canstar_verify::conformance::set_lockstep(true);
    let mut b = Bench::new(vec![cfg(), cfg()], false, None);
    canstar_verify::conformance::set_lockstep(false);
    b.node_mut(1).request(canstar_controller::frame::Frame::std(0x123, &[1]));
    // N1 reads its own ACK recessive: a bit error, REC > 0.
    b.force_at(&[0], canstar_controller::fsm::Field::AckSlot, 1, false, FaultMode::StuckRecessive, 1).unwrap();
    b.run_bits(20);
    assert!(b.rec(0) > 0, "REC {}", b.rec(0));
    b.node_mut(0).hard_reset();
    b.run_bits(60);
    assert_eq!(b.rec(0), 0);
    assert!(b.lockstep(0).is_some_and(|l| l.stats().bits > 50));
    assert!(b.divergences().is_empty(), "{}", b.divergences()[0]);
}

/// The bench plumbing reports what a checker finds: a golden TEC corrupted
/// on purpose shows up as a `tec` divergence of that node only.
#[test]
fn an_injected_golden_fault_is_reported_by_the_bench() {
    use canstar_verify::conformance::{cfg, set_lockstep, Bench, NodeHandle};
    set_lockstep(true);
    let mut b = Bench::new(vec![cfg(), cfg()], false, None);
    set_lockstep(false);
    let NodeHandle::Lockstep(h) = b.nodes[0] else { panic!("not a lock-step bench") };
    b.sim.get_mut(h).inject_tec_fault = Some(8);
    b.node_mut(1).request(canstar_controller::frame::Frame::std(0x123, &[1]));
    b.run_bits(3);
    b.run_idle(200).unwrap();
    let d = b.divergences();
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!((d[0].node.as_str(), d[0].signal.as_str()), ("n1", "tec"));
    // The step that ran while it was found fails; the next one does not.
    let mut ctx = canstar_verify::conformance::Ctx { program: "x".into(), vcd: None, results: vec![] };
    ctx.record("x_1", Ok(()));
    ctx.record("x_2", Ok(()));
    assert!(!ctx.results[0].pass && ctx.results[0].msg.contains("lock-step divergence") && ctx.results[0].msg.contains("tec"), "{:?}", ctx.results[0]);
    assert!(ctx.results[1].pass);
}

/// `canstar conformance --lockstep`: the throughput line, then the final
/// line with the divergence count.
#[test]
fn cli_lockstep_final_line_counts_divergences() {
    let mut out = Vec::new();
    let (p, f, d) = canstar_verify::conformance::run_cli_with(Some("txarb"), None, true, &mut out).unwrap();
    let s = String::from_utf8(out).unwrap();
    assert_eq!((p, f, d), (20, 0, 0), "{s}");
    let lines: Vec<&str> = s.lines().collect();
    assert_eq!(*lines.last().unwrap(), "20 passed, 0 failed, 0 divergences");
    assert!(lines[lines.len() - 2].starts_with("simulated ") && lines[lines.len() - 2].contains("node cycles/s"), "{s}");
    assert!(lines[0].starts_with("txarb") && lines[0].contains("0 divergences"), "{s}");
}
