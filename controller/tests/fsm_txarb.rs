//! The txarb program of conformance-tests.md §13 on the bit-level harness
//! (one node, every level it reads beyond its own TX comes from its
//! override): bit errors in the arbitration field. Derived totals after the
//! 20 steps: TEC 96, REC 5, error-active throughout.
mod common;
use canstar_controller::frame::{bus_bits, BuildOptions, BusBit, Frame};
use canstar_controller::fsm::*;
use common::*;

/// First frame (from a deterministic family) whose bus bits satisfy `pred`.
#[track_caller]
fn find(ide: bool, rtr: bool, pred: impl Fn(&[BusBit]) -> bool) -> Frame {
    for k in 0u32..200_000 {
        let id = if ide { k.wrapping_mul(2_654_435_761) & 0x1FFF_FFFF } else { k & 0x7FF };
        let dlc = ((k >> 11) % 9) as u8;
        let f = if rtr { Frame::remote(ide, id, dlc) } else { Frame::data(ide, id, dlc, &[0x5A, 0xF0, 0x0F, 0x33]) };
        if pred(&bus_bits(&f, BuildOptions::default(), false)) {
            return f;
        }
    }
    panic!("no frame found");
}

fn bit(bits: &[BusBit], f: Field, pos: u8, stuff: bool) -> Option<BusBit> {
    bits.iter().copied().find(|b| b.field == f && b.pos == pos && b.stuff == stuff)
}

/// Force N1 at (field, pos[, stuff bit]) and return its record of that bit.
fn step(b: &mut Bus, f: &Frame, field: Field, pos: u8, stuff: bool, o: Ovr) -> Rec {
    b.request(0, f);
    if stuff {
        b.run_to_stuff(0, field, pos, 500);
    } else {
        b.run_to(0, field, pos, 500);
    }
    b.force_bit(0, o);
    let r = b.last(0).clone();
    b.withdraw(0);
    b.run_idle(300);
    r
}

#[test]
fn txarb_program() {
    let mut b = Bus::integrated(1);
    let (d, r) = (Ovr::StuckD, Ovr::StuckR);
    let mut tec = 0;
    let mut rec = 0;
    let mut check = |b: &Bus, name: &str, dt: u64, dr: u64| {
        tec += dt;
        rec += dr;
        assert_eq!((b.tec(0), b.rec(0)), (tec, rec), "{name}");
        assert_eq!(b.state(0), 0, "{name}");
    };
    let lev = |bits: &[BusBit], f, p, s| bit(bits, f, p, s).map(|x| x.level);

    // 1: std, ID 2 recessive, forced D -> lost arbitration, then a stuff error as receiver
    let f = find(false, false, |x| lev(x, Field::Ident, 2, false) == Some(true));
    let rr = step(&mut b, &f, Field::Ident, 2, false, d);
    assert!(rr.has(EV_ARB_LOST));
    assert_eq!(b.events(0, EV_STUFF_ERR, rr.bit).len(), 1);
    check(&b, "txarb_1", 0, 1);
    // 2: std, ID 7 dominant, forced R -> bit error
    let f = find(false, false, |x| lev(x, Field::Ident, 7, false) == Some(false));
    assert!(step(&mut b, &f, Field::Ident, 7, false, r).has(EV_BIT_ERR));
    check(&b, "txarb_2", 8, 0);
    // 3: std remote, RTR forced D -> lost; N1 reads IDE R (extended), stuff error
    let f = find(false, true, |_| true);
    let rr = step(&mut b, &f, Field::Rtr, 1, false, d);
    assert!(rr.has(EV_ARB_LOST));
    let se = b.events(0, EV_STUFF_ERR, rr.bit);
    assert!(se[0].field == Field::ExIdent && se[0].pos == 4, "{:?}", se[0]);
    check(&b, "txarb_3", 0, 1);
    // 4: std data, RTR forced R -> bit error
    let f = find(false, false, |_| true);
    assert!(step(&mut b, &f, Field::Rtr, 1, false, r).has(EV_BIT_ERR));
    check(&b, "txarb_4", 8, 0);
    // 5: R stuff bit after ID 9, forced D -> stuff error inside arbitration, EXC2
    let f = find(false, false, |x| lev(x, Field::Ident, 9, true) == Some(true));
    let rr = step(&mut b, &f, Field::Ident, 9, true, d);
    assert!(rr.has(EV_STUFF_ERR) && rr.has(EV_EXC2));
    check(&b, "txarb_5", 0, 0);
    // 6: D stuff bit after ID 5, forced R -> bit error
    let f = find(false, false, |x| lev(x, Field::Ident, 5, true) == Some(false));
    assert!(step(&mut b, &f, Field::Ident, 5, true, r).has(EV_BIT_ERR));
    check(&b, "txarb_6", 8, 0);
    // 7: std, R stuff bit after RTR, forced D -> EXC2
    let f = find(false, false, |x| lev(x, Field::Rtr, 1, true) == Some(true));
    let rr = step(&mut b, &f, Field::Rtr, 1, true, d);
    assert!(rr.has(EV_STUFF_ERR) && rr.has(EV_EXC2));
    check(&b, "txarb_7", 0, 0);
    // 8: std (remote: RTR recessive), D stuff bit after RTR, forced R -> bit error
    let f = find(false, true, |x| lev(x, Field::Rtr, 1, true) == Some(false));
    assert!(step(&mut b, &f, Field::Rtr, 1, true, r).has(EV_BIT_ERR));
    check(&b, "txarb_8", 8, 0);
    // 9: extended, IDE forced D -> lost; N1 reads a standard remote frame, stuff error
    let f = find(true, false, |_| true);
    let rr = step(&mut b, &f, Field::Ide, 1, false, d);
    assert!(rr.has(EV_ARB_LOST));
    let se = b.events(0, EV_STUFF_ERR, rr.bit);
    assert!(se[0].field == Field::Dlc && se[0].pos == 4, "{:?}", se[0]);
    check(&b, "txarb_9", 0, 1);
    // 10: std, IDE forced R -> bit error
    let f = find(false, false, |_| true);
    assert!(step(&mut b, &f, Field::Ide, 1, false, r).has(EV_BIT_ERR));
    check(&b, "txarb_10", 8, 0);
    // 11: std, R stuff bit after IDE, forced D -> stuff error outside arbitration, +8
    let f = find(false, false, |x| lev(x, Field::Ide, 1, true) == Some(true));
    let rr = step(&mut b, &f, Field::Ide, 1, true, d);
    assert!(rr.has(EV_STUFF_ERR) && !rr.has(EV_EXC2));
    check(&b, "txarb_11", 8, 0);
    // 12: std, "D stuff bit after IDE": a standard IDE is dominant, so the
    // stuff bit right after it is always recessive; use a dominant
    // stuff bit after it (in the data field; r0 is dominant too), forced R -> bit error
    let f = Frame::std(0x555, &[0x1F]);
    assert_eq!(lev(&bus_bits(&f, BuildOptions::default(), false), Field::Data, 8, true), Some(false));
    assert!(step(&mut b, &f, Field::Data, 8, true, r).has(EV_BIT_ERR));
    check(&b, "txarb_12", 8, 0);
    // 13: ext, Ex_Identifier 4 recessive, forced D -> lost, stuff error
    let f = find(true, false, |x| lev(x, Field::ExIdent, 4, false) == Some(true));
    let rr = step(&mut b, &f, Field::ExIdent, 4, false, d);
    assert!(rr.has(EV_ARB_LOST));
    check(&b, "txarb_13", 0, 1);
    // 14: ext, Ex_Identifier 2 dominant, forced R -> bit error
    let f = find(true, false, |x| lev(x, Field::ExIdent, 2, false) == Some(false));
    assert!(step(&mut b, &f, Field::ExIdent, 2, false, r).has(EV_BIT_ERR));
    check(&b, "txarb_14", 8, 0);
    // 15: ext remote, RTR forced D -> lost; N1 reads a data frame, stuff error
    let f = find(true, true, |_| true);
    let rr = step(&mut b, &f, Field::Rtr, 1, false, d);
    assert!(rr.has(EV_ARB_LOST));
    check(&b, "txarb_15", 0, 1);
    // 16: ext data, RTR forced R -> bit error
    let f = find(true, false, |_| true);
    assert!(step(&mut b, &f, Field::Rtr, 1, false, r).has(EV_BIT_ERR));
    check(&b, "txarb_16", 8, 0);
    // 17: ext, R stuff bit after Ex_Identifier 15, forced D -> EXC2
    let f = find(true, false, |x| lev(x, Field::ExIdent, 15, true) == Some(true));
    let rr = step(&mut b, &f, Field::ExIdent, 15, true, d);
    assert!(rr.has(EV_STUFF_ERR) && rr.has(EV_EXC2));
    check(&b, "txarb_17", 0, 0);
    // 18: ext, D stuff bit after Ex_Identifier 11, forced R -> bit error
    let f = find(true, false, |x| lev(x, Field::ExIdent, 11, true) == Some(false));
    assert!(step(&mut b, &f, Field::ExIdent, 11, true, r).has(EV_BIT_ERR));
    check(&b, "txarb_18", 8, 0);
    // 19: ext, R stuff bit after RTR, forced D -> stuff error outside arbitration, +8
    let f = find(true, false, |x| lev(x, Field::Rtr, 1, true) == Some(true));
    let rr = step(&mut b, &f, Field::Rtr, 1, true, d);
    assert!(rr.has(EV_STUFF_ERR) && !rr.has(EV_EXC2));
    check(&b, "txarb_19", 8, 0);
    // 20: ext (remote), D stuff bit after RTR, forced R -> bit error
    let f = find(true, true, |x| lev(x, Field::Rtr, 1, true) == Some(false));
    assert!(step(&mut b, &f, Field::Rtr, 1, true, r).has(EV_BIT_ERR));
    check(&b, "txarb_20", 8, 0);

    assert_eq!((b.tec(0), b.rec(0)), (96, 5));
    assert!(b.nodes[0].err_warn.val(), "warning set at TEC 96");
}
