//! Error-flag generator (H6): 6 dominant bits from the next bit after a trigger.
use canstar_hdl::{drive, flow};
use canstar_hub::efg::ErrorFlagGen;
use rand::Rng;

const BIT: usize = 16; // clocks per bit
const SAMPLE: usize = 12; // clock index of the sample point in the bit

/// Run `bits` bits; trigger at the sample point of the bits in `trig`.
/// Returns, per bit, the efg level at the sample point, and the busy flag there.
fn run(bits: usize, trig: &[usize]) -> Vec<(bool, bool)> {
    let mut e = ErrorFlagGen::default();
    drive::init(&mut e);
    let mut out = vec![];
    for b in 0..bits {
        for k in 0..BIT {
            e.bit_start.next = k == 0;
            e.trigger.next = k == SAMPLE && trig.contains(&b);
            drive::settle(&mut e);
            if k == SAMPLE {
                out.push((e.efg.val(), e.busy.val()));
            }
            drive::cycle(&mut e);
        }
    }
    out
}

#[test]
fn six_dominant_bits_from_next_bit() {
    let r = run(20, &[3]);
    for (b, (efg, _)) in r.iter().enumerate() {
        let expect_dom = (4..=9).contains(&b);
        assert_eq!(!efg, expect_dom, "bit {b}");
    }
    // busy covers the flag bits (and the trigger bit after its sample point)
    for (b, (_, busy)) in r.iter().enumerate() {
        assert_eq!(*busy, (4..=9).contains(&b), "busy at bit {b}");
    }
}

#[test]
fn retrigger_while_busy_is_ignored_and_later_trigger_works() {
    let r = run(30, &[2, 4, 12]);
    let dom: Vec<usize> = r.iter().enumerate().filter(|(_, (e, _))| !e).map(|(b, _)| b).collect();
    assert_eq!(dom, vec![3, 4, 5, 6, 7, 8, 13, 14, 15, 16, 17, 18]);
}

#[test]
fn dominant_for_exactly_96_clocks_and_stopped_by_reset() {
    let mut e = ErrorFlagGen::default();
    drive::init(&mut e);
    let mut dom_clocks = 0;
    for c in 0..BIT * 12 {
        e.bit_start.next = c % BIT == 0;
        e.trigger.next = c == SAMPLE;
        drive::cycle(&mut e);
        if !e.efg.val() {
            dom_clocks += 1;
        }
    }
    assert_eq!(dom_clocks, 6 * BIT);
    e.trigger.next = true;
    drive::cycle(&mut e);
    e.trigger.next = false;
    e.bit_start.next = true;
    drive::cycle(&mut e);
    assert!(!e.efg.val() && e.active.val());
    e.bit_start.next = false;
    e.reset.next = true;
    drive::cycle(&mut e);
    assert!(e.efg.val() && !e.busy.val() && !e.active.val());
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn efg_flow() {
    let mut e = ErrorFlagGen::default();
    flow::full_check(&mut e, "efg", 100_000, 5, |e: &mut ErrorFlagGen, rng, c| {
        e.reset.next = c < 2 || rng.gen_ratio(1, 20_000);
        e.bit_start.next = c % 16 == 0;
        e.trigger.next = c % 16 == 12 && rng.gen_ratio(1, 12);
    })
    .expect("efg flow");
}
