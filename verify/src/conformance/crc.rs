//! crc (§4 of the plan): CRC errors and acknowledgement errors, N2 → N1
//! (`crc_rx_*`) and N1 → N2 (`crc_tx_*`, N2 made deaf with a stuck-recessive
//! override so that N1 gets no acknowledgement).
use super::*;

const D: FaultMode = FaultMode::StuckDominant;
const R: FaultMode = FaultMode::StuckRecessive;

/// Does inverting the bus bit of `f` at (field, pos, non-stuff) leave every
/// run shorter than six (so the receiver's destuffing is unchanged)?
pub(crate) fn flip_keeps_stuffing(f: &Frame, field: Field, pos: u32) -> bool {
    let bits = bus_bits(f, BuildOptions::default(), false);
    let Some(k) = bits.iter().position(|b| b.field == field && b.pos as u32 == pos && !b.stuff) else { return false };
    let end = bits.iter().position(|b| b.field == Field::CrcDel).unwrap();
    let mut lv: Vec<bool> = bits[..end].iter().map(|b| b.level).collect();
    lv[k] = !lv[k];
    // no run of 5 may now end right before a non-stuff bit, and every stuff bit must still follow a run of 5
    let mut run = 0;
    let mut last = None;
    for (j, &l) in lv.iter().enumerate() {
        // every stuff bit must still follow a run of five and differ from it
        if bits[j].stuff && (run != 5 || Some(l) == last) {
            return false;
        }
        if Some(l) == last {
            run += 1;
        } else {
            run = 1;
            last = Some(l);
        }
        if run == 5 && j + 1 < lv.len() && !bits[j + 1].stuff {
            return false;
        }
    }
    true
}

fn rx_step(b: &mut Bench, f: &Frame, field: Field, pos: u32, mode: FaultMode, exact: bool) -> Result<(), String> {
    let (rec0, tec2) = (b.rec(0), b.tec(1));
    let rx0 = b.node(0).received().len();
    b.node_mut(1).request(f.clone());
    let mr2 = b.mark(1);
    let m = b.force_at(&[0], field, pos, false, mode, 1)?;
    let _ = mr2;
    b.run_until(200, |b| b.count(0, m, EV_CRC_ERR) > 0 || b.count(0, m, EV_AEF) > 0)?;
    let s = b.since(0, m);
    let ack = s.iter().find(|r| r.field == Field::AckSlot).copied().ok_or_else(|| format!("no ACK slot:{}\n  N2:{}", b.dump(0, m), b.dump(1, mr2)))?;
    ensure!(ack.drove, "N1 acknowledged: {ack}");
    let e = b.events(0, m, EV_CRC_ERR);
    ensure!(!e.is_empty() && e[0].field == Field::AckDel && e[0].has(EV_AEF), "expected CRC_ERR with AEF at ACK_Delimiter:{}", b.dump_events(0, m));
    b.settle(0)?;
    ensure!(if exact { b.rec(0) == rec0 + 1 } else { b.rec(0) > rec0 }, "REC {rec0}→{} (expected +1{})", b.rec(0), if exact { "" } else { " or more" });
    let m2 = b.mark(1);
    ensure!(b.tec(1) == tec2 + 8 && b.count(1, 0, EV_ACK_ERR) > 0, "N2 TEC {tec2}→{} (expected an ACK error, +8)", b.tec(1));
    let rec1 = b.rec(0);
    b.run_until(300, |b| b.node(0).received().len() > rx0)?;
    b.run_idle(100)?;
    check_delivered(b, 0, rx0, std::slice::from_ref(f))?;
    ensure!(b.rec(0) == rec1 - 1, "retry received: REC {rec1}→{} (expected −1)", b.rec(0));
    ensure!(b.count(1, m2, EV_AEF) + b.count(1, m2, EV_PEF) == 0, "N2's retry failed:{}", b.dump_events(1, m2));
    Ok(())
}

pub fn run(ctx: &mut Ctx) {
    let mut b = ctx.bench(vec![cfg(), cfg()], false);
    let f = choose(false, false, |f| flip_keeps_stuffing(f, Field::Resv, 1));
    let r = rx_step(&mut b, &f, Field::Resv, 1, R, true);
    ctx.record("crc_rx_1", r);
    let g = choose(false, false, |f| level_of(f, Field::Crc, 2, false) == Some(true) && flip_keeps_stuffing(f, Field::Crc, 2));
    let r = rx_step(&mut b, &g, Field::Crc, 2, D, false);
    ctx.record("crc_rx_2", r);

    // Transmitter part.
    let h = Frame::std(0x0C5, &[0x3E, 0x81]); // Identifier 2 dominant (tx_5)
    let r = (|| {
        ensure!(b.tec(0) == 0, "TEC {} at the start", b.tec(0));
        b.set(1, R);
        b.node_mut(0).request(h.clone());
        let m = b.mark(0);
        b.run_until(200, |b| b.count(0, m, EV_ACK_ERR) > 0)?;
        let e = b.events(0, m, EV_ACK_ERR)[0];
        ensure!(e.has(EV_AEF) && e.tec == 8, "{e} (expected ACK_ERR, AEF, TEC 8)");
        b.settle(0)?;
        ensure!(b.tec(0) == 8, "TEC {}", b.tec(0));
        Ok(())
    })();
    ctx.record("crc_tx_1", r);
    let r = (|| {
        let m0 = b.mark(0);
        let m = b.force_at(&[0], Field::ActFlag, 2, false, R, 14)?;
        let a = b.events(0, m0, EV_ACK_ERR);
        ensure!(a.len() == 1 && a[0].tec == 16, "retry: ACK errors:{}", b.dump_events(0, m0));
        b.settle(0)?;
        let be = b.events(0, m, EV_BIT_ERR);
        ensure!(be.len() == 14 && b.tec(0) == 128 && b.state(0) == 1, "{} bit errors, TEC {} state {} (expected 14, 128, passive):{}", be.len(), b.tec(0), b.state(0), b.dump_events(0, m));
        ensure!(be[13].has(EV_AEF) && !be[13].has(EV_PEF), "the last flag must be active: {}", be[13]);
        Ok(())
    })();
    ctx.record("crc_tx_2", r);
    let r = (|| {
        let m = b.mark(0);
        b.run_until(300, |b| b.count(0, m, EV_ACK_ERR) > 0)?;
        b.settle(0)?;
        let susp = b.since(0, m).iter().filter(|r| r.field == Field::Suspend).count();
        ensure!(susp == 8, "{susp} suspend bits before the retry (expected 8)");
        let a = b.events(0, m, EV_ACK_ERR)[0];
        ensure!(a.has(EV_PEF) && b.count(0, m, EV_EXC1) == 1 && b.tec(0) == 128, "{a}: expected ACK_ERR, PEF, EXC1, TEC 128 (TEC {})", b.tec(0));
        Ok(())
    })();
    ctx.record("crc_tx_3", r);
    let r = (|| {
        b.set(1, FaultMode::None);
        let n = b.node(0).sent().len();
        b.run_until(300, |b| b.node(0).sent().len() > n)?;
        b.run_idle(100)?;
        ensure!((b.tec(0), b.state(0)) == (127, 0), "TEC {} state {} (expected 127, error-active)", b.tec(0), b.state(0));
        Ok(())
    })();
    ctx.record("crc_tx_4", r);
    let r = (|| {
        b.node_mut(0).request(h.clone());
        let m = b.force_at(&[0], Field::Ident, 2, false, R, 1)?;
        let x = b.rec_at(0, m)?;
        ensure!(x.has(EV_BIT_ERR) && x.has(EV_AEF) && x.tec == 135 && x.state == 1, "{x}: expected BIT_ERR, AEF, TEC 135, passive");
        b.settle(0)?;
        Ok(())
    })();
    ctx.record("crc_tx_5", r);
    let r = (|| {
        b.set(1, R);
        let m0 = b.mark(0);
        let m = b.force_at(&[0], Field::PasFlag, 7, false, D, 113)?;
        let a = b.events(0, m0, EV_ACK_ERR);
        ensure!(a.len() == 1 && a[0].has(EV_PEF) && b.count(0, m0, EV_EXC1) == 1, "retry: expected ACK_ERR, PEF, EXC1:{}", b.dump_events(0, m0));
        b.settle(0)?;
        let incs = b.since(0, m).windows(2).filter(|w| w[1].tec == w[0].tec + 8).count() + (b.rec_at(0, m)?.tec == 143) as usize;
        ensure!(b.tec(0) == 247 && incs == 14, "TEC {} after {incs} increments (expected 247, 14)", b.tec(0));
        Ok(())
    })();
    ctx.record("crc_tx_6", r);
    let r = (|| {
        let m = b.force_at(&[0], Field::PasFlag, 2, false, D, 1)?;
        ensure!(b.count(0, b.mark(0).saturating_sub(20), EV_ACK_ERR) > 0 || b.events(0, 0, EV_ACK_ERR).last().is_some(), "no ACK error");
        b.settle(0)?;
        ensure!(b.tec(0) == 255 && b.state(0) == 1, "TEC {} state {} (expected 255, passive):{}", b.tec(0), b.state(0), b.dump_events(0, m.saturating_sub(12)));
        Ok(())
    })();
    ctx.record("crc_tx_7", r);
    let r = (|| {
        let m = b.force_at(&[0], Field::PasFlag, 6, false, D, 1)?;
        b.run_bits(3);
        ensure!(b.state(0) == 2 && b.tec(0) == 263, "TEC {} state {} (expected 263, bus-off):{}", b.tec(0), b.state(0), b.dump_events(0, m.saturating_sub(12)));
        b.node_mut(0).withdraw();
        b.set(1, FaultMode::None);
        Ok(())
    })();
    ctx.record("crc_tx_8", r);
}
