//! How BT's dominant run began (hub.md §5.10, §5.26), the first-flagger rule's excuse, in
//! isolation: 16 clocks per bit, bit start at clock 0, sample at clock 12.
use canstar_hdl::{drive, flow};
use canstar_hub::run_start::RunStart;
use rand::Rng;

fn fresh(min: u64) -> RunStart {
    let mut r = RunStart::new(min);
    drive::init(&mut r);
    r.bt.next = true;
    r.reset.next = true;
    drive::cycle(&mut r);
    r.reset.next = false;
    r
}

/// One bit: BT is dominant from clock `fall` on (16 = not in this bit, 0 = the whole bit),
/// through a sublink alone when `sub`; `stuff`/`sof` go with the sample. Returns
/// `stuff_dom` at the sample and `excused` in the clock after it.
fn bit(r: &mut RunStart, fall: usize, sub: bool, stuff: bool, sof: bool) -> (bool, bool) {
    let mut out = (false, false);
    for k in 0..16 {
        r.bit_start.next = k == 0;
        r.sample.next = k == 12;
        r.stuff.next = stuff && k == 12;
        r.sof.next = sof && k == 12;
        r.bt.next = k < fall;
        r.sub_lead.next = sub && k >= fall;
        drive::settle(r);
        if k == 12 {
            out.0 = r.stuff_dom.val();
        }
        if k == 13 {
            out.1 = r.excused.val();
        }
        drive::cycle(r);
    }
    out
}

/// Intermission bits 1 and 2 with BT falling at clock `fall` of bit 2, then the SOF (taken by
/// the monitor) and five dominant bits. Returns `excused` after each of those six samples.
fn early_sof(min: u64, fall: usize, sub: bool) -> Vec<bool> {
    let mut r = fresh(min);
    for _ in 0..3 {
        bit(&mut r, 16, false, false, false);
    }
    bit(&mut r, fall, sub, false, false);
    let mut v = vec![bit(&mut r, 0, sub, false, true).1];
    for _ in 0..5 {
        v.push(bit(&mut r, 0, sub, false, false).1);
    }
    v
}

#[test]
fn an_early_sof_through_a_sublink_excuses_its_dominant_run() {
    // BT falls at the sample (clock 12): 4 clocks before the bit start
    assert_eq!(early_sof(3, 12, true), vec![true; 6]);
    assert_eq!(early_sof(3, 13, true), vec![true; 6], "3 clocks");
    assert_eq!(early_sof(3, 14, true), vec![false; 6], "2 clocks: a SOF from the peer's bit start");
    assert_eq!(early_sof(2, 14, true), vec![true; 6], "2 clocks with min 2");
    assert_eq!(early_sof(3, 12, false), vec![false; 6], "a port led: no excuse");
    assert_eq!(early_sof(0, 12, true), vec![false; 6], "off");
    // the run ends at a recessive sample
    let mut r = fresh(3);
    bit(&mut r, 16, false, false, false);
    bit(&mut r, 12, true, false, false);
    assert!(bit(&mut r, 0, true, false, true).1);
    assert!(!bit(&mut r, 16, false, false, false).1, "recessive sample");
    assert!(!bit(&mut r, 0, false, false, false).1, "a new run");
}

#[test]
fn a_dominant_stuff_bit_excuses_its_dominant_run() {
    let mut r = fresh(3);
    for _ in 0..5 {
        assert_eq!(bit(&mut r, 16, false, false, false), (false, false));
    }
    assert_eq!(bit(&mut r, 0, false, true, false), (true, true), "stuff bit after a recessive sample");
    assert_eq!(bit(&mut r, 0, false, false, false), (false, true), "the run goes on");
    assert_eq!(bit(&mut r, 0, false, true, false), (false, true), "a stuff bit after a dominant sample is recessive");
    assert_eq!(bit(&mut r, 16, false, false, false), (false, false));
    // reset clears the run and takes BT as recessive
    bit(&mut r, 0, false, true, false);
    r.reset.next = true;
    drive::cycle(&mut r);
    r.reset.next = false;
    assert!(!r.excused.val());
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn run_start_flow() {
    let mut r = RunStart::new(3);
    flow::full_check(&mut r, "run_start", 100_000, 26, |r: &mut RunStart, rng, c| {
        r.reset.next = c < 2 || rng.gen_ratio(1, 20_000);
        r.bit_start.next = c % 16 == 0;
        r.sample.next = c % 16 == 12;
        r.stuff.next = rng.gen_ratio(1, 8);
        r.sof.next = rng.gen_ratio(1, 4);
        if rng.gen_ratio(1, 6) {
            r.bt.next = !r.bt.val();
        }
        r.sub_lead.next = !r.bt.val() && rng.gen_ratio(3, 4);
    })
    .expect("run start flow");
}
