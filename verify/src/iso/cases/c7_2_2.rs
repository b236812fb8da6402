//! ISO 16845-1:2016 clause 7.2.2 — the IUT as receiver: stuff error in a
//! base-format frame.
//!
//! What the case checks (in our words): the lower tester sends standard
//! data frames in which one stuff bit is replaced by a bit of the level of
//! the five bits before it, so that the IUT reads six equal bits. This is
//! done at stuff bits of both levels in every stuffed part of the frame
//! (identifier, control field, data field, CRC sequence). At each of them
//! the IUT, error-active with REC 0 (set through the counter-load port),
//! must flag a stuff error at that bit, drive an active error flag (six
//! dominant bits) from the next bit on, then release the bus for its error
//! delimiter, and count REC +1. The LT stays recessive after the wrong bit.
//!
//! Elementary tests: `iso_7_2_2_f<k>_<field>_<pos>_<D|R>` (frame k of
//! [`frames`], the stuff bit after bit `pos` of `field`, its correct level).

use super::super::{LtBench, Plan};
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// Frames whose stuff bits together cover every stuffed field with both levels.
pub fn frames() -> Vec<Frame> {
    vec![
        Frame::std(0x078, &[0x00, 0xFF]), // ID: R stuff after 4, D after 8; data stuff of both levels
        Frame::std(0x7C0, &[]),           // ID 1..5 R: D stuff; r0, IDE, RTR, DLC 0 dominant: stuff in the control field
        Frame::std(0x001, &[0xFF]),       // ID 1..10 dominant; control field 000 0001 and data ones
        Frame::std(0x3E0, &[0x0F, 0xF0, 0x83]),
        Frame::std(0x555, &[0xAA, 0x00, 0x00, 0x00]),
        Frame::std(0x120, &[0x1F, 0x80, 0x07, 0xE0, 0x3C]),
        // ID 10, 11, RTR, IDE, r0 dominant: R stuff after r0; DLC 15 = 1111 then makes
        // five recessive bits: D stuff after DLC 4
        Frame::data(false, 0x124, 15, &[0x11; 8]),
    ]
}

fn short(f: Field) -> &'static str {
    match f {
        Field::Ident => "id",
        Field::Rtr => "rtr",
        Field::Ide => "ide",
        Field::Resv => "r0",
        Field::Dlc => "dlc",
        Field::Data => "data",
        Field::Crc => "crc",
        _ => "other",
    }
}

/// One elementary test: stuff bit `s` of `f` sent at the wrong level.
pub fn stuff_error_at(lb: &mut LtBench, f: &Frame, s: usize) -> Result<(), String> {
    lb.begin_step("stuff error");
    lb.preset(0, 0, 0);
    let got0 = lb.b.node(0).received().len();
    let mut p = Plan::frame(lb.timing, f, BuildOptions::default());
    let lvl = p.bits[s].level;
    p.set_level(s, !lvl).truncate(s + 1).push_recessive(8 + 8 + 3);
    for k in 1..=6 {
        p.expect(s + k, false, "active error flag");
    }
    p.expect(s + 7, true, "error delimiter");
    lb.play_and_run(&p);
    lb.run_idle(30)?;
    let r = lb.end_step();
    let l = p.bits[s].label.unwrap();
    let at: Vec<_> = r.iut().iter().filter(|b| b.has(EV_STUFF_ERR)).collect();
    ensure!(at.len() == 1, "{} stuff errors:{}", at.len(), r.dump(0));
    ensure!((at[0].field, at[0].pos, at[0].stuff) == (l.field, l.pos, true), "stuff error at {}, expected at the stuff bit after {} {}", at[0], l.field.name(), l.pos);
    ensure!(at[0].has(EV_AEF), "no active error flag started: {}", at[0]);
    r.check_expects()?;
    ensure!(lb.b.rec(0) == 1, "REC {} after the stuff error, expected 1:{}", lb.b.rec(0), r.dump(0));
    ensure!(lb.b.node(0).received().len() == got0, "a frame was delivered");
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    stuff_error_case("iso_7_2_2", &frames(), short)
}

/// Every stuff bit of every frame sent at the wrong level ([`stuff_error_at`]),
/// one elementary test each, named `<program>_f<k>_<short(field)>_<pos>_<D|R>`
/// (7.2.2 and 7.2.3).
pub fn stuff_error_case(program: &str, frames: &[Frame], short: fn(Field) -> &'static str) -> Vec<StepResult> {
    let mut ctx = Ctx { program: program.into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    for (k, f) in frames.iter().enumerate() {
        let p = Plan::frame(lb.timing, f, BuildOptions::default());
        for s in p.stuff_bits() {
            let l = p.bits[s].label.unwrap();
            let name = format!("{program}_f{k}_{}_{}_{}", short(l.field), l.pos, if p.bits[s].level { "R" } else { "D" });
            let r = stuff_error_at(&mut lb, f, s);
            ctx.record(&name, r);
        }
    }
    ctx.results
}

/// The (field group, level) pairs of the stuff bits of `frames`, fields grouped by `group`.
#[cfg(test)]
pub fn stuffed(frames: &[Frame], group: impl Fn(Field) -> &'static str) -> std::collections::BTreeSet<(&'static str, bool)> {
    use canstar_controller::frame::bus_bits;
    let mut seen = std::collections::BTreeSet::new();
    for f in frames {
        for b in bus_bits(f, BuildOptions::default(), false).iter().filter(|b| b.stuff) {
            seen.insert((group(b.field), b.level));
        }
    }
    seen
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_frames_cover_every_stuffed_field_with_both_levels() {
        let seen = stuffed(&frames(), |f| if matches!(f, Field::Rtr | Field::Ide | Field::Resv | Field::Dlc) { "control" } else { short(f) });
        for field in ["id", "control", "data", "crc"] {
            for level in [false, true] {
                assert!(seen.contains(&(field, level)), "no {} stuff bit in {field}: {seen:?}", if level { "R" } else { "D" });
            }
        }
    }
}
