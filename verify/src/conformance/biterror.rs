//! biterror (§2 of the plan): confinement of bit errors, N2 → N1
//! (`biterror_rx_*`) and N1 → N2 (`biterror_tx_*`), all forcing at N1.
//! Between the parts N1 gets a hardware reset (counters 0, integration), so
//! that the transmitter part starts error-active (after rx_9 N1 is
//! error-passive through REC, and a good reception would only bring REC
//! to 127).
use super::*;

const D: FaultMode = FaultMode::StuckDominant;
const R: FaultMode = FaultMode::StuckRecessive;
const BE_A: &[usize] = &[EV_BIT_ERR, EV_AEF];
const BE_P: &[usize] = &[EV_BIT_ERR, EV_PEF];
const OL: &[usize] = &[EV_OVL, EV_OLF];

fn frame() -> Frame {
    Frame::std(0x356, &[0xA1, 0x0B])
}

/// Let the frame in flight (a retry) complete and the bus go idle.
fn finish(b: &mut Bench) -> Result<(), String> {
    b.run_idle(400)
}

/// rx_1-type stimulus: R! at N1's ACK slot, then R! at flag bit `bit`.
fn ack_then_flag(b: &mut Bench, bit: u32) -> Result<(), String> {
    let rec0 = b.rec(0);
    let tec2 = b.tec(1);
    let m2 = b.mark(1);
    b.node_mut(1).request(frame());
    b.forced_bit(&[0], Field::AckSlot, 1, R, 1, BE_A)?;
    ensure!(b.rec(0) == rec0 + 1, "ACK bit error: REC {rec0}→{}", b.rec(0));
    b.forced_bit(&[0], Field::ActFlag, bit, R, 1, BE_A)?;
    b.settle(0)?;
    ensure!(b.rec(0) == rec0 + 9, "REC {rec0}→{} (expected +9)", b.rec(0));
    let fe = b.events(1, m2, EV_FORM_ERR);
    ensure!(!fe.is_empty() && fe[0].field == Field::AckDel && b.tec(1) == tec2 + 8, "N2: expected a form error at ACK_Delimiter, TEC +8 (TEC {tec2}→{}):{}", b.tec(1), b.dump_events(1, m2));
    Ok(())
}

/// D! at Intermission 1 (overload), then R! at overload flag bit `bit`.
fn im1_olf(b: &mut Bench, bit: u32, flag: &[usize], ctr: Ctr, delta: i64) -> Result<(), String> {
    let m = b.forced_bit(&[0], Field::Inter, 1, D, 1, OL)?;
    // (a good frame before takes its −1 at End_Of_Frame 7, just before)
    let ctr_of = |r: BitRec| if ctr == Ctr::Tec { r.tec } else { r.rec } as i64;
    let c0 = ctr_of(b.rec_at(0, m)?);
    ensure!(m > 0 && ctr_of(b.rec_at(0, m - 1)?) == c0, "the overload changed {ctr:?}");
    ensure!(b.at(0) == (Field::OvlFlag, 1), "after the overload N1 is at {:?}:{}", b.at(0), b.dump(0, m.saturating_sub(3)));
    b.forced_bit(&[0], Field::OvlFlag, bit, R, 1, flag)?;
    b.settle(0)?;
    ensure!(b.ctr(0, ctr) as i64 - c0 == delta, "{ctr:?} {c0}→{} (expected Δ {delta:+})", b.ctr(0, ctr));
    Ok(())
}

fn rx_part(ctx: &mut Ctx, b: &mut Bench) {
    let r = ack_then_flag(b, 1).and_then(|_| finish(b));
    ctx.record("biterror_rx_1", r);
    let r = ack_then_flag(b, 6).and_then(|_| finish(b));
    ctx.record("biterror_rx_2", r);
    // rx_3: after a good frame: D! at Intermission 1, R! at OLF bit 1.
    let r = (|| {
        b.node_mut(1).request(frame());
        b.run_until(300, |b| b.at(0) == (Field::Eof, 7))?;
        im1_olf(b, 1, BE_A, Ctr::Rec, 8)
    })();
    ctx.record("biterror_rx_3", r);
    let r = im1_olf(b, 6, BE_A, Ctr::Rec, 8).and_then(|_| finish(b));
    ctx.record("biterror_rx_4", r);
    // rx_5: precondition REC 40..47 when the 11 bits start: add rx_1-type
    // errors (each +9, then −1 for the good retry) while needed.
    let r = (|| {
        finish(b)?;
        while b.rec(0) + 1 < 40 {
            ack_then_flag(b, 1)?;
            finish(b)?;
        }
        ensure!((40..=47).contains(&(b.rec(0) + 1)), "precondition: REC {} + 1 not in 40..47", b.rec(0));
        b.node_mut(1).request(frame());
        b.forced_bit(&[0], Field::AckSlot, 1, R, 1, BE_A)?;
        let m = b.force_at(&[0], Field::ActFlag, 1, false, R, 11)?;
        b.settle(0)?;
        let be = b.events(0, m, EV_BIT_ERR);
        ensure!(be.len() == 11, "{} bit errors (expected 11):{}", be.len(), b.dump_events(0, m));
        ensure!(be[9].rec <= 127 && be[10].rec > 127 && be[10].state == 1, "the 11th must cross 127: {} / {}", be[9], be[10]);
        ensure!(be[10].has(EV_AEF) && !be[10].has(EV_PEF), "the flag started by the 11th must be active: {}", be[10]);
        let k = b.since(0, m).iter().position(|r| *r == be[10]).unwrap();
        let flag: Vec<BitRec> = b.since(0, m)[k + 1..k + 7].to_vec();
        ensure!(flag.iter().all(|r| r.field == Field::ActFlag && !r.drove), "active flag not completed:{}", b.dump(0, m + k));
        Ok(())
    })();
    ctx.record("biterror_rx_5", r);
    // rx_6: N2's retry: R! at the ACK slot, D! at PEF bit 1.
    let r = (|| {
        let n2 = b.node(1).sent().len();
        let rx0 = b.node(0).received().len();
        b.forced_bit(&[0], Field::AckSlot, 1, R, 1, BE_P)?;
        ensure!(b.rec(0) > 127, "REC {} (expected > 127)", b.rec(0));
        let rec = b.rec(0);
        let m = b.forced_bit(&[0], Field::PasFlag, 1, D, 1, &[])?;
        b.settle(0)?;
        ensure!(b.rec(0) == rec, "REC {rec}→{} (expected unchanged)", b.rec(0));
        ensure!(b.since(0, m).iter().filter(|r| r.field == Field::PasFlag).count() >= 7, "the D did not restart the equal-bit count:{}", b.dump(0, m));
        finish(b)?;
        ensure!(b.node(1).sent().len() == n2 + 1, "N2 did not complete its frame");
        ensure!(b.node(0).received().len() == rx0, "N1 completed a reception");
        Ok(())
    })();
    ctx.record("biterror_rx_6", r);
    let r = (|| {
        b.node_mut(1).request(frame());
        b.forced_bit(&[0], Field::AckSlot, 1, R, 1, BE_P)?;
        let rec = b.rec(0);
        let m = b.forced_bit(&[0], Field::PasFlag, 6, D, 1, &[])?;
        b.run_until(80, |b| b.at(0).0 == Field::Inter)?;
        ensure!(b.rec(0) == rec, "REC {rec}→{} (expected unchanged)", b.rec(0));
        let pf = b.since(0, m).iter().filter(|r| r.field == Field::PasFlag && r.pos >= 7).count();
        ensure!(pf >= 6, "PEF did not continue for 6 more equal bits:{}", b.dump(0, m));
        Ok(())
    })();
    ctx.record("biterror_rx_7", r);
    let r = im1_olf(b, 1, BE_P, Ctr::Rec, 0);
    ctx.record("biterror_rx_8", r);
    let r = im1_olf(b, 6, BE_P, Ctr::Rec, 0).and_then(|_| finish(b));
    ctx.record("biterror_rx_9", r);
}

/// N1 sends a frame, `f` forced at (field, pos) with `mode`: +8 and the
/// given flag; the retry then succeeds.
fn tx_simple(b: &mut Bench, f: &Frame, field: Field, pos: u32, mode: FaultMode, flag: &[usize]) -> Result<(), String> {
    b.node_mut(0).request(f.clone());
    b.forced_step(&[0], field, pos, mode, 1, flag, Ctr::Tec, 8)?;
    finish(b)
}

fn tx_part(ctx: &mut Ctx, b: &mut Bench) {
    let f = frame();
    let r = (|| {
        let m2 = b.mark(1);
        let rec2 = b.rec(1);
        b.node_mut(0).request(f.clone());
        b.forced_step(&[0], Field::Sof, 1, R, 1, BE_A, Ctr::Tec, 8)?;
        let se = b.events(1, m2, EV_STUFF_ERR);
        ensure!(se.len() == 1 && b.rec(1) == rec2 + 1, "N2: expected a stuff error, REC +1:{}", b.dump_events(1, m2));
        finish(b)
    })();
    ctx.record("biterror_tx_1", r);
    let r = (|| {
        b.node_mut(0).request(f.clone());
        let t0 = b.tec(0);
        b.forced_bit(&[0], Field::Resv, 1, R, 1, BE_A)?;
        b.forced_step(&[0], Field::ActFlag, 1, R, 1, BE_A, Ctr::Tec, 8)?;
        ensure!(b.tec(0) == t0 + 16, "TEC {t0}→{} (expected +16)", b.tec(0));
        finish(b)
    })();
    ctx.record("biterror_tx_2", r);
    let r = (|| {
        b.node_mut(0).request(f.clone());
        let t0 = b.tec(0);
        b.forced_bit(&[0], Field::Sof, 1, R, 1, BE_A)?;
        b.forced_step(&[0], Field::ActFlag, 6, R, 1, BE_A, Ctr::Tec, 8)?;
        ensure!(b.tec(0) == t0 + 16, "TEC {t0}→{} (expected +16)", b.tec(0));
        finish(b)
    })();
    ctx.record("biterror_tx_3", r);
    let r = (|| {
        b.node_mut(0).request(f.clone());
        b.run_until(300, |b| b.at(0) == (Field::Eof, 7))?;
        im1_olf(b, 1, BE_A, Ctr::Tec, 8)
    })();
    ctx.record("biterror_tx_4", r);
    let r = im1_olf(b, 6, BE_A, Ctr::Tec, 8).and_then(|_| finish(b));
    ctx.record("biterror_tx_5", r);
    let lv = level_of;
    let f6 = choose(false, false, |f| f.dlc >= 8);
    let f7 = choose(false, false, |f| f.dlc % 2 == 0);
    let f8 = choose(false, false, |f| !f.data.is_empty() && f.data[0] >= 0x80);
    let f9 = choose(false, false, |f| !f.data.is_empty() && f.data[0] % 2 == 0);
    let f10 = choose(false, false, |f| lv(f, Field::Crc, 1, false) == Some(true));
    let f11 = choose(false, false, |f| lv(f, Field::Crc, 15, false) == Some(false));
    let six: [(&Frame, Field, u32, FaultMode); 6] =
        [(&f6, Field::Dlc, 1, D), (&f7, Field::Dlc, 4, R), (&f8, Field::Data, 1, D), (&f9, Field::Data, 8, R), (&f10, Field::Crc, 1, D), (&f11, Field::Crc, 15, R)];
    for (k, (ff, field, pos, mode)) in six.iter().enumerate() {
        let r = tx_simple(b, ff, *field, *pos, *mode, BE_A);
        ctx.record(&format!("biterror_tx_{}", k + 6), r);
    }
    // tx_12: precondition TEC 104..111 when the 3 bits start; the flag is
    // started by an R! at SOF (+8). Adjust with SOF errors (+7 with the
    // good retry) or good frames (−1).
    let r = (|| {
        while b.tec(0) + 8 < 104 {
            tx_simple(b, &f, Field::Sof, 1, R, BE_A)?;
        }
        while b.tec(0) + 8 > 111 {
            let n = b.node(0).sent().len();
            b.node_mut(0).request(f.clone());
            b.run_until(300, |b| b.node(0).sent().len() > n)?;
            finish(b)?;
        }
        b.node_mut(0).request(f.clone());
        b.forced_bit(&[0], Field::Sof, 1, R, 1, BE_A)?;
        let t0 = b.tec(0);
        let m = b.force_at(&[0], Field::ActFlag, 1, false, R, 3)?;
        b.settle(0)?;
        let be = b.events(0, m, EV_BIT_ERR);
        ensure!(be.len() == 3 && b.tec(0) == t0 + 24, "{} bit errors, TEC {t0}→{} (expected 3, +24)", be.len(), b.tec(0));
        ensure!(be[2].state == 1 && be[1].state == 0 && be[2].has(EV_AEF), "the 3rd must make N1 passive with an active flag: {} / {}", be[1], be[2]);
        let k = b.since(0, m).iter().position(|r| *r == be[2]).unwrap();
        ensure!(b.since(0, m)[k + 1..k + 7].iter().all(|r| r.field == Field::ActFlag && !r.drove), "active flag not completed:{}", b.dump(0, m));
        finish(b)
    })();
    ctx.record("biterror_tx_12", r);
    let r = (|| {
        b.node_mut(0).request(f.clone());
        let m = b.mark(0);
        b.forced_step(&[0], Field::Sof, 1, R, 1, BE_P, Ctr::Tec, 8)?;
        b.run_until(60, |b| b.count(0, m + 1, EV_SOF) > 0)?;
        let susp = b.since(0, m).iter().filter(|r| r.field == Field::Suspend).count();
        ensure!(susp == 8, "{susp} suspend bits before the retry (expected 8)");
        finish(b)
    })();
    ctx.record("biterror_tx_13", r);
    let r = (|| {
        b.node_mut(0).request(f.clone());
        let t0 = b.tec(0);
        b.forced_bit(&[0], Field::Resv, 1, R, 1, BE_P)?;
        b.forced_step(&[0], Field::PasFlag, 1, D, 1, &[], Ctr::Tec, 0)?;
        ensure!(b.tec(0) == t0 + 8, "TEC {t0}→{} (expected +8)", b.tec(0));
        finish(b)
    })();
    ctx.record("biterror_tx_14", r);
    let r = (|| {
        b.node_mut(0).request(f.clone());
        let t0 = b.tec(0);
        b.forced_bit(&[0], Field::Resv, 1, R, 1, BE_P)?;
        let m = b.forced_step(&[0], Field::PasFlag, 6, D, 1, &[], Ctr::Tec, 0)?;
        ensure!(b.tec(0) == t0 + 8, "TEC {t0}→{} (expected +8)", b.tec(0));
        ensure!(b.since(0, m).iter().filter(|r| r.field == Field::PasFlag && r.pos >= 7).count() >= 6, "count not restarted:{}", b.dump(0, m));
        finish(b)
    })();
    ctx.record("biterror_tx_15", r);
    let r = (|| {
        b.node_mut(0).request(f.clone());
        b.run_until(300, |b| b.at(0) == (Field::Eof, 7))?;
        im1_olf(b, 1, BE_P, Ctr::Tec, 8)
    })();
    ctx.record("biterror_tx_16", r);
    let r = im1_olf(b, 6, BE_P, Ctr::Tec, 8).and_then(|_| finish(b));
    ctx.record("biterror_tx_17", r);
    for (k, (ff, field, pos, mode)) in six.iter().enumerate() {
        let r = tx_simple(b, ff, *field, *pos, *mode, BE_P).and_then(|_| {
            ensure!(b.state(0) == 1, "N1 not error-passive (state {})", b.state(0));
            Ok(())
        });
        ctx.record(&format!("biterror_tx_{}", k + 18), r);
    }
}

pub fn run(ctx: &mut Ctx) {
    let mut b = ctx.bench(vec![cfg(), cfg()], false);
    rx_part(ctx, &mut b);
    b.node_mut(0).hard_reset();
    let _ = b.run_until(60, |b| b.at(0).0 == Field::Idle && !b.node(0).pending() && b.tec(0) == 0);
    b.run_bits(15);
    tx_part(ctx, &mut b);
}
