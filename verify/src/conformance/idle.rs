//! idle (§9 of the plan): reset and bus-off recovery sequences of a single
//! node (T10/8/1); every level N1 reads beyond its own TX comes from its
//! override.
use canstar_controller::view::CoreView;
use super::*;

const D: FaultMode = FaultMode::StuckDominant;
const R: FaultMode = FaultMode::StuckRecessive;

fn restarted(b: &Bench, field: Field, what: &str) -> Result<(), String> {
    ensure!(b.at(0) == (field, 1), "{what}: N1 at {:?} {}, expected {} 1 (count restarted)", b.at(0).0, b.at(0).1, field.name());
    Ok(())
}

/// The STUFF_ERR a receiver of a silent bus gets at the 6th bit after SOF.
fn stuff_err_after_sof(b: &mut Bench, m: usize) -> Result<(), String> {
    b.run_until(12, |b| b.count(0, m, EV_STUFF_ERR) > 0)?;
    let e = b.events(0, m, EV_STUFF_ERR)[0];
    ensure!(e.field == Field::Ident && e.pos == 5 && e.has(EV_AEF) && !e.tx_role, "STUFF_ERR at {e}, expected after Identifier 5 with AEF, receiver");
    let k = b.since(0, m).iter().position(|r| r.has(EV_SOF)).unwrap_or(usize::MAX);
    let j = b.since(0, m).iter().position(|r| r.has(EV_STUFF_ERR)).unwrap();
    ensure!(j == k + 6, "STUFF_ERR is bit {} after SOF, expected the 6th", j.wrapping_sub(k));
    ensure!(b.rec(0) == 1, "REC {} (expected 1)", b.rec(0));
    Ok(())
}

pub fn run(ctx: &mut Ctx) {
    let vcd = ctx.vcd.as_ref().map(|d| d.join("idle.vcd"));
    let mut b = Bench::new_unintegrated(vec![cfg_t10_8_1()], false, vcd.as_deref());
    let frame = Frame::std(0x1F0, &[0x42]); // Identifier 2 dominant (idle_6)

    let r = (|| {
        b.force_at(&[0], Field::WaitIdle, 9, false, D, 1)?;
        restarted(&b, Field::WaitIdle, "idle_1")
    })();
    ctx.record("idle_1", r);

    let r = (|| {
        b.force_at(&[0], Field::WaitIdle, 11, false, D, 1)?;
        restarted(&b, Field::WaitIdle, "idle_2")?;
        let m = b.mark(0);
        b.run_until(20, |b| b.node(0).field() == Field::Idle)?;
        let s = b.since(0, m);
        ensure!(s.len() == 11 && s.iter().all(|r| r.field == Field::WaitIdle && r.level), "integration took {} bits:{}", s.len(), b.dump(0, m));
        ensure!(s[10].has(EV_INTEGRATED), "no INTEGRATED event at the 11th bit: {}", s[10]);
        ensure!(b.state(0) == 0, "state {}", b.state(0));
        Ok(())
    })();
    ctx.record("idle_2", r);

    let r = (|| {
        let m = b.force_at(&[0], Field::Idle, 2, false, D, 1)?;
        let x = b.rec_at(0, m)?;
        ensure!(x.has(EV_SOF) && x.field == Field::Idle && x.pos == 2, "forced bit {x}: expected SOF at Bus_Idle 2");
        stuff_err_after_sof(&mut b, m)
    })();
    ctx.record("idle_3", r);

    let r = (|| {
        b.node_mut(0).request(frame.clone());
        let m = b.force_at(&[0], Field::Inter, 3, false, D, 1)?;
        let x = b.rec_at(0, m)?;
        ensure!(x.has(EV_SOF), "Intermission 3 forced D: no SOF at {x}");
        ensure!(b.at(0) == (Field::Ident, 1) && b.node(0).core.dbg_role(), "after the SOF N1 is at {:?} (role tx {})", b.at(0), b.node(0).core.dbg_role());
        let y = b.since(0, m).get(1).copied();
        b.run_bits(1);
        let y = y.or_else(|| b.since(0, m).get(1).copied()).ok_or("no bit after the SOF")?;
        ensure!(y.field == Field::Ident && y.pos == 1 && y.tx_role, "bit after the SOF: {y}");
        Ok(())
    })();
    ctx.record("idle_4", r);

    let r = (|| {
        let m = b.mark(0);
        b.run_until(200, |b| b.count(0, m, EV_ACK_ERR) > 0)?;
        let e = b.events(0, m, EV_ACK_ERR)[0];
        ensure!(e.has(EV_AEF) && e.tec == 8, "first ACK error: {e} (expected AEF, TEC 8)");
        // R! from the first flag bit while N1 sends active flags, until TEC >= 128.
        b.wait_for(0, Field::ActFlag, 1, false, 3)?;
        let t = b.sim.now() + b.ph2_rest_ps(0);
        b.run_until_time(t);
        let m2 = b.mark(0);
        b.set(0, R);
        b.run_until(200, |b| b.tec(0) >= 128)?;
        b.set(0, FaultMode::None);
        let errs = b.events(0, m2, EV_BIT_ERR);
        ensure!(b.tec(0) == 128 && errs.len() == 15, "TEC {} after {} bit errors (expected 128 after 15)", b.tec(0), errs.len());
        ensure!(errs.iter().all(|r| r.field == Field::ActFlag), "bit errors outside active flags:{}", b.dump_events(0, m2));
        let last = errs[14];
        ensure!(last.has(EV_AEF) && !last.has(EV_PEF) && last.state == 1, "the last flag must be active (N1 passive): {last}");
        // Error delimiter, Intermission, 8 bits of Suspend_Transmission, retry.
        let m3 = b.mark(0);
        b.run_until(60, |b| b.count(0, m3, EV_SOF) > 0)?;
        let s = b.since(0, m3);
        let susp = s.iter().filter(|r| r.field == Field::Suspend).count();
        ensure!(susp == 8, "{susp} Suspend_Transmission bits before the retry (expected 8)");
        // Error delimiter: the first recessive bit after the flag (still
        // labelled with the flag) and Error_Delimiter 2..8.
        let first_r = s.iter().position(|r| r.field == Field::ActFlag && r.level && r.pos >= 7);
        ensure!(first_r.is_some() && s.iter().filter(|r| r.field == Field::ErrDel).count() == 7 && s.iter().filter(|r| r.field == Field::Inter).count() == 3, "error delimiter / intermission ({} / {} bits):{}", s.iter().filter(|r| r.field == Field::ErrDel).count(), s.iter().filter(|r| r.field == Field::Inter).count(), b.dump(0, m3));
        // The retries end in ACK_ERR + PEF with EXC1: no change.
        let m4 = b.mark(0);
        b.run_until(200, |b| b.count(0, m4, EV_ACK_ERR) > 0)?;
        let a = b.events(0, m4, EV_ACK_ERR)[0];
        ensure!(a.has(EV_PEF), "retry: {a} (expected ACK_ERR, PEF)");
        b.run_until(20, |b| b.node(0).field() == Field::ErrDel)?;
        ensure!(b.count(0, m4, EV_EXC1) == 1 && b.tec(0) == 128, "retry: EXC1 {} TEC {} (expected EXC1, 128)", b.count(0, m4, EV_EXC1), b.tec(0));
        Ok(())
    })();
    ctx.record("idle_5", r);

    let r = (|| {
        let m = b.force_at(&[0], Field::Ident, 2, false, R, 1)?;
        let x = b.rec_at(0, m)?;
        ensure!(x.has(EV_BIT_ERR) && x.has(EV_PEF) && x.tx_role, "forced Identifier 2: {x} (expected BIT_ERR, PEF)");
        ensure!(b.tec(0) == 136, "TEC {} (expected 136)", b.tec(0));
        Ok(())
    })();
    ctx.record("idle_6", r);

    let r = (|| {
        b.run_until(40, |b| b.node(0).field() == Field::Inter)?;
        let m = b.mark(0);
        b.set(0, R);
        b.run_until(5000, |b| b.state(0) == 2)?;
        let errs = b.events(0, m, EV_BIT_ERR);
        // Every bit error is at SOF with a passive flag, except the last: it
        // takes TEC past 255, and a node entering bus-off sends no flag
        // (can-protocol.md §13.1: it stops driving at once).
        let (last, before) = errs.split_last().ok_or_else(|| "no bit error".to_string())?;
        ensure!(
            before.iter().all(|r| r.field == Field::Sof && r.has(EV_PEF)) && last.field == Field::Sof && !last.has(EV_PEF) && last.state == 2,
            "bit errors not at SOF with PEF (the last one entering bus-off without a flag):{}",
            b.dump_events(0, m)
        );
        let mut t = 136;
        for e in &errs {
            t += 8;
            ensure!(e.tec == t.min(256) || (t > 255 && e.state == 2), "TEC {} at {e}, expected {t}", e.tec);
        }
        ensure!(errs.len() == 15 && b.tec(0) > 255, "{} bit errors, TEC {} (expected 15, > 255)", errs.len(), b.tec(0));
        let others = b.count(0, m, EV_STUFF_ERR) + b.count(0, m, EV_FORM_ERR) + b.count(0, m, EV_ACK_ERR);
        ensure!(others == 0, "other errors:{}", b.dump_events(0, m));
        Ok(())
    })();
    ctx.record("idle_7", r);

    let r = (|| {
        b.node_mut(0).withdraw();
        b.set(0, FaultMode::None);
        let m = b.mark(0);
        b.run_bits(5);
        let s = b.since(0, m);
        ensure!(b.state(0) == 2 && s.len() >= 4 && s.iter().all(|r| r.field == Field::BusOff), "N1 not counting in Bus_Off:{}", b.dump(0, m));
        ensure!(s.windows(2).all(|w| w[1].pos == w[0].pos + 1), "run positions not consecutive:{}", b.dump(0, m));
        Ok(())
    })();
    ctx.record("idle_8", r);

    let r = (|| {
        b.force_at(&[0], Field::BusOff, 9, false, D, 1)?;
        restarted(&b, Field::BusOff, "idle_9")?;
        ensure!(b.runs(0) == 0, "completed runs {}", b.runs(0));
        Ok(())
    })();
    ctx.record("idle_9", r);

    let r = (|| {
        b.force_at(&[0], Field::BusOff, 11, false, D, 1)?;
        restarted(&b, Field::BusOff, "idle_10")?;
        ensure!(b.runs(0) == 0, "completed runs {}", b.runs(0));
        Ok(())
    })();
    ctx.record("idle_10", r);

    let r = (|| {
        b.run_bits(1);
        b.wait_for(0, Field::BusOff, 1, false, 12)?;
        ensure!(b.runs(0) == 1, "completed runs {} after 11 R bits (expected 1)", b.runs(0));
        let t = b.sim.now() + b.ph2_rest_ps(0);
        b.run_until_time(t);
        let m = b.mark(0);
        b.force_now(&[0], D, 1);
        b.run_until(2, |b| b.mark(0) > m)?;
        restarted(&b, Field::BusOff, "idle_11")?;
        ensure!(b.runs(0) == 1, "completed runs {} (expected to stay 1)", b.runs(0));
        Ok(())
    })();
    ctx.record("idle_11", r);

    let r = (|| {
        let t_end = b.sim.now() + 2000 * b.bit_ps;
        loop {
            b.wait_for(0, Field::BusOff, 10, false, 12)?;
            if b.runs(0) >= 127 || b.sim.now() > t_end {
                break;
            }
            b.run_bits(1);
        }
        ensure!(b.runs(0) == 127, "completed runs {} (expected 127)", b.runs(0));
        let t = b.sim.now() + b.ph2_rest_ps(0);
        b.run_until_time(t);
        let m = b.mark(0);
        b.force_now(&[0], D, 1);
        b.run_until(2, |b| b.mark(0) > m)?;
        restarted(&b, Field::BusOff, "idle_12")?;
        ensure!(b.runs(0) == 127 && b.state(0) == 2, "runs {} state {} (expected 127, bus-off)", b.runs(0), b.state(0));
        let m = b.mark(0);
        b.run_until(20, |b| b.count(0, m, EV_RECOVERED) > 0)?;
        ensure!(b.since(0, m).len() == 11, "recovered after {} R bits (expected 11)", b.since(0, m).len());
        b.run_bits(1);
        ensure!(
            b.node(0).field() == Field::Idle && (b.tec(0), b.rec(0), b.state(0)) == (0, 0, 0),
            "after recovery: {:?} TEC {} REC {} state {}",
            b.node(0).field(),
            b.tec(0),
            b.rec(0),
            b.state(0)
        );
        Ok(())
    })();
    ctx.record("idle_12", r);

    let r = (|| {
        let m = b.force_at(&[0], Field::Idle, 12, false, D, 1)?;
        let x = b.rec_at(0, m)?;
        ensure!(x.has(EV_SOF) && x.field == Field::Idle && x.pos == 12, "forced bit {x}: expected SOF at Bus_Idle 12");
        stuff_err_after_sof(&mut b, m)
    })();
    ctx.record("idle_13", r);
}
