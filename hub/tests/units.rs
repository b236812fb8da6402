//! Unit tests of the judge unit and the frame-state decoder in isolation, and their
//! Verilog flows.
use canstar_hdl::{drive, flow};
use canstar_hub::frame_state::{Field, FrameDecode};
use canstar_hub::judge::{JudgeParams, JudgeUnit};
use rand::Rng;

fn params() -> JudgeParams {
    JudgeParams { bic_limit: 64, bic_decay: 1, life_limit: 32, dbc_threshold: 13, nack_threshold: 7, replica_limit: 3, reintegration: None, glitch_min: 1, glitch_max: 11, glitch_limit: 3, glitch_decay: 16, peer_glitch_limit: 12, peer_glitch_decay: 4, window_lag: 7, crc_window_end: 8, first_flagger: false }
}

#[derive(Default, Clone, Copy)]
struct Bit {
    c: bool,
    bt: bool,
    sof: bool,
    tx: bool,
    crc_delim: bool,
    ack_slot: bool,
    ack_delim: bool,
    eof: bool,
    im: bool,
    err: bool,
    crc_ok: bool,
    frame_ok: bool,
}

/// One sampled bit: inputs, a sample strobe, two more clocks.
fn sample(j: &mut JudgeUnit, b: Bit) -> bool {
    j.c.next = b.c;
    j.bt.next = b.bt;
    j.sof.next = b.sof;
    j.tx_region.next = b.tx;
    j.crc_delim.next = b.crc_delim;
    j.ack_slot.next = b.ack_slot;
    j.ack_delim.next = b.ack_delim;
    j.eof_1_6.next = b.eof;
    j.im_2.next = b.im;
    j.err_phase.next = b.err;
    j.crc_ok.next = b.crc_ok;
    j.frame_ok.next = b.frame_ok;
    // one bit of 16 clocks (the reference timing), sample point at clock 12: the input
    // holds its level for the whole bit, so the pulse check never sees a glitch here
    for k in 0..SAMPLE_AT {
        clock_at(j, k);
    }
    j.sample.next = true;
    j.bs_cnt.next = SAMPLE_AT.into();
    drive::settle(j);
    let blame = j.blame.val();
    drive::cycle(j);
    j.sample.next = false;
    for k in SAMPLE_AT + 1..16 {
        clock_at(j, k);
    }
    blame
}

const SAMPLE_AT: u64 = 12;

/// One clock at `k` clocks after the bit start (bit_start strobe at 0, no sample).
fn clock_at(j: &mut JudgeUnit, k: u64) {
    j.bit_start.next = k == 0;
    j.bs_cnt.next = k.into();
    drive::cycle(j);
    j.bit_start.next = false;
}

fn unit(p: JudgeParams) -> JudgeUnit {
    reset(JudgeUnit::port(p))
}

/// `j` initialised and reset.
fn reset(mut j: JudgeUnit) -> JudgeUnit {
    drive::init(&mut j);
    j.reset.next = true;
    drive::cycle(&mut j);
    j.reset.next = false;
    j
}

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
    for which in 0..5 {
        let mut j = unit(params());
        let mut b = Bit { c: false, bt: false, ..Default::default() };
        match which {
            0 => b.crc_delim = true,
            1 => b.ack_delim = true,
            2 => b.eof = true,
            3 => b.im = true,
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

/// One bit of 16 clocks, recessive but dominant from clock `from` for `len` clocks, in
/// the EOF (a recessive-only position); returns (blame at the sample point, glitches).
fn pulse_bit(j: &mut JudgeUnit, from: u64, len: u64, suppress: bool) -> (bool, usize) {
    let (mut blame, mut glitches) = (false, 0);
    j.bt.next = true;
    j.eof_1_6.next = true;
    j.suppress.next = suppress;
    for k in 0..16u64 {
        j.c.next = !(from..from + len).contains(&k);
        j.sample.next = k == SAMPLE_AT;
        j.bit_start.next = k == 0;
        j.bs_cnt.next = k.into();
        drive::settle(j);
        blame |= j.blame.val();
        glitches += j.glitch.val() as usize;
        drive::cycle(j);
    }
    j.sample.next = false;
    j.eof_1_6.next = false;
    j.suppress.next = false;
    // the run ending in the first clock of the next bit: count it here
    j.c.next = true;
    drive::settle(j);
    glitches += j.glitch.val() as usize;
    (blame, glitches)
}

/// One CRC delimiter bit of 16 clocks, recessive until clock `from`, then dominant to the
/// end of the bit (an acknowledgement that starts early, or a fault); returns the blame at
/// the sample point (clock 12).
fn crc_delimiter_dominant_from(j: &mut JudgeUnit, from: u64) -> bool {
    let mut blame = false;
    j.bt.next = true;
    j.crc_delim.next = true;
    for k in 0..16u64 {
        j.c.next = k < from;
        j.bt.next = k < from;
        j.sample.next = k == SAMPLE_AT;
        j.bit_start.next = k == 0;
        j.bs_cnt.next = k.into();
        drive::settle(j);
        blame |= j.blame.val();
        drive::cycle(j);
    }
    j.sample.next = false;
    j.crc_delim.next = false;
    blame
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

/// The first intermission bit is not blamed (a node's reaction to a dominant last EOF
/// bit that only it saw); the decoder's `im_2` marks the second bit only.
#[test]
fn first_intermission_bit_not_blamed() {
    let mut j = unit(params());
    assert!(!sample(&mut j, Bit { c: false, bt: false, ..Default::default() }), "im bit 1: no rule");
    assert!(sample(&mut j, Bit { c: false, bt: false, im: true, ..Default::default() }), "im bit 2 blamed");
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

#[test]
fn replica_rule_charges_by_consequence() {
    let mut j = JudgeUnit::sublink(params());
    drive::init(&mut j);
    // dominant-minority then an error episode: charged
    for _ in 0..3 {
        j.rep_rec.next = true;
        sample(&mut j, Bit { c: false, bt: false, err: true, ..Default::default() });
        j.rep_rec.next = false;
        j.err_start.next = true;
        drive::cycle(&mut j);
        j.err_start.next = false;
    }
    assert_eq!(j.rep_cnt.val().index(), 3);
    drive::cycle(&mut j);
    assert!(j.dis.val());
    // recessive-minority then a good frame: charged; dominant-minority then a good frame: not
    let mut j = JudgeUnit::sublink(params());
    drive::init(&mut j);
    j.rep_dom.next = true;
    sample(&mut j, Bit { c: true, bt: false, ..Default::default() });
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

/// §5.1 with §5.7: a sublink that is recessive while BT is dominant has lost arbitration
/// (it becomes a receiver, and its next dominant bit is blamed) only when no replica is
/// dominant; recessive while a replica is dominant is a replica disagreement, not a loss.
#[test]
fn recessive_replica_minority_stays_a_contender() {
    for (rep_dom, blamed) in [(false, true), (true, false)] {
        let mut j = JudgeUnit::sublink(params());
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

/// §5.7: a sublink blamed while a replica had no dominant level in its window is the
/// dominant minority of the episode and is charged, even when its own pulse ended before
/// the sample point (window rule); units blamed for a pulse that every replica carried
/// (all recessive again at the sample point) are not.
#[test]
fn window_blame_is_not_a_dominant_minority() {
    for (replica_carried_it, charged) in [(true, 0), (false, 1)] {
        let mut j = reset(JudgeUnit::sublink(params()));
        // an EOF bit, dominant from clock 8 to 10, every replica recessive at the sample
        // point; the hub starts its episode one clock after the sample (registered)
        let mut blame = false;
        j.bt.next = true;
        j.eof_1_6.next = true;
        j.rep_rec.next = true;
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
        assert_eq!(j.rep_cnt.val().index(), charged, "replica carried the pulse: {replica_carried_it}");
    }
}

/// hub.md §5.11 peer-hub rule: common glitches (every replica at once) are counted in
/// `pgc` on sublinks only, decay by one per `peer_glitch_decay` good frames, and isolate at
/// `peer_glitch_limit`; they never count in `gc` or `life`.
#[test]
fn common_glitches_isolate_the_peer_hub() {
    let p = JudgeParams { peer_glitch_limit: 4, peer_glitch_decay: 2, ..params() };
    let mut j = reset(JudgeUnit::sublink(p));
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

/// §5.8 with §5.7: while another replica has glitches on its counter (and this one has
/// none), the replica rule does not charge this one.
#[test]
fn replica_rule_spares_the_unit_whose_replica_glitches() {
    let mut j = JudgeUnit::sublink(params());
    drive::init(&mut j);
    j.rep_glitched.next = true;
    for _ in 0..3 {
        j.rep_rec.next = true;
        sample(&mut j, Bit { c: false, bt: false, err: true, ..Default::default() });
        j.rep_rec.next = false;
        j.err_start.next = true;
        drive::cycle(&mut j);
        j.err_start.next = false;
    }
    assert_eq!(j.rep_cnt.val().index(), 0);
    j.rep_glitched.next = false;
    j.rep_rec.next = true;
    sample(&mut j, Bit { c: false, bt: false, err: true, ..Default::default() });
    j.rep_rec.next = false;
    j.err_start.next = true;
    drive::cycle(&mut j);
    assert_eq!(j.rep_cnt.val().index(), 1, "charged again without the replica's glitches");
    // an episode started by the blame of another sublink (not this one): not charged
    assert_eq!(dominant_minority_then_episode(true, false), 0, "another sublink's blame started the episode");
}

/// A fresh sublink unit is the dominant minority of a replica disagreement, then the hub
/// starts an episode (`err_start`) with `rep_blamed` and `ff` as given; returns `rep_cnt`.
fn dominant_minority_then_episode(rep_blamed: bool, ff: bool) -> usize {
    let mut j = JudgeUnit::sublink(params());
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

#[test]
fn frame_decode_matches_its_table() {
    let mut d = FrameDecode::default();
    drive::init(&mut d);
    for f in 0..16u64 {
        for pos in 0..16u64 {
            d.field.next = f.into();
            d.pos.next = pos.into();
            drive::settle(&mut d);
            let field = Field::from_code(f);
            assert_eq!(field.code(), f);
            assert_eq!(d.sof.val(), field == Field::Sof);
            assert_eq!(d.tx_region.val(), matches!(field, Field::Id | Field::Rtr | Field::Res | Field::Dlc | Field::Data | Field::Crc));
            assert_eq!(d.crc_delim.val(), field == Field::CrcDelim);
            assert_eq!(d.ack_slot.val(), field == Field::AckSlot);
            assert_eq!(d.ack_delim.val(), field == Field::AckDelim);
            assert_eq!(d.eof_1_6.val(), field == Field::Eof && pos < 6);
            assert_eq!(d.eof_last.val(), field == Field::Eof && pos == 6);
            assert_eq!(d.im_2.val(), field == Field::Intermission && pos == 1);
            assert_eq!(d.err_phase.val(), matches!(field, Field::ErrorFlag | Field::ErrorDelim | Field::Overload));
        }
    }
}

fn judge_stim(j: &mut JudgeUnit, rng: &mut rand_chacha::ChaCha8Rng, c: usize) {
    j.reset.next = c < 2 || rng.gen_ratio(1, 20_000);
    let k = c % 16;
    j.sample.next = k == 12;
    // in the hub `ff` only comes with `err_start` (both registered from the same trigger)
    let err_start = k == 13 && rng.gen_ratio(1, 20);
    j.err_start.next = err_start;
    j.ff.next = err_start && rng.gen_bool(0.5);
    j.gl_others.next = rng.gen_ratio(1, 4);
    if k == 0 {
        // a rough frame-like field sequence, biased towards fault-free behaviour
        let phase = (c / 16) % 120;
        let f = match phase {
            0 => 1,
            1..=60 => 2 + (phase % 6) as u64,
            61 => 8,
            62 => 9,
            63 => 10,
            64..=70 => 11,
            71..=73 => 12,
            _ => 0,
        };
        let err = rng.gen_ratio(1, 30);
        j.sof.next = f == 1;
        j.tx_region.next = (2..=7).contains(&f);
        j.crc_delim.next = f == 8;
        j.ack_slot.next = f == 9;
        j.ack_delim.next = f == 10;
        j.eof_1_6.next = (64..70).contains(&phase);
        j.im_2.next = phase == 72;
        j.frame_ok.next = phase == 70;
        j.crc_ok.next = rng.gen_bool(0.9);
        j.err_phase.next = err;
        j.bt.next = rng.gen_bool(0.5);
        j.c.next = if rng.gen_ratio(1, 25) { false } else { j.bt.val() | rng.gen_bool(0.5) };
        if rng.gen_ratio(1, 300) {
            j.c.next = false; // occasionally long dominant runs
        }
        j.rep_rec.next = rng.gen_ratio(1, 10);
        j.rep_rec_w.next = rng.gen_ratio(1, 10);
        j.rep_dom.next = rng.gen_ratio(1, 10);
        j.delim.next = rng.gen_ratio(1, 20);
        j.suppress.next = rng.gen_ratio(1, 8);
        j.stuff_dom.next = rng.gen_ratio(1, 10);
        j.rep_glitched.next = rng.gen_ratio(1, 4);
        j.rep_blamed.next = rng.gen_ratio(1, 6);
        j.common.next = rng.gen_ratio(1, 5);
    }
    // bit-start estimate and its counter; an occasional mid-bit level change (a glitch)
    j.bit_start.next = k == 0;
    j.bs_cnt.next = (k as u64).into();
    if k != 0 && rng.gen_ratio(1, 60) {
        j.c.next = !j.c.val();
    }
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn port_judge_flow() {
    let mut j = JudgeUnit::port(JudgeParams { reintegration: Some(3), first_flagger: true, ..params() });
    flow::full_check(&mut j, "port_judge", 100_000, 21, judge_stim).expect("port judge flow");
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn sublink_judge_flow() {
    let mut j = JudgeUnit::sublink(JudgeParams { bic_limit: 128, dbc_threshold: 28, first_flagger: true, ..params() });
    flow::full_check(&mut j, "sublink_judge", 100_000, 22, judge_stim).expect("sublink judge flow");
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn frame_decode_flow() {
    let mut d = FrameDecode::default();
    flow::full_check(&mut d, "frame_decode", 100_000, 23, |d: &mut FrameDecode, rng, _| {
        d.field.next = rng.gen_range(0..16u64).into();
        d.pos.next = rng.gen_range(0..16u64).into();
    })
    .expect("frame decode flow");
}

#[test]
fn adapter_maps_fields_events_and_estimates_bit_start() {
    use canstar_hub::frame_state::{ctrl_field, MonitorAdapter};
    let mut a = MonitorAdapter::new(2);
    drive::init(&mut a);
    let strobe = |a: &mut MonitorAdapter, field: u64, pos: u64, ev: u64| -> (u64, u64, bool, bool, bool) {
        a.sample.next = true;
        a.field.next = field.into();
        a.pos.next = pos.into();
        drive::cycle(a);
        a.sample.next = false;
        a.events.next = ev.into();
        drive::settle(a);
        let r = (a.mon_field.val().index() as u64, a.mon_pos.val().index() as u64, a.mon_sample.val(), a.mon_error.val(), a.mon_frame_ok.val());
        drive::cycle(a);
        a.events.next = 0.into();
        r
    };
    assert_eq!(strobe(&mut a, ctrl_field::BUS_IDLE, 1, 1), (Field::Sof.code(), 0, true, false, false));
    assert_eq!(strobe(&mut a, ctrl_field::BUS_IDLE, 1, 0), (Field::Idle.code(), 0, true, false, false));
    assert_eq!(strobe(&mut a, ctrl_field::INTERMISSION, 3, 1), (Field::Sof.code(), 2, true, false, false));
    assert_eq!(strobe(&mut a, ctrl_field::EX_IDENTIFIER, 18, 0), (Field::Id.code(), 15, true, false, false));
    assert_eq!(strobe(&mut a, ctrl_field::DATA, 9, 1 << 3), (Field::Data.code(), 8, true, true, false));
    assert_eq!(strobe(&mut a, ctrl_field::END_OF_FRAME, 7, 1 << 13), (Field::Eof.code(), 6, true, false, true));
    assert_eq!(strobe(&mut a, ctrl_field::PASSIVE_ERROR_FLAG, 2, 0).0, Field::ErrorFlag.code());
    assert_eq!(strobe(&mut a, ctrl_field::OVERLOAD_DELIMITER, 4, 0).0, Field::Overload.code());
    // the field is held between samples
    drive::cycle(&mut a);
    assert_eq!(a.mon_field.val().index() as u64, Field::Overload.code());
    assert!(!a.mon_sample.val());
    // bit start: bs_delay (2) clocks after mon_sample
    a.sample.next = true;
    drive::cycle(&mut a);
    a.sample.next = false;
    let mut at = None;
    for k in 0..8 {
        drive::settle(&mut a);
        if a.bit_start.val() {
            at = Some(k);
            break;
        }
        drive::cycle(&mut a);
    }
    assert_eq!(at, Some(3), "mon_sample at k = 0, bit_start 2 clocks later plus the counter load");
}

/// `mon_stuff` is the controller's `dbg_stuff` at the sample strobe, held to the next one.
#[test]
fn adapter_reports_stuff_bits() {
    use canstar_hub::frame_state::{ctrl_field, MonitorAdapter};
    let mut a = MonitorAdapter::new(2);
    drive::init(&mut a);
    for stuff in [true, false, true] {
        a.sample.next = true;
        a.stuff.next = stuff;
        a.field.next = ctrl_field::DATA.into();
        drive::cycle(&mut a);
        a.sample.next = false;
        a.stuff.next = !stuff;
        drive::settle(&mut a);
        assert!(a.mon_sample.val());
        assert_eq!(a.mon_stuff.val(), stuff);
        for _ in 0..5 {
            drive::cycle(&mut a);
            assert_eq!(a.mon_stuff.val(), stuff, "held between samples");
        }
    }
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn adapter_flow() {
    use canstar_hub::frame_state::MonitorAdapter;
    let mut a = MonitorAdapter::new(2);
    flow::full_check(&mut a, "monitor_adapter", 100_000, 24, |a: &mut MonitorAdapter, rng, c| {
        a.reset.next = c < 2 || rng.gen_ratio(1, 20_000);
        a.sample.next = c % 16 == 13;
        if c % 16 == 13 {
            a.field.next = rng.gen_range(0..25u64).into();
            a.pos.next = rng.gen_range(0..20u64).into();
        }
        a.events.next = if c % 16 == 14 { rng.gen_range(0..1u64 << 20).into() } else { 0.into() };
        a.stuff.next = rng.gen_ratio(1, 4);
    })
    .expect("adapter flow");
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn pulse_check_flow() {
    use canstar_hub::pulse::PulseCheck;
    let mut p = PulseCheck::new(3, 11);
    flow::full_check(&mut p, "pulse_check", 100_000, 25, |p: &mut PulseCheck, rng, c| {
        p.reset.next = c < 2 || rng.gen_ratio(1, 20_000);
        // runs of 1..40 clocks: glitches and legal bits
        if rng.gen_ratio(1, 12) {
            p.c.next = !p.c.val();
        }
    })
    .expect("pulse check flow");
}
