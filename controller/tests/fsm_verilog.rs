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
use canstar_controller::fsm::EV_RECOVERED;
use rand::Rng;

/// Co-simulation of CanFsm against its Verilog on a bit stream of real frames
/// (sample strobe every 2..4 clocks, the FSM's own drive wired-AND into the
/// bus), with random disturbances, transmit requests and resets, and a phase
/// in which the node is alone on a recessive bus with a request: ACK errors,
/// error-passive, then (RX stuck recessive) bit errors up to bus-off and the
/// 128 x 11 recovery.
#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn fsm_cosim() {
    let mut u = CanFsm::new();
    let mut script = BusScript::new(0.004);
    let mut wait = 0u32;
    let mut req_timer = 0u32;
    let seen = std::rc::Rc::new(std::cell::Cell::new([false; 4]));
    let seen2 = seen.clone();
    flow::cosim(&mut u, "canfsm", 160_000, 11, move |u, rng, cycle| {
        let mut sn = seen2.get();
        sn[u.state.val().index() & 3] = true;
        sn[3] |= u.events.val().get_bit(EV_RECOVERED);
        seen2.set(sn);
        let alone = (60_000..80_000).contains(&cycle);
        u.reset.next = cycle < 2 || (!alone && rng.gen_bool(0.00003));
        u.sample.next = false;
        if wait == 0 {
            let level = if alone { true } else { script.next_bit(rng) };
            wait = rng.gen_range(2..5);
            u.sample.next = true;
            // from 66000 on the node reads its SOF recessive: bit errors
            u.busmon.next = level & (u.drive.val() || (66_000..68_000).contains(&cycle));
        }
        wait -= 1;
        if alone {
            u.tx_req.next = cycle < 68_000;
        } else if req_timer == 0 {
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
        u.single_shot.next = !alone && cycle % 40_000 > 30_000;
        u.self_test.next = !alone && cycle % 50_000 > 45_000;
        u.listen_only.next = !alone && cycle % 70_000 > 66_000;
        u.host_recovery.next = !alone && cycle % 60_000 > 50_000;
        u.recover.next = rng.gen_bool(0.001);
        u.tx_abort.next = !alone && rng.gen_bool(0.0002);
        (u.cnt_load.next, u.tec_in.next, u.rec_in.next) = (!alone && cycle % 23_000 < 3, ((cycle * 37 % 512) as u64).into(), ((cycle * 11 % 256) as u64).into());
    })
    .expect("cosim");
    assert_eq!(seen.get(), [true; 4], "active, passive, bus-off and recovery all reached");
}
