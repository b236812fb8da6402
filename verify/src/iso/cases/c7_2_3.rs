//! ISO 16845-1:2016 clause 7.2.3 — the IUT as receiver: stuff error in an
//! extended-format frame.
//!
//! What the case checks (in our words): as 7.2.2 for extended frames: the
//! LT sends 29-bit-identifier frames in which one stuff bit is sent at the
//! level of the five bits before it, at stuff bits of both levels in the
//! base identifier, the SRR/IDE/extension part, the control field, the
//! data and the CRC. At each, the IUT (REC 0) must flag a stuff error at
//! that bit, send an active error flag from the next bit, deliver nothing
//! and count REC +1 (the checks of [`super::c7_2_2::stuff_error_at`]).
//!
//! Elementary tests: `iso_7_2_3_f<k>_<field>_<pos>_<D|R>`.

use super::c7_2_2::stuff_error_case;
use crate::conformance::StepResult;
use canstar_controller::frame::Frame;
use canstar_controller::fsm::*;

/// Frames whose stuff bits cover every stuffed field of an extended frame
/// with both levels.
pub fn frames() -> Vec<Frame> {
    vec![
        Frame::ext(0x07C3_0F0F, &[0x3C; 8]),
        Frame::ext(0x07C0_F0F0, &[0x00]),
        Frame::ext(0x1FB8_0000, &[0xA0]),
        Frame::ext(0x0000_001F, &[0xFF, 0x00]),
        Frame::ext(0x1F83_E0F8, &[0x0F, 0x83]),
        Frame::data(true, 0x0000_0000, 15, &[0x11; 8]),
        // extension ending in four recessive bits and a recessive RTR: a
        // dominant stuff bit after RTR, then r1, r0 and DLC 0 dominant
        Frame::remote(true, 0x0000_000F, 0),
    ]
}

fn short(f: Field) -> &'static str {
    match f {
        Field::Ident => "id",
        Field::Srr => "srr",
        Field::Ide => "ide",
        Field::ExIdent => "exid",
        Field::Rtr => "rtr",
        Field::Resv => "r",
        Field::Dlc => "dlc",
        Field::Data => "data",
        Field::Crc => "crc",
        _ => "other",
    }
}

pub fn run() -> Vec<StepResult> {
    stuff_error_case("iso_7_2_3", &frames(), short)
}

#[cfg(test)]
mod tests {
    use super::*;
    use super::super::c7_2_2::stuffed;

    #[test]
    fn the_frames_cover_every_stuffed_field_with_both_levels() {
        let seen = stuffed(&frames(), |f| match f {
            Field::Srr | Field::Ide | Field::ExIdent => "ext",
            Field::Rtr | Field::Resv | Field::Dlc => "control",
            f => short(f),
        });
        for field in ["id", "ext", "control", "data", "crc"] {
            for level in [false, true] {
                assert!(seen.contains(&(field, level)), "no {} stuff bit in {field}: {seen:?}", if level { "R" } else { "D" });
            }
        }
    }
}
