//! ISO 16845-1:2016 clause 7.1.2 — the IUT as receiver of valid
//! extended-format data frames: identifier and number of data bytes.
//!
//! What the case checks (in our words): like 7.1.1, but the LT's frames
//! carry 29-bit identifiers (alternating patterns, all dominant, all
//! recessive and one arbitrary value), each with every data length 0..8.
//! The IUT must acknowledge each frame in the ACK slot and nowhere else,
//! deliver it unchanged, detect no error and keep REC at 0.
//!
//! Elementary tests: `iso_7_1_2_id<ID>_dlc<N>`, one LT step each.

use super::super::LtBench;
use super::common::receive_frame;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};

/// The 29-bit identifiers of the case (the last one arbitrary).
pub const IDS: [u32; 5] = [0x1555_5555, 0x0AAA_AAAA, 0x0000_0000, 0x1FFF_FFFF, 0x0B3C_5A17];

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_1_2".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for id in IDS {
        for dlc in 0..=8usize {
            let data: Vec<u8> = (0..dlc).map(|i| (id >> (i * 3)) as u8 ^ (0xA7_u8.wrapping_mul(i as u8 + 1))).collect();
            let f = Frame::ext(id, &data);
            let r = (|| {
                receive_frame(&mut lb, &f, BuildOptions::default())?;
                ensure!(lb.b.rec(0) == 0 && lb.b.tec(0) == 0, "counters TEC {} REC {}", lb.b.tec(0), lb.b.rec(0));
                Ok(())
            })();
            ctx.record(&format!("iso_7_1_2_id{id:08x}_dlc{dlc}"), r);
        }
    }
    ctx.results
}
