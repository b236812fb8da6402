//! emlcount (§6 of the plan), **partial**: the transmitter steps after the
//! hardware reset of N1, `emlcount_tx_7` .. `emlcount_tx_15` (T10/6/2).
//! The receiver part and tx_1..6, tx_16..37 are not implemented yet.
use super::*;

const D: Interference = Interference::StuckDominant;
const R: Interference = Interference::StuckRecessive;

pub fn run(ctx: &mut Ctx) {
    let c = cfg().timing(1, 1, 4, 2);
    let mut b = ctx.bench(vec![c.clone(), c], false);
    let f = Frame::std(0x2B9, &[0x81, 0x7E]);
    b.node_mut(0).request(f.clone());
    let r = b.forced_step(&[0], Field::Sof, 1, R, 1, &[EV_BIT_ERR, EV_AEF], Ctr::Tec, 8).and_then(|_| {
        ensure!(b.tec(0) == 8, "TEC {} (expected 8)", b.tec(0));
        Ok(())
    });
    ctx.record("emlcount_tx_7", r);
    let r = b.forced_step(&[0], Field::AckDel, 1, D, 1, &[EV_AEF], Ctr::Tec, 8).map(|_| ());
    ctx.record("emlcount_tx_8", r);
    let r = b.forced_step(&[0], Field::Eof, 1, D, 1, &[EV_AEF], Ctr::Tec, 8).map(|_| ());
    ctx.record("emlcount_tx_9", r);
    let r = b.forced_step(&[0], Field::Eof, 7, D, 1, &[EV_AEF], Ctr::Tec, 8).map(|_| ());
    ctx.record("emlcount_tx_10", r);
    let r = b.forced_step(&[0], Field::ErrDel, 8, D, 14, &[EV_OVL, EV_OLF], Ctr::Tec, 0).map(|_| ());
    ctx.record("emlcount_tx_11", r);
    let r = b.forced_step(&[0], Field::OvlDel, 8, D, 15, &[EV_OVL, EV_OLF], Ctr::Tec, 8).map(|_| ());
    ctx.record("emlcount_tx_12", r);
    let r = b.forced_step(&[0], Field::OvlDel, 2, D, 1, &[EV_FORM_ERR, EV_AEF], Ctr::Tec, 8).map(|_| ());
    ctx.record("emlcount_tx_13", r);
    let r = b.forced_step(&[0], Field::ErrDel, 2, D, 1, &[EV_FORM_ERR, EV_AEF], Ctr::Tec, 8).map(|_| ());
    ctx.record("emlcount_tx_14", r);
    let r = (|| {
        let t0 = b.tec(0);
        let m = b.forced_bit(&[0], Field::AckSlot, 1, R, 1, &[EV_ACK_ERR, EV_AEF])?;
        ensure!(b.rec_at(0, m)?.tec == t0 + 8, "ACK error: {}", b.rec_at(0, m)?);
        let m2 = b.force_at(&[0], Field::ActFlag, 7, false, D, 32)?;
        let s: Vec<BitRec> = b.since(0, m2)[..32].to_vec();
        for (k, r) in s.iter().enumerate() {
            let want = t0 + 8 + 8 * ((k as u32 + 1) / 8);
            ensure!(r.tec == want, "dominant bit {} after the flag: {r} (expected TEC {want})", k + 1);
        }
        b.settle(0)?;
        ensure!(b.tec(0) == t0 + 40, "TEC {t0}→{} (expected +40)", b.tec(0));
        b.run_idle(400)
    })();
    ctx.record("emlcount_tx_15", r);
}
