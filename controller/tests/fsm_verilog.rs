//! Verilog flow of the frame state machine alone.
use canstar_controller::fsm::CanFsm;
use canstar_hdl::{drive, flow};

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn fsm_lint_and_synth() {
    let mut u = CanFsm::new();
    drive::init(&mut u);
    let v = flow::emit(&u);
    if let Ok(d) = std::env::var("CANSTAR_DUMP_V") {
        std::fs::write(d, &v).unwrap();
    }
    flow::lint(&v, "top").expect("lint");
    flow::synth_check(&v, "top", flow::SynthTarget::Generic).expect("synth");
}

mod common;
use common::stim::{random_frame, BusScript};
use rand::Rng;

/// Co-simulation of CanFsm against its Verilog on a bit stream of real frames
/// (sample strobe every 2..4 clocks, the FSM's own drive wired-AND into the
/// bus), with random disturbances, transmit requests and resets.
#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn fsm_cosim() {
    let mut u = CanFsm::new();
    let mut script = BusScript::new(0.004);
    let mut wait = 0u32;
    let mut req_timer = 0u32;
    flow::cosim(&mut u, "canfsm", 150_000, 11, move |u, rng, cycle| {
        u.reset.next = cycle < 2 || rng.gen_bool(0.00003);
        u.sample.next = false;
        if wait == 0 {
            let level = script.next_bit(rng);
            wait = rng.gen_range(2..5);
            u.sample.next = true;
            u.busmon.next = level & u.drive.val();
        }
        wait -= 1;
        if req_timer == 0 {
            req_timer = rng.gen_range(50..3000);
            let want = rng.gen_bool(0.6);
            u.tx_req.next = want;
            if want {
                let f = random_frame(rng);
                u.tx_ide.next = f.ide;
                u.tx_rtr.next = f.rtr;
                u.tx_id.next = (f.id as u64).into();
                u.tx_dlc.next = (f.dlc as u64).into();
                u.tx_data.next = f.data_word().into();
            }
        }
        req_timer -= 1;
        u.single_shot.next = cycle % 40_000 > 30_000;
        u.self_test.next = cycle % 50_000 > 45_000;
        u.listen_only.next = cycle % 70_000 > 66_000;
        u.host_recovery.next = cycle % 60_000 > 50_000;
        u.recover.next = rng.gen_bool(0.001);
        u.tx_abort.next = rng.gen_bool(0.0002);
    })
    .expect("cosim");
}
