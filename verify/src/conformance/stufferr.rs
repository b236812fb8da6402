//! stufferr (§12 of the plan): a stuff bit forced at both nodes (`N1+N2`,
//! ×1), which acts like a disturbance of the bus at that bit. `stufferr_<k>`:
//! N1 transmits, N2 receives; the plan's addition `stufferr_rx_<k>`: the
//! same frames with the roles swapped.
use super::*;

const D: FaultMode = FaultMode::StuckDominant;
const R: FaultMode = FaultMode::StuckRecessive;

struct Row {
    k: u32,
    frame: Frame,
    field: Field,
    pos: u32,
    mode: FaultMode,
    /// Transmitter: stuff error in arbitration (EXC2, +0) instead of +8.
    exc2: bool,
}

fn stuff_after(f: &Frame, field: Field, pos: u32) -> Option<bool> {
    level_of(f, field, pos, true)
}

fn rows() -> Vec<Row> {
    use Field::*;
    let c = |ide, rtr, field, pos, lvl: bool| choose(ide, rtr, move |f| stuff_after(f, field, pos) == Some(lvl));
    let row = |k, frame, field, pos, mode| Row { k, frame, field, pos, mode, exc2: false };
    vec![
        row(1, c(false, false, Ident, 8, false), Ident, 8, R),
        Row { exc2: true, ..row(2, c(false, false, Ident, 4, true), Ident, 4, D) },
        row(3, c(true, false, Rtr, 1, true), Rtr, 1, D),
        row(4, c(false, true, Rtr, 1, false), Rtr, 1, R),
        // A dominant stuff bit after DLC 2 needs five recessive bits ending at
        // DLC 2, i.e. a recessive r0: no legal frame has it, and the RTL
        // transmitter sends legal frames only. Step 5 uses the only dominant
        // stuff bit a legal frame can have in the DLC field (after DLC 4,
        // r0 dominant, DLC 15), in an extended frame (step 8 uses a standard one).
        row(5, c(true, false, Dlc, 4, false), Dlc, 4, R),
        row(6, c(false, false, Dlc, 2, true), Dlc, 2, D),
        row(7, c(false, false, Dlc, 4, true), Dlc, 4, D),
        row(8, c(false, false, Dlc, 4, false), Dlc, 4, R),
        row(9, c(false, false, Data, 8, false), Data, 8, R),
        row(10, c(false, false, Data, 12, true), Data, 12, D),
        row(11, c(false, false, Data, 64, true), Data, 64, D),
        row(12, c(true, false, Data, 8, false), Data, 8, R),
        row(13, c(false, false, Crc, 8, false), Crc, 8, R),
        row(14, c(false, false, Crc, 1, true), Crc, 1, D),
        row(15, c(false, false, Crc, 15, true), Crc, 15, D),
        row(16, c(false, false, Crc, 15, false), Crc, 15, R),
    ]
}

/// Node `t` sends the row's frame to node `r`; the stuff bit is forced at both.
fn one(b: &mut Bench, row: &Row, t: usize, r: usize) -> Result<(), String> {
    let (tec0, rec0) = (b.tec(t), b.rec(r));
    let rx0 = b.node(r).received().len();
    let mr = b.mark(r);
    let mt0 = b.mark(t);
    b.node_mut(t).request(row.frame.clone());
    let m = b.force_at(&[t, r], row.field, row.pos, true, row.mode, 1)?;
    let ft = b.rec_at(t, m)?;
    // Counters once the error frame is over (before the retry ends).
    b.run_until(40, |b| b.node(t).field() == Field::Inter).map_err(|e| format!("no intermission after the error: {e}{}", b.dump_events(t, m)))?;
    let (tec1, rec1) = (b.tec(t), b.rec(r));
    ensure!(ft.field == row.field && ft.pos == row.pos && ft.stuff && ft.tx_role, "forced bit recorded as {ft}");
    if row.exc2 {
        ensure!(ft.has(EV_STUFF_ERR) && ft.has(EV_EXC2) && ft.has(EV_AEF), "transmitter: expected STUFF_ERR, EXC2, AEF at {ft}");
    } else if row.mode == R {
        ensure!(ft.has(EV_BIT_ERR) && ft.has(EV_AEF), "transmitter: expected BIT_ERR, AEF at {ft}");
    } else {
        ensure!((ft.has(EV_BIT_ERR) || ft.has(EV_STUFF_ERR)) && ft.has(EV_AEF), "transmitter: expected an error and AEF at {ft}");
    }
    let want_tec = tec0 + if row.exc2 { 0 } else { 8 };
    ensure!(tec1 == want_tec, "transmitter TEC {tec0}→{tec1}, expected {want_tec}:{}", b.dump_events(t, mt0));
    let re = b.events(r, mr, EV_STUFF_ERR);
    ensure!(!re.is_empty(), "receiver: no STUFF_ERR:{}", b.dump_events(r, mr));
    ensure!(
        re[0].field == row.field && re[0].pos == row.pos && re[0].has(EV_AEF) && !re[0].tx_role,
        "receiver: STUFF_ERR at {} (expected with AEF at the forced bit {ft})",
        re[0]
    );
    ensure!(rec1 == rec0 + 1, "receiver REC {rec0}→{rec1}, expected +1:{}", b.dump_events(r, mr));
    let errs_t = b.count(t, m, EV_BIT_ERR) + b.count(t, m, EV_STUFF_ERR) + b.count(t, m, EV_FORM_ERR) + b.count(t, m, EV_DAF);
    ensure!(errs_t == 1, "transmitter: further errors:{}", b.dump_events(t, m));
    // The retry succeeds.
    b.run_until(400, |b| b.node(r).received().len() > rx0).map_err(|e| format!("retry not delivered: {e}"))?;
    b.run_idle(100)?;
    check_delivered(b, r, rx0, std::slice::from_ref(&row.frame))?;
    Ok(())
}

pub fn run(ctx: &mut Ctx) {
    let mut b = ctx.bench(vec![cfg(), cfg()], false);
    let rows = rows();
    for row in &rows {
        let r = one(&mut b, row, 0, 1);
        ctx.record(&format!("stufferr_{}", row.k), r);
    }
    for row in &rows {
        let r = one(&mut b, row, 1, 0);
        ctx.record(&format!("stufferr_rx_{}", row.k), r);
    }
}
