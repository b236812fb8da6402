//! formerr (§8 of the plan): confinement of form errors, N2 → N1
//! (`formerr_rx_*`) and N1 → N2 (`formerr_tx_*`), all forcing at N1. The
//! steps of each part run on one frame and its retries, chained as the plan
//! orders them.
use super::*;

const D: FaultMode = FaultMode::StuckDominant;
const OL: &[usize] = &[EV_OVL, EV_OLF];
const FE: &[usize] = &[EV_FORM_ERR, EV_AEF];

/// `D!` for 16 bits right after the flag N1 is sending (from its first bit
/// after the flag): +8 at the 8th and the 16th (and `first` more at the
/// first bit). Returns the counter change.
fn sixteen_after_flag(b: &mut Bench, flag: Field, ctr: Ctr, first: i64) -> Result<(), String> {
    let c0 = b.ctr(0, ctr) as i64;
    let m = b.force_at(&[0], flag, 7, false, D, 16)?;
    let s: Vec<BitRec> = b.since(0, m)[..16].to_vec();
    let mut want = c0 + first;
    ensure!(s[0].has(EV_DAF) || first == 0, "first bit after the flag: {} (expected DAF)", s[0]);
    ensure!(s[0].tec as i64 == want || ctr == Ctr::Rec, "TEC {} at the first bit after the flag (expected {want})", s[0].tec);
    for (k, r) in s.iter().enumerate() {
        if k == 7 || k == 15 {
            want += 8;
        }
        let v = if ctr == Ctr::Tec { r.tec } else { r.rec } as i64;
        ensure!(v == want, "bit {} after the flag: {r} (expected {ctr:?} {want}):{}", k + 1, b.dump(0, m));
    }
    b.settle(0)?;
    ensure!(b.ctr(0, ctr) as i64 == want, "{ctr:?} {} after the delimiter (expected {want})", b.ctr(0, ctr));
    Ok(())
}

pub fn run(ctx: &mut Ctx) {
    let mut b = ctx.bench(vec![cfg(), cfg()], false);
    // Receiver part: one frame of N2 and its retries.
    let f = Frame::std(0x4B2, &[0x9C, 0x3D]);
    b.node_mut(1).request(f.clone());
    let rx0 = b.node(0).received().len();
    let r = b.forced_step(&[0], Field::CrcDel, 1, D, 1, FE, Ctr::Rec, 9).map(|_| ());
    ctx.record("formerr_rx_1", r);
    let r = b.forced_step(&[0], Field::AckDel, 1, D, 1, FE, Ctr::Rec, 9).map(|_| ());
    ctx.record("formerr_rx_2", r);
    let r = b.forced_step(&[0], Field::Eof, 1, D, 1, FE, Ctr::Rec, 9).map(|_| ());
    ctx.record("formerr_rx_3", r);
    let r = b.forced_step(&[0], Field::Eof, 7, D, 1, OL, Ctr::Rec, 0).and_then(|_| check_delivered(&b, 0, rx0, std::slice::from_ref(&f)));
    ctx.record("formerr_rx_4", r);
    let r = b.forced_step(&[0], Field::OvlDel, 8, D, 1, OL, Ctr::Rec, 0).map(|_| ());
    ctx.record("formerr_rx_5", r);
    let r = b.forced_step(&[0], Field::OvlDel, 2, D, 1, FE, Ctr::Rec, 9).map(|_| ());
    ctx.record("formerr_rx_6", r);
    let r = b.forced_step(&[0], Field::ErrDel, 2, D, 1, FE, Ctr::Rec, 9).map(|_| ());
    ctx.record("formerr_rx_7", r);
    let rec8 = b.rec(0);
    let r = b.forced_bit(&[0], Field::ErrDel, 8, D, 1, OL).and_then(|m| {
        ensure!(b.rec_at(0, m)?.rec == rec8, "REC changed at the overload: {}", b.rec_at(0, m)?);
        Ok(())
    });
    ctx.record("formerr_rx_8", r);
    let r = sixteen_after_flag(&mut b, Field::OvlFlag, Ctr::Rec, 0);
    ctx.record("formerr_rx_9", r);
    // rx_10: FORM_ERR +1 at Overload_Delimiter 2, then the first bit after
    // the AEF is the first of rx_11's 16 dominant bits (+8): Δ +9; rx_10 and
    // rx_11 together +25.
    let rec0 = b.rec(0) as i64;
    let r10 = (|| {
        let m = b.force_at(&[0], Field::OvlDel, 2, false, D, 1)?;
        let x = b.rec_at(0, m)?;
        ensure!(x.has(EV_FORM_ERR) && x.has(EV_AEF) && x.rec as i64 == rec0 + 1, "forced bit {x}: expected FORM_ERR, AEF, REC {}", rec0 + 1);
        Ok(())
    })();
    let r11 = if r10.is_ok() { sixteen_after_flag(&mut b, Field::ActFlag, Ctr::Rec, 8) } else { Err("rx_10 failed".into()) };
    let r10 = r10.and_then(|_| {
        let first = b.recs(0).iter().rev().find(|r| r.field == Field::ActFlag && r.pos == 7).copied().ok_or("no bit after the flag")?;
        ensure!(first.rec as i64 == rec0 + 9, "REC {} after the first bit after the flag (expected {})", first.rec, rec0 + 9);
        Ok(())
    });
    ctx.record("formerr_rx_10", r10);
    let r11 = r11.and_then(|_| {
        ensure!(b.rec(0) as i64 == rec0 + 25, "rx_10 + rx_11: REC {} (expected {})", b.rec(0), rec0 + 25);
        b.run_idle(300)
    });
    ctx.record("formerr_rx_11", r11);

    // Transmitter part: one frame of N1 and its retries.
    let _ = b.run_idle(300);
    let g = Frame::std(0x2D4, &[0x77]);
    b.node_mut(0).request(g.clone());
    let rx1 = b.node(1).received().len();
    let r = b.forced_step(&[0], Field::CrcDel, 1, D, 1, FE, Ctr::Tec, 8).map(|_| ());
    ctx.record("formerr_tx_1", r);
    let r = b.forced_step(&[0], Field::AckDel, 1, D, 1, FE, Ctr::Tec, 8).map(|_| ());
    ctx.record("formerr_tx_2", r);
    let r = b.forced_step(&[0], Field::Eof, 1, D, 1, FE, Ctr::Tec, 8).map(|_| ());
    ctx.record("formerr_tx_3", r);
    let m2 = b.mark(1);
    let m1 = b.mark(0);
    let r = b.forced_step(&[0], Field::Eof, 7, D, 1, &[EV_AEF], Ctr::Tec, 8).and_then(|_| {
        check_delivered(&b, 1, rx1, std::slice::from_ref(&g))?;
        let o = b.events(1, m2, EV_OVL);
        ensure!(!o.is_empty() && o[0].field == Field::Inter && o[0].pos == 1, "N2 did not overload at its Intermission 1:{}\n  N1:{}", b.dump(1, m2), b.dump(0, m1));
        Ok(())
    });
    ctx.record("formerr_tx_4", r);
    let r = b.forced_step(&[0], Field::ErrDel, 8, D, 1, OL, Ctr::Tec, 0).map(|_| ());
    ctx.record("formerr_tx_5", r);
    let r = b.forced_step(&[0], Field::OvlDel, 8, D, 1, OL, Ctr::Tec, 0).map(|_| ());
    ctx.record("formerr_tx_6", r);
    let r = b.forced_step(&[0], Field::OvlDel, 2, D, 1, FE, Ctr::Tec, 8).map(|_| ());
    ctx.record("formerr_tx_7", r);
    let r = b.forced_step(&[0], Field::ErrDel, 2, D, 1, FE, Ctr::Tec, 8).map(|_| ());
    ctx.record("formerr_tx_8", r);
    let r = (|| {
        let t0 = b.tec(0);
        let m = b.forced_bit(&[0], Field::ErrDel, 8, D, 1, OL)?;
        ensure!(b.rec_at(0, m)?.tec == t0, "TEC changed at the overload: {}", b.rec_at(0, m)?);
        sixteen_after_flag(&mut b, Field::OvlFlag, Ctr::Tec, 0)
    })();
    ctx.record("formerr_tx_9", r);
    // tx_10: an AEF of N1 (form error at the CRC delimiter of the retry,
    // +8), then 16 dominant bits after it: +16, no first-bit rule.
    let r = (|| {
        let t0 = b.tec(0);
        let m = b.forced_bit(&[0], Field::CrcDel, 1, D, 1, FE)?;
        ensure!(b.rec_at(0, m)?.tec == t0 + 8, "form error: {}", b.rec_at(0, m)?);
        sixteen_after_flag(&mut b, Field::ActFlag, Ctr::Tec, 0)?;
        ensure!(b.tec(0) == t0 + 24, "TEC {} (expected {})", b.tec(0), t0 + 24);
        b.run_idle(300)?;
        check_delivered(&b, 1, rx1, &[g.clone(), g.clone()])
    })();
    ctx.record("formerr_tx_10", r);
}
