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


/// (hs_en, drive) of a situation: 'a' hard sync driving R, 'b' resync
/// driving R (receiver), 'd' resync driving D (transmitter), 'f' hard sync
/// driving D (own SOF).
fn situation(case: char) -> (bool, bool) {
    match case {
        'a' => (true, R),
        'b' => (false, R),
        'd' => (false, D),
        'f' => (true, D),
        _ => panic!("case {case}"),
    }
}

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

/// Expected ticks from the bit start of the edge bit: (sample points,
/// transmit points, tick of the transmit point that takes the new level,
/// horizon).
fn expect(cfg: &BtlConfig, outcome: Outcome, j: u32) -> (Vec<u32>, Vec<u32>, u32, u32) {
    let (sp, ntq, ipt) = (cfg.sp(), cfg.ntq(), cfg.ipt());
    let (mut samples, tx_tick, origin) = match outcome {
        Outcome::Nothing => (vec![sp], ntq, ntq),
        Outcome::Ph1Plus(d) => (vec![sp + d], ntq + d, ntq + d),
        Outcome::Ph2Minus(s) => (vec![sp], (ntq - s).max(sp + ipt), ntq - s),
        // the edge's TQ (index j) becomes SYNC_SEG: cnt = 0 at tick j
        Outcome::Restart if j >= sp => (vec![sp], (j + 1).max(sp + ipt), j),
        Outcome::Restart => (vec![], j + 1, j),
    };
    let horizon = origin + 2 * ntq;
    let mut starts = vec![0, tx_tick];
    for k in 1..=2 {
        starts.push(origin + k * ntq);
    }
    for k in 0..=2 {
        if origin + k * ntq + sp <= horizon {
            samples.push(origin + k * ntq + sp);
        }
    }
    samples.sort();
    samples.dedup();
    (samples, starts, tx_tick, horizon)
}

/// One edge in TQ j (at a random clock inside it) after two recessive bits;
/// the RTL and the model on the rig, checked against [`rule`].
fn check(cfg: &BtlConfig, case: char, j: u32, rng: &mut ChaCha8Rng) {
    let (sp, ntq, b) = (cfg.sp(), cfg.ntq(), cfg.brp as usize);
    let outcome = rule(cfg, case, j);
    let (want_samples, want_starts, tx_tick, horizon) = expect(cfg, outcome, j);
    let tag = format!("{cfg:?} case {case} j {j} ({outcome:?})");
    let (hs_en, level) = situation(case);
    let mut rig = Rig::new(true);
    rig.reset(cfg);
    let mut i = BtlInputs::with_config(cfg);
    i.hs_en = hs_en;
    i.drive = !level;
    let mut n = 0;
    let c0 = loop {
        if rig.step(&i).bit_start {
            n += 1;
            if n == 2 {
                break rig.trace.len() - 1;
            }
        }
        assert!(rig.trace.len() < 3 * ntq as usize * b + 10, "{tag}: no bit start");
    };
    let c_edge = c0 + j as usize * b + rng.gen_range(1..=b);
    let end = c0 + horizon as usize * b + 2;
    i.drive = level;
    while rig.trace.len() < end {
        i.rx = rig.trace.len() < c_edge;
        rig.step(&i);
    }
    let tick = |c: usize| {
        assert_eq!((c - c0) % b, 0, "{tag}: strobe at cycle {c} off the TQ grid");
        ((c - c0) / b) as u32
    };
    let (mut samples, mut starts, mut syncs) = (vec![], vec![], vec![]);
    for (c, p) in rig.trace.iter().enumerate().skip(c0) {
        if p.bit_start {
            starts.push(tick(c));
        }
        if c > c0 && p.sample {
            let k = tick(c - 1);
            samples.push(k);
            assert_eq!(p.busmon, if k > j { D } else { R }, "{tag}: level sampled at tick {k}");
        }
        if c > c0 && (p.hard_sync || p.resync) {
            syncs.push((tick(c - 1), p.hard_sync));
        }
    }
    samples.retain(|&k| k <= horizon);
    starts.retain(|&k| k <= horizon);
    assert_eq!(samples, want_samples, "{tag}: sample points (ticks from the bit start)");
    assert_eq!(starts, want_starts, "{tag}: transmit points");
    assert_eq!(syncs, vec![(j + 1, hs_en)], "{tag}: one synchronisation, on the tick after the edge's TQ");
    let tx_change = c0 + tx_tick as usize * b + 1;
    for (c, p) in rig.trace.iter().enumerate().skip(c0 + 1) {
        assert_eq!(p.tx, if c >= tx_change { level } else { !level }, "{tag}: TX at cycle {c}");
    }
    if cfg.ph2 == 1 && outcome == Outcome::Restart {
        assert_eq!(tx_tick, j + 1, "{tag}: PH2 = 1 transmits at the edge");
    }
    if outcome == Outcome::Restart && j >= sp && j + 1 < sp + cfg.ipt() {
        assert!(tx_tick > j + 1, "{tag}: postponed");
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
