//! Unit tests of the judge unit and the frame-state decoder in isolation, and their
//! Verilog flows.
use canstar_hdl::{drive, flow};
use canstar_hub::frame_state::{Field, FrameDecode};
use canstar_hub::judge::{JudgeParams, JudgeUnit};
use rand::Rng;

fn params() -> JudgeParams {
    JudgeParams { bic_limit: 64, life_limit: 32, dbc_threshold: 13, nack_threshold: 7, replica_limit: 3, reintegration: None }
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
    j.sample.next = true;
    drive::settle(j);
    let blame = j.blame.val();
    drive::cycle(j);
    j.sample.next = false;
    drive::cycle(j);
    drive::cycle(j);
    blame
}

fn unit(p: JudgeParams) -> JudgeUnit {
    let mut j = JudgeUnit::port(p);
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

/// Arbitration field: a port that dropped out (recessive while BT dominant) and is
/// dominant again is not blamed there and is a contender again (it may be a transmitter
/// that never saw a glitch); after the arbitration field a non-contender is blamed.
#[test]
fn arbitration_field_readmits_instead_of_blaming() {
    let mut j = unit(params());
    sample(&mut j, Bit { c: false, bt: false, sof: true, ..Default::default() });
    j.arb.next = true;
    sample(&mut j, Bit { c: true, bt: false, tx: true, ..Default::default() });
    assert!(!j.contender.val(), "dropped out");
    assert!(!sample(&mut j, Bit { c: false, bt: false, tx: true, ..Default::default() }), "not blamed in arbitration");
    assert!(j.contender.val(), "contender again");
    j.arb.next = false;
    assert!(!sample(&mut j, Bit { c: false, bt: false, tx: true, ..Default::default() }), "transmitter's dominant data bit");
    sample(&mut j, Bit { c: true, bt: false, tx: true, ..Default::default() });
    assert!(!j.contender.val());
    assert!(sample(&mut j, Bit { c: false, bt: false, tx: true, ..Default::default() }), "receiver dominant after arbitration");
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
    j.err_start.next = k == 13 && rng.gen_ratio(1, 40);
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
        j.rep_dom.next = rng.gen_ratio(1, 10);
    }
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn port_judge_flow() {
    let mut j = JudgeUnit::port(JudgeParams { reintegration: Some(3), ..params() });
    flow::full_check(&mut j, "port_judge", 100_000, 21, judge_stim).expect("port judge flow");
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn sublink_judge_flow() {
    let mut j = JudgeUnit::sublink(JudgeParams { bic_limit: 128, dbc_threshold: 28, ..params() });
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
    })
    .expect("adapter flow");
}
