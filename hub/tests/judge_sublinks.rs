//! Judge-unit rules of the sublinks in isolation (hub.md §5.7, §5.11-§5.14): replica
//! rule, first flagger, peer-hub glitches.
mod judge_common;
use canstar_hdl::drive;
use canstar_hub::judge::{JudgeParams, JudgeUnit};
use judge_common::*;

/// A dominant-minority disagreement (a replica recessive at the sample), then the hub's
/// `err_start` for one clock; returns `charged` at that clock.
fn dominant_minority_episode(j: &mut JudgeUnit) -> bool {
    j.rep_rec.next = true;
    sample(j, Bit { c: false, bt: false, err: true, ..Default::default() });
    j.rep_rec.next = false;
    episode(j)
}

#[test]
fn replica_rule_charges_by_consequence() {
    let mut j = sublink_unit(params());
    drive::init(&mut j);
    // dominant-minority then an error episode: charged
    for _ in 0..3 {
        dominant_minority_episode(&mut j);
    }
    assert_eq!(j.rep_cnt.val().index(), 3);
    drive::cycle(&mut j);
    assert!(j.dis.val());
    // recessive-minority then a good frame: charged; dominant-minority then a good frame: not
    let mut j = sublink_unit(params());
    drive::init(&mut j);
    j.rep_dom.next = true;
    sample(&mut j, Bit { c: true, bt: false, tx: true, ..Default::default() });
    j.rep_dom.next = false;
    sample(&mut j, Bit { c: true, bt: true, frame_ok: true, ..Default::default() });
    assert_eq!(j.rep_cnt.val().index(), 1);
    j.rep_rec.next = true;
    sample(&mut j, Bit { c: false, bt: false, err: true, ..Default::default() });
    j.rep_rec.next = false;
    sample(&mut j, Bit { c: true, bt: true, frame_ok: true, ..Default::default() });
    assert_eq!(j.rep_cnt.val().index(), 1);
}

/// One clock with the first-flagger strobe `ff` (the hub raises it one clock after the
/// sample at which its monitor alone started an error episode); returns `charged`.
fn first_flagger_clock(j: &mut JudgeUnit) -> bool {
    j.ff.next = true;
    drive::settle(j);
    let charged = j.charged.val() && j.blame.val();
    drive::cycle(j);
    j.ff.next = false;
    drive::cycle(j);
    charged
}

/// hub.md §5.12: at an episode the monitor alone started, a unit that was a dominant
/// contender at that sample (a transmitter sending its error flag) is charged like a
/// blame (`bic += 8`, `life += 1`); a recessive contender, a dominant receiver, a unit
/// excused by another input's glitch in the frame, and every unit with the rule off are not.
#[test]
fn first_flagger_charges_the_dominant_contender() {
    let on = JudgeParams { first_flagger: true, ..params() };
    let mut j = unit(on);
    sample(&mut j, Bit { c: false, bt: false, sof: true, ..Default::default() });
    sample(&mut j, Bit { c: false, bt: false, tx: true, ..Default::default() });
    assert!(j.contender.val());
    assert!(first_flagger_clock(&mut j));
    assert_eq!((j.bic.val().index(), j.life.val().index()), (8, 1));
    // recessive at the sample: not the flagger
    sample(&mut j, Bit { c: true, bt: false, tx: true, err: true, ..Default::default() });
    assert!(!first_flagger_clock(&mut j));
    assert_eq!(j.bic.val().index(), 8);
    // a receiver (lost arbitration) dominant at the sample: not a contender, not charged
    let mut r = unit(on);
    sample(&mut r, Bit { c: false, bt: false, sof: true, ..Default::default() });
    sample(&mut r, Bit { c: true, bt: false, tx: true, ..Default::default() });
    sample(&mut r, Bit { c: false, bt: false, tx: true, err: true, ..Default::default() });
    assert!(!r.contender.val());
    assert!(!first_flagger_clock(&mut r));
    assert_eq!(r.bic.val().index(), 0);
    // another input glitched in this frame (`gl_others` at the sample): excused
    let mut g = unit(on);
    sample(&mut g, Bit { c: false, bt: false, sof: true, ..Default::default() });
    g.gl_others.next = true;
    sample(&mut g, Bit { c: false, bt: false, tx: true, ..Default::default() });
    g.gl_others.next = false;
    assert!(!first_flagger_clock(&mut g));
    assert_eq!(g.bic.val().index(), 0);
    // its own glitch does not excuse a unit: `glf` marks it until the next SOF
    let mut s = unit(on);
    sample(&mut s, Bit { c: false, bt: false, sof: true, ..Default::default() });
    sample(&mut s, Bit { c: false, bt: false, tx: true, ..Default::default() });
    assert!(!s.glf.val());
    pulse_bit(&mut s, 1, 4, false);
    assert!(s.glf.val());
    sample(&mut s, Bit { c: false, bt: false, tx: true, ..Default::default() });
    assert!(first_flagger_clock(&mut s));
    assert!(s.glf.val());
    sample(&mut s, Bit { c: false, bt: false, sof: true, ..Default::default() });
    assert!(!s.glf.val(), "cleared at SOF");
    // the rule off
    let mut o = unit(params());
    sample(&mut o, Bit { c: false, bt: false, sof: true, ..Default::default() });
    sample(&mut o, Bit { c: false, bt: false, tx: true, ..Default::default() });
    assert!(!first_flagger_clock(&mut o));
    assert_eq!(o.bic.val().index(), 0);
    // eight first-flagger charges reach the limit 64 (a new frame: a contender again)
    sample(&mut j, Bit { c: false, bt: false, sof: true, ..Default::default() });
    for _ in 0..7 {
        sample(&mut j, Bit { c: false, bt: false, tx: true, ..Default::default() });
        assert!(first_flagger_clock(&mut j));
    }
    assert_eq!(j.bic.val().index(), 64);
    drive::cycle(&mut j);
    assert!(j.dis.val());
}

/// hub.md §5.16: the dominant contender of the first-flagger rule is judged by the window
/// (dominant at any clock from the window lag to the sample, like the unjustified-dominant
/// rules): a transmitter's error flag that ends a clock before this hub's sample point (its
/// oscillator fast, the other hub sampling it a crossing later) is still its flag; a level
/// that ends before the window lag is not.
#[test]
fn first_flagger_judges_the_contender_by_the_window() {
    for (ends_at, charged) in [(SAMPLE_AT - 1, true), (SAMPLE_AT, true), (6, false)] {
        let mut j = unit(JudgeParams { first_flagger: true, ..params() });
        sample(&mut j, Bit { c: false, bt: false, sof: true, ..Default::default() });
        sample(&mut j, Bit { c: false, bt: false, tx: true, ..Default::default() });
        apply(&mut j, Bit { c: false, bt: false, tx: true, ..Default::default() });
        bit_clocks(&mut j, &|j, k| j.c.next = k >= ends_at);
        assert_eq!(first_flagger_clock(&mut j), charged, "dominant up to clock {ends_at}");
        assert_eq!(j.bic.val().index(), if charged { 8 } else { 0 });
    }
}

/// §5.1 with §5.7: a sublink that is recessive while BT is dominant has lost arbitration
/// (it becomes a receiver, and its next dominant bit is blamed) only when no replica is
/// dominant; recessive while a replica is dominant is a replica disagreement, not a loss.
#[test]
fn recessive_replica_minority_stays_a_contender() {
    for (rep_dom, blamed) in [(false, true), (true, false)] {
        let mut j = sublink_unit(params());
        drive::init(&mut j);
        sample(&mut j, Bit { c: false, bt: false, sof: true, ..Default::default() });
        j.rep_dom.next = rep_dom;
        sample(&mut j, Bit { c: true, bt: false, tx: true, ..Default::default() });
        j.rep_dom.next = false;
        assert_eq!(j.contender.val(), rep_dom, "contender after a recessive bit with rep_dom = {rep_dom}");
        // the peer's next dominant data bit
        sample(&mut j, Bit { c: true, bt: true, tx: true, ..Default::default() });
        let b = sample(&mut j, Bit { c: false, bt: false, tx: true, ..Default::default() });
        assert_eq!(b, blamed, "dominant bit blamed with rep_dom = {rep_dom}");
    }
    // ports have no replicas: unchanged
    let mut j = unit(params());
    sample(&mut j, Bit { c: false, bt: false, sof: true, ..Default::default() });
    sample(&mut j, Bit { c: true, bt: false, tx: true, ..Default::default() });
    assert!(!j.contender.val());
}

/// A blame in an EOF bit, dominant from clock 8 to 10, every replica recessive at the
/// sample point (the hub starts its episode one clock after the sample, registered);
/// `replica_carried_it`: the other replicas were dominant in the window too; `suppress`:
/// another unit glitched in the last two bits. Returns the replica count after the episode.
fn window_blame_episode(replica_carried_it: bool, suppress: bool) -> usize {
    let mut j = reset(sublink_unit(params()));
    let mut blame = false;
    j.bt.next = true;
    j.eof_1_6.next = true;
    j.rep_rec.next = true;
    j.suppress.next = suppress;
    for k in 0..16u64 {
        j.c.next = !(8..11).contains(&k);
        j.rep_rec_w.next = !replica_carried_it && k >= 7;
        j.sample.next = k == SAMPLE_AT;
        j.err_start.next = k == SAMPLE_AT + 1;
        j.bit_start.next = k == 0;
        j.bs_cnt.next = k.into();
        drive::settle(&mut j);
        blame |= j.blame.val();
        assert_eq!(j.window_dom.val(), (8..16).contains(&k), "window_dom at clock {k}");
        drive::cycle(&mut j);
    }
    assert!(blame, "dominant at clocks 8..10: blamed");
    j.rep_cnt.val().index()
}

/// §5.7: a sublink blamed while a replica had no dominant level in its window is the
/// dominant minority of the episode and is charged, even when its own pulse ended before
/// the sample point (window rule); units blamed for a pulse that every replica carried
/// (all recessive again at the sample point) are not.
#[test]
fn window_blame_is_not_a_dominant_minority() {
    assert_eq!(window_blame_episode(true, false), 0, "every replica carried the pulse");
    assert_eq!(window_blame_episode(false, false), 1, "this replica alone carried it");
}

/// hub.md §5.24: a blame suppressed by another unit's glitch (the other replica of a
/// flipping interlink turned the peer's dominant level recessive) does not make this
/// unit the charged dominant minority.
#[test]
fn suppressed_blame_is_not_a_dominant_minority() {
    assert_eq!(window_blame_episode(false, true), 0, "suppressed: no replica charge");
}

/// hub.md §5.11 peer-hub rule: common glitches (every replica at once) are counted in
/// `pgc` on sublinks only, decay by one per `peer_glitch_decay` good frames, and isolate at
/// `peer_glitch_limit`; they never count in `gc` or `life`.
#[test]
fn common_glitches_isolate_the_peer_hub() {
    let p = JudgeParams { peer_glitch_limit: 4, peer_glitch_decay: 2, ..params() };
    let mut j = reset(sublink_unit(p));
    j.common.next = true;
    pulse_bit(&mut j, 3, 4, false);
    pulse_bit(&mut j, 3, 4, false);
    assert_eq!(j.pgc.val().index(), 2);
    assert_eq!(j.gc.val().index(), 0);
    assert_eq!(j.life.val().index(), 0);
    j.common.next = false;
    // a glitch on this replica alone counts in gc, not in pgc
    pulse_bit(&mut j, 3, 4, false);
    assert_eq!((j.pgc.val().index(), j.gc.val().index()), (2, 1));
    // two good frames take one off
    for _ in 0..2 {
        sample(&mut j, Bit { c: true, bt: true, frame_ok: true, ..Default::default() });
    }
    assert_eq!(j.pgc.val().index(), 1, "decayed");
    j.common.next = true;
    for k in 1..=3 {
        assert!(!j.dis.val(), "not isolated at pgc {k}");
        pulse_bit(&mut j, 3, 4, false);
    }
    drive::cycle(&mut j);
    assert_eq!(j.pgc.val().index(), 4);
    assert!(j.dis.val(), "isolated at the limit");
    // a port never counts common glitches (its `common` input is 0 in the hub anyway)
    let mut j = unit(p);
    j.common.next = true;
    for _ in 0..5 {
        pulse_bit(&mut j, 3, 4, false);
    }
    assert_eq!(j.pgc.val().index(), 0);
}

/// One error-flag bit of 16 clocks on a sublink: the input dominant but recessive at
/// clocks `from..from + len` (the gap between a dominant run and a flag that starts inside
/// the bit); returns the glitch strobes.
fn recessive_sliver_bit(j: &mut JudgeUnit, from: u64, len: u64) -> usize {
    j.bt.next = false;
    j.err_phase.next = true;
    let (_, glitches) = bit_clocks(j, &|j, k| j.c.next = (from..from + len).contains(&k));
    j.err_phase.next = false;
    glitches
}

/// hub.md §5.15: with the default sublink parameters a recessive sliver shorter than 3
/// clocks is legal (an isolation or a flag starting inside a bit), a dominant run of 1 or
/// 2 clocks is a glitch: it counts in `gc`, or in `pgc` when every replica shows it.
#[test]
fn short_dominant_runs_on_a_sublink_are_glitches() {
    let p = canstar_hub::config::HubConfig::default().sublink_params();
    assert_eq!((p.glitch_min, p.glitch_min_dominant), (3, 1));
    let mut j = reset(sublink_unit(p));
    // a dominant bit first: the dominant runs around the slivers are long
    sample(&mut j, Bit { c: false, bt: false, err: true, ..Default::default() });
    assert_eq!(recessive_sliver_bit(&mut j, 5, 2), 0, "2-clock recessive sliver: legal");
    assert_eq!(recessive_sliver_bit(&mut j, 5, 1), 0, "1-clock recessive sliver: legal");
    assert_eq!(recessive_sliver_bit(&mut j, 5, 3), 1, "3-clock recessive run: a glitch");
    let mut j = reset(sublink_unit(p));
    for len in [1, 2] {
        assert_eq!(pulse_bit(&mut j, 3, len, false).1, 1, "{len}-clock dominant pulse: a glitch");
        sample(&mut j, Bit { c: true, bt: true, ..Default::default() });
    }
    assert_eq!(j.gc.val().index(), 2);
    assert!(j.glf_own.val(), "glitches of its own excuse the other sublinks (§5.15)");
    let mut j = reset(sublink_unit(p));
    j.common.next = true;
    pulse_bit(&mut j, 3, 2, false);
    sample(&mut j, Bit { c: true, bt: true, ..Default::default() });
    assert_eq!((j.gc.val().index(), j.pgc.val().index()), (0, 1), "common: the peer's");
    assert!(j.glf.val() && !j.glf_own.val(), "a common glitch excuses no other sublink");
}

/// The hub's `err_start` strobe for one clock (between samples); returns `charged`.
fn episode(j: &mut JudgeUnit) -> bool {
    j.err_start.next = true;
    drive::settle(j);
    let charged = j.charged.val();
    drive::cycle(j);
    j.err_start.next = false;
    charged
}

/// A sublink unit after a glitch at clocks 3..6 of an EOF bit; `common`: every replica
/// glitched with it (the peer's contribution).
fn sublink_after_glitch(common: bool) -> JudgeUnit {
    let mut j = reset(sublink_unit(params()));
    j.common.next = common;
    pulse_bit(&mut j, 3, 4, false);
    j.common.next = false;
    j
}

/// hub.md §5.14: an error episode that starts within two bits after a common glitch (the
/// peer's contribution glitched on every replica, and nodes that sampled it flag) is
/// charged to the sublink, +8 like a blame, unless the sublink was charged at the sample
/// that started the episode. Later, after a glitch of this replica alone (`gc`), or on a
/// port, the episode charges nothing.
#[test]
fn episode_after_a_common_glitch_is_charged_to_the_sublink() {
    let mut j = sublink_after_glitch(true);
    assert_eq!((j.pgc.val().index(), j.bic.val().index()), (1, 0), "counted as the peer's glitch");
    assert!(episode(&mut j), "charged");
    assert_eq!((j.bic.val().index(), j.life.val().index()), (8, 1));
    // three samples later the glitch no longer explains an episode
    let mut j = sublink_after_glitch(true);
    for _ in 0..3 {
        sample(&mut j, Bit { c: true, bt: true, ..Default::default() });
    }
    assert!(!episode(&mut j));
    assert_eq!(j.bic.val().index(), 0);
    // a glitch of this replica alone counts in gc (§5.8), the episode is not charged here
    let mut j = sublink_after_glitch(false);
    assert_eq!(j.gc.val().index(), 1);
    assert!(!episode(&mut j));
    assert_eq!(j.bic.val().index(), 0);
    // charged at the sample that started the episode (dominant in the EOF): not twice
    let mut j = sublink_after_glitch(true);
    apply(&mut j, Bit { c: false, bt: false, eof: true, ..Default::default() });
    for k in 0..SAMPLE_AT {
        clock_at(&mut j, k);
    }
    j.sample.next = true;
    j.bs_cnt.next = SAMPLE_AT.into();
    drive::cycle(&mut j);
    j.sample.next = false;
    assert_eq!(j.bic.val().index(), 8, "blamed and charged at the sample");
    assert!(!episode(&mut j), "not charged again");
    assert_eq!(j.bic.val().index(), 8);
    // a port unit never (its `common` is 0 in the hub; the rule is the sublinks')
    let mut j = unit(params());
    j.common.next = true;
    pulse_bit(&mut j, 3, 4, false);
    assert!(!episode(&mut j));
    assert_eq!(j.bic.val().index(), 0);
}

/// hub.md §5.16: an episode that starts at a dominant stuff bit (`stuff_dom` at the sample
/// that started it: six recessive bits, which every node and the monitor saw alike, as when
/// a transmitter behind the peer is switched off in a dominant bit) is not charged by the
/// common-glitch rule; the same episode one clock later without the stuff bit is.
#[test]
fn episode_at_a_dominant_stuff_bit_is_not_charged_for_a_common_glitch() {
    for (stuff_dom, charged) in [(true, false), (false, true)] {
        let mut j = sublink_after_glitch(true);
        j.stuff_dom.next = stuff_dom;
        drive::cycle(&mut j);
        j.stuff_dom.next = false;
        assert_eq!(episode(&mut j), charged, "stuff_dom {stuff_dom}");
        assert_eq!(j.bic.val().index(), if charged { 8 } else { 0 });
    }
}

/// §5.8 with §5.7: while another replica has glitches on its counter (and this one has
/// none), the replica rule does not charge this one.
#[test]
fn replica_rule_spares_the_unit_whose_replica_glitches() {
    let mut j = sublink_unit(params());
    drive::init(&mut j);
    j.rep_glitched.next = true;
    for _ in 0..3 {
        dominant_minority_episode(&mut j);
    }
    assert_eq!(j.rep_cnt.val().index(), 0);
    j.rep_glitched.next = false;
    dominant_minority_episode(&mut j);
    assert_eq!(j.rep_cnt.val().index(), 1, "charged again without the replica's glitches");
    // an episode started by the blame of another sublink (not this one): not charged
    assert_eq!(dominant_minority_then_episode(true, false), 0, "another sublink's blame started the episode");
}

/// A fresh sublink unit is the dominant minority of a replica disagreement, then the hub
/// starts an episode (`err_start`) with `rep_blamed` and `ff` as given; returns `rep_cnt`.
fn dominant_minority_then_episode(rep_blamed: bool, ff: bool) -> usize {
    let mut j = sublink_unit(params());
    drive::init(&mut j);
    j.rep_rec.next = true;
    sample(&mut j, Bit { c: false, bt: false, err: true, ..Default::default() });
    j.rep_rec.next = false;
    j.err_start.next = true;
    j.rep_blamed.next = rep_blamed;
    j.ff.next = ff;
    drive::cycle(&mut j);
    j.rep_cnt.val().index()
}

/// §5.7 refinement (4), hub.md §5.13: the dominant minority is not charged by the replica
/// rule at an episode that the frame monitor alone detected (`ff`, the first-flagger strobe
/// that comes with `err_start`): the first-flagger rule charges the dominant contenders of
/// that bit instead. Without `ff` the same disagreement is charged.
#[test]
fn replica_rule_leaves_monitor_episodes_to_the_first_flagger() {
    for (ff, charged) in [(false, 1), (true, 0)] {
        assert_eq!(dominant_minority_then_episode(false, ff), charged, "ff {ff}");
    }
}

/// A fresh sublink unit (a replica beside it unless `alone`) sees one disagreement at a
/// sample of `b` (`minority_dom`: it is the dominant minority, else the recessive one),
/// with `rep_mask` as given; then, at a later clock, `alone` takes effect and the hub starts
/// an episode (`episode`) or the frame completes; returns `rep_cnt`.
fn disagreement_then(b: Bit, minority_dom: bool, mask: bool, alone: bool, episode_follows: bool) -> usize {
    let mut j = reset(sublink_unit(params()));
    j.rep_mask.next = mask;
    j.rep_rec.next = minority_dom;
    j.rep_dom.next = !minority_dom;
    sample(&mut j, Bit { c: !minority_dom, ..b });
    j.rep_mask.next = false;
    j.rep_rec.next = false;
    j.rep_dom.next = false;
    j.rep_other.next = !alone;
    episode_or_good_frame(&mut j, episode_follows)
}

/// An error episode (`err_start`) if `episode_follows`, else a good frame; returns `rep_cnt`.
fn episode_or_good_frame(j: &mut JudgeUnit, episode_follows: bool) -> usize {
    if episode_follows {
        episode(j);
    } else {
        sample(j, Bit { c: true, bt: true, frame_ok: true, ..Default::default() });
    }
    j.rep_cnt.val().index()
}

/// hub.md §5.18: a replica disagreement records a role only where the replicas decided BT
/// and the consequence can tell which one was wrong: not while a port or the hub's error
/// flag is dominant (`rep_mask`); outside a frame (Bus_Idle, SOF, Intermission, error
/// phase) only as the dominant minority, since a dominant level there is a SOF that a node
/// with a frame pending takes as its own and the frame then completes whichever replica was
/// wrong; and no record is charged once no other replica is enabled (`rep_other`).
#[test]
fn replica_disagreements_count_where_the_replicas_decide_bt() {
    let in_frame = Bit { bt: false, tx: true, ..Default::default() };
    let at_sof = Bit { bt: false, sof: true, ..Default::default() };
    let idle = Bit { bt: false, ..Default::default() };
    // recessive minority, then the frame completes: charged only inside a frame, unmasked
    assert_eq!(disagreement_then(in_frame, false, false, false, false), 1, "in a frame");
    assert_eq!(disagreement_then(in_frame, false, true, false, false), 0, "masked by a port");
    assert_eq!(disagreement_then(at_sof, false, false, false, false), 0, "at SOF");
    assert_eq!(disagreement_then(idle, false, false, false, false), 0, "in Bus_Idle");
    assert_eq!(disagreement_then(in_frame, false, false, true, false), 0, "the other replica isolated since");
    // dominant minority, then an episode: charged in a frame and at SOF, not when masked
    assert_eq!(disagreement_then(in_frame, true, false, false, true), 1, "in a frame");
    assert_eq!(disagreement_then(at_sof, true, false, false, true), 1, "at SOF");
    assert_eq!(disagreement_then(at_sof, true, true, false, true), 0, "masked by a port");
    assert_eq!(disagreement_then(in_frame, true, false, true, true), 0, "the other replica isolated since");
}

/// hub.md §5.18: a disagreement counts only when the replicas have differed for
/// `replica_skew` clocks (4) before the sample; a peer edge reaches replicas of unequal
/// length a few clocks apart. Dominant minority from clock `from` of the bit (sample at
/// clock 12), then an error episode; returns `rep_cnt`.
fn late_disagreement(from: u64) -> usize {
    let mut j = reset(sublink_unit(params()));
    apply(&mut j, Bit { c: false, bt: false, tx: true, ..Default::default() });
    bit_clocks(&mut j, &|j, k| j.rep_rec.next = k >= from);
    j.rep_rec.next = false;
    episode(&mut j);
    j.rep_cnt.val().index()
}

#[test]
fn replica_disagreement_must_outlast_the_skew() {
    assert_eq!(late_disagreement(SAMPLE_AT - 2), 0, "2 clocks: an edge seen through replicas of unequal length");
    assert_eq!(late_disagreement(SAMPLE_AT - 4), 1, "4 clocks: a disagreement");
}

/// hub.md §5.21: a fresh sublink unit (replica overload rule `on`) is the dominant minority
/// at a sample (`im12`: Intermission bit 1 or 2; `mask`: a port dominant; `other`: a replica
/// beside it); then the overload (`episode`: an error episode follows, else a good frame);
/// returns `rep_cnt`.
fn overload_minority(on: bool, im12: bool, mask: bool, other: bool, episode_follows: bool) -> usize {
    let mut j = reset(sublink_unit(JudgeParams { replica_overload: on, ..params() }));
    j.rep_mask.next = mask;
    j.rep_rec.next = true;
    j.rep_other.next = other;
    sample(&mut j, Bit { c: false, bt: false, im12, ..Default::default() });
    j.rep_mask.next = false;
    j.rep_rec.next = false;
    // the nodes' overload flags (BT dominant, the sublink recessive again)
    sample(&mut j, Bit { c: true, bt: false, err: true, ..Default::default() });
    episode_or_good_frame(&mut j, episode_follows)
}

/// The dominant minority that raised an overload condition by itself is charged at that
/// sample, whatever follows (the error episode may start on the peer's side only), and only
/// once when an episode does follow; not masked by a port, not without a replica beside it,
/// not outside Intermission bits 1-2, not with the rule off.
#[test]
fn replica_overload_rule_charges_the_dominant_minority_at_once() {
    assert_eq!(overload_minority(true, true, false, true, false), 1, "overload, then a good frame");
    assert_eq!(overload_minority(false, true, false, true, false), 0, "rule off: recorded, not charged at a good frame");
    assert_eq!(overload_minority(true, true, false, true, true), 1, "overload, then an episode: charged once");
    assert_eq!(overload_minority(false, true, false, true, true), 1, "rule off: charged at the episode");
    assert_eq!(overload_minority(true, false, false, true, false), 0, "not Intermission bit 1 or 2");
    assert_eq!(overload_minority(true, true, true, true, false), 0, "masked by a port");
    assert_eq!(overload_minority(true, true, false, false, false), 0, "no replica beside it");
}

/// The nodes sample before the hub: a dominant-minority pulse of Intermission bit 1 that
/// ends before the hub's sample (clocks `from..to` of the bit, sample at 12) still raised
/// their overload condition. Returns `rep_cnt` after a good frame.
fn overload_pulse(on: bool, from: u64, to: u64) -> usize {
    let mut j = reset(sublink_unit(JudgeParams { replica_overload: on, ..params() }));
    apply(&mut j, Bit { c: true, bt: true, im12: true, ..Default::default() });
    bit_clocks(&mut j, &|j, k| {
        let pulse = (from..to).contains(&k);
        j.c.next = !pulse;
        j.bt.next = !pulse;
        j.rep_rec.next = pulse;
    });
    apply(&mut j, Bit::default());
    sample(&mut j, Bit { c: true, bt: true, frame_ok: true, ..Default::default() });
    j.rep_cnt.val().index()
}

#[test]
fn replica_overload_rule_counts_a_pulse_that_ends_before_the_sample() {
    assert_eq!(overload_pulse(true, 1, 11), 1, "10 clocks, ended 1 clock before the sample");
    assert_eq!(overload_pulse(false, 1, 11), 0, "rule off");
    assert_eq!(overload_pulse(true, 1, 4), 0, "3 clocks: shorter than replica_skew");
}
