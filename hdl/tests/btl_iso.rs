//! The bit-timing clauses of ISO 11898-1 (CAN 2.0 §9, can-protocol.md §2–§3)
//! across the programmable range, PH2 = 1 TQ and PH2 != PH1 included: for
//! one edge at every TQ index j of a bit, in the four situations of the Bosch
//! btl program (hard synchronisation and resynchronisation, driving R or D),
//! the sample points, transmit points and TX of the RTL (and of the model,
//! which the rig compares on every clock) are those the rules give:
//!
//! - the sample point lies SP = 1 + PROP + PH1 TQ after the bit start; a
//!   hard synchronisation makes the edge's TQ SYNC_SEG (§3.3);
//! - a late edge (e > 0) lengthens PH1 by min(e, SJW) when driving R, and
//!   does nothing when driving D (§3.4, §3.5);
//! - an early edge (e < 0) restarts the bit when |e| <= SJW, else shortens
//!   PH2 by SJW (§3.4); with PH2 = 1 every early edge has e = −1 and
//!   restarts;
//! - a transmit point is never less than IPT = min(PH2, 2) TQ after the
//!   sample point (§2.5): with PH2 = 1 a restart in PH2 transmits at the
//!   edge, nothing is postponed.
//!
//! Expectations are computed from these rules, not from `BtlModel`
//! (`btl_cases.rs` does the same for the three timings of the Bosch tables).

mod btl_util;
use btl_util::*;

/// The rules of §3.3–§3.5 for an edge in TQ j of a bit that started normally.
fn rule(cfg: &BtlConfig, case: char, j: u32) -> Outcome {
    let (sp, ntq, sjw) = (cfg.sp(), cfg.ntq(), cfg.sjw);
    let (hard, drive) = situation(case);
    if hard {
        // §3.3: restart with drive R; with drive D only after the sample point
        return if drive == R || j >= sp { Outcome::Restart } else { Outcome::Nothing };
    }
    if j == 0 {
        Outcome::Nothing
    } else if j < sp {
        // e = j > 0 (the edge on the sample tick itself, j = SP − 1, too: it
        // is synchronised before it is sampled)
        if drive == R {
            Outcome::Ph1Plus(j.min(sjw))
        } else {
            Outcome::Nothing
        }
    } else if ntq - j <= sjw {
        Outcome::Restart
    } else {
        Outcome::Ph2Minus(sjw)
    }
}

/// One edge in TQ j, checked against [`rule`].
fn check(cfg: &BtlConfig, case: char, j: u32, rng: &mut ChaCha8Rng) {
    let outcome = rule(cfg, case, j);
    let tag = format!("{cfg:?} case {case} j {j} ({outcome:?})");
    let exp = check_edge(cfg, case, j, outcome, true, rng, &tag);
    if cfg.ph2 == 1 && outcome == Outcome::Restart {
        assert_eq!(exp.tx_tick, j + 1, "{tag}: PH2 = 1 transmits at the edge");
    }
    if outcome == Outcome::Restart && j >= cfg.sp() && j + 1 < cfg.sp() + cfg.ipt() {
        assert!(exp.tx_tick > j + 1, "{tag}: postponed");
    }
}

fn sweep(cfg: BtlConfig, seed: u64) {
    assert!(cfg.is_valid(), "{cfg:?}");
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    for case in ['a', 'b', 'd', 'f'] {
        for j in 0..cfg.ntq() {
            check(&cfg, case, j, &mut rng);
        }
    }
}

/// PH2 = 1 at the shortest TQ (2 clocks) and at several sample points, SJW
/// from 1 to 4 (SJW > PH2 is legal: C22).
#[test]
fn iso_ph2_1_sample_points() {
    sweep(BtlConfig::new(2, 1, 5, 1).with_ph2(1), 1); // 8 TQ, SP 87.5 %
    sweep(BtlConfig::new(2, 2, 8, 4).with_ph2(1), 2); // 12 TQ, SP 91.7 %, SJW 4
    sweep(BtlConfig::new(3, 8, 8, 2).with_ph2(1), 3); // 18 TQ, SP 94.4 %
    sweep(BtlConfig::new(2, 16, 7, 3).with_ph2(1), 4); // 25 TQ, SP 96 %
}

/// PH2 != PH1 (both ways) and PH2 = 2, where IPT is 2 TQ and a restart in
/// the first PH2 TQ is postponed.
#[test]
fn iso_ph2_other_than_ph1() {
    sweep(BtlConfig::new(1, 1, 1, 1).with_ph2(5), 5); // 8 TQ, SP 37.5 %
    sweep(BtlConfig::new(2, 3, 2, 2).with_ph2(8), 6); // 14 TQ, SP 43 %
    sweep(BtlConfig::new(1, 5, 6, 4).with_ph2(2), 7); // 14 TQ, SP 86 %, SJW > PH2
    sweep(BtlConfig::new(4, 2, 4, 3).with_ph2(3), 8); // 10 TQ, SP 70 %
}

/// Random valid settings over the whole range (BRP, PROP, PH1, PH2, SJW),
/// every situation and edge position.
#[test]
fn iso_random_settings() {
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    let mut n = 0;
    while n < 12 {
        let cfg =
            BtlConfig::new(rng.gen_range(1..=5), rng.gen_range(1..=16), rng.gen_range(1..=8), rng.gen_range(1..=4))
                .with_ph2(rng.gen_range(1..=8));
        if cfg.is_valid() {
            sweep(cfg, 100 + n);
            n += 1;
        }
    }
}
