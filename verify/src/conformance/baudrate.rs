//! baudrate (§1 of the plan): three nodes on independent clocks (N1 110 ns
//! BRP 10 T10/6/4, N2 1118 ns BRP 1 T10/6/4, N3 442 ns BRP 1 T25 PROP 8
//! PH1 8 SJW 4; bit times 11.00 / 11.18 / 11.05 µs), frames with many stuff
//! bits, every loser losing arbitration right after a stuff bit.
use canstar_controller::view::CoreView;
use super::*;

/// Bus-bit index where `a` loses against `b` (first differing bit), if it does.
fn loses_at(a: &Frame, b: &Frame) -> Option<usize> {
    let x = bus_bits(a, BuildOptions::default(), false);
    let y = bus_bits(b, BuildOptions::default(), false);
    let k = x.iter().zip(&y).position(|(p, q)| p.level != q.level)?;
    (x[k].level && !y[k].level && x[k].field == Field::Ident).then_some(k)
}

fn after_stuff(f: &Frame, k: usize) -> bool {
    let x = bus_bits(f, BuildOptions::default(), false);
    k > 0 && x[k - 1].stuff
}

/// Three standard frames (ids ascending): each later frame loses against
/// each earlier one right after a stuff bit.
fn frames() -> [Frame; 3] {
    let mut x: u64 = 0x1234_5678_9ABC_DEF1;
    loop {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        let base = (x & 0x7FF) as u32;
        let mut ids = [base, base ^ ((x >> 11) & 0x3F) as u32, base ^ ((x >> 17) & 0x3F) as u32];
        ids.sort();
        if ids[0] == ids[1] || ids[1] == ids[2] {
            continue;
        }
        let fr: Vec<Frame> = ids.iter().enumerate().map(|(i, &id)| Frame::std(id, &[0x00, 0xFF, 0x00, 0xFF][..2 + i])).collect();
        let ok = [(1, 0), (2, 0), (2, 1)].iter().all(|&(a, b)| loses_at(&fr[a], &fr[b]).is_some_and(|k| after_stuff(&fr[a], k)));
        if ok {
            return [fr[0].clone(), fr[1].clone(), fr[2].clone()];
        }
    }
}

fn bench(ctx: &Ctx) -> Bench {
    let cfgs = vec![cfg().timing(10, 1, 4, 4), cfg(), cfg().timing(1, 8, 8, 4)];
    let clocks = vec![ClockSpec::new(110_000), ClockSpec::new(1_118_000), ClockSpec::new(442_000)];
    let vcd = ctx.vcd.as_ref().map(|d| d.join("baudrate.vcd"));
    let mut b = Bench::with_clocks(cfgs, clocks, false, vcd.as_deref());
    let ok = b.run_until(40, |b| (0..3).all(|i| b.node(i).field() == Field::Idle));
    assert!(ok.is_ok(), "start-up: nodes did not integrate");
    b
}

/// All three request together (N2, N3 once N1 raised tx_rqst); `winner`
/// gets the lowest identifier.
fn round(b: &mut Bench, winner: usize) -> Result<(), String> {
    let fr = frames();
    // node i sends fr[order[i]]: the winner gets fr[0]
    let mut assign = [0usize; 3];
    let others: Vec<usize> = (0..3).filter(|&i| i != winner).collect();
    assign[winner] = 0;
    assign[others[0]] = 1;
    assign[others[1]] = 2;
    let marks: Vec<usize> = (0..3).map(|i| b.mark(i)).collect();
    let rx0: Vec<usize> = (0..3).map(|i| b.node(i).received().len()).collect();
    b.node_mut(0).request(fr[assign[0]].clone());
    b.run_until(5, |b| b.node(0).core.dbg_tx_rqst())?;
    b.node_mut(1).request(fr[assign[1]].clone());
    b.node_mut(2).request(fr[assign[2]].clone());
    b.run_until(3000, |b| (0..3).all(|i| !b.node(i).pending()))?;
    b.run_idle(200)?;
    for i in 0..3 {
        let want: Vec<Frame> = (0..3).filter(|&k| (0..3).any(|j| j != i && assign[j] == k)).map(|k| fr[k].clone()).collect();
        check_delivered(b, i, rx0[i], &want)?;
        let flags = b.since(i, marks[i]).iter().filter(|r| r.ev & ((1 << EV_AEF) | (1 << EV_PEF) | (1 << EV_OLF)) != 0).count();
        ensure!(flags == 0, "N{} flagged:{}", i + 1, b.dump_events(i, marks[i]));
        ensure!((b.tec(i), b.rec(i)) == (0, 0), "N{} TEC {} REC {}", i + 1, b.tec(i), b.rec(i));
        if i != winner {
            let l = b.events(i, marks[i], EV_ARB_LOST);
            ensure!(!l.is_empty(), "N{} never lost arbitration", i + 1);
            let k = b.since(i, marks[i]).iter().position(|r| r.has(EV_ARB_LOST)).unwrap();
            ensure!(k > 0 && b.since(i, marks[i])[k - 1].stuff, "N{} lost at {} not right after a stuff bit", i + 1, l[0]);
        }
    }
    Ok(())
}

pub fn run(ctx: &mut Ctx) {
    let mut b = bench(ctx);
    for (name, w) in [("baudrate_1", 2), ("baudrate_2", 1), ("baudrate_3", 0)] {
        let r = round(&mut b, w);
        ctx.record(name, r);
    }
    let tq1 = 10 * 110_000; // N1's TQ: 10 clocks of 110 ns
    for (name, len, sof) in [("baudrate_4", 5 * tq1, false), ("baudrate_4b", 6 * tq1, true)] {
        let r = (|| {
            b.run_idle(200)?;
            b.run_bits(3);
            let m = b.mark(0);
            let rec0 = b.rec(0);
            b.set(0, FaultMode::StuckDominant);
            let t = b.sim.now() + len as u64;
            b.run_until_time(t);
            b.set(0, FaultMode::None);
            b.run_bits(12);
            let s = b.count(0, m, EV_SOF);
            if sof {
                ensure!(s == 1, "N1 did not sample the dominant pulse:{}", b.dump_events(0, m));
                let e = b.events(0, m, EV_STUFF_ERR);
                ensure!(e.len() == 1 && e[0].has(EV_AEF) && b.rec(0) == rec0 + 1, "expected STUFF_ERR, AEF, REC +1:{}", b.dump_events(0, m));
            } else {
                ensure!(s == 0 && b.rec(0) == rec0 && b.since(0, m).iter().all(|r| r.field == Field::Idle), "N1 reacted to the spike:{}", b.dump_events(0, m));
                ensure!(b.count(0, m, EV_BIT) > 0 && b.since(0, m).iter().take(3).any(|r| r.level), "no samples");
            }
            Ok(())
        })();
        ctx.record(name, r);
    }
}
