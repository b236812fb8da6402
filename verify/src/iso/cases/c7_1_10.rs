//! ISO 16845-1:2016 clause 7.1.10 — the IUT as receiver of base-format
//! frames with critical stuffing patterns.
//!
//! What the case checks (in our words): the LT sends valid base-format
//! frames whose identifier, control field (including a recessive r0 and
//! DLC codes above 8) and data are chosen so that stuff bits fall at the
//! edges of fields (after the last identifier bit, after RTR/IDE/r0,
//! inside and after the DLC, around data byte boundaries, before the CRC)
//! and so that stuff bits themselves start new runs of five. The IUT must
//! acknowledge each frame, deliver it unchanged and detect no error.
//!
//! Elementary tests: `iso_7_1_10_f<k>_id<ID>`, the ten classical-CAN
//! frames of the standard (control value: bit 6 RTR, bit 4 r0, bits 3..0
//! DLC).

use super::super::LtBench;
use super::common::receive_frame;
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{data_len, BuildOptions, Frame};

/// (identifier, control, data) of the standard's ten elementary tests.
pub fn table() -> Vec<(u32, u8, Vec<u8>)> {
    let mut first = vec![0xE1u8; 8];
    first[0] = 0x01;
    vec![
        (0x078, 0x08, first),
        (0x41F, 0x01, vec![0x00]),
        (0x707, 0x1F, vec![0x0F; 8]),
        (0x360, 0x10, vec![]),
        (0x730, 0x10, vec![]),
        (0x47F, 0x01, vec![0x1F]),
        (0x758, 0x00, vec![]),
        (0x777, 0x01, vec![0x1F]),
        (0x7EF, 0x42, vec![]),
        (0x3EA, 0x5F, vec![]),
    ]
}

/// The frame and build options of a control value (bit 6 RTR, bit 5 IDE,
/// bit 4 r0, bit 8 SRR, bit 7 IDE of extended frames, bit 5 r1 there).
pub fn decode(ide: bool, id: u32, ctrl: u16, data: &[u8]) -> (Frame, BuildOptions) {
    let dlc = (ctrl & 0xF) as u8;
    let rtr = ctrl & 0x40 != 0;
    let o = BuildOptions { srr: if ide { ctrl & 0x100 != 0 } else { true }, r1: ide && ctrl & 0x20 != 0, r0: ctrl & 0x10 != 0 };
    let f = if rtr { Frame::remote(ide, id, dlc) } else { Frame::data(ide, id, dlc, data) };
    assert!(rtr || data.len() == data_len(dlc), "table row {id:x}: {} bytes for DLC {dlc}", data.len());
    (f, o)
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_1_10".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for (k, (id, ctrl, data)) in table().into_iter().enumerate() {
        let (f, o) = decode(false, id, ctrl as u16, &data);
        let r = (|| {
            receive_frame(&mut lb, &f, o)?;
            ensure!(lb.b.rec(0) == 0, "REC {}", lb.b.rec(0));
            Ok(())
        })();
        ctx.record(&format!("iso_7_1_10_f{}_id{id:03x}", k + 1), r);
    }
    ctx.results
}
