//! stuffbit (§11 of the plan): N2 sends 11 frames to N1 (`stuffbit_rx_*`,
//! frames with recessive r0/r1 from the scripted transmitter), N1 sends 8
//! frames to N2 (`stuffbit_tx_*`). The frame set is picked greedily from a
//! deterministic pool to reach the plan's stuff-bit coverage (every stuffed
//! field group: a `D` and an `R` stuff bit inside the group and after its
//! last bit, each followed once by `R` and once by `D`; standard and
//! extended frames; data lengths 0..8). The coverage check is part of the
//! last step (`stuffbit_tx_8`).
use super::*;
use std::collections::BTreeSet;

/// Field group of a bit for the coverage items.
fn group(f: Field) -> Option<u8> {
    match f {
        Field::Ident => Some(0),
        Field::Srr | Field::Ide | Field::Rtr => Some(1),
        Field::ExIdent => Some(2),
        Field::Resv | Field::Dlc => Some(3),
        Field::Data => Some(4),
        Field::Crc => Some(5),
        _ => None,
    }
}

const GROUPS: [&str; 6] = ["Identifier", "SRR/IDE/RTR", "Ex_Identifier", "control/DLC", "Data_Field", "CRC_Sequence"];

/// Coverage items of one frame: (group, after-last-bit, stuff level,
/// follower level) encoded as numbers, plus 100 + data length, 200 + ide.
fn items(f: &Frame, o: BuildOptions) -> BTreeSet<u32> {
    let bits = bus_bits(f, o, false);
    let mut s = BTreeSet::new();
    for k in 1..bits.len() - 1 {
        let b = bits[k];
        if !b.stuff {
            continue;
        }
        let Some(g) = group(b.field) else { continue };
        let next = bits[k + 1];
        let after = group(next.field) != Some(g);
        s.insert((g as u32) * 8 + (after as u32) * 4 + (b.level as u32) * 2 + next.level as u32);
    }
    s.insert(100 + if f.rtr { 0 } else { f.data.len() as u32 });
    s.insert(200 + f.ide as u32);
    s
}

fn describe(item: u32) -> String {
    if item >= 200 {
        return if item == 201 { "an extended frame".into() } else { "a standard frame".into() };
    }
    if item >= 100 {
        return format!("data length {}", item - 100);
    }
    let g = (item / 8) as usize;
    format!(
        "{} stuff bit {} {} followed by {}",
        if item & 2 != 0 { "R" } else { "D" },
        if item & 4 != 0 { "after the last bit of" } else { "inside" },
        GROUPS[g],
        if item & 1 != 0 { "R" } else { "D" }
    )
}

fn pool() -> Vec<Frame> {
    let mut x: u64 = 0x2545_F491_4F6C_DD1D;
    let mut next = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x
    };
    let pats = [0x00u8, 0xFF, 0x0F, 0xF0, 0x1F, 0xF8, 0x83, 0x7C, 0x3E, 0xC1, 0x07, 0xE0];
    let mut v = vec![];
    for k in 0..4000u32 {
        let r = next();
        let ide = k % 2 == 1;
        let rtr = k % 7 == 3;
        let dlc = (k / 2 % 9) as u8;
        let idpat = (r >> 8) as u32;
        let id = if ide { idpat & 0x1FFF_FFFF } else { idpat & 0x7FF };
        let data: Vec<u8> = (0..dlc as usize).map(|i| if (r >> (40 + i)) & 1 == 0 { pats[((r >> (4 * i)) % 12) as usize] } else { (r >> (3 * i)) as u8 }).collect();
        v.push(if rtr { Frame::remote(ide, id, dlc) } else { Frame::data(ide, id, dlc, &data) });
    }
    v
}

/// (frame, options) for the 11 rx and 8 tx steps, and the items of the
/// pool the set does not reach (must be empty).
pub fn frame_set() -> (Vec<(Frame, BuildOptions)>, Vec<Frame>, Vec<String>) {
    let pool = pool();
    let d = BuildOptions::default();
    let opt = |r1, r0| BuildOptions { r1, r0, ..d };
    let mut reach = BTreeSet::new();
    let variants = [opt(false, false), opt(false, true), opt(true, false), opt(true, true)];
    let mut cand: Vec<(Frame, BuildOptions, BTreeSet<u32>)> = vec![];
    for f in &pool {
        for &o in if f.ide { &variants[..] } else { &variants[..2] } {
            let it = items(f, o);
            reach.extend(it.iter().copied());
            cand.push((f.clone(), o, it));
        }
    }
    // Rare items weigh more, so the greedy choice does not strand them.
    let mut freq = std::collections::BTreeMap::new();
    for c in &cand {
        for &i in &c.2 {
            *freq.entry(i).or_insert(0u64) += 1;
        }
    }
    let gain = |c: &BTreeSet<u32>, covered: &BTreeSet<u32>| -> u64 { c.difference(covered).map(|i| 1_000_000 / freq[i]).sum() };
    let mut covered = BTreeSet::new();
    let pick = |filter: &dyn Fn(&Frame, BuildOptions) -> bool, covered: &mut BTreeSet<u32>| -> (Frame, BuildOptions) {
        let best = cand.iter().filter(|c| filter(&c.0, c.1)).max_by_key(|c| gain(&c.2, covered)).unwrap();
        covered.extend(best.2.iter().copied());
        (best.0.clone(), best.1)
    };
    // rx: std r0 D, std r0 R, ext (r1, r0) = DD, DR, RD, RR, then 5 free.
    let mut rx = vec![];
    rx.push(pick(&|f, o| !f.ide && o == d, &mut covered));
    rx.push(pick(&|f, o| !f.ide && o == opt(false, true), &mut covered));
    for (r1, r0) in [(false, false), (false, true), (true, false), (true, true)] {
        rx.push(pick(&|f, o| f.ide && o == opt(r1, r0), &mut covered));
    }
    for _ in 0..5 {
        rx.push(pick(&|_, _| true, &mut covered));
    }
    let mut tx = vec![];
    for _ in 0..8 {
        tx.push(pick(&|_, o| o == d, &mut covered).0);
    }
    let missing = reach.difference(&covered).map(|&i| describe(i)).collect();
    (rx, tx, missing)
}

pub fn run(ctx: &mut Ctx) {
    let mut b = ctx.bench(vec![cfg(), cfg()], true);
    let (rx, tx, missing) = frame_set();
    for (k, (f, o)) in rx.iter().enumerate() {
        let name = format!("stuffbit_rx_{}", k + 1);
        let r = (|| {
            let marks = [b.mark(0), b.mark(1)];
            let rx0 = b.node(0).received().len();
            if *o == BuildOptions::default() {
                b.node_mut(1).request(f.clone());
            } else {
                let h = b.script.unwrap();
                b.sim.get_mut(h).send(script_bits(f, *o));
            }
            b.run_bits(5);
            b.run_idle(300)?;
            check_delivered(&b, 0, rx0, std::slice::from_ref(f))?;
            for (i, &m) in marks.iter().enumerate() {
                let flags = b.since(i, m).iter().filter(|r| r.ev & ((1 << EV_AEF) | (1 << EV_PEF) | (1 << EV_OLF)) != 0).count();
                ensure!(flags == 0, "N{} flagged:{}", i + 1, b.dump_events(i, m));
                ensure!((b.tec(i), b.rec(i)) == (0, 0), "N{} TEC {} REC {}", i + 1, b.tec(i), b.rec(i));
            }
            Ok(())
        })();
        ctx.record(&name, r);
    }
    for (k, f) in tx.iter().enumerate() {
        let name = format!("stuffbit_tx_{}", k + 1);
        let mut r = super::dlc::exchange(&mut b, 0, 1, f);
        if k == tx.len() - 1 && r.is_ok() && !missing.is_empty() {
            r = Err(format!("frame set misses coverage: {}", missing.join("; ")));
        }
        ctx.record(&name, r);
    }
}
