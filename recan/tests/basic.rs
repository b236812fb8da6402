//! ReCANcentrate reference network without faults: both senders' frames reach
//! every node in sequence, nobody is isolated or quarantined.
use canstar_recan::{run, NetworkSpec, RunSpec};

#[test]
fn fault_free_reference_network_delivers_every_frame() {
    let mut spec = RunSpec::new(NetworkSpec::default(), 1, 16);
    spec.trace = true;
    let t = std::time::Instant::now();
    let r = run(&spec);
    let dt = t.elapsed().as_secs_f64();
    if !r.ok {
        for l in &r.trace {
            eprintln!("{l}");
        }
    }
    eprintln!("{} cycles in {dt:.2}s = {:.0} cycles/s; end {} us, delivered {:?}", r.sim_cycles, r.sim_cycles as f64 / dt, r.end_ps / 1_000_000, r.delivered_per_node);
    assert!(r.ok, "{:?}", r.failures);
    assert!(r.isolated.is_empty(), "{:?}", r.isolated);
    assert!(r.quarantined.is_empty());
    assert_eq!(r.max_retransmissions, 0);
    assert!(r.delivered_per_node[0] >= 7 && r.delivered_per_node[1] >= 7, "{:?}", r.delivered_per_node);
    assert_eq!(r.worst_healthy_tec_rec, 0);
    assert_eq!(r.duplicates, 0);
    // the two senders alternate (the app delay exceeds the intermission)
    assert!(r.delivered_per_node[0].abs_diff(r.delivered_per_node[1]) <= 1);
}
