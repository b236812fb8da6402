//! txarb (§13 of the plan): bit errors in the arbitration field. N1 is
//! alone; every step uses a fresh frame, forces one bit at N1 and then
//! withdraws the request. Derived totals after txarb_20: TEC 96, REC 5,
//! error-active throughout.
use canstar_controller::view::CoreView;
use super::*;

const D: FaultMode = FaultMode::StuckDominant;
const R: FaultMode = FaultMode::StuckRecessive;

struct Step {
    name: &'static str,
    frame: Frame,
    field: Field,
    pos: u32,
    stuff: bool,
    mode: FaultMode,
    /// Expected: (event at the forced bit, TEC delta, REC delta, where the
    /// stuff error of a lost arbitration falls).
    ev: usize,
    dtec: u32,
    drec: u32,
    stuff_err_at: Option<(Field, u32)>,
    exc2: Option<bool>,
}

fn lv(f: &Frame, field: Field, pos: u32, stuff: bool) -> Option<bool> {
    level_of(f, field, pos, stuff)
}

/// The first stuff bit after IDE of `f` (any field), if dominant.
fn first_stuff_after_ide(f: &Frame) -> Option<BusBit> {
    let bits = bus_bits(f, BuildOptions::default(), false);
    let k = bits.iter().position(|b| b.field == Field::Ide)?;
    bits[k + 1..].iter().copied().find(|b| b.stuff)
}

fn steps() -> Vec<Step> {
    use Field::*;
    let st = |name, frame, field, pos, stuff, mode, ev, dtec, drec| Step { name, frame, field, pos, stuff, mode, ev, dtec, drec, stuff_err_at: None, exc2: None };
    let mut v = vec![];
    let f = choose(false, false, |f| lv(f, Ident, 2, false) == Some(true));
    v.push(Step { stuff_err_at: Some((Ident, 7)), ..st("txarb_1", f, Ident, 2, false, D, EV_ARB_LOST, 0, 1) });
    let f = choose(false, false, |f| lv(f, Ident, 7, false) == Some(false));
    v.push(st("txarb_2", f, Ident, 7, false, R, EV_BIT_ERR, 8, 0));
    let f = choose(false, true, |_| true);
    v.push(Step { stuff_err_at: Some((ExIdent, 4)), ..st("txarb_3", f, Rtr, 1, false, D, EV_ARB_LOST, 0, 1) });
    let f = choose(false, false, |_| true);
    v.push(st("txarb_4", f, Rtr, 1, false, R, EV_BIT_ERR, 8, 0));
    let f = choose(false, false, |f| lv(f, Ident, 9, true) == Some(true));
    v.push(Step { exc2: Some(true), ..st("txarb_5", f, Ident, 9, true, D, EV_STUFF_ERR, 0, 0) });
    let f = choose(false, false, |f| lv(f, Ident, 5, true) == Some(false));
    v.push(st("txarb_6", f, Ident, 5, true, R, EV_BIT_ERR, 8, 0));
    let f = choose(false, false, |f| lv(f, Rtr, 1, true) == Some(true));
    v.push(Step { exc2: Some(true), ..st("txarb_7", f, Rtr, 1, true, D, EV_STUFF_ERR, 0, 0) });
    let f = choose(false, true, |f| lv(f, Rtr, 1, true) == Some(false));
    v.push(st("txarb_8", f, Rtr, 1, true, R, EV_BIT_ERR, 8, 0));
    let f = choose(true, false, |_| true);
    v.push(Step { stuff_err_at: Some((Dlc, 4)), ..st("txarb_9", f, Ide, 1, false, D, EV_ARB_LOST, 0, 1) });
    let f = choose(false, false, |_| true);
    v.push(st("txarb_10", f, Ide, 1, false, R, EV_BIT_ERR, 8, 0));
    let f = choose(false, false, |f| lv(f, Ide, 1, true) == Some(true));
    v.push(Step { exc2: Some(false), ..st("txarb_11", f, Ide, 1, true, D, EV_STUFF_ERR, 8, 0) });
    // A standard IDE is dominant, so the stuff bit right after it is always
    // recessive: use the first stuff bit after IDE that is dominant.
    let f = choose(false, false, |f| first_stuff_after_ide(f).is_some_and(|b| !b.level));
    let sb = first_stuff_after_ide(&f).unwrap();
    v.push(st("txarb_12", f, sb.field, sb.pos as u32, true, R, EV_BIT_ERR, 8, 0));
    let f = choose(true, false, |f| lv(f, ExIdent, 4, false) == Some(true));
    v.push(Step { stuff_err_at: Some((ExIdent, 9)), ..st("txarb_13", f, ExIdent, 4, false, D, EV_ARB_LOST, 0, 1) });
    let f = choose(true, false, |f| lv(f, ExIdent, 2, false) == Some(false));
    v.push(st("txarb_14", f, ExIdent, 2, false, R, EV_BIT_ERR, 8, 0));
    let f = choose(true, true, |_| true);
    v.push(Step { stuff_err_at: Some((Dlc, 3)), ..st("txarb_15", f, Rtr, 1, false, D, EV_ARB_LOST, 0, 1) });
    let f = choose(true, false, |_| true);
    v.push(st("txarb_16", f, Rtr, 1, false, R, EV_BIT_ERR, 8, 0));
    let f = choose(true, false, |f| lv(f, ExIdent, 15, true) == Some(true));
    v.push(Step { exc2: Some(true), ..st("txarb_17", f, ExIdent, 15, true, D, EV_STUFF_ERR, 0, 0) });
    let f = choose(true, false, |f| lv(f, ExIdent, 11, true) == Some(false));
    v.push(st("txarb_18", f, ExIdent, 11, true, R, EV_BIT_ERR, 8, 0));
    let f = choose(true, false, |f| lv(f, Rtr, 1, true) == Some(true));
    v.push(Step { exc2: Some(false), ..st("txarb_19", f, Rtr, 1, true, D, EV_STUFF_ERR, 8, 0) });
    let f = choose(true, true, |f| lv(f, Rtr, 1, true) == Some(false));
    v.push(st("txarb_20", f, Rtr, 1, true, R, EV_BIT_ERR, 8, 0));
    v
}

fn one(b: &mut Bench, s: &Step) -> Result<(), String> {
    let (tec0, rec0) = (b.tec(0), b.rec(0));
    b.node_mut(0).request(s.frame.clone());
    let m = b.force_at(&[0], s.field, s.pos, s.stuff, s.mode, 1);
    b.node_mut(0).withdraw();
    let m = m?;
    b.run_idle(200)?;
    let r = b.rec_at(0, m)?;
    ensure!(r.field == s.field && r.pos == s.pos && r.stuff == s.stuff && r.tx_role, "forced bit recorded as {r}");
    ensure!(r.has(s.ev), "forced bit: expected {} at {r}", ["", "ARB_LOST", "BIT_ERR", "STUFF_ERR"][s.ev]);
    if s.ev == EV_BIT_ERR || s.ev == EV_STUFF_ERR {
        ensure!(r.has(EV_AEF), "expected an active error flag at {r}");
    }
    if let Some(x) = s.exc2 {
        ensure!(r.has(EV_EXC2) == x, "EXC2 expected {x} at {r}");
    }
    if let Some((field, pos)) = s.stuff_err_at {
        let e = b.events(0, m, EV_STUFF_ERR);
        ensure!(!e.is_empty(), "no stuff error after the lost arbitration:{}", b.dump_events(0, m));
        ensure!(e[0].field == field && e[0].pos == pos && !e[0].tx_role && e[0].has(EV_AEF), "stuff error at {} (expected after {}{pos}, receiver, AEF)", e[0], field.name());
    }
    let errs = b.count(0, m, EV_BIT_ERR) + b.count(0, m, EV_STUFF_ERR) + b.count(0, m, EV_FORM_ERR) + b.count(0, m, EV_ACK_ERR);
    ensure!(errs == 1, "expected exactly one error, got:{}", b.dump_events(0, m));
    ensure!(
        (b.tec(0), b.rec(0)) == (tec0 + s.dtec, rec0 + s.drec),
        "TEC {}→{} REC {}→{} (expected Δ +{} / +{})",
        tec0,
        b.tec(0),
        rec0,
        b.rec(0),
        s.dtec,
        s.drec
    );
    ensure!(b.state(0) == 0, "N1 not error-active (state {})", b.state(0));
    Ok(())
}

pub fn run(ctx: &mut Ctx) {
    let mut b = ctx.bench(vec![cfg()], false);
    let steps = steps();
    let last = steps.len() - 1;
    for (k, s) in steps.iter().enumerate() {
        let mut r = one(&mut b, s);
        if k == last && r.is_ok() {
            r = (|| {
                ensure!((b.tec(0), b.rec(0)) == (96, 5), "totals TEC {} REC {} (expected 96 / 5)", b.tec(0), b.rec(0));
                ensure!(b.node(0).core.err_warn(), "error warning not set at TEC 96");
                Ok(())
            })();
        }
        ctx.record(s.name, r);
    }
}
