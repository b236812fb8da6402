//! ISO 16845-1:2016 clause 8.1.1 — the IUT as transmitter of base-format
//! data frames: identifier and number of data bytes.
//!
//! What the case checks (in our words): the IUT is asked to send standard
//! data frames over the identifiers of [`super::c7_1_1::IDS`] and every data
//! length 0..8. The lower tester acknowledges each frame and compares every
//! bit the IUT drives, from SOF to the end of End_Of_Frame, with the frame
//! as the frame builder stuffs it (identifier, control field, data, CRC,
//! delimiters). The IUT must report a successful transmission, detect no
//! error and keep TEC at 0.
//!
//! Elementary tests: `iso_8_1_1_id<ID>_dlc<N>`, one LT step each, on one
//! bench (the IUT alone with the LT, default timing T10/6/4). This case is
//! the template of the IUT-as-transmitter cases ([`super::super::Plan::answer`]).

use super::super::{LtBench, Plan, Trigger};
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// One elementary test: the IUT sends `f`, the LT answers and checks it.
pub fn transmit_one(lb: &mut LtBench, f: &Frame) -> Result<(), String> {
    lb.begin_step("tx");
    lb.b.node_mut(0).request(f.clone());
    lb.wait(Trigger::at(Field::Sof, 1), 30)?;
    let p = Plan::answer(lb.timing, f, BuildOptions::default(), 3);
    lb.play_and_run(&p);
    lb.run_idle(20)?;
    let r = lb.end_step();
    r.check_expects()?;
    ensure!(r.iut_events(EV_TX_OK).len() == 1, "no successful transmission:{}", r.dump(0));
    let errs: Vec<_> = r.iut().iter().filter(|b| b.ev & ((1 << EV_BIT_ERR) | (1 << EV_STUFF_ERR) | (1 << EV_FORM_ERR) | (1 << EV_ACK_ERR)) != 0).collect();
    ensure!(errs.is_empty(), "IUT detected errors: {errs:?}");
    ensure!(lb.b.tec(0) == 0 && lb.b.rec(0) == 0, "counters TEC {} REC {}", lb.b.tec(0), lb.b.rec(0));
    ensure!(!lb.b.node(0).pending(), "the frame is still pending");
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_1_1".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for id in super::c7_1_1::IDS {
        for dlc in 0..=8usize {
            let data: Vec<u8> = (0..dlc).map(|i| (id as u8) ^ (0x5D_u8.wrapping_mul(i as u8 + 1))).collect();
            let f = Frame::std(id, &data);
            let r = transmit_one(&mut lb, &f);
            ctx.record(&format!("iso_8_1_1_id{id:03x}_dlc{dlc}"), r);
        }
    }
    ctx.results
}
