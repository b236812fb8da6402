//! btl (§3 of the plan), **case a only** (hard synchronisation of an idle
//! node that drives recessive): N1 alone in Bus_Idle, its override goes from
//! `R` to `D` at TQ j of its current bit and stays `D` one bit time (a SOF).
//! Expected for every j: restart, i.e. N1 samples the SOF the same time
//! after the edge as for j = 0 (the edge's TQ becomes SYNC_SEG). Cases b–f
//! are not implemented yet.
use super::*;

/// The plan's three timings: (number, config, SP in TQ).
fn timings() -> Vec<(u32, NodeConfig)> {
    vec![(1, cfg()), (2, cfg().timing(1, 8, 8, 1)), (3, cfg_t10_8_1())]
}

pub fn run(ctx: &mut Ctx) {
    for (tn, c) in timings() {
        let ntq = c.ntq() as u64;
        let sp = 1 + c.prop + c.ph1;
        let vcd = ctx.vcd.as_ref().map(|d| d.join(format!("btl_{tn}.vcd")));
        let mut b = Bench::with_clocks(vec![c.clone()], vec![ClockSpec::new(CLOCK_PS)], false, vcd.as_deref());
        let ok = b.run_until(40, |b| b.node(0).field() == Field::Idle);
        let tq = CLOCK_PS * c.brp as u64;
        let l_rx = canstar_controller::core::CanCore::l_rx(c.sync_depth) as i64;
        let mut reference: Option<u64> = None;
        for j in (0..ntq).filter(|&j| j != (sp - 1) as u64) {
            let name = format!("btl_{tn}a_j{j}");
            let r = (|| {
                ok.clone()?;
                b.run_idle(300)?;
                b.run_bits(2);
                // the next idle bit's start as N1 perceives it (see Bench::ph2_rest_ps)
                b.wait_for(0, Field::Idle, b.node(0).pos().min(254) + 1, false, 3)?;
                let e = b.recs(0).last().unwrap().t as i64;
                let mut start = e + (c.ph2() as i64 * c.brp as i64 - 1 - l_rx) * CLOCK_PS as i64;
                if start < b.sim.now() as i64 {
                    start += (ntq * tq) as i64;
                }
                let edge = start as u64 + j * tq;
                let m = b.mark(0);
                b.run_until_time(edge);
                ensure!(b.since(0, m).iter().all(|r| r.level), "an earlier bit was not recessive");
                b.set(0, Interference::StuckDominant);
                let t = b.sim.now() + ntq * tq;
                b.run_until_time(t);
                b.set(0, Interference::None);
                b.run_until(3, |b| b.count(0, m, EV_SOF) > 0)?;
                let sof = b.events(0, m, EV_SOF)[0];
                ensure!(sof.field == Field::Idle && !sof.level, "SOF record {sof}");
                let d = sof.t - edge;
                match reference {
                    None => {
                        ensure!(d >= sp as u64 * tq && d <= (sp as u64 + 6) * tq, "sample {} ns after the edge (SP {sp} TQ)", d / 1000);
                        reference = Some(d);
                    }
                    Some(r0) => ensure!(d == r0, "sample {} ns after the edge, {} ns for j = 0: no restart", d / 1000, r0 / 1000),
                }
                Ok(())
            })();
            ctx.record(&name, r);
        }
    }
}
