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

/// Run one btl case and check it against the tables.
fn check_case(t: u32, case: char, j: u32, brp: u32, with_rtl: bool, rng: &mut ChaCha8Rng) {
    let cfg = timing(t).with_brp(brp);
    let sp = cfg.sp();
    let (outcome, note) = table(t, case, j);
    let tag = format!("btl_{t}{case}_j{j} (BRP {brp}, {outcome:?})");
    let exp = check_edge(&cfg, case, j, outcome, with_rtl, rng, &tag);
    match note {
        TxNote::Rule => {}
        TxNote::AtEdge => assert_eq!(exp.tx_tick, j + 1, "{tag}: table says TX@edge"),
        TxNote::PlusOne => assert_eq!(exp.tx_tick, j + 2, "{tag}: table says TX+1"),
        TxNote::SpPlus2 => assert_eq!(exp.tx_tick, sp + 2, "{tag}: table says TX at SP + 2"),
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

