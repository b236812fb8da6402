//! ISO 16845-1:2016 clause 7.2.5 — the IUT as receiver: CRC error.
//!
//! What the case checks (in our words): the LT sends a frame whose CRC
//! sequence has one bit inverted (a dominant bit sent recessive, and a
//! recessive bit sent dominant), chosen so that the stuffing stays
//! consistent and only the CRC is wrong. The IUT must not acknowledge the
//! frame (recessive in the ACK slot), must report the CRC error at the ACK
//! delimiter and start its active error flag with the first EOF bit,
//! deliver nothing and count REC +1. In the third test the LT sends the
//! frame with identifier 0x001 with its SOF recessive: the IUT takes the
//! first dominant bit (identifier bit 10) for the SOF and comes back in
//! step with the LT at the recessive stuff bit after identifier bit 7,
//! which it reads as an identifier bit, so it receives a frame of the same
//! length whose CRC is wrong, and must answer as in the first two tests
//! (its SOF must be the LT's second bit).
//!
//! Elementary tests: `iso_7_2_5_crc<P>_<D|R>_inverted` (P: CRC position)
//! and `iso_7_2_5_sof_recessive_id001`.

use super::super::{LtBench, Plan, StepRecord};
use super::common::{receive_error, RxError};
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::frame::{BuildOptions, Frame};
use canstar_controller::fsm::*;

/// Does a receiver destuff `levels` (SOF to the end of the stuffed part)
/// exactly at the indices `stuff`, without a stuff error?
pub fn destuffs_at(levels: &[bool], stuff: &[usize]) -> bool {
    let (mut run, mut last, mut got) = (0, None, vec![]);
    for (i, &l) in levels.iter().enumerate() {
        if run == 5 {
            if Some(l) == last {
                return false;
            }
            got.push(i);
            run = 1;
            last = Some(l);
            continue;
        }
        if Some(l) == last {
            run += 1;
        } else {
            run = 1;
            last = Some(l);
        }
    }
    got == stuff
}

/// A frame plan with CRC bit (non-stuff) of level `lvl` inverted such that
/// the stuffing is unchanged; the index of the inverted bit.
pub fn crc_flip(p: &Plan, lvl: bool) -> Option<usize> {
    let end = p.find(Field::CrcDel, 1, false)?;
    let stuff: Vec<usize> = p.stuff_bits();
    (0..end).find(|&i| {
        let b = p.bits[i];
        if !b.label.is_some_and(|l| l.field == Field::Crc && !l.stuff) || b.level != lvl {
            return false;
        }
        let mut v: Vec<bool> = p.bits[..end].iter().map(|b| b.level).collect();
        v[i] = !v[i];
        destuffs_at(&v, &stuff)
    })
}

/// The step of 7.2.5 (and 7.6.10): CRC bit of level `lvl` inverted, REC
/// `rec0` before.
pub fn crc_error(lb: &mut LtBench, f: &Frame, lvl: bool, rec0: u32) -> Result<String, String> {
    let mut p = Plan::frame(lb.timing, f, BuildOptions::default());
    let i = crc_flip(&p, lvl).ok_or("no CRC bit to invert without changing the stuffing")?;
    let name = format!("crc{}_{}_inverted", p.bits[i].label.unwrap().pos, if lvl { "R" } else { "D" });
    p.set_level(i, !lvl);
    crc_error_plan(lb, p, rec0)?;
    Ok(name)
}

/// The IUT (REC `rec0` before) receives frame plan `p` (made faulty by the
/// caller so that only the CRC check fails): no ACK, the CRC error at the
/// ACK delimiter, an active error flag from the first EOF bit, REC + 1.
pub fn crc_error_plan(lb: &mut LtBench, mut p: Plan, rec0: u32) -> Result<StepRecord, String> {
    let ack = p.find(Field::AckSlot, 1, false).ok_or("no ACK slot")?;
    let ad = ack + 1;
    p.expects.retain(|e| e.bit != ack);
    p.expect(ack, true, "no ACK after a CRC error");
    let r = receive_error(lb, p, ad, RxError { ev: EV_CRC_ERR, at: (Field::AckDel, 1), flag: ad + 1, rec: None }, rec0)?;
    ensure!(!r.iut().iter().any(|b| b.field == Field::AckSlot && !b.drove), "the IUT acknowledged");
    Ok(r)
}

/// The third elementary test: frame `f` (identifier 0x001) with its SOF
/// sent recessive. The IUT takes identifier bit 10 (dominant) for the SOF
/// and the recessive stuff bit after identifier bit 7 for an identifier
/// bit (it has seen four dominant bits only), which puts it back in step
/// with the LT: it receives identifier 0x081 instead of 0x001, a frame of
/// the same length whose CRC does not match.
pub fn shifted_sof(lb: &mut LtBench, f: &Frame) -> Result<(), String> {
    let mut p = Plan::frame(lb.timing, f, BuildOptions::default());
    ensure!(p.bits[0].label.is_some_and(|l| l.field == Field::Sof), "plan bit 0 is not the SOF");
    let st = p.find(Field::Ident, 4, true).ok_or("no stuff bit after Identifier 4")?;
    ensure!(p.bits[st].level && (0..st).all(|i| !p.bits[i].level), "the frame does not start with five dominant bits and a recessive stuff bit");
    p.set_level(0, true);
    let r = crc_error_plan(lb, p, 0)?;
    let sof = r.iut().iter().find(|b| b.has(EV_SOF)).copied().ok_or("no SOF")?;
    ensure!(sof.t >= r.bit_start(0, 1), "the IUT took the recessive SOF for its SOF:{}", r.dump(0));
    Ok(())
}

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_7_2_5".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let f = Frame::std(0x35C, &[0x96, 0x0E]);
    for lvl in [false, true] {
        let r = crc_error(&mut lb, &f, lvl, 0);
        let name = match &r {
            Ok(n) => n.clone(),
            Err(_) => format!("{}_inverted", if lvl { "R" } else { "D" }),
        };
        ctx.record(&format!("iso_7_2_5_{name}"), r.map(|_| ()));
    }
    let r = shifted_sof(&mut lb, &Frame::std(0x001, &[0x96, 0x0E]));
    ctx.record("iso_7_2_5_sof_recessive_id001", r);
    ctx.results
}

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::timing::BtlConfig;

    #[test]
    fn the_destuffer_model_finds_the_builders_stuff_bits() {
        for f in [Frame::std(0x078, &[0x00, 0xFF]), Frame::ext(0x07C3_0F0F, &[0x3C; 8]), Frame::std(0x35C, &[0x96, 0x0E])] {
            let p = Plan::frame(BtlConfig::T10_6_4, &f, BuildOptions::default());
            let end = p.find(Field::CrcDel, 1, false).unwrap();
            let v: Vec<bool> = p.bits[..end].iter().map(|b| b.level).collect();
            assert!(destuffs_at(&v, &p.stuff_bits()), "{f:?}");
            assert!(crc_flip(&p, false).is_some() && crc_flip(&p, true).is_some(), "{f:?}");
        }
    }
}
