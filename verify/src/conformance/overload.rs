//! overload (§10 of the plan): overload conditions and their confinement,
//! N2 → N1 (`overload_rx_*`) and N1 → N2 (`overload_tx_*`).
use super::*;

const D: FaultMode = FaultMode::StuckDominant;
const R: FaultMode = FaultMode::StuckRecessive;
const OL: &[usize] = &[EV_OVL, EV_OLF];

/// `N1+N2 D!` at Intermission 3 with a request pending at `t`: both take the
/// bit as SOF, `t` continues as transmitter from Identifier 1, the other
/// node delivers the frame, no error.
fn im3_sof(b: &mut Bench, t: usize, f: &Frame) -> Result<(), String> {
    let rcv = 1 - t;
    let rx0 = b.node(rcv).received().len();
    let marks = [b.mark(0), b.mark(1)];
    b.node_mut(t).request(f.clone());
    let m = b.force_at(&[0, 1], Field::Inter, 3, false, D, 1)?;
    let x = b.rec_at(0, m)?;
    ensure!(x.has(EV_SOF), "N1 at Intermission 3: {x} (expected SOF)");
    let sof_t = b.events(t, marks[t], EV_SOF);
    ensure!(!sof_t.is_empty() && sof_t[0].field == Field::Inter && sof_t[0].pos == 3, "N{} did not take Intermission 3 as SOF:{}", t + 1, b.dump_events(t, marks[t]));
    b.run_bits(2);
    let k = b.since(t, marks[t]).iter().position(|r| r.has(EV_SOF)).unwrap();
    let nx = b.since(t, marks[t]).get(k + 1).copied().ok_or("no bit after the SOF")?;
    ensure!(nx.field == Field::Ident && nx.pos == 1 && nx.tx_role, "N{} after the SOF: {nx} (expected Tx_Identifier 1)", t + 1);
    b.run_until(300, |b| b.node(rcv).received().len() > rx0)?;
    b.run_idle(100)?;
    check_delivered(b, rcv, rx0, std::slice::from_ref(f))?;
    for (i, &mk) in marks.iter().enumerate() {
        let errs = b.since(i, mk).iter().filter(|r| r.ev & ((1 << EV_AEF) | (1 << EV_PEF)) != 0).count();
        ensure!(errs == 0, "N{} flagged:{}", i + 1, b.dump_events(i, mk));
    }
    Ok(())
}

pub fn run(ctx: &mut Ctx) {
    let mut b = ctx.bench(vec![cfg(), cfg()], false);
    // Receiver part.
    let f = Frame::std(0x3A5, &[0x12, 0x34]);
    b.node_mut(1).request(f.clone());
    let rx0 = b.node(0).received().len();
    let r = b.forced_step(&[0], Field::Eof, 7, D, 1, OL, Ctr::Rec, 0).and_then(|_| check_delivered(&b, 0, rx0, std::slice::from_ref(&f)));
    ctx.record("overload_rx_1a", r);
    let r = b.forced_step(&[0], Field::OvlDel, 8, D, 1, OL, Ctr::Rec, 0).map(|_| ());
    ctx.record("overload_rx_1b", r);
    let r = b.forced_step(&[0], Field::Inter, 1, D, 1, OL, Ctr::Rec, 0).map(|_| ());
    ctx.record("overload_rx_1c", r);
    let r = b.forced_step(&[0], Field::Inter, 2, D, 1, OL, Ctr::Rec, 0).and_then(|_| {
        // (N2 takes N1's overload flag at its Intermission 3 as a SOF and
        // gets a stuff error: the plan states N1's counters only.)
        ensure!((b.tec(0), b.rec(0)) == (0, 0), "N1 counters changed: TEC {} REC {}", b.tec(0), b.rec(0));
        check_delivered(&b, 0, rx0, std::slice::from_ref(&f))
    });
    ctx.record("overload_rx_1d", r);
    let r = im3_sof(&mut b, 1, &Frame::std(0x1C3, &[0xAB]));
    ctx.record("overload_rx_2", r);
    let r = (|| {
        b.node_mut(1).request(Frame::std(0x2F1, &[0x5A]));
        b.forced_step(&[0], Field::AckSlot, 1, R, 1, &[EV_BIT_ERR, EV_AEF], Ctr::Rec, 9)?;
        b.forced_step(&[0], Field::ErrDel, 8, D, 1, OL, Ctr::Rec, 0)?;
        b.run_idle(300)
    })();
    ctx.record("overload_rx_3", r);
    // Transmitter part.
    let r = (|| {
        b.run_idle(300)?;
        b.node_mut(0).request(Frame::std(0x155, &[0xC3]));
        b.forced_step(&[0], Field::Inter, 1, D, 1, OL, Ctr::Tec, 0).map(|_| ())
    })();
    ctx.record("overload_tx_1a", r);
    let r = b.forced_step(&[0], Field::OvlDel, 8, D, 1, OL, Ctr::Tec, 0).map(|_| ());
    ctx.record("overload_tx_1b", r);
    let r = b.forced_step(&[0], Field::Inter, 2, D, 1, OL, Ctr::Tec, 0).map(|_| ());
    ctx.record("overload_tx_1c", r);
    let r = im3_sof(&mut b, 0, &Frame::std(0x0E7, &[0x01, 0x02]));
    ctx.record("overload_tx_2", r);
    let r = (|| {
        let g = choose(false, false, |f| level_of(f, Field::Ident, 4, false) == Some(false));
        b.node_mut(0).request(g);
        b.forced_step(&[0], Field::Ident, 4, R, 1, &[EV_BIT_ERR, EV_AEF], Ctr::Tec, 8).map(|_| ())
    })();
    ctx.record("overload_tx_3", r);
    let r = b.forced_step(&[0], Field::ErrDel, 8, D, 1, OL, Ctr::Tec, 0).and_then(|_| b.run_idle(300));
    ctx.record("overload_tx_4", r);
}
