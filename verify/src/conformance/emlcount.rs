//! emlcount (§6 of the plan, T10/6/2): the receiver steps
//! `emlcount_rx_1` .. `emlcount_rx_20`, then the transmitter steps
//! `emlcount_tx_1` .. `emlcount_tx_6` on the counters rx_20 left (N1
//! error-passive through REC 128, TEC 0), the plan's hardware reset of N1,
//! and `emlcount_tx_7` .. `emlcount_tx_37`.
//!
//! tx_1..tx_6 need N2's retry withdrawn at rx_20 (a received retry would
//! make N1 error-active before tx_1), and N1's retries (and in tx_5 N2's) withdrawn where the
//! manual's counter values leave no room for a successful retry: after
//! tx_2 (TEC 120 must meet tx_4's +8 as 128), after tx_4 (TEC 128 until
//! tx_6's good frame) and N2's after tx_5 (a received retry would take REC
//! from 135 to 127 before tx_6).
use super::*;

const D: FaultMode = FaultMode::StuckDominant;
const R: FaultMode = FaultMode::StuckRecessive;

/// Move the R→D edge at the start of N1's bit (field, pos) by `d` TQ
/// (positive: later, by reading `R` for d TQ; negative: earlier, by reading
/// `D` for the last |d| TQ of the bit before).
fn move_edge(b: &mut Bench, field: Field, pos: u32, d: i64) -> Result<(), String> {
    let tq = CLOCK_PS as i64;
    if d > 0 {
        b.wait_for(0, field, pos, false, 300)?;
        let t = b.recs(0).last().unwrap().t + b.ph2_rest_ps(0);
        b.run_until_time(t);
        b.set(0, R);
        b.run_until_time((t as i64 + d * tq) as u64);
    } else {
        b.wait_for(0, field, pos - 1, false, 300)?;
        let t = b.recs(0).last().unwrap().t + b.ph2_rest_ps(0);
        let ntq = b.node(0).config().timing.ntq() as i64;
        b.run_until_time((t as i64 + (ntq + d) * tq) as u64);
        b.set(0, D);
        b.run_until_time((t as i64 + ntq * tq) as u64);
    }
    b.set(0, FaultMode::None);
    Ok(())
}

fn rx_part(ctx: &mut Ctx, b: &mut Bench) {
    let f1 = choose(false, false, |f| (f.id >> 7) == 0 && level_of(f, Field::Ident, 4, true) == Some(true));
    let r = (|| {
        b.node_mut(1).request(f1.clone());
        let m = b.force_at(&[0], Field::Ident, 4, true, D, 1)?;
        let x = b.rec_at(0, m)?;
        ensure!(x.has(EV_STUFF_ERR) && x.has(EV_AEF) && x.stuff, "{x}: expected STUFF_ERR, AEF at the stuff bit");
        b.settle(0)?;
        rec_is(b, 9)?;
        b.run_idle(400)?;
        rec_is(b, 8)
    })();
    ctx.record("emlcount_rx_1", r);
    // Data 0x55: R→D edges at Data_Field 3, 5, 7, ... (R at even positions).
    let f2 = Frame::std(0x2A7, &[0x55, 0x55, 0x55, 0x55]);
    let r = (|| {
        let m = b.mark(0);
        b.node_mut(1).request(f2.clone());
        for (k, d) in [1i64, 2, 3, -1, -2, -3].iter().enumerate() {
            move_edge(b, Field::Data, 3 + 4 * k as u32, *d)?;
        }
        b.forced_bit(&[0], Field::CrcDel, 1, D, 1, &[EV_FORM_ERR, EV_AEF])?;
        let first = b.since(0, m).iter().position(|r| r.has(EV_AEF)).unwrap();
        ensure!(b.since(0, m)[..first].iter().all(|r| r.ev & ((1 << EV_BIT_ERR) | (1 << EV_STUFF_ERR) | (1 << EV_FORM_ERR)) == 0), "error before CRC_Delimiter");
        b.settle(0)?;
        rec_is(b, 17)
    })();
    ctx.record("emlcount_rx_2", r);
    let r = b.forced_step(&[0], Field::AckSlot, 1, R, 1, &[EV_BIT_ERR, EV_AEF], Ctr::Rec, 9).and_then(|_| rec_is(b, 26));
    ctx.record("emlcount_rx_3", r);
    let r = (|| {
        let rx0 = b.node(0).received().len();
        b.forced_step(&[0], Field::Eof, 7, D, 14, &[EV_OVL, EV_OLF], Ctr::Rec, 0)?;
        check_delivered(b, 0, rx0, std::slice::from_ref(&f2))?;
        rec_is(b, 26)
    })();
    ctx.record("emlcount_rx_4", r);
    // (no settling: rx_6 forces the first bit of this overload flag)
    let r = b.forced_bit(&[0], Field::OvlDel, 8, D, 1, &[EV_OVL, EV_OLF]).and_then(|_| rec_is(b, 26));
    ctx.record("emlcount_rx_5", r);
    let r = (|| {
        b.forced_bit(&[0], Field::OvlFlag, 1, R, 1, &[EV_BIT_ERR, EV_AEF])?;
        let m = b.force_at(&[0], Field::ActFlag, 1, false, R, 9)?;
        b.settle(0)?;
        ensure!(b.count(0, m, EV_BIT_ERR) == 9, "bit errors:{}", b.dump_events(0, m));
        rec_is(b, 106)
    })();
    ctx.record("emlcount_rx_6", r);
    let fg = Frame::std(0x3C1, &[0x42]);
    for (k, want) in [(7, 105), (8, 104), (9, 103)] {
        let r = (|| {
            b.run_idle(400)?;
            b.node_mut(1).request(fg.clone());
            b.run_bits(5);
            b.run_idle(400)?;
            rec_is(b, want)
        })();
        ctx.record(&format!("emlcount_rx_{k}"), r);
    }
    let r = (|| {
        let rx0 = b.node(0).received().len();
        b.node_mut(1).request(fg.clone());
        let m = b.forced_step(&[0], Field::Eof, 7, D, 39, &[EV_OVL, EV_OLF], Ctr::Rec, 32)?;
        check_delivered(b, 0, rx0, std::slice::from_ref(&fg))?;
        let ep = b.since(0, m).iter().position(|r| r.state == 1).ok_or("never error-passive")?;
        let s = b.since(0, m);
        ensure!(ep > 0 && s[ep].rec == 135 && s[ep - 1].rec == 127, "TO_EP not at the 4th increment: {} after {}", s[ep], s[ep.max(1) - 1]);
        rec_is(b, 135)
    })();
    ctx.record("emlcount_rx_10", r);
    let r = (|| {
        b.forced_bit(&[0], Field::OvlDel, 3, D, 1, &[EV_FORM_ERR, EV_PEF])?;
        ensure!(b.rec(0) > 127, "REC {}", b.rec(0));
        b.force_at(&[0], Field::PasFlag, 7, false, D, 16)?;
        b.settle(0)?;
        rec_is(b, 135)
    })();
    ctx.record("emlcount_rx_11", r);
    let r = (|| {
        b.run_idle(400)?;
        b.node_mut(1).request(fg.clone());
        b.run_bits(5);
        b.run_idle(400)?;
        rec_is(b, 127)
    })();
    ctx.record("emlcount_rx_12", r);
    let r = if b.state(0) == 0 { Ok(()) } else { Err(format!("state {} after the good frame (expected error-active)", b.state(0))) };
    ctx.record("emlcount_rx_13", r);
    let r = (|| {
        b.node_mut(1).request(fg.clone());
        b.run_bits(5);
        b.run_until(300, |b| b.at(0) == (Field::Inter, 1))?;
        rec_is(b, 126)
    })();
    ctx.record("emlcount_rx_14", r);
    let r = (|| {
        b.forced_bit(&[0], Field::Inter, 1, D, 1, &[EV_OVL, EV_OLF])?;
        let m = b.forced_bit(&[0], Field::OvlFlag, 1, R, 1, &[EV_BIT_ERR, EV_AEF])?;
        let x = b.rec_at(0, m)?;
        ensure!(x.rec == 134 && x.state == 1, "{x}: expected REC 134, error-passive, flag active");
        b.forced_bit(&[0], Field::ActFlag, 1, R, 1, &[EV_BIT_ERR, EV_PEF])?;
        b.settle(0)?;
        rec_is(b, 134)
    })();
    ctx.record("emlcount_rx_15", r);
    let r = (|| {
        b.run_idle(400)?;
        b.node_mut(1).request(fg.clone());
        b.run_bits(5);
        b.run_idle(400)?;
        rec_is(b, 127)?;
        ensure!(b.state(0) == 0, "state {}", b.state(0));
        Ok(())
    })();
    ctx.record("emlcount_rx_16", r);
    let fc = choose(false, false, |f| super::crc::flip_keeps_stuffing(f, Field::Crc, 5));
    let r = (|| {
        let m = b.mark(0);
        b.node_mut(1).request(fc.clone());
        b.force_at(&[0], Field::Crc, 5, false, FaultMode::Invert, 1)?;
        b.wait_for(0, Field::AckSlot, 1, false, 30)?;
        ensure!(b.since(0, m).iter().all(|r| r.ev & ((1 << EV_AEF) | (1 << EV_PEF)) == 0), "error before the ACK slot:{}", b.dump_events(0, m));
        Ok(())
    })();
    ctx.record("emlcount_rx_17", r);
    let m2 = b.mark(1);
    let r = (|| {
        let rec0 = b.rec(0);
        let m = b.forced_bit(&[0], Field::AckSlot, 1, D, 1, &[])?;
        let x = b.rec_at(0, m)?;
        ensure!(x.drove && x.rec == rec0, "{x}: N1 must not acknowledge, REC unchanged");
        b.run_bits(2);
        let a = b.events(1, m2, EV_ACK_ERR);
        ensure!(a.len() == 1 && a[0].has(EV_AEF), "N2: expected ACK_ERR, AEF:{}", b.dump_events(1, m2));
        Ok(())
    })();
    ctx.record("emlcount_rx_18", r);
    let r = (|| {
        let c = b.recs(0).iter().rev().find(|r| r.has(EV_CRC_ERR)).copied().ok_or("no CRC error")?;
        ensure!(c.field == Field::AckDel && c.has(EV_AEF) && c.rec == 128 && c.state == 1, "{c}: expected CRC_ERR, AEF at ACK_Delimiter, REC 128, TO_EP");
        Ok(())
    })();
    ctx.record("emlcount_rx_19", r);
    let r = (|| {
        b.forced_bit(&[0], Field::ActFlag, 3, R, 1, &[EV_BIT_ERR, EV_PEF])?;
        // (N2's retry is withdrawn: tx_1 starts with N1 passive through REC)
        b.node_mut(1).withdraw();
        b.settle(0)?;
        rec_is(b, 128)?;
        b.run_idle(400)?;
        rec_is(b, 128)
    })();
    ctx.record("emlcount_rx_20", r);
}

pub fn run(ctx: &mut Ctx) {
    let c = cfg().timing(1, 1, 4, 2);
    let mut b = ctx.bench(vec![c.clone(), c], false);
    rx_part(ctx, &mut b);
    tx_1_to_6(ctx, &mut b);
    // The plan's hardware reset of N1.
    b.node_mut(0).withdraw();
    b.node_mut(0).hard_reset();
    b.run_bits(2);
    let _ = b.run_until(60, |b| b.node(0).field() == Field::Idle);
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

    tx_16_on(ctx, &mut b, &f);
}

/// Run until node 0 has completed a passive error flag (6 consecutive equal
/// levels sampled, counted from the first flag bit; the records since mark
/// `m` must start at or before the flag), then force it `D` for `k` bits
/// from the first bit after the flag. Returns the mark of that bit.
fn force_after_pef(b: &mut Bench, m: usize, k: u64) -> Result<usize, String> {
    b.run_until(200, |b| {
        let s = b.since(0, m);
        let Some(start) = s.iter().position(|r| r.field == Field::PasFlag) else { return false };
        let flag = &s[start..];
        let mut run = 0;
        let mut last = None;
        for r in flag {
            run = if Some(r.level) == last { run + 1 } else { 1 };
            last = Some(r.level);
            if run >= 6 {
                return true;
            }
        }
        false
    })
    .map_err(|e| format!("passive flag not complete: {e}:{}", b.dump(0, m)))?;
    let t = b.recs(0).last().unwrap().t + b.ph2_rest_ps(0);
    b.run_until_time(t);
    let m2 = b.mark(0);
    b.force_now(&[0], D, k);
    b.run_until(2, |b| b.mark(0) >= m2 + k as usize)?;
    Ok(m2)
}

/// tx_1..tx_6 (see the module documentation). `f`: ID 0x2B9, Identifier 3 `D`.
fn tx_1_to_6(ctx: &mut Ctx, b: &mut Bench) {
    let f = Frame::std(0x2B9, &[0x81, 0x7E]);
    debug_assert_eq!(level_of(&f, Field::Ident, 3, false), Some(false));
    let r = (|| {
        b.run_idle(400)?;
        ensure!(b.state(0) == 1 && b.rec(0) > 127 && b.tec(0) < 128, "precondition: passive through REC, TEC < 128; TEC {} REC {} state {}", b.tec(0), b.rec(0), b.state(0));
        let t0 = b.tec(0);
        b.node_mut(0).request(f.clone());
        let m = b.forced_step(&[0], Field::Ident, 3, R, 1, BE_P, Ctr::Tec, 8)?;
        tec_is(b, t0 + 8, 1)?;
        // The retry: Intermission, 8 bits of Suspend_Transmission, then SOF.
        b.run_until(60, |b| b.at(0) == (Field::Sof, 1))?;
        let s = b.since(0, m);
        let inter: Vec<u32> = s.iter().filter(|r| r.field == Field::Inter).map(|r| r.pos).collect();
        let susp: Vec<u32> = s.iter().filter(|r| r.field == Field::Suspend).map(|r| r.pos).collect();
        ensure!(inter == [1, 2, 3] && susp == (1..=8).collect::<Vec<_>>(), "before the retry: Intermission {inter:?}, Suspend {susp:?}:{}", b.dump(0, m));
        ensure!(s.iter().all(|r| r.field != Field::Idle), "N1 went through Bus_Idle before the retry");
        Ok(())
    })();
    ctx.record("emlcount_tx_1", r);
    let r = (|| {
        let m = b.forced_bit(&[0], Field::Ident, 3, R, 1, BE_P)?;
        // (the host withdraws the retry: tx_4 needs TEC 120 + 8)
        b.node_mut(0).withdraw();
        tec_is(b, 16, 1)?;
        let m2 = force_after_pef(b, m, 104)?;
        let s: Vec<BitRec> = b.since(0, m2)[..104].to_vec();
        for (k, r) in s.iter().enumerate() {
            let want = 16 + 8 * ((k as u32 + 1) / 8);
            ensure!(!r.level && r.tec == want, "dominant bit {} after the flag: {r} (expected TEC {want})", k + 1);
        }
        b.settle(0)?;
        b.run_idle(400)?;
        tec_is(b, 120, 1)
    })();
    ctx.record("emlcount_tx_2", r);
    let fg = Frame::std(0x3C1, &[0x42]);
    let r = (|| {
        ensure!(b.rec(0) == 128, "REC {} before the good frames (expected 128)", b.rec(0));
        for k in 0..18 {
            let n = b.node(0).received().len();
            b.node_mut(1).request(fg.clone());
            b.run_until(400, |b| b.node(0).received().len() > n)?;
            b.run_idle(200)?;
            let want = 127 - k;
            ensure!(b.rec(0) == want, "after good frame {}: REC {} (expected {want})", k + 1, b.rec(0));
            ensure!(b.state(0) == 0, "after good frame {}: state {} (expected error-active)", k + 1, b.state(0));
        }
        ensure!(b.tec(0) == 120, "TEC {}", b.tec(0));
        Ok(())
    })();
    ctx.record("emlcount_tx_3", r);
    let r = (|| {
        b.node_mut(0).request(f.clone());
        b.forced_bit(&[0], Field::Ident, 3, R, 1, BE_A)?;
        // (withdrawn: TEC must stay 128 until tx_6's good frame)
        b.node_mut(0).withdraw();
        b.settle(0)?;
        b.run_idle(400)?;
        tec_is(b, 128, 1)
    })();
    ctx.record("emlcount_tx_4", r);
    let f1 = choose(false, false, |f| (f.id >> 7) == 0 && level_of(f, Field::Ident, 4, true) == Some(true));
    let r = (|| {
        ensure!(b.rec(0) == 110, "REC {} before the step (expected 110)", b.rec(0));
        b.node_mut(1).request(f1.clone());
        let m = b.force_at(&[0], Field::Ident, 4, true, D, 1)?;
        // (N2's retry withdrawn: its reception would take REC to 127)
        b.node_mut(1).withdraw();
        let x = b.rec_at(0, m)?;
        ensure!(x.has(EV_STUFF_ERR) && x.has(EV_PEF) && x.rec == 111, "{x}: expected STUFF_ERR, PEF, REC 111");
        let m2 = force_after_pef(b, m, 16)?;
        let s: Vec<BitRec> = b.since(0, m2)[..16].to_vec();
        for (k, want) in [(0usize, 119u32), (6, 119), (7, 127), (14, 127), (15, 135)] {
            ensure!(s[k].rec == want, "dominant bit {} after the flag: {} (expected REC {want})", k + 1, s[k]);
        }
        b.settle(0)?;
        b.run_idle(400)?;
        rec_is(b, 135)?;
        tec_is(b, 128, 1)
    })();
    ctx.record("emlcount_tx_5", r);
    let r = (|| {
        good(b, &f)?;
        tec_is(b, 127, 1)?;
        rec_is(b, 135)?;
        b.node_mut(0).request(f.clone());
        b.forced_step(&[0], Field::Ident, 3, R, 1, BE_P, Ctr::Tec, 8)?;
        tec_is(b, 135, 1)
    })();
    ctx.record("emlcount_tx_6", r);
}

const BE_A: &[usize] = &[EV_BIT_ERR, EV_AEF];
const BE_P: &[usize] = &[EV_BIT_ERR, EV_PEF];
const OL: &[usize] = &[EV_OVL, EV_OLF];

fn good(b: &mut Bench, f: &Frame) -> Result<(), String> {
    let n = b.node(0).sent().len();
    b.node_mut(0).request(f.clone());
    b.run_until(400, |b| b.node(0).sent().len() > n)?;
    b.run_idle(200)
}

fn tec_is(b: &Bench, want: u32, state: u32) -> Result<(), String> {
    ensure!((b.tec(0), b.state(0)) == (want, state), "TEC {} state {} (expected {want}, state {state})", b.tec(0), b.state(0));
    Ok(())
}

fn tx_16_on(ctx: &mut Ctx, b: &mut Bench, f: &Frame) {
    // Precondition of tx_16: TEC 103 after the good frame whose
    // Intermission 2 is forced, i.e. 104 before it: withdrawn SOF errors
    // (+8) and good frames (−1).
    let r = (|| {
        let mut guard = 0;
        while b.tec(0) != 104 && guard < 40 {
            guard += 1;
            if b.tec(0) < 104 {
                b.node_mut(0).request(f.clone());
                let m = b.force_at(&[0], Field::Sof, 1, false, R, 1);
                b.node_mut(0).withdraw();
                m?;
                b.run_idle(200)?;
            } else {
                good(b, f)?;
            }
        }
        b.node_mut(0).request(f.clone());
        b.run_until(300, |b| b.at(0) == (Field::Eof, 7))?;
        let m = b.forced_bit(&[0], Field::Inter, 2, D, 1, OL)?;
        ensure!(b.rec_at(0, m)?.tec == 103, "TEC {} at the start (expected 103)", b.rec_at(0, m)?.tec);
        b.forced_bit(&[0], Field::OvlFlag, 1, R, 1, BE_A)?;
        let m3 = b.force_at(&[0], Field::ActFlag, 1, false, R, 3)?;
        b.settle(0)?;
        let be = b.events(0, m3, EV_BIT_ERR);
        ensure!(be.len() == 3 && be[2].has(EV_AEF) && be[2].state == 1 && be[1].state == 0, "3 bit errors in the flags, the last active and making N1 passive:{}", b.dump_events(0, m3));
        tec_is(b, 135, 1)
    })();
    ctx.record("emlcount_tx_16", r);
    let r = (|| {
        for _ in 0..7 {
            good(b, f)?;
        }
        tec_is(b, 128, 1)
    })();
    ctx.record("emlcount_tx_17", r);
    let g = choose(false, false, |f| level_of(f, Field::Ident, 9, true) == Some(true));
    let r = (|| {
        b.node_mut(0).request(g.clone());
        b.force_at(&[0], Field::Ident, 9, true, D, 1).and_then(|m| {
            let x = b.rec_at(0, m)?;
            ensure!(x.has(EV_STUFF_ERR) && x.has(EV_PEF) && x.has(EV_EXC2), "{x}: expected STUFF_ERR, PEF, EXC2");
            Ok(())
        })?;
        b.settle(0)?;
        tec_is(b, 128, 1)
    })();
    ctx.record("emlcount_tx_18", r);
    let r = b.run_idle(400).and_then(|_| tec_is(b, 127, 0));
    ctx.record("emlcount_tx_19", r);
    let r = (|| {
        b.node_mut(0).request(f.clone());
        b.forced_step(&[0], Field::Sof, 1, R, 1, BE_A, Ctr::Tec, 8)?;
        tec_is(b, 135, 1)
    })();
    ctx.record("emlcount_tx_20", r);
    let r = b.forced_step(&[0], Field::Sof, 1, R, 1, BE_P, Ctr::Tec, 8).and_then(|_| tec_is(b, 143, 1));
    ctx.record("emlcount_tx_21", r);
    let r = b.forced_step(&[0], Field::AckDel, 1, D, 1, &[EV_PEF], Ctr::Tec, 8).and_then(|_| tec_is(b, 151, 1));
    ctx.record("emlcount_tx_22", r);
    let r = b.forced_step(&[0], Field::Eof, 1, D, 7, &[EV_PEF], Ctr::Tec, 8).and_then(|_| tec_is(b, 159, 1));
    ctx.record("emlcount_tx_23", r);
    let r = (|| {
        b.forced_bit(&[0], Field::Eof, 7, D, 1, &[EV_PEF])?;
        let m = b.forced_step(&[0], Field::PasFlag, 3, D, 1, &[], Ctr::Tec, 0)?;
        ensure!(b.since(0, m).iter().filter(|r| r.field == Field::PasFlag && r.pos >= 7).count() >= 4, "equal-bit count not restarted:{}", b.dump(0, m));
        tec_is(b, 167, 1)
    })();
    ctx.record("emlcount_tx_24", r);
    let r = b.forced_step(&[0], Field::ErrDel, 8, D, 14, OL, Ctr::Tec, 0).and_then(|_| tec_is(b, 167, 1));
    ctx.record("emlcount_tx_25", r);
    let r = b.forced_step(&[0], Field::OvlDel, 8, D, 15, OL, Ctr::Tec, 8).and_then(|_| tec_is(b, 175, 1));
    ctx.record("emlcount_tx_26", r);
    let r = b.forced_step(&[0], Field::OvlDel, 2, D, 1, &[EV_FORM_ERR, EV_PEF], Ctr::Tec, 8).and_then(|_| tec_is(b, 183, 1));
    ctx.record("emlcount_tx_27", r);
    let r = (|| {
        let m = b.forced_bit(&[0], Field::AckSlot, 1, R, 1, &[EV_ACK_ERR, EV_PEF])?;
        b.settle(0)?;
        ensure!(b.count(0, m, EV_EXC1) == 1, "no EXC1:{}", b.dump_events(0, m));
        tec_is(b, 183, 1)
    })();
    ctx.record("emlcount_tx_28", r);
    let r = (|| {
        b.forced_bit(&[0], Field::ErrDel, 2, D, 1, &[EV_FORM_ERR, EV_PEF])?;
        ensure!(b.tec(0) == 191, "TEC {} after the form error (expected 191)", b.tec(0));
        b.force_at(&[0], Field::PasFlag, 7, false, D, 64)?;
        b.settle(0)?;
        tec_is(b, 255, 1)
    })();
    ctx.record("emlcount_tx_29", r);
    let r = b.forced_step(&[0], Field::ErrDel, 8, D, 1, OL, Ctr::Tec, 0).and_then(|_| tec_is(b, 255, 1));
    ctx.record("emlcount_tx_30", r);

    tx_31_on(ctx, b);
}

fn rec_is(b: &Bench, want: u32) -> Result<(), String> {
    ensure!(b.rec(0) == want, "REC {} (expected {want})", b.rec(0));
    Ok(())
}

fn tx_31_on(ctx: &mut Ctx, b: &mut Bench) {
    let r = (|| {
        let m = b.force_at(&[0], Field::Inter, 3, false, D, 6)?;
        let x = b.rec_at(0, m)?;
        ensure!(x.has(EV_SOF), "{x}: expected SOF");
        let s: Vec<BitRec> = b.since(0, m)[1..6].to_vec();
        ensure!(s.iter().all(|r| !r.tx_role), "N1 did not become a receiver:{}", b.dump(0, m));
        let e = b.events(0, m, EV_STUFF_ERR);
        ensure!(e.len() == 1 && e[0].has(EV_PEF) && b.since(0, m).iter().position(|r| r.has(EV_STUFF_ERR)) == Some(5), "expected STUFF_ERR, PEF at the 6th dominant bit:{}", b.dump_events(0, m));
        rec_is(b, 1)
    })();
    ctx.record("emlcount_tx_31", r);
    let r = b.forced_step(&[0], Field::PasFlag, 7, D, 1, &[EV_DAF], Ctr::Rec, 8).and_then(|_| rec_is(b, 9));
    ctx.record("emlcount_tx_32", r);
    // (no settling: tx_34 forces the first bit after this flag)
    let r = b.forced_bit(&[0], Field::ErrDel, 4, D, 1, &[EV_FORM_ERR, EV_PEF]).and_then(|m| {
        ensure!(b.rec_at(0, m)?.rec == 10, "{}: expected REC 10", b.rec_at(0, m)?);
        Ok(())
    });
    ctx.record("emlcount_tx_33", r);
    let r = b.forced_step(&[0], Field::PasFlag, 7, D, 1, &[EV_DAF], Ctr::Rec, 8).and_then(|_| rec_is(b, 18));
    ctx.record("emlcount_tx_34", r);
    let r = (|| {
        let m = b.forced_step(&[0], Field::ErrDel, 2, D, 8, &[EV_FORM_ERR, EV_PEF], Ctr::Rec, 9)?;
        rec_is(b, 27)?;
        let n = b.node(0).sent().len();
        b.run_until(400, |b| b.node(0).sent().len() > n)?;
        let s = b.since(0, m);
        let k = s.iter().rposition(|r| r.has(EV_SOF)).unwrap_or(0);
        ensure!(s[..k].iter().all(|r| r.field != Field::Suspend), "suspend before the retry:{}", b.dump(0, m));
        tec_is(b, 254, 1)
    })();
    ctx.record("emlcount_tx_35", r);
    let r = b.forced_bit(&[0], Field::Inter, 1, D, 1, OL).and_then(|_| tec_is(b, 254, 1));
    ctx.record("emlcount_tx_36", r);
    let r = (|| {
        let m = b.forced_bit(&[0], Field::OvlFlag, 2, R, 1, &[EV_BIT_ERR])?;
        ensure!(b.rec_at(0, m)?.tec == 262 && b.rec_at(0, m)?.state == 2, "{}: expected TEC 262, bus-off", b.rec_at(0, m)?);
        Ok(())
    })();
    ctx.record("emlcount_tx_37", r);
}

