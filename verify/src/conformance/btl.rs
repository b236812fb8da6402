//! btl (§3 of the plan): one `R`→`D` edge in TQ j of N1's current bit,
//! for the three timings (1 = T10/6/4, 2 = T25/17/1, 3 = T10/8/1) and the
//! six cases a–f; steps `btl_<timing><case>_j<j>`.
//!
//! - **a** (hard sync, driving `R`, idle): N1 alone in Bus_Idle, its
//!   override goes from `R` to `D` at TQ j and stays `D` one bit time (a
//!   SOF). Expected for every j: restart, i.e. N1 samples the SOF the same
//!   time after the edge as for j = 0.
//! - **b–f**: see [`cases_b_to_f`]. Each step asserts the instant of N1's
//!   first sample point after the edge and, where N1's TX changes level at
//!   the next transmit point, the instant of that TX edge, both against the
//!   plan's table (none / PH1 + x / restart / PH2 − x, TX at the edge, 1 TQ
//!   later or at SP + IPT), plus the secondary effect the plan names (bit
//!   error, delivered frame, SOF).
use super::*;

/// The plan's three timings: (number, config, SP in TQ).
fn timings() -> Vec<(u32, NodeConfig)> {
    vec![(1, cfg()), (2, cfg().timing(1, 8, 8, 1)), (3, cfg_t10_8_1())]
}

pub fn run(ctx: &mut Ctx) {
    for (tn, c) in timings() {
        let ntq = c.timing.ntq() as u64;
        let sp = 1 + c.timing.prop + c.timing.ph1;
        let vcd = ctx.vcd.as_ref().map(|d| d.join(format!("btl_{tn}.vcd")));
        let mut b = Bench::with_clocks(vec![c.clone()], vec![ClockSpec::new(CLOCK_PS)], false, vcd.as_deref());
        let ok = b.run_until(40, |b| b.node(0).field() == Field::Idle);
        let tq = CLOCK_PS * c.timing.brp as u64;
        let l_rx = canstar_controller::core::CanCore::l_rx(c.sync_depth) as i64;
        for j in (0..ntq).filter(|&j| j != (sp - 1) as u64) {
            let name = format!("btl_{tn}a_j{j}");
            let r = (|| {
                ok.clone()?;
                b.run_idle(300)?;
                b.run_bits(2);
                // TQ 0 of the next idle bit on the override's time axis (see tq0_after)
                b.wait_for(0, Field::Idle, b.node(0).pos().min(254) + 1, false, 3)?;
                let e = b.recs(0).last().unwrap().t as i64;
                let mut start = tq0_after(&b, e as u64) as i64;
                if start < b.sim.now() as i64 {
                    start += (ntq * tq) as i64;
                }
                let edge = start as u64 + j * tq;
                let m = b.mark(0);
                b.run_until_time(edge);
                ensure!(b.since(0, m).iter().all(|r| r.level), "an earlier bit was not recessive");
                b.set(0, FaultMode::StuckDominant);
                let t = b.sim.now() + ntq * tq;
                b.run_until_time(t);
                b.set(0, FaultMode::None);
                b.run_until(3, |b| b.count(0, m, EV_SOF) > 0)?;
                let sof = b.events(0, m, EV_SOF)[0];
                ensure!(sof.field == Field::Idle && !sof.level, "SOF record {sof}");
                // restart: the edge's TQ becomes SYNC_SEG, the SOF is sampled
                // SP TQ after the edge's TQ (record l_rx clocks later, see check_timing)
                let d = sof.t - edge;
                let want = sp as u64 * tq + l_rx as u64 * CLOCK_PS;
                ensure!(d == want, "SOF sampled {} ns after the edge, expected {} ns (restart)", d / 1000, want / 1000);
                Ok(())
            })();
            ctx.record(&name, r);
        }
        drop(b);
        cases_b_to_f(ctx, tn, &c);
    }
}

/// Error events (bit, stuff, CRC, form, ACK).
const ERRS: u32 = (1 << EV_BIT_ERR) | (1 << EV_STUFF_ERR) | (1 << EV_CRC_ERR) | (1 << EV_FORM_ERR) | (1 << EV_ACK_ERR);

/// Information processing time (TQ), P§2.2.
const IPT: u64 = 2;

/// Synchronisation outcome for an edge in TQ j (the plan's table for b–e,
/// which is P§3.4/§3.5 with the phase error e = j for j < SP, j − NTQ else).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Sync {
    None,
    /// PH1 lengthened by x TQ.
    Lengthen(u64),
    /// The edge's TQ becomes SYNC_SEG.
    Restart,
    /// PH2 shortened by x TQ.
    Shorten(u64),
}

struct Tm {
    tn: u32,
    ntq: u64,
    sp: u64,
    sjw: u64,
}

impl Tm {
    /// Expected resynchronisation for an edge at TQ j while driving `D` (c, d)
    /// or `R` (b, e).
    fn resync(&self, drive_d: bool, j: u64) -> Sync {
        if j == 0 {
            Sync::None
        } else if j < self.sp {
            if drive_d {
                Sync::None
            } else {
                Sync::Lengthen(j.min(self.sjw))
            }
        } else if self.ntq - j <= self.sjw {
            Sync::Restart
        } else {
            Sync::Shorten(self.sjw)
        }
    }
    /// TQ from the start of the edge's bit to N1's first sample point after
    /// the edge (the sample point of tick `cnt = sp`).
    fn sample_at(&self, s: Sync, j: u64) -> u64 {
        match s {
            Sync::None if j < self.sp => self.sp,
            Sync::None => self.ntq + self.sp,
            Sync::Lengthen(x) => self.sp + x,
            Sync::Restart => j + self.sp,
            Sync::Shorten(x) => self.ntq - x + self.sp,
        }
    }
    /// TQ from the start of the edge's bit to the next transmit point: the
    /// end of the (possibly lengthened or shortened) bit, or the tick that
    /// detects the edge (end of TQ j) on a restart; postponed to SP + IPT if
    /// earlier (P§2.5).
    fn tx_at(&self, s: Sync, j: u64) -> u64 {
        let t = match s {
            Sync::None => self.ntq,
            Sync::Lengthen(x) => self.ntq + x,
            Sync::Restart => j + 1,
            Sync::Shorten(x) => self.ntq - x,
        };
        t.max(self.sp + IPT)
    }
}

fn desc(s: Sync, tx: u64, sp: u64, j: u64) -> String {
    let tx = if tx == j + 1 { "TX@edge".to_string() } else if tx == sp + IPT { format!("TX at SP+{IPT}") } else { format!("TX at {tx} TQ") };
    match s {
        Sync::None => "no synchronisation".into(),
        Sync::Lengthen(x) => format!("PH1 + {x}"),
        Sync::Restart => format!("restart, {tx}"),
        Sync::Shorten(x) => format!("PH2 - {x}, {tx}"),
    }
}

/// Runs the bench to `until`, noting every change of N1's TX pin.
fn run_watch(b: &mut Bench, until: u64, tx: &mut Vec<(u64, bool)>) {
    let txn = b.bus.nodes[0].tx;
    let mut last = tx.last().map(|x| x.1).unwrap_or_else(|| b.sim.value(txn));
    while b.sim.next_edge_time().is_some_and(|e| e <= until) {
        b.step();
        let v = b.sim.value(txn);
        if v != last {
            tx.push((b.sim.now(), v));
            last = v;
        }
    }
}

/// Override changes (time, mode) applied in order, watching TX, then run to `end`.
fn play(b: &mut Bench, seq: &[(u64, FaultMode)], end: u64) -> Vec<(u64, bool)> {
    let mut tx = vec![];
    for &(t, m) in seq {
        run_watch(b, t, &mut tx);
        b.set(0, m);
    }
    run_watch(b, end, &mut tx);
    tx
}

/// Hardware reset of N1 (request withdrawn, scripted transmitter finished),
/// integration, two idle bits: every step starts error-active with TEC = REC = 0.
fn fresh(b: &mut Bench) -> Result<(), String> {
    let sc = b.script;
    b.run_until(400, |b| sc.is_none_or(|h| !b.sim.get(h).busy()))?;
    b.set(0, FaultMode::None);
    b.node_mut(0).withdraw();
    b.node_mut(0).hard_reset();
    b.run_bits(1);
    b.run_until(60, |b| b.node(0).field() == Field::Idle).map_err(|e| format!("after reset: {e}"))?;
    b.run_bits(2);
    ensure!(b.tec(0) == 0 && b.rec(0) == 0, "counters after reset");
    Ok(())
}

/// Offset from the record of a bit to the forcing instant of the next bit
/// (conformance-tests.md §0 WAIT_FOR, see [`Bench::ph2_rest_ps`]), unsaturated: it may lie
/// before the record.
fn ph2_off(b: &Bench) -> i64 {
    let c = b.node(0).config();
    let l_rx = canstar_controller::core::CanCore::l_rx(c.sync_depth) as i64;
    (c.timing.ph2 as i64 * c.timing.brp as i64 - l_rx) * CLOCK_PS as i64
}

/// Start of TQ 0 of the bit after the one whose record is at `t_rec`, on
/// the override's time axis (the WAIT_FOR instant of
/// [`Bench::ph2_rest_ps`], unsaturated): an override change at
/// `start + j TQ` is first read by N1 in TQ j of that bit.
fn tq0_after(b: &Bench, t_rec: u64) -> u64 {
    (t_rec as i64 + ph2_off(b)) as u64
}

/// Runs until N1 has processed the bit before `prev` (so `prev` is in
/// progress) and returns the start of TQ 0 of the bit after `prev` (see
/// [`tq0_after`]), the bit containing the edge. `prev` must not synchronise.
fn t0_after(b: &mut Bench, prev: (Field, u32)) -> Result<u64, String> {
    b.wait_for(0, prev.0, prev.1, false, 300)?;
    let t = tq0_after(b, b.recs(0).last().unwrap().t);
    Ok(t + b.bit_ps)
}

/// The data frame of b–e: data bits 5..8 are `R R D R`, none a stuff bit
/// and no stuff bit between them (checked).
fn frame_bde() -> Result<Frame, String> {
    let f = Frame::std(0x4D5, &[0x4D, 0x2B]);
    let bits = bus_bits(&f, BuildOptions::default(), false);
    let k = bits.iter().position(|x| x.field == Field::Data && x.pos == 5).ok_or("no Data 5")?;
    let w: Vec<(u8, bool, bool)> = bits[k..k + 4].iter().map(|x| (x.pos, x.level, x.stuff)).collect();
    ensure!(w == [(5, true, false), (6, true, false), (7, false, false), (8, true, false)], "frame bits around Data 6: {w:?}");
    Ok(f)
}

/// Sample-point and TX-edge check of one step. `t0`: start of TQ 0 of the
/// edge's bit on the override's time axis ([`tq0_after`]); `m`: mark before the edge; `tx_want`: (TQ after t0, level) of
/// the next TX edge, if N1's TX changes there.
#[allow(clippy::too_many_arguments)]
fn check_timing(b: &Bench, tm: &Tm, t0: u64, j: u64, m: usize, x_sample: u64, tx: &[(u64, bool)], tx_want: Option<(u64, bool)>, what: &str) -> Result<BitRec, String> {
    let tq = CLOCK_PS;
    let c = b.node(0).config();
    let l_rx = canstar_controller::core::CanCore::l_rx(c.sync_depth) as u64;
    // N1's tick at the end of TQ k − 1 of the bit (its time k) evaluates
    // the level the override set before t0 + k TQ; its sample record comes
    // l_rx clocks after t0 + k TQ (synchroniser and input stage, then the
    // clock carrying the events), and a TX change on that tick reaches the
    // bus l_rx − 1 clocks after t0 + k TQ.
    // The first sample point at or after the tick that detects the edge
    // (the end of TQ j); earlier records belong to earlier sample points.
    let detect = t0 + (j + 1) * tq + l_rx * CLOCK_PS;
    let r = *b.since(0, m).iter().find(|r| r.t >= detect).ok_or("no sample point after the edge")?;
    let want = t0 + x_sample * tq + l_rx * CLOCK_PS;
    ensure!(
        r.t == want,
        "{what}: first sample after the edge {} TQ after the bit start (record {r}), expected {x_sample} TQ",
        (r.t as i64 - (t0 + l_rx * CLOCK_PS) as i64) as f64 / tq as f64
    );
    if let Some((y, lvl)) = tx_want {
        let e = tx.iter().find(|x| x.0 + CLOCK_PS >= detect).ok_or_else(|| format!("{what}: no TX edge after the edge"))?;
        let want = t0 + y * tq + (l_rx - 1) * CLOCK_PS;
        ensure!(
            e.0 == want && e.1 == lvl,
            "{what}: TX edge to {} {} TQ after the bit start, expected to {} at {y} TQ (timing {})",
            e.1 as u8,
            (e.0 as i64 - (t0 + (l_rx - 1) * CLOCK_PS) as i64) as f64 / tq as f64,
            lvl as u8,
            tm.tn
        );
    }
    Ok(r)
}

/// Cases b–f of the plan on one bench per timing (N1 with the scripted
/// transmitter as the source of the played frames of b and c):
///
/// - **b** (resync, driving `R`, receiver): the scripted transmitter sends
///   a frame whose data bits 6, 7 are `R`, `D`. For j < SP the `R`→`D` edge
///   at the start of Data 7 is moved late, to TQ j of Data 7 (the override
///   reads `R` until then); for j ≥ SP it comes early, in TQ j of Data 6
///   (the override reads `D` from then). The frame content is unchanged:
///   N1 must deliver it.
/// - **c** (resync, driving `D`, receiver): same frame, N1 drives its ACK;
///   the override reads `R` from the ACK slot's start to TQ j. j < SP: no
///   synchronisation, TX to `R` at the normal end of the ACK slot, frame
///   delivered; j ≥ SP: bit error at the ACK slot (REC 1) and the table's
///   synchronisation.
/// - **d** (resync, driving `D`, transmitter): N1 sends the frame; its
///   Data 7 (`D` after `R`) reads `R` until TQ j. j < SP: TX to `R` (Data 8)
///   at the normal bit end; j ≥ SP: bit error.
/// - **e** (resync, driving `R`, transmitter): N1's Data 6 (`R`, followed by
///   `D`) reads `D` from TQ j. j < SP: bit error, the error flag's `D` on TX
///   at the lengthened bit end; j ≥ SP: Data 7's `D` on TX at the table's
///   transmit point.
/// - **f** (hard sync, driving `D`, transmitter): N1 requests a frame (ID 1
///   `R`) in Bus_Idle and decides on SOF at the next sample point. j ≥ SP +
///   2: the override reads `D` from TQ j of that idle bit: restart, the SOF
///   starts on TX at the edge. j ≤ SP − 2: the override reads `R` in the
///   SOF bit until TQ j: no synchronisation, SOF sampled `D` at SP and TX to
///   `R` (ID 1) at the normal bit end. Other j are left to lock-step.
pub fn cases_b_to_f(ctx: &mut Ctx, tn: u32, c: &NodeConfig) {
    let ntq = c.timing.ntq() as u64;
    let sp = (1 + c.timing.prop + c.timing.ph1) as u64;
    let tm = Tm { tn, ntq, sp, sjw: c.timing.sjw as u64 };
    let tq = CLOCK_PS;
    let vcd = ctx.vcd.as_ref().map(|d| d.join(format!("btl_{tn}_bf.vcd")));
    let mut bench = Bench::with_clocks(vec![c.clone()], vec![ClockSpec::new(CLOCK_PS)], true, vcd.as_deref());
    let b = &mut bench;
    let start = b.run_until(40, |b| b.node(0).field() == Field::Idle);
    let js: Vec<u64> = (0..ntq).filter(|&j| j != sp - 1).collect();
    let f = frame_bde();
    const R: FaultMode = FaultMode::StuckRecessive;
    const D: FaultMode = FaultMode::StuckDominant;
    const NONE: FaultMode = FaultMode::None;

    // b and c: the scripted transmitter plays the frame.
    for case in ['b', 'c'] {
        for &j in &js {
            let name = format!("btl_{tn}{case}_j{j}");
            let r = (|| {
                start.clone()?;
                let f = f.clone()?;
                fresh(b)?;
                let rx0 = b.node(0).received().len();
                let h = b.script.unwrap();
                b.sim.get_mut(h).send(script_bits(&f, BuildOptions::default()));
                let s = tm.resync(case == 'c', j);
                let (t0, seq, m) = if case == 'b' && j >= sp {
                    let t0 = t0_after(b, (Field::Data, 5))?;
                    (t0, vec![(t0 + j * tq, D), (t0 + ntq * tq, NONE)], b.mark(0))
                } else if case == 'b' {
                    let t0 = t0_after(b, (Field::Data, 6))?;
                    (t0, vec![(b.sim.now(), R), (t0 + j * tq, NONE)], b.mark(0))
                } else {
                    // N1's own ACK reaches its RX only in TQ L_rx − 1: the
                    // override reads D from TQ j to the end of the slot.
                    let t0 = t0_after(b, (Field::CrcDel, 1))?;
                    (t0, vec![(b.sim.now(), R), (t0 + j * tq, D), (t0 + ntq * tq, NONE)], b.mark(0))
                };
                let tx = play(b, &seq, t0 + (2 * ntq + sp) * tq);
                let what = desc(s, tm.tx_at(s, j), sp, j);
                let tx_want = (case == 'c' && j < sp).then(|| (tm.tx_at(s, j), true));
                let rc = check_timing(b, &tm, t0, j, m, tm.sample_at(s, j), &tx, tx_want, &what)?;
                if case == 'c' {
                    let ack = *b.since(0, m).iter().find(|r| r.field == Field::AckSlot).ok_or("no ACK slot record")?;
                    ensure!(!ack.drove, "N1 did not acknowledge: {ack}");
                    if j >= sp {
                        ensure!(ack.has(EV_BIT_ERR) && ack.rec == 1, "ACK slot read R after the sample point: expected BIT_ERR, REC 1: {ack}");
                        return Ok(());
                    }
                    ensure!(ack.ev & (1 << EV_BIT_ERR) == 0 && !ack.level, "ACK slot: {ack} (next sample {rc})");
                }
                b.run_idle(200)?;
                ensure!(b.since(0, m).iter().all(|r| r.ev & ERRS == 0) && b.rec(0) == 0, "errors after the edge:{}", b.dump_events(0, m));
                check_delivered(b, 0, rx0, std::slice::from_ref(&f))
            })();
            ctx.record(&name, r);
        }
    }

    // d and e: N1 transmits (alone: no ACK, the step ends before it).
    for case in ['d', 'e'] {
        for &j in &js {
            let name = format!("btl_{tn}{case}_j{j}");
            let r = (|| {
                start.clone()?;
                let f = f.clone()?;
                fresh(b)?;
                b.node_mut(0).request(f.clone());
                let s = tm.resync(case == 'd', j);
                let (t0, seq) = if case == 'd' {
                    let t0 = t0_after(b, (Field::Data, 6))?;
                    (t0, vec![(b.sim.now(), R), (t0 + j * tq, D), (t0 + ntq * tq, NONE)])
                } else {
                    let t0 = t0_after(b, (Field::Data, 5))?;
                    (t0, vec![(t0 + j * tq, D), (t0 + ntq * tq, NONE)])
                };
                let m = b.mark(0);
                let tx = play(b, &seq, t0 + (2 * ntq + sp) * tq);
                let what = desc(s, tm.tx_at(s, j), sp, j);
                let err_expected = (case == 'd') == (j >= sp);
                // The next TX level: d: Data 8 `R` (no error); e: Data 7 `D`,
                // or the error flag's `D` after a bit error.
                let tx_want = match case {
                    'd' if j < sp => Some((tm.tx_at(s, j), true)),
                    'e' => Some((tm.tx_at(s, j), false)),
                    _ => None,
                };
                check_timing(b, &tm, t0, j, m, tm.sample_at(s, j), &tx, tx_want, &what)?;
                let tpos = if case == 'd' { 7 } else { 6 };
                let tgt = *b.since(0, m).iter().find(|r| r.field == Field::Data && r.pos == tpos && !r.stuff).ok_or_else(|| format!("no record of the edge bit:{}", b.dump(0, m)))?;
                ensure!(tgt.tx_role, "edge bit recorded as {tgt}");
                ensure!(tgt.has(EV_BIT_ERR) == err_expected, "{tgt}: bit error expected: {err_expected}");
                if err_expected {
                    ensure!(tgt.tec == 8 && tgt.has(EV_AEF), "{tgt}: expected TEC 8, AEF");
                }
                Ok(())
            })();
            ctx.record(&name, r);
        }
    }

    // f: hard synchronisation while driving D (N1 has decided on SOF).
    let ff = Frame::std(0x4D5, &[]);
    let jf: Vec<u64> = (0..ntq).filter(|&j| j + 2 <= sp || j >= sp + 2).collect();
    for &j in &jf {
        let name = format!("btl_{tn}f_j{j}");
        let r = (|| {
            start.clone()?;
            fresh(b)?;
            // R1: a record in Bus_Idle; R2 the next one. The request follows R2,
            // so N1 decides on SOF at the sample point of the bit after R2's.
            let n0 = b.mark(0);
            b.run_until(3, |b| b.mark(0) > n0)?;
            let r1 = *b.recs(0).last().unwrap();
            b.run_until(3, |b| b.mark(0) > n0 + 1)?;
            ensure!(r1.field == Field::Idle && b.node(0).field() == Field::Idle, "not in Bus_Idle: {r1}");
            b.node_mut(0).request(ff.clone());
            let t_k = tq0_after(b, r1.t) + b.bit_ps;
            let l_rx = canstar_controller::core::CanCore::l_rx(c.sync_depth) as u64;
            let m = b.mark(0);
            let (t0, seq, s, x, y) = if j >= sp {
                // edge in the idle bit before SOF: restart, SOF from the edge
                // (D held until N1's own SOF is on the bus)
                (t_k, vec![(t_k + j * tq, D), (t_k + (j + 2) * tq + l_rx * CLOCK_PS, NONE)], "restart, SOF at the edge", j + sp, j + 1)
            } else {
                let t_sof = t_k + ntq * tq;
                (t_sof, vec![(b.sim.now(), R), (t_sof + j * tq, D), (t_sof + ntq * tq, NONE)], "no synchronisation", sp, ntq)
            };
            let tx = play(b, &seq, t0 + (2 * ntq + sp) * tq);
            // j ≥ SP: the next TX edge is the SOF (to D); else ID 1 (to R).
            let tx_want = Some((y, j < sp));
            let r = check_timing(b, &tm, t0, j, m, x, &tx, tx_want, s)?;
            let sof = *b.since(0, m).iter().find(|r| r.has(EV_SOF)).ok_or_else(|| format!("no SOF:{}", b.dump(0, m)))?;
            ensure!(sof == r && sof.field == Field::Sof && !sof.level && sof.tx_role, "SOF record {sof}, first sample after the edge {r}");
            ensure!(b.since(0, m).iter().all(|r| r.ev & ERRS == 0), "error after the edge:{}", b.dump_events(0, m));
            Ok(())
        })();
        ctx.record(&name, r);
    }
}
