//! Shared stimulus for the judge-unit tests (`judge_rules.rs`, `judge_sublinks.rs`):
//! one sampled bit of 16 clocks, sub-bit pulses, the reference parameters.
#![allow(dead_code)]
use canstar_hdl::drive;
use canstar_hub::judge::{JudgeParams, JudgeUnit};

pub fn params() -> JudgeParams {
    JudgeParams { bic_limit: 64, bic_decay: 1, life_limit: 32, dbc_threshold: 13, nack_threshold: 7, replica_limit: 3, reintegration: None, glitch_min: 1, glitch_min_dominant: 1, glitch_max: 11, glitch_limit: 3, glitch_decay: 16, peer_glitch_limit: 12, peer_glitch_decay: 4, window_lag: 7, crc_window_end: 8, first_flagger: false, eof_last: false, delim_blames: 1, replica_skew: 4, replica_overload: false, dbc_bridge: false, im2_lag: 0, stuff_pulse: false, sub_follower: false, ff_replica: false }
}

#[derive(Default, Clone, Copy)]
pub struct Bit {
    pub c: bool,
    pub bt: bool,
    pub sof: bool,
    pub tx: bool,
    pub crc_delim: bool,
    pub ack_slot: bool,
    pub ack_delim: bool,
    pub eof: bool,
    /// The last EOF bit (§5.19).
    pub eof_last: bool,
    pub im: bool,
    /// Intermission bit 1 or 2 (`im_12`, §5.21).
    pub im12: bool,
    pub err: bool,
    pub crc_ok: bool,
    pub frame_ok: bool,
}

/// Sets the frame-state inputs and the levels of `b`.
pub fn apply(j: &mut JudgeUnit, b: Bit) {
    j.c.next = b.c;
    j.bt.next = b.bt;
    j.sof.next = b.sof;
    j.tx_region.next = b.tx;
    j.crc_delim.next = b.crc_delim;
    j.ack_slot.next = b.ack_slot;
    j.ack_delim.next = b.ack_delim;
    j.eof_1_6.next = b.eof;
    j.eof_last.next = b.eof_last;
    j.im_2.next = b.im;
    j.im_12.next = b.im12;
    j.err_phase.next = b.err;
    j.crc_ok.next = b.crc_ok;
    j.frame_ok.next = b.frame_ok;
}

/// One sampled bit: inputs, a sample strobe, two more clocks.
pub fn sample(j: &mut JudgeUnit, b: Bit) -> bool {
    apply(j, b);
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

pub const SAMPLE_AT: u64 = 12;

/// One clock at `k` clocks after the bit start (bit_start strobe at 0, no sample).
pub fn clock_at(j: &mut JudgeUnit, k: u64) {
    j.bit_start.next = k == 0;
    j.bs_cnt.next = k.into();
    drive::cycle(j);
    j.bit_start.next = false;
}

/// A sublink unit with a replica beside it (`rep_other`, hub.md §5.18), not initialised.
pub fn sublink_unit(p: JudgeParams) -> JudgeUnit {
    let mut j = JudgeUnit::sublink(p);
    j.rep_other.next = true;
    j
}

pub fn unit(p: JudgeParams) -> JudgeUnit {
    reset(JudgeUnit::port(p))
}

/// `j` initialised and reset.
pub fn reset(mut j: JudgeUnit) -> JudgeUnit {
    drive::init(&mut j);
    j.reset.next = true;
    drive::cycle(&mut j);
    j.reset.next = false;
    j
}


/// The 16 clocks of one bit: `levels(j, k)` sets the inputs of clock k, the sample strobe
/// comes at `SAMPLE_AT`; returns (blame at any clock, glitch strobes).
pub fn bit_clocks(j: &mut JudgeUnit, levels: &dyn Fn(&mut JudgeUnit, u64)) -> (bool, usize) {
    let (mut blame, mut glitches) = (false, 0);
    for k in 0..16u64 {
        levels(j, k);
        j.sample.next = k == SAMPLE_AT;
        j.bit_start.next = k == 0;
        j.bs_cnt.next = k.into();
        drive::settle(j);
        blame |= j.blame.val();
        glitches += j.glitch.val() as usize;
        drive::cycle(j);
    }
    j.sample.next = false;
    (blame, glitches)
}

/// One bit of 16 clocks, recessive but dominant from clock `from` for `len` clocks, in
/// the EOF (a recessive-only position); returns (blame at the sample point, glitches).
pub fn pulse_bit(j: &mut JudgeUnit, from: u64, len: u64, suppress: bool) -> (bool, usize) {
    j.bt.next = true;
    j.eof_1_6.next = true;
    j.suppress.next = suppress;
    let (blame, mut glitches) = bit_clocks(j, &|j, k| j.c.next = !(from..from + len).contains(&k));
    j.eof_1_6.next = false;
    j.suppress.next = false;
    // the run ending in the first clock of the next bit: count it here
    j.c.next = true;
    drive::settle(j);
    glitches += j.glitch.val() as usize;
    (blame, glitches)
}

/// One bit of 16 clocks with the frame state of `b`: the input and BT recessive until
/// clock `from`, then dominant to the end of the bit; returns the blame at the sample point
/// (clock 12).
pub fn bit_dominant_from(j: &mut JudgeUnit, b: Bit, from: u64) -> bool {
    apply(j, b);
    let (blame, _) = bit_clocks(j, &|j, k| {
        j.c.next = k < from;
        j.bt.next = k < from;
    });
    apply(j, Bit { c: j.c.val(), bt: j.bt.val(), ..Default::default() });
    blame
}

/// One CRC delimiter bit, dominant from clock `from` (an acknowledgement that starts
/// early, or a fault); returns the blame at the sample point.
pub fn crc_delimiter_dominant_from(j: &mut JudgeUnit, from: u64) -> bool {
    bit_dominant_from(j, Bit { crc_delim: true, ..Default::default() }, from)
}
