//! The frame-state decoder, the monitor adapter and the pulse check in isolation, and the
//! Verilog flows (co-simulation, lint, latch check) of the judge unit and those blocks.
use canstar_hdl::{drive, flow};
use canstar_hub::frame_state::{Field, FrameDecode};
use canstar_hub::judge::{JudgeParams, JudgeUnit};
use rand::Rng;

mod judge_common;
use judge_common::params;

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
            assert_eq!(d.im_12.val(), field == Field::Intermission && pos < 2);
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
        j.eof_last.next = phase == 70;
        j.im_2.next = phase == 72;
        j.im_12.next = phase == 71 || phase == 72;
        j.frame_ok.next = phase == 70;
        j.crc_ok.next = rng.gen_bool(0.9);
        j.err_phase.next = err;
        j.bt.next = rng.gen_bool(0.5);
        j.c.next = if rng.gen_ratio(1, 25) { false } else { j.bt.val() | rng.gen_bool(0.5) };
        if rng.gen_ratio(1, 300) {
            j.c.next = false; // occasionally long dominant runs
        }
        // (more often in Intermission bits 1-2, for the overload rule of hub.md §5.21)
        j.rep_rec.next = rng.gen_ratio(1, if matches!(phase, 71 | 72) { 3 } else { 10 });
        j.rep_rec_w.next = rng.gen_ratio(1, 10);
        j.rep_dom.next = rng.gen_ratio(1, 10);
        j.rep_mask.next = rng.gen_ratio(1, 4);
        j.rep_other.next = !rng.gen_ratio(1, 8);
        j.delim.next = rng.gen_ratio(1, 20);
        j.suppress.next = rng.gen_ratio(1, 8);
        j.stuff_dom.next = rng.gen_ratio(1, 10);
        j.rep_glitched.next = rng.gen_ratio(1, 4);
        j.rep_blamed.next = rng.gen_ratio(1, 6);
        j.common.next = rng.gen_ratio(1, 5);
        j.guard.next = rng.gen_ratio(1, 10);
    }
    // bit-start estimate and its counter; an occasional mid-bit level change (a glitch)
    j.bit_start.next = k == 0;
    j.bs_cnt.next = (k as u64).into();
    if k != 0 && rng.gen_ratio(1, 60) {
        j.c.next = !j.c.val();
    }
    // and BT changing in the first clocks of a bit (the §5.23 Intermission-bit-2 lag)
    if (1..4).contains(&k) && rng.gen_ratio(1, 40) {
        j.bt.next = !j.bt.val();
    }
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn port_judge_flow() {
    let mut j = JudgeUnit::port(JudgeParams { reintegration: Some(3), first_flagger: true, eof_last: true, dbc_bridge: true, stuff_pulse: true, ..params() });
    flow::full_check(&mut j, "port_judge", 100_000, 21, judge_stim).expect("port judge flow");
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn sublink_judge_flow() {
    let mut j = JudgeUnit::sublink(JudgeParams { bic_limit: 128, dbc_threshold: 28, first_flagger: true, replica_overload: true, im2_lag: 2, ..params() });
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
    let mut p = PulseCheck::new(3, 1, 11);
    flow::full_check(&mut p, "pulse_check", 100_000, 25, |p: &mut PulseCheck, rng, c| {
        p.reset.next = c < 2 || rng.gen_ratio(1, 20_000);
        // runs of 1..40 clocks: glitches and legal bits
        if rng.gen_ratio(1, 12) {
            p.c.next = !p.c.val();
        }
    })
    .expect("pulse check flow");
}
