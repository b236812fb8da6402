//! The btl program of conformance-tests.md §3 on the bit timing logic
//! (`canstar_hdl::btl`), BRP 1 and BRP > 1, RTL and model.
//!
//! `btl_<timing><case>_j<j>`: timing 1 = T10/6/4, 2 = T25/17/1, 3 = T10/8/1. Cases:
//! `a` hard sync with drive `R`, `b` resync with drive `R` (receiver; the
//! program's case `e` is the same at the BTL ports), `d` resync with drive
//! `D` (transmitter; case `c` is the same at the BTL ports), `f` hard sync
//! with drive `D`. The expected sample points, transmit points and TX edges
//! come from the tables of conformance-tests.md §3 and can-protocol.md
//! §3.3–3.6 and §2.5, not from `BtlModel`. `btl_brp_<timing><case>`: the same
//! with BRP > 1, the edge at a random clock inside TQ j.

mod btl_util;
use btl_util::*;

fn timing(t: u32) -> BtlConfig {
    match t {
        1 => BtlConfig::T10_6_4,
        2 => BtlConfig::T25_17_1,
        3 => BtlConfig::T10_8_1,
        _ => panic!("no timing {t}"),
    }
}


#[derive(Debug, Clone, Copy, PartialEq)]
enum TxNote {
    /// The table says nothing; §2.5 decides.
    Rule,
    /// "TX@edge": the transmit point is the tick that detects the edge.
    AtEdge,
    /// "TX+1": one TQ later.
    PlusOne,
    /// "TX postponed to SP + 2".
    SpPlus2,
}

/// The rows of conformance-tests.md §3 (cases a–e) and its case f rules;
/// case f positions the plan leaves to lock-step follow §3.3 (restart only
/// after the sample point).
fn table(t: u32, case: char, j: u32) -> (Outcome, TxNote) {
    use Outcome::*;
    use TxNote::*;
    let sp = timing(t).sp();
    let drive_r = matches!(case, 'b' | 'e');
    if j + 1 == sp {
        // Excluded by the program; P§2.3 fixes the order for canstar: the
        // synchronisation comes before the sample point on that tick.
        return match case {
            'a' => (Restart, Rule),
            'f' | 'c' | 'd' => (Nothing, Rule),
            _ => (Ph1Plus(j.min(timing(t).sjw)), Rule),
        };
    }
    match case {
        'a' => (Restart, Rule),
        'f' => {
            if j + 2 <= sp {
                (Nothing, Rule)
            } else if j >= sp + 2 {
                (Restart, AtEdge)
            } else {
                (Restart, Rule)
            }
        }
        _ => match (t, j) {
            (_, 0) => (Nothing, Rule),
            (1, 1..=4) => (if drive_r { Ph1Plus(j) } else { Nothing }, Rule),
            (1, 6) => (Restart, PlusOne),
            (1, 7..=9) => (Restart, AtEdge),
            (2, 1..=15) => (if drive_r { Ph1Plus(1) } else { Nothing }, Rule),
            (2, 17..=23) => (Ph2Minus(1), Rule),
            (2, 24) => (Restart, AtEdge),
            (3, 1..=6) => (if drive_r { Ph1Plus(1) } else { Nothing }, Rule),
            (3, 8) => (Ph2Minus(1), SpPlus2),
            (3, 9) => (Restart, AtEdge),
            _ => panic!("j = {j} is not in the table of timing {t}"),
        },
    }
}

/// Expected ticks, counted from the bit start (transmit point) of the bit
/// that holds the edge.
#[derive(Debug)]
struct Expect {
    samples: Vec<u32>,
    bit_starts: Vec<u32>,
    /// Tick of the transmit point that takes the new drive level.
    tx_tick: u32,
    horizon: u32,
}

fn expect(cfg: &BtlConfig, outcome: Outcome, j: u32) -> Expect {
    let (sp, ntq) = (cfg.sp(), cfg.ntq());
    // (samples inside the edge bit, first transmit point, origin (cnt = 0) of the next bit)
    let (mut samples, tx_tick, origin) = match outcome {
        Outcome::Nothing => (vec![], ntq, ntq),
        Outcome::Ph1Plus(d) => (vec![sp + d], ntq + d, ntq + d),
        Outcome::Ph2Minus(s) => (vec![sp], (ntq - s).max(sp + 2), ntq - s),
        Outcome::Restart => {
            // The restart makes the edge's TQ (index j) SYNC_SEG: cnt = 0 at tick j.
            // §2.5: the transmit point is not earlier than the latest sample + IPT.
            if j >= sp {
                (vec![sp], (j + 1).max(sp + 2), j)
            } else {
                (vec![], j + 1, j)
            }
        }
    };
    if outcome == Outcome::Nothing {
        samples.push(sp);
    }
    let horizon = origin + 2 * ntq;
    let mut bit_starts = vec![0, tx_tick];
    let mut k = 0;
    while origin + k * ntq <= horizon {
        if k > 0 {
            bit_starts.push(origin + k * ntq);
        }
        if origin + k * ntq + sp <= horizon {
            samples.push(origin + k * ntq + sp);
        }
        k += 1;
    }
    samples.sort();
    samples.dedup();
    Expect { samples, bit_starts, tx_tick, horizon }
}

/// Run one btl case and check it against the tables.
fn check_case(t: u32, case: char, j: u32, brp: u32, with_rtl: bool, rng: &mut ChaCha8Rng) {
    let cfg = timing(t).with_brp(brp);
    let (sp, ntq) = (cfg.sp(), cfg.ntq());
    let (outcome, note) = table(t, case, j);
    let exp = expect(&cfg, outcome, j);
    let tag = format!("btl_{t}{case}_j{j} (BRP {brp}, {outcome:?})");
    match note {
        TxNote::Rule => {}
        TxNote::AtEdge => assert_eq!(exp.tx_tick, j + 1, "{tag}: table says TX@edge"),
        TxNote::PlusOne => assert_eq!(exp.tx_tick, j + 2, "{tag}: table says TX+1"),
        TxNote::SpPlus2 => assert_eq!(exp.tx_tick, sp + 2, "{tag}: table says TX at SP + 2"),
    }
    let (hs_en, level) = match case {
        'a' => (true, R),
        'b' | 'e' => (false, R),
        'c' | 'd' => (false, D),
        'f' => (true, D),
        _ => panic!("case {case}"),
    };
    let b = brp as usize;
    let mut rig = Rig::new(with_rtl);
    rig.reset(&cfg);
    // Two bits with a recessive bus: the last sample is R, sync enabled.
    // TX carries the opposite of `level` in the edge bit, so that the
    // transmit point that takes `level` is visible on TX.
    let mut i = BtlInputs::with_config(&cfg);
    i.hs_en = hs_en;
    i.drive = !level;
    let mut starts = 0;
    let c0 = loop {
        let p = rig.step(&i);
        if p.bit_start {
            starts += 1;
            if starts == 2 {
                break rig.trace.len() - 1;
            }
        }
        assert!(rig.trace.len() < 3 * ntq as usize * b + 10, "{tag}: no bit start");
    };
    let c_edge = c0 + j as usize * b + rng.gen_range(1..=b);
    let end = c0 + exp.horizon as usize * b + 2;
    i.drive = level;
    while rig.trace.len() < end {
        i.rx = rig.trace.len() < c_edge;
        rig.step(&i);
    }
    let tr = &rig.trace;
    let tick_of = |c: usize, what: &str| -> u32 {
        assert_eq!((c - c0) % b, 0, "{tag}: {what} at cycle {c} is not on the TQ grid (bit start at {c0})");
        ((c - c0) / b) as u32
    };
    let mut samples = vec![];
    let mut starts = vec![];
    let mut syncs = vec![];
    for (c, p) in tr.iter().enumerate().skip(c0) {
        if p.bit_start {
            starts.push(tick_of(c, "bit_start"));
            assert!(p.tq, "{tag}: bit_start without tq at cycle {c}");
        }
        if c > c0 && p.sample {
            let k = tick_of(c - 1, "sample");
            samples.push(k);
            let want = if k > j { D } else { R };
            assert_eq!(p.busmon, want, "{tag}: sampled level at tick {k}");
        }
        if c > c0 && (p.hard_sync || p.resync) {
            syncs.push((tick_of(c - 1, "sync"), p.hard_sync, p.resync));
        }
    }
    samples.retain(|&k| k <= exp.horizon);
    starts.retain(|&k| k <= exp.horizon);
    assert_eq!(samples, exp.samples, "{tag}: sample points (ticks from the bit start)");
    assert_eq!(starts, exp.bit_starts, "{tag}: transmit points (ticks from the bit start)");
    assert_eq!(syncs, vec![(j + 1, hs_en, !hs_en)], "{tag}: synchronisation strobes (tick, hard, resync)");
    // TX: the old level up to the transmit point, the new one from the next clock.
    let tx_change = c0 + exp.tx_tick as usize * b + 1;
    for (c, p) in tr.iter().enumerate().skip(c0 + 1) {
        let want = if c >= tx_change { level } else { !level };
        assert_eq!(p.tx, want, "{tag}: TX at cycle {c} (tick {}); expected change at tick {}", (c - c0) / b, exp.tx_tick);
    }
}

macro_rules! btl_case_tests {
    ($t:expr, $case:expr; $($name:ident = $j:expr),* $(,)?) => {
        $(
            #[test]
            fn $name() {
                let mut rng = ChaCha8Rng::seed_from_u64($j);
                check_case($t, $case, $j, 1, true, &mut rng);
            }
        )*
    };
}

btl_case_tests!(1, 'a'; btl_1a_j0 = 0, btl_1a_j1 = 1, btl_1a_j2 = 2, btl_1a_j3 = 3, btl_1a_j4 = 4, btl_1a_j6 = 6, btl_1a_j7 = 7, btl_1a_j8 = 8, btl_1a_j9 = 9,);
btl_case_tests!(1, 'b'; btl_1b_j0 = 0, btl_1b_j1 = 1, btl_1b_j2 = 2, btl_1b_j3 = 3, btl_1b_j4 = 4, btl_1b_j6 = 6, btl_1b_j7 = 7, btl_1b_j8 = 8, btl_1b_j9 = 9,);
btl_case_tests!(1, 'd'; btl_1d_j0 = 0, btl_1d_j1 = 1, btl_1d_j2 = 2, btl_1d_j3 = 3, btl_1d_j4 = 4, btl_1d_j6 = 6, btl_1d_j7 = 7, btl_1d_j8 = 8, btl_1d_j9 = 9,);
btl_case_tests!(1, 'f'; btl_1f_j0 = 0, btl_1f_j1 = 1, btl_1f_j2 = 2, btl_1f_j3 = 3, btl_1f_j4 = 4, btl_1f_j6 = 6, btl_1f_j7 = 7, btl_1f_j8 = 8, btl_1f_j9 = 9,);
btl_case_tests!(2, 'a'; btl_2a_j0 = 0, btl_2a_j1 = 1, btl_2a_j2 = 2, btl_2a_j3 = 3, btl_2a_j4 = 4, btl_2a_j5 = 5, btl_2a_j6 = 6, btl_2a_j7 = 7, btl_2a_j8 = 8, btl_2a_j9 = 9, btl_2a_j10 = 10, btl_2a_j11 = 11, btl_2a_j12 = 12, btl_2a_j13 = 13, btl_2a_j14 = 14, btl_2a_j15 = 15, btl_2a_j17 = 17, btl_2a_j18 = 18, btl_2a_j19 = 19, btl_2a_j20 = 20, btl_2a_j21 = 21, btl_2a_j22 = 22, btl_2a_j23 = 23, btl_2a_j24 = 24,);
btl_case_tests!(2, 'b'; btl_2b_j0 = 0, btl_2b_j1 = 1, btl_2b_j2 = 2, btl_2b_j3 = 3, btl_2b_j4 = 4, btl_2b_j5 = 5, btl_2b_j6 = 6, btl_2b_j7 = 7, btl_2b_j8 = 8, btl_2b_j9 = 9, btl_2b_j10 = 10, btl_2b_j11 = 11, btl_2b_j12 = 12, btl_2b_j13 = 13, btl_2b_j14 = 14, btl_2b_j15 = 15, btl_2b_j17 = 17, btl_2b_j18 = 18, btl_2b_j19 = 19, btl_2b_j20 = 20, btl_2b_j21 = 21, btl_2b_j22 = 22, btl_2b_j23 = 23, btl_2b_j24 = 24,);
btl_case_tests!(2, 'd'; btl_2d_j0 = 0, btl_2d_j1 = 1, btl_2d_j2 = 2, btl_2d_j3 = 3, btl_2d_j4 = 4, btl_2d_j5 = 5, btl_2d_j6 = 6, btl_2d_j7 = 7, btl_2d_j8 = 8, btl_2d_j9 = 9, btl_2d_j10 = 10, btl_2d_j11 = 11, btl_2d_j12 = 12, btl_2d_j13 = 13, btl_2d_j14 = 14, btl_2d_j15 = 15, btl_2d_j17 = 17, btl_2d_j18 = 18, btl_2d_j19 = 19, btl_2d_j20 = 20, btl_2d_j21 = 21, btl_2d_j22 = 22, btl_2d_j23 = 23, btl_2d_j24 = 24,);
btl_case_tests!(2, 'f'; btl_2f_j0 = 0, btl_2f_j1 = 1, btl_2f_j2 = 2, btl_2f_j3 = 3, btl_2f_j4 = 4, btl_2f_j5 = 5, btl_2f_j6 = 6, btl_2f_j7 = 7, btl_2f_j8 = 8, btl_2f_j9 = 9, btl_2f_j10 = 10, btl_2f_j11 = 11, btl_2f_j12 = 12, btl_2f_j13 = 13, btl_2f_j14 = 14, btl_2f_j15 = 15, btl_2f_j17 = 17, btl_2f_j18 = 18, btl_2f_j19 = 19, btl_2f_j20 = 20, btl_2f_j21 = 21, btl_2f_j22 = 22, btl_2f_j23 = 23, btl_2f_j24 = 24,);
btl_case_tests!(3, 'a'; btl_3a_j0 = 0, btl_3a_j1 = 1, btl_3a_j2 = 2, btl_3a_j3 = 3, btl_3a_j4 = 4, btl_3a_j5 = 5, btl_3a_j6 = 6, btl_3a_j8 = 8, btl_3a_j9 = 9,);
btl_case_tests!(3, 'b'; btl_3b_j0 = 0, btl_3b_j1 = 1, btl_3b_j2 = 2, btl_3b_j3 = 3, btl_3b_j4 = 4, btl_3b_j5 = 5, btl_3b_j6 = 6, btl_3b_j8 = 8, btl_3b_j9 = 9,);
btl_case_tests!(3, 'd'; btl_3d_j0 = 0, btl_3d_j1 = 1, btl_3d_j2 = 2, btl_3d_j3 = 3, btl_3d_j4 = 4, btl_3d_j5 = 5, btl_3d_j6 = 6, btl_3d_j8 = 8, btl_3d_j9 = 9,);
btl_case_tests!(3, 'f'; btl_3f_j0 = 0, btl_3f_j1 = 1, btl_3f_j2 = 2, btl_3f_j3 = 3, btl_3f_j4 = 4, btl_3f_j5 = 5, btl_3f_j6 = 6, btl_3f_j8 = 8, btl_3f_j9 = 9,);

fn sp_minus_1(t: u32) -> u32 {
    timing(t).sp() - 1
}

macro_rules! btl_brp_tests {
    ($($name:ident = $t:expr, $case:expr;)*) => {
        $(
            #[test]
            fn $name() {
                let mut rng = ChaCha8Rng::seed_from_u64(0xb7 + $t);
                for brp in [2, 3, 5, 32] {
                    for j in 0..timing($t).ntq() {
                        if j != sp_minus_1($t) {
                            check_case($t, $case, j, brp, true, &mut rng);
                        }
                    }
                }
            }
        )*
    };
}

btl_brp_tests! {
    btl_brp_1a = 1, 'a'; btl_brp_1b = 1, 'b'; btl_brp_1d = 1, 'd'; btl_brp_1f = 1, 'f';
    btl_brp_2a = 2, 'a'; btl_brp_2b = 2, 'b'; btl_brp_2d = 2, 'd'; btl_brp_2f = 2, 'f';
    btl_brp_3a = 3, 'a'; btl_brp_3b = 3, 'b'; btl_brp_3d = 3, 'd'; btl_brp_3f = 3, 'f';
}

/// j = SP − 1, which the Bosch program leaves out: P§2.3 puts the
/// synchronisation before the sample point on the same tick.
#[test]
fn btl_sp_minus_1_ordering() {
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    for t in 1..=3 {
        for case in ['a', 'b', 'd', 'f'] {
            for brp in [1, 3] {
                check_case(t, case, sp_minus_1(t), brp, true, &mut rng);
            }
        }
    }
}

/// The reference model alone reproduces every table row, for all six cases
/// of the program (b/e and c/d differ only above the BTL).
#[test]
fn model_follows_btl_tables() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for t in 1..=3 {
        for case in ['a', 'b', 'c', 'd', 'e', 'f'] {
            for brp in [1, 4] {
                for j in 0..timing(t).ntq() {
                    if j != sp_minus_1(t) {
                        check_case(t, case, j, brp, false, &mut rng);
                    }
                }
            }
        }
    }
}

/// §3.6: the worked example, straight on the TQ-level model.
#[test]
fn model_worked_example_3_6() {
    for j in 1..10u32 {
        if j == 5 {
            continue;
        }
        for drive in [R, D] {
            let mut m = BtlModel::new(BtlConfig::T10_6_4);
            // One full bit with a recessive bus, ending in a bit start.
            for _ in 0..10 {
                m.tq_tick(R, drive, false);
            }
            assert_eq!(m.cnt, 0);
            for _ in 0..j {
                m.tq_tick(R, drive, false);
            }
            let ev = m.tq_tick(D, drive, false);
            let e = ev.phase_error.expect("synchronisation");
            let want_e = if j < 6 { j as i32 } else { j as i32 - 10 };
            assert_eq!(e, want_e, "j {j}");
            match (j, drive) {
                (1..=4, R) => assert_eq!((m.sp, m.nb), (6 + j, 10 + j), "j {j}: PH1 + e"),
                (1..=4, D) => assert_eq!((m.sp, m.nb), (6, 10), "j {j}: none while driving D"),
                (6, _) => assert!(ev.restart && ev.postponed && !ev.bit_start, "j 6: restart, TX postponed"),
                _ => assert!(ev.restart && ev.bit_start, "j {j}: restart, TX at the edge"),
            }
        }
    }
}

