//! Coupler: input stage, ANDC / ANDT, fault hooks, output registers, latency (H2, H3).
use canstar_hdl::{drive, flow};
use canstar_hdl::sync::Synchroniser;
use canstar_hub::coupler::{self, Coupler};
use rand::Rng;

fn settle_cycles(c: &mut Coupler, k: usize) {
    for _ in 0..k {
        drive::cycle(c);
    }
}

fn idle(c: &mut Coupler) {
    c.reset.next = false;
    c.efg.next = true;
    for s in c.rx.iter_mut().chain(c.reh_rx.iter_mut()) {
        s.next = true;
    }
    for s in c.dis.iter_mut().chain(c.hdis.iter_mut()) {
        s.next = false;
    }
    for s in c.up_fault.iter_mut().chain(c.down_fault.iter_mut()).chain(c.hub_fault.iter_mut()) {
        s.next = 0.into();
    }
}

#[test]
fn outputs_recessive_at_power_up_and_in_reset() {
    let mut c = Coupler::new(3, 2, 2);
    drive::init(&mut c);
    idle(&mut c);
    for i in 0..3 {
        c.rx[i].next = false;
    }
    c.reset.next = true;
    for _ in 0..10 {
        drive::cycle(&mut c);
        assert!(c.tx.iter().all(|t| t.val()), "tx recessive in reset");
        assert!(c.hub_tx.iter().all(|t| t.val()), "hub_tx recessive in reset");
    }
    c.reset.next = false;
    settle_cycles(&mut c, 4);
    assert!(c.tx.iter().all(|t| !t.val()), "dominant uplinks reach the downlinks after reset");
}

#[test]
fn andc_and_bt_truth_table() {
    for (n, m) in [(1, 0), (3, 0), (3, 2), (4, 3)] {
        let mut c = Coupler::new(n, m, 1);
        drive::init(&mut c);
        idle(&mut c);
        let mut rng = canstar_hdl::flow::rng(n as u64 * 10 + m as u64);
        for _ in 0..300 {
            let u: Vec<bool> = (0..n).map(|_| rng.gen_bool(0.7)).collect();
            let s: Vec<bool> = (0..m).map(|_| rng.gen_bool(0.7)).collect();
            let dis: Vec<bool> = (0..n).map(|_| rng.gen_bool(0.3)).collect();
            let hdis: Vec<bool> = (0..m).map(|_| rng.gen_bool(0.3)).collect();
            let efg = rng.gen_bool(0.8);
            for i in 0..n {
                c.rx[i].next = u[i];
                c.dis[i].next = dis[i];
            }
            for j in 0..m {
                c.reh_rx[j].next = s[j];
                c.hdis[j].next = hdis[j];
            }
            c.efg.next = efg;
            // one synchroniser flip-flop: after one cycle u/s hold the new values
            drive::cycle(&mut c);
            let andc = efg && (0..n).all(|i| u[i] || dis[i]);
            let bt = andc && (0..m).all(|j| s[j] || hdis[j]);
            assert_eq!(c.andc.val(), andc);
            assert_eq!(c.bt.val(), bt);
            drive::cycle(&mut c);
            assert!(c.tx.iter().all(|t| t.val() == bt), "tx = BT");
            assert!(c.hub_tx.iter().all(|t| t.val() == andc), "hub_tx = ANDC, not BT");
        }
    }
}

/// H2: an edge on an uplink pin reaches every downlink pin after exactly
/// `coupling_latency(depth)` clock edges; likewise sublink -> downlink and uplink -> hub_tx.
#[test]
fn coupling_latency_is_depth_plus_one() {
    for depth in [1usize, 2] {
        let lat = coupler::coupling_latency(depth);
        assert_eq!(lat, depth + 1);
        for path in 0..3 {
            let mut c = Coupler::new(3, 2, depth);
            drive::init(&mut c);
            idle(&mut c);
            settle_cycles(&mut c, 5);
            match path {
                0 | 2 => c.rx[1].next = false,
                _ => c.reh_rx[1].next = false,
            }
            let mut edges = 0;
            loop {
                drive::cycle(&mut c);
                edges += 1;
                let seen = if path == 2 { !c.hub_tx[0].val() } else { !c.tx[2].val() };
                if seen {
                    break;
                }
                assert!(edges < 10);
            }
            assert_eq!(edges, lat, "depth {depth} path {path}");
        }
    }
}

#[test]
fn fault_hooks() {
    let mut c = Coupler::new(2, 1, 1);
    drive::init(&mut c);
    idle(&mut c);
    settle_cycles(&mut c, 3);
    // stuck dominant on uplink 0: u[0] and every downlink dominant
    c.up_fault[0].next = coupler::FAULT_STUCK_DOMINANT.into();
    settle_cycles(&mut c, 2);
    assert!(!c.u[0].val() && c.u[1].val());
    assert!(c.tx.iter().all(|t| !t.val()));
    // stuck recessive on uplink 0 hides a dominant uplink
    c.up_fault[0].next = coupler::FAULT_STUCK_RECESSIVE.into();
    c.rx[0].next = false;
    settle_cycles(&mut c, 3);
    assert!(c.u[0].val() && c.tx[1].val());
    // bit flip inverts
    c.up_fault[0].next = coupler::FAULT_BIT_FLIP.into();
    settle_cycles(&mut c, 2);
    assert!(c.u[0].val());
    c.rx[0].next = true;
    settle_cycles(&mut c, 2);
    assert!(!c.u[0].val() && !c.tx[1].val());
    c.up_fault[0].next = 0.into();
    // downlink fault only on downlink 1
    c.down_fault[1].next = coupler::FAULT_STUCK_DOMINANT.into();
    settle_cycles(&mut c, 3);
    assert!(c.tx[0].val() && !c.tx[1].val());
    c.down_fault[1].next = 0.into();
    // outgoing sublink fault does not change BT
    c.hub_fault[0].next = coupler::FAULT_BIT_FLIP.into();
    settle_cycles(&mut c, 3);
    assert!(!c.hub_tx[0].val() && c.tx[0].val() && c.tx[1].val());
}

#[test]
fn sync_stage_depth() {
    for depth in [1usize, 2] {
        let mut s = Synchroniser::new(depth);
        drive::init(&mut s);
        assert!(s.q.val(), "recessive at power-up");
        s.d.next = false;
        let mut k = 0;
        while s.q.val() {
            drive::cycle(&mut s);
            k += 1;
        }
        assert_eq!(k, depth);
    }
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn coupler_flow() {
    let mut c = Coupler::new(3, 2, 2);
    let (synth, cs) = flow::full_check(&mut c, "coupler", 100_000, 11, |c: &mut Coupler, rng, cycle| {
        c.reset.next = cycle < 3 || rng.gen_ratio(1, 5000);
        // slowly changing lines (bit-like), occasional faults and disables
        if cycle % 16 == 0 {
            for i in 0..3 {
                c.rx[i].next = rng.gen_bool(0.6);
                if rng.gen_ratio(1, 20) {
                    c.dis[i].next = !c.dis[i].val();
                }
                c.up_fault[i].next = if rng.gen_ratio(1, 8) { rng.gen_range(0..4u64).into() } else { 0.into() };
                c.down_fault[i].next = if rng.gen_ratio(1, 8) { rng.gen_range(0..4u64).into() } else { 0.into() };
            }
            for j in 0..2 {
                c.reh_rx[j].next = rng.gen_bool(0.6);
                if rng.gen_ratio(1, 20) {
                    c.hdis[j].next = !c.hdis[j].val();
                }
                c.hub_fault[j].next = if rng.gen_ratio(1, 8) { rng.gen_range(0..4u64).into() } else { 0.into() };
            }
            c.efg.next = rng.gen_bool(0.9);
        }
        if rng.gen_ratio(1, 50) {
            c.rx[rng.gen_range(0..3)].next = rng.gen();
        }
    })
    .expect("coupler flow");
    assert_eq!(cs.cycles, 100_000);
    assert!(synth.cells > 0);
}
