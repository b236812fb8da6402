//! Judge-unit rules of one port in isolation (hub.md §5.1-§5.10, §5.14, §5.19): roles,
//! recessive-only positions, blame counters, windows, glitches, dominant runs (and the
//! bus-run rule, §5.22), NACK.
mod judge_common;
use canstar_hdl::drive;
use canstar_hub::judge::{JudgeParams, JudgeUnit};
use judge_common::*;

#[test]
fn contender_role_and_loss() {
    let mut j = unit(params());
    // dominant at SOF: contender; dominant while BT dominant: still contender
    sample(&mut j, Bit { c: false, bt: false, sof: true, ..Default::default() });
    assert!(j.contender.val());
    assert!(!sample(&mut j, Bit { c: false, bt: false, tx: true, ..Default::default() }));
    // recessive while BT recessive: still
    sample(&mut j, Bit { c: true, bt: true, tx: true, ..Default::default() });
    assert!(j.contender.val());
    // recessive while BT dominant: lost
    sample(&mut j, Bit { c: true, bt: false, tx: true, ..Default::default() });
    assert!(!j.contender.val());
    // now a dominant bit in the transmission region is unjustified: +8, once per episode
    assert!(sample(&mut j, Bit { c: false, bt: false, tx: true, ..Default::default() }));
    assert_eq!(j.bic.val().index(), 8);
    // in the error phase nothing is blamed
    assert!(!sample(&mut j, Bit { c: false, bt: false, tx: true, err: true, ..Default::default() }));
    assert_eq!(j.bic.val().index(), 8);
}

#[test]
fn recessive_only_positions() {
    // (intermission bit 2: `intermission_bit_2_blames_only_a_flag_that_starts_in_it`)
    for which in 0..4 {
        let mut j = unit(params());
        let mut b = Bit { c: false, bt: false, ..Default::default() };
        match which {
            0 => b.crc_delim = true,
            1 => b.ack_delim = true,
            2 => b.eof = true,
            _ => {
                // transmitter dominant in the ACK slot
                sample(&mut j, Bit { c: false, bt: false, sof: true, ..Default::default() });
                b.ack_slot = true;
            }
        }
        assert!(sample(&mut j, b), "case {which}");
        assert_eq!(j.bic.val().index(), 8);
    }
    // a receiver acknowledging is fine
    let mut j = unit(params());
    sample(&mut j, Bit { c: true, bt: false, sof: true, ..Default::default() });
    sample(&mut j, Bit { c: true, bt: false, tx: true, ..Default::default() });
    assert!(!sample(&mut j, Bit { c: false, bt: false, ack_slot: true, crc_ok: true, ..Default::default() }));
    // ACK delimiter after a recessive ACK slot (ACK error flag) is fine
    let mut j = unit(params());
    sample(&mut j, Bit { c: true, bt: true, ack_slot: true, ..Default::default() });
    assert!(!sample(&mut j, Bit { c: false, bt: false, ack_delim: true, ..Default::default() }));
}

/// §5.19: with the rule on, a dominant last EOF bit outside an error phase is blamed, for
/// a receiver and a transmitter alike; off (the sublink units), it is not; inside an error
/// or overload phase it is not either.
#[test]
fn last_eof_bit_is_blamed_with_the_rule() {
    for on in [false, true] {
        for contender in [false, true] {
            let mut j = unit(JudgeParams { eof_last: on, ..params() });
            sample(&mut j, Bit { c: false, bt: false, sof: true, ..Default::default() });
            // recessive against a dominant BT in the transmission region: a receiver
            sample(&mut j, Bit { c: !contender, bt: false, tx: true, ..Default::default() });
            assert_eq!(j.contender.val(), contender);
            let blamed = sample(&mut j, Bit { c: false, bt: false, eof_last: true, ..Default::default() });
            assert_eq!(blamed, on, "rule {on}, contender {contender}");
            assert_eq!(j.bic.val().index(), if on { 8 } else { 0 });
        }
        let mut j = unit(JudgeParams { eof_last: on, ..params() });
        assert!(!sample(&mut j, Bit { c: false, bt: false, eof_last: true, err: true, ..Default::default() }));
        assert_eq!(j.bic.val().index(), 0);
    }
    // ports have it, sublinks do not
    let cfg = canstar_hub::config::HubConfig::default();
    assert!(cfg.port_params().eof_last && !cfg.sublink_params().eof_last);
}

#[test]
fn bic_saturates_isolates_and_decays() {
    let mut j = unit(params());
    for k in 1..=8u64 {
        assert!(!j.dis.val());
        assert!(sample(&mut j, Bit { c: false, bt: false, crc_delim: true, ..Default::default() }));
        assert_eq!(j.bic.val().index() as u64, 8 * k);
    }
    assert!(j.dis.val(), "isolated at 64");
    // isolated: no more blame, no decay
    assert!(!sample(&mut j, Bit { c: false, bt: false, crc_delim: true, ..Default::default() }));
    sample(&mut j, Bit { c: true, bt: true, frame_ok: true, ..Default::default() });
    assert_eq!(j.bic.val().index(), 64);
    // decay while enabled
    let mut j = unit(params());
    sample(&mut j, Bit { c: false, bt: false, eof: true, ..Default::default() });
    for k in 0..10 {
        sample(&mut j, Bit { c: true, bt: true, frame_ok: true, ..Default::default() });
        assert_eq!(j.bic.val().index(), 7usize.saturating_sub(k));
    }
}

/// hub.md §5.3 decay prescaler (`bic_decay`, sublinks 2 by default): one count off `bic`
/// per `bic_decay` good frames, the frames counted only while `bic` is not 0, and a blame
/// in between does not restart the count.
#[test]
fn bic_decays_once_per_bic_decay_frames() {
    let good = Bit { c: true, bt: true, frame_ok: true, ..Default::default() };
    let blame = Bit { c: false, bt: false, eof: true, ..Default::default() };
    let mut j = unit(JudgeParams { bic_decay: 3, ..params() });
    // frames while bic is 0 are not counted
    sample(&mut j, good);
    sample(&mut j, good);
    assert!(sample(&mut j, blame));
    let mut seen = vec![];
    for _ in 0..7 {
        sample(&mut j, good);
        seen.push(j.bic.val().index());
    }
    assert_eq!(seen, [8, 8, 7, 7, 7, 6, 6]);
    // the prescaler keeps its count across a blame: 1 frame so far, the second decays
    assert!(sample(&mut j, blame));
    assert_eq!(j.bic.val().index(), 14);
    sample(&mut j, good);
    assert_eq!(j.bic.val().index(), 14);
    sample(&mut j, good);
    assert_eq!(j.bic.val().index(), 13);
    // reset clears the prescaler: three more frames for the next count
    j.reset.next = true;
    drive::cycle(&mut j);
    j.reset.next = false;
    assert!(sample(&mut j, blame));
    let mut seen = vec![];
    for _ in 0..3 {
        sample(&mut j, good);
        seen.push(j.bic.val().index());
    }
    assert_eq!(seen, [8, 8, 7]);
}

/// hub.md §5.3 lifetime counter: blames rarer than the decay can absorb (one per 9 frames,
/// so `bic` never exceeds 8) still isolate after `life_limit` blames.
#[test]
fn lifetime_counter_isolates_rare_blames() {
    let mut j = unit(JudgeParams { life_limit: 5, ..params() });
    for k in 1..=5u64 {
        assert!(!j.dis.val(), "not yet isolated after {} blames", k - 1);
        assert!(sample(&mut j, Bit { c: false, bt: false, eof: true, ..Default::default() }));
        assert_eq!(j.life.val().index() as u64, k);
        assert!(j.bic.val().index() <= 8);
        for _ in 0..9 {
            sample(&mut j, Bit { c: true, bt: true, frame_ok: true, ..Default::default() });
        }
        if k < 5 {
            assert_eq!(j.bic.val().index(), 0, "decayed");
        }
    }
    assert!(j.dis.val(), "isolated by the lifetime counter");
    // reset clears it
    j.reset.next = true;
    drive::cycle(&mut j);
    j.reset.next = false;
    drive::cycle(&mut j);
    assert!(!j.dis.val());
    assert_eq!(j.life.val().index(), 0);
}

/// Arbitration field (changed back, hub.md §5.2): a port that dropped out (recessive while
/// BT dominant) is a receiver, and its dominant bits in the rest of the transmission
/// region are blamed, in the arbitration field too. Collateral blame of a healthy
/// transmitter that never saw another port's glitch is handled by the glitch rule (the
/// glitching port is charged, the others' blames are not: `suppress`).
#[test]
fn receiver_dominant_in_arbitration_is_blamed() {
    let mut j = unit(params());
    sample(&mut j, Bit { c: false, bt: false, sof: true, ..Default::default() });
    j.arb.next = true;
    sample(&mut j, Bit { c: true, bt: false, tx: true, ..Default::default() });
    assert!(!j.contender.val(), "dropped out");
    assert!(sample(&mut j, Bit { c: false, bt: false, tx: true, ..Default::default() }), "blamed in arbitration");
    assert!(!j.contender.val(), "no readmission");
    assert_eq!(j.bic.val().index(), 8);
}

/// hub.md §5.2 early-ACK rule: in the CRC delimiter a dominant level counts only up to
/// `crc_window_end` (8) clocks after the bit start. A fast receiver's ACK that reaches the
/// hub in the last clocks before the sample point, or at it, is not blamed (the soak at the
/// tolerance limit, README "No false blame", `canstar soak --chunk 2`: a hub one interlink
/// further from the transmitter sees the other hub's receivers' ACK at its sample point);
/// a dominant level from the window start on is.
#[test]
fn early_ack_in_the_crc_delimiter_is_not_blamed() {
    for from in 9..=SAMPLE_AT {
        let mut j = unit(params());
        assert!(!crc_delimiter_dominant_from(&mut j, from), "dominant from clock {from}: an early ACK, not blamed");
        assert_eq!(j.bic.val().index(), 0);
    }
    for from in [0, 7, 8] {
        let mut j = unit(params());
        assert!(crc_delimiter_dominant_from(&mut j, from), "dominant from clock {from}: blamed");
        assert_eq!(j.bic.val().index(), 8);
    }
    // the window rule still applies to the other recessive-only positions up to the sample point
    let mut j = unit(params());
    assert!(pulse_bit(&mut j, 10, 6, false).0, "EOF dominant from clock 10: blamed");
}

/// hub.md §5.8 glitch rule: a run of at most `glitch_max` clocks on the input counts
/// against the unit, `glitch_limit` of them isolate it, good frames decay the count.
#[test]
fn glitches_isolate_and_decay() {
    let mut j = unit(params());
    // a pulse before the window (clocks 1..5) is a glitch, not a blame
    assert_eq!(pulse_bit(&mut j, 1, 4, false), (false, 1));
    assert_eq!(j.gc.val().index(), 1);
    assert_eq!(j.bic.val().index(), 0);
    // 16 good frames take one glitch off
    for _ in 0..16 {
        sample(&mut j, Bit { c: true, bt: true, frame_ok: true, ..Default::default() });
    }
    assert_eq!(j.gc.val().index(), 0, "decayed");
    for k in 1..=3 {
        assert!(!j.dis.val(), "not isolated after {} glitches", k - 1);
        pulse_bit(&mut j, 1, 4, false);
    }
    drive::cycle(&mut j);
    assert!(j.dis.val(), "three glitches isolate");
    assert_eq!(j.life.val().index(), 4, "every glitch counts in the lifetime counter");
    // a glitch that every replica sublink saw (`common`) is the peer's: not counted
    let mut j = unit(params());
    j.common.next = true;
    assert_eq!(pulse_bit(&mut j, 1, 4, false).1, 1);
    assert_eq!(j.gc.val().index(), 0);
    assert_eq!(j.life.val().index(), 0);
    j.common.next = false;
    // a bit shortened by SJW (14 clocks) and a normal bit are no glitch
    let mut j = unit(params());
    assert_eq!(pulse_bit(&mut j, 2, 14, false).1, 0);
    sample(&mut j, Bit { c: false, bt: false, tx: true, ..Default::default() });
    sample(&mut j, Bit { c: true, bt: true, tx: true, ..Default::default() });
    assert_eq!(j.gc.val().index(), 0);
}

/// hub.md §5.2 window rule: a dominant level from `window_lag` clocks after the bit start
/// up to the sample point counts as a dominant bit for the unjustified-dominant rules,
/// even when the input is recessive again at the sample point; earlier it does not
/// (a late edge of the previous bit).
#[test]
fn window_rule_sees_dominant_before_the_sample_point() {
    let mut j = unit(params());
    let (blame, g) = pulse_bit(&mut j, 8, 3, false);
    assert!(blame, "dominant at clocks 8..10, recessive at the sample point: blamed");
    assert_eq!(g, 1);
    assert_eq!(j.bic.val().index(), 8);
    let mut j = unit(params());
    assert!(!pulse_bit(&mut j, 2, 4, false).0, "dominant only before the window: not blamed");
}

/// `suppress` (another unit glitched within the last bits): the blame still starts the
/// hub's error flag, but is not charged to this unit.
#[test]
fn suppressed_blames_are_not_charged() {
    let mut j = unit(params());
    let (blame, _) = pulse_bit(&mut j, 8, 8, true);
    assert!(blame);
    assert_eq!(j.bic.val().index(), 0, "not charged");
    assert_eq!(j.life.val().index(), 0);
    let mut j = unit(params());
    assert!(pulse_bit(&mut j, 8, 8, false).0);
    assert_eq!(j.bic.val().index(), 8);
}

/// Stuff-bit rule: a receiver's dominant level at a stuff bit that must be dominant (after
/// five recessive bits) still starts the hub's error flag but is not charged; the same
/// level at an ordinary bit is.
#[test]
fn dominant_stuff_bit_is_blamed_but_not_charged() {
    let receiver = |j: &mut JudgeUnit| {
        sample(j, Bit { c: false, bt: false, sof: true, ..Default::default() });
        sample(j, Bit { c: true, bt: false, tx: true, ..Default::default() });
        assert!(!j.contender.val());
    };
    let mut j = unit(params());
    receiver(&mut j);
    j.stuff_dom.next = true;
    assert!(sample(&mut j, Bit { c: false, bt: false, tx: true, ..Default::default() }), "blamed: starts the error flag");
    assert_eq!(j.bic.val().index(), 0, "not charged");
    assert_eq!(j.life.val().index(), 0);
    j.stuff_dom.next = false;
    let mut j = unit(params());
    receiver(&mut j);
    assert!(sample(&mut j, Bit { c: false, bt: false, tx: true, ..Default::default() }));
    assert_eq!(j.bic.val().index(), 8, "charged at an ordinary bit");
}

/// §5.23 stuff-bit pulse rule: a port blamed (not charged) at a dominant stuff bit and
/// recessive at the next sample is charged one blame then; a port still dominant there
/// (an error flag) is not; without the rule nothing is charged; an ordinary charged blame
/// is not charged again.
#[test]
fn stuff_bit_pulse_is_charged_at_the_next_sample() {
    let receiver = |j: &mut JudgeUnit| {
        sample(j, Bit { c: false, bt: false, sof: true, ..Default::default() });
        sample(j, Bit { c: true, bt: false, tx: true, ..Default::default() });
    };
    let dominant = Bit { c: false, bt: false, tx: true, ..Default::default() };
    // the next bit under the hub's error flag
    let flag_bit = |c| Bit { c, bt: false, err: true, ..Default::default() };
    for (rule, next_recessive, charged) in [(true, true, true), (true, false, false), (false, true, false)] {
        let mut j = unit(JudgeParams { stuff_pulse: rule, ..params() });
        receiver(&mut j);
        j.stuff_dom.next = true;
        assert!(sample(&mut j, dominant), "blamed at the stuff bit");
        j.stuff_dom.next = false;
        assert_eq!(j.bic.val().index(), 0, "not charged at the stuff bit");
        sample(&mut j, flag_bit(next_recessive));
        let what = format!("rule {rule}, recessive at the next sample {next_recessive}");
        assert_eq!(j.bic.val().index(), 8 * charged as usize, "{what}");
        assert_eq!(j.life.val().index(), charged as usize, "{what}");
        assert!(!sample(&mut j, flag_bit(true)), "{what}: charged once");
        assert_eq!(j.bic.val().index(), 8 * charged as usize, "{what}");
    }
    let mut j = unit(JudgeParams { stuff_pulse: true, ..params() });
    receiver(&mut j);
    assert!(sample(&mut j, dominant));
    sample(&mut j, flag_bit(true));
    assert_eq!(j.bic.val().index(), 8, "an ordinary bit: charged at its own sample only");
}

/// Error and overload delimiter bits 2..7 (`delim`, after BT went recessive) are
/// recessive-only positions, in the error phase too.
#[test]
fn dominant_in_a_delimiter_is_blamed() {
    let mut j = unit(params());
    j.delim.next = true;
    assert!(sample(&mut j, Bit { c: false, bt: false, err: true, ..Default::default() }));
    assert!(!sample(&mut j, Bit { c: true, bt: true, err: true, ..Default::default() }));
    j.delim.next = false;
    assert!(!sample(&mut j, Bit { c: false, bt: false, err: true, ..Default::default() }));
}

/// hub.md §5.17: a charged dominant bit in a delimiter counts `delim_blames` blames
/// (`bic += 8 * delim_blames`); a blame anywhere else counts one; `bic` saturates at 255.
#[test]
fn delimiter_blame_counts_delim_blames() {
    let delim = Bit { c: false, bt: false, err: true, ..Default::default() };
    let eof = Bit { c: false, bt: false, eof: true, ..Default::default() };
    for n in 1..=3u64 {
        let mut j = unit(JudgeParams { delim_blames: n, bic_limit: 255, ..params() });
        j.delim.next = true;
        assert!(sample(&mut j, delim));
        assert_eq!(j.bic.val().index() as u64, 8 * n, "delim_blames {n}");
        j.delim.next = false;
        assert!(sample(&mut j, eof));
        assert_eq!(j.bic.val().index() as u64, 8 * n + 8, "a blame outside a delimiter, delim_blames {n}");
    }
    let mut j = unit(JudgeParams { delim_blames: 3, bic_limit: 255, ..params() });
    j.delim.next = true;
    let mut last = 0;
    for k in 1..=11 {
        sample(&mut j, delim);
        let b = j.bic.val().index();
        assert_eq!(b, (24 * k).min(255), "charge {k}");
        assert!(b >= last);
        last = b;
    }
}

/// hub.md §5.17 follower: a delimiter blame counts `delim_blames` only for a unit whose
/// dominant level led; one that rose after another unit (`others_dom`) had been dominant
/// since the last sample point counts one blame. `others_dom` before the last sample point
/// (the tails of the error flags) makes no follower, nor does a level that comes later.
#[test]
fn delimiter_follower_counts_one_blame() {
    type Span = std::ops::Range<u64>;
    // (others dominant in the previous bit, in the delimiter bit, the unit dominant from, bic)
    let cases: [(Span, Span, u64, usize); 6] = [
        (0..0, 0..0, 4, 24),
        (0..0, 1..4, 4, 8),
        (0..0, 4..9, 4, 24),
        (0..0, 6..10, 4, 24),
        (2..11, 0..0, 4, 24),
        (13..16, 0..0, 2, 8),
    ];
    for (prev, cur, from, bic) in cases {
        let mut j = unit(JudgeParams { delim_blames: 3, ..params() });
        apply(&mut j, Bit { c: true, bt: true, err: true, ..Default::default() });
        let (blamed, _) = bit_clocks(&mut j, &|j, k| j.others_dom.next = prev.contains(&k));
        assert!(!blamed);
        j.delim.next = true;
        let (blamed, _) = bit_clocks(&mut j, &|j, k| {
            j.others_dom.next = cur.contains(&k);
            j.c.next = k < from;
            j.bt.next = k < from;
        });
        assert!(blamed, "others {prev:?} / {cur:?}, dominant from {from}");
        assert_eq!(j.bic.val().index(), bic, "others {prev:?} / {cur:?}, dominant from {from}");
    }
}

/// §5.25: a port whose delimiter flag rose while a sublink had been dominant since the last
/// sample (the node reacting to the peer's pulse) is blamed, not charged, with
/// `sub_follower`; a port led by another port only, or that rose with the sublink, is
/// charged as before, and without the rule a sublink follower counts one blame.
#[test]
fn sublink_follower_is_blamed_not_charged() {
    type Span = std::ops::Range<u64>;
    // (rule, sublinks dominant in the delimiter bit, other ports dominant, dominant from, bic)
    let cases: [(bool, Span, Span, u64, usize); 5] = [
        (true, 1..4, 0..0, 4, 0),
        (true, 0..0, 1..4, 4, 8),
        (true, 4..9, 0..0, 4, 24),
        (false, 1..4, 0..0, 4, 8),
        (true, 0..0, 0..0, 4, 24),
    ];
    for (rule, sub, port, from, bic) in cases {
        let mut j = unit(JudgeParams { delim_blames: 3, sub_follower: rule, ..params() });
        apply(&mut j, Bit { c: true, bt: true, err: true, ..Default::default() });
        j.delim.next = true;
        let (blamed, _) = bit_clocks(&mut j, &|j, k| {
            j.sub_dom.next = sub.contains(&k);
            j.others_dom.next = sub.contains(&k) || port.contains(&k);
            j.c.next = k < from;
            j.bt.next = k < from;
        });
        let what = format!("rule {rule}, sublinks {sub:?}, ports {port:?}");
        assert!(blamed, "{what}");
        assert_eq!(j.bic.val().index(), bic, "{what}");
    }
}

/// Intermission bit 1 is not blamed (a node's reaction to a dominant last EOF bit that only
/// it saw). In bit 2 (`im_2`) an overload flag starts at a bit start (hub.md §5.2, §5.14):
/// a dominant level is blamed only if BT was recessive at the hub's bit start and the level
/// is there within the early-ACK window (`window_lag`..=`crc_window_end`, clocks 7..=8). BT
/// already dominant at the bit start went dominant late in bit 1, after the hub's sample:
/// nodes that sample later saw a dominant bit 1 and rightly flag in bit 2. A level that
/// starts after the window is a node's SOF of bit 3, a little early.
#[test]
fn intermission_bit_2_blames_only_a_flag_that_starts_in_it() {
    let im1 = Bit { c: true, bt: true, ..Default::default() };
    let im2 = Bit { im: true, ..Default::default() };
    let mut j = unit(params());
    assert!(!sample(&mut j, Bit { c: false, bt: false, ..Default::default() }), "im bit 1: no rule");
    // (§5.22: a level that rises in the bit-start clock itself starts in bit 2)
    for (from, blamed) in [(0, true), (1, true), (7, true), (8, true), (9, false), (12, false)] {
        let mut j = unit(params());
        sample(&mut j, im1);
        assert_eq!(bit_dominant_from(&mut j, im2, from), blamed, "dominant from clock {from}");
        assert_eq!(j.bic.val().index(), 8 * blamed as usize);
    }
    // BT went dominant at clock 14 of bit 1, after the sample: not blamed in bit 2
    let mut j = unit(params());
    assert!(!bit_dominant_from(&mut j, Bit::default(), 14));
    assert!(!bit_dominant_from(&mut j, im2, 0));
    assert_eq!(j.bic.val().index(), 0);
    // ... nor at clock 15, the last clock before the bit start
    let mut j = unit(params());
    assert!(!bit_dominant_from(&mut j, Bit::default(), 15));
    assert!(!bit_dominant_from(&mut j, im2, 0));
    assert_eq!(j.bic.val().index(), 0);
}

/// §5.23: with `im2_lag` (sublinks) the Intermission-bit-2 test reads BT at that clock
/// after the bit start (here clock 1 = `bs_cnt` 1 of the test's bit; the hub's `bs_cnt`
/// starts in the clock after the bit-start clock): a level that rose before it is taken
/// for one that started in bit 1 at the peer; a level that was there at the bit start but
/// gone at that clock, and rose again later, started in bit 2.
#[test]
fn intermission_bit_2_lag_excuses_a_level_that_rose_in_the_first_clocks() {
    let im1 = Bit { c: true, bt: true, ..Default::default() };
    let im2 = Bit { im: true, ..Default::default() };
    let lagged = || unit(JudgeParams { im2_lag: 2, ..params() });
    for (from, blamed) in [(0, false), (1, false), (2, true), (8, true), (9, false)] {
        let mut j = lagged();
        sample(&mut j, im1);
        assert_eq!(bit_dominant_from(&mut j, im2, from), blamed, "lag 2: dominant from clock {from}");
        assert_eq!(j.bic.val().index(), 8 * blamed as usize);
    }
    // dominant late in bit 1, recessive at clocks 0..3 of bit 2, dominant again from 4:
    // excused without the lag (BT dominant before the bit start), blamed with it
    for (lag, blamed) in [(0, false), (2, true)] {
        let mut j = unit(JudgeParams { im2_lag: lag, ..params() });
        assert!(!bit_dominant_from(&mut j, Bit::default(), 14));
        assert_eq!(bit_dominant_from(&mut j, im2, 4), blamed, "lag {lag}: a new level from clock 4");
    }
}

#[test]
fn dominant_run_threshold() {
    for thr in [13u64, 24] {
        let mut j = unit(JudgeParams { dbc_threshold: thr, ..params() });
        for k in 1..=thr {
            assert!(!j.dis.val(), "isolated too early at {k}");
            sample(&mut j, Bit { c: false, bt: false, err: true, ..Default::default() });
        }
        assert!(j.dis.val());
        assert_eq!(j.bic.val().index(), 0, "error phase: no blame");
    }
    // a recessive sample clears the run
    let mut j = unit(params());
    for _ in 0..3 {
        for _ in 0..12 {
            sample(&mut j, Bit { c: false, bt: false, err: true, ..Default::default() });
        }
        sample(&mut j, Bit { c: true, bt: true, err: true, ..Default::default() });
    }
    assert!(!j.dis.val());
}

/// §5.22: with the bus-run rule a recessive sample of the port in an error phase, under a
/// bus dominant for the whole bit, holds the run (a node restarting its error flag under
/// the others' flags); a recessive bus, a bus recessive at any clock of the bit, or a
/// sample outside an error phase clears it; without the rule the port's own recessive
/// sample clears it.
#[test]
fn bus_run_rule_holds_the_run_while_the_bus_stays_dominant() {
    let dom = Bit { c: false, bt: false, err: true, ..Default::default() };
    let gap = Bit { c: true, bt: false, err: true, ..Default::default() };
    let idle = Bit { c: true, bt: true, err: true, ..Default::default() };
    for bridge in [false, true] {
        let mut j = unit(JudgeParams { dbc_bridge: bridge, ..params() });
        // 6 dominant, 1 recessive under a dominant bus, 6 dominant: 12 of the port's own
        for _ in 0..6 {
            sample(&mut j, dom);
        }
        sample(&mut j, gap);
        assert_eq!(j.dbc.val().index(), if bridge { 6 } else { 0 }, "bridge {bridge}: held, not cleared");
        for _ in 0..6 {
            sample(&mut j, dom);
        }
        assert!(!j.dis.val(), "bridge {bridge}: 12 dominant samples are below 13");
        sample(&mut j, gap);
        sample(&mut j, dom);
        assert_eq!(j.dis.val(), bridge, "bridge {bridge}: the 13th dominant sample of one bus run");
        // a recessive bus clears the run in either case
        let mut j = unit(JudgeParams { dbc_bridge: bridge, ..params() });
        for _ in 0..3 {
            for _ in 0..12 {
                sample(&mut j, dom);
            }
            sample(&mut j, gap);
            sample(&mut j, idle);
            assert_eq!(j.dbc.val().index(), 0);
        }
        assert!(!j.dis.val());
        // neither a gap outside an error phase nor one under a bus that was recessive for
        // three clocks of the bit (a pulse on another input at this hub's sample) holds it
        let mut j = unit(JudgeParams { dbc_bridge: bridge, ..params() });
        for _ in 0..6 {
            sample(&mut j, dom);
        }
        sample(&mut j, Bit { err: false, ..gap });
        assert_eq!(j.dbc.val().index(), 0, "bridge {bridge}: outside an error phase");
        for _ in 0..6 {
            sample(&mut j, dom);
        }
        apply(&mut j, gap);
        bit_clocks(&mut j, &|j, k| j.bt.next = k < 3);
        assert_eq!(j.dbc.val().index(), 0, "bridge {bridge}: the bus recessive in the bit");
    }
}

#[test]
fn nack_counts_only_correct_frames_and_never_isolates() {
    let mut j = unit(params());
    let frame = |j: &mut JudgeUnit, ack: bool, crc_ok: bool| {
        sample(j, Bit { c: true, bt: false, sof: true, ..Default::default() });
        sample(j, Bit { c: true, bt: false, tx: true, ..Default::default() });
        sample(j, Bit { c: !ack, bt: false, ack_slot: true, ..Default::default() });
        sample(j, Bit { c: true, bt: true, ack_delim: true, crc_ok, ..Default::default() });
    };
    for _ in 0..5 {
        frame(&mut j, false, false);
    }
    assert_eq!(j.nack.val().index(), 0, "CRC not correct: not counted");
    for k in 1..=6 {
        frame(&mut j, false, true);
        assert_eq!(j.nack.val().index(), k);
        assert!(!j.silent.val());
    }
    frame(&mut j, false, true);
    assert!(j.silent.val() && !j.dis.val());
    frame(&mut j, true, true);
    assert_eq!(j.nack.val().index(), 0);
    assert!(!j.silent.val());
}
