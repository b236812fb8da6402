//! Tests of the bit stuffer and destuffer (`canstar_hdl::stuff`): software stuffing, the
//! RTL against a window-rule destuffer, and (ignored without the tools) the Verilog flow.

mod util;
use util::*;

// ---------------------------------------------------------------- stuffing, software

#[test]
fn stuff_bits_examples() {
    let (f, t) = (false, true);
    assert_eq!(stuff_bits(&[]), Vec::<bool>::new());
    assert_eq!(stuff_bits(&[f, f, f, f]), vec![f, f, f, f]);
    assert_eq!(stuff_bits(&[f; 5]), vec![f, f, f, f, f, t]);
    // The stuff bit starts the next run: 4 more ones make 5 again.
    assert_eq!(stuff_bits(&[f, f, f, f, f, t, t, t, t]), vec![f, f, f, f, f, t, t, t, t, t, f]);
    assert_eq!(stuff_bits(&[t; 10]), vec![t, t, t, t, t, f, t, t, t, t, t, f]);
    assert_eq!(stuff_bits(&[t, f, t, f, t, f]), vec![t, f, t, f, t, f]);
    // Stuff bit equal to the following data bit: 00000 1 1111 ...
    assert_eq!(stuff_bits(&[f, f, f, f, f, f]), vec![f, f, f, f, f, t, f]);
}

proptest! {
    #[test]
    fn stuff_bits_round_trips(bits in proptest::collection::vec(any::<bool>(), 0..300), long in proptest::collection::vec(1usize..9, 0..40)) {
        // Mix uniform bits with long runs so stuffing is exercised.
        let mut data = bits;
        let mut level = false;
        for l in long { data.extend(std::iter::repeat_n(level, l)); level = !level; }
        let s = stuff_bits(&data);
        prop_assert!(max_run(&s) <= 5);
        prop_assert!(s.len() >= data.len() && s.len() <= data.len() + data.len() / 4 + 1);
        let (back, stuff) = destuff_sw(&s).expect("stuffed stream has no stuff error");
        prop_assert_eq!(back, data.clone());
        prop_assert_eq!(stuff.len(), s.len() - data.len());
        // A stream that ends in 5 equal bits gets its trailing stuff bit.
        prop_assert!(s.len() < 5 || !s[s.len() - 5..].iter().all(|&b| b == s[s.len() - 1]));
    }
}

// ---------------------------------------------------------------- stuffing, RTL

/// One stretch of bits the frame logic sends with `active` fixed.
#[derive(Clone)]
struct Segment {
    active: bool,
    bits: Vec<bool>,
}

/// Drive a BitStuffer as a frame logic would: `data` = next bit, consume it
/// at an `en` unless `is_stuff`; keep `active` high after an active segment
/// until no stuff bit is pending. Random idle cycles between strobes.
/// Returns the sent bits with their `active` level.
fn run_stuffer(u: &mut BitStuffer, segs: &[Segment], rng: &mut ChaCha8Rng) -> Vec<(bool, bool)> {
    let mut sent = vec![];
    for seg in segs {
        let mut i = 0;
        loop {
            if i == seg.bits.len() && !(seg.active && u.stuff_pending.val()) {
                break;
            }
            while rng.gen_bool(0.3) {
                u.en.next = false;
                u.active.next = rng.gen();
                u.data.next = rng.gen();
                drive::cycle(u);
            }
            u.en.next = true;
            u.active.next = seg.active;
            u.data.next = if i < seg.bits.len() { seg.bits[i] } else { rng.gen() };
            drive::settle(u);
            if !seg.active {
                assert!(!u.is_stuff.val(), "no stuff bit while inactive");
            }
            if !u.is_stuff.val() {
                assert!(i < seg.bits.len(), "data consumed past the end");
                assert_eq!(u.out.val(), seg.bits[i], "a data bit is sent unchanged");
                i += 1;
            }
            sent.push((u.out.val(), seg.active));
            drive::cycle(u);
        }
    }
    u.en.next = false;
    sent
}

/// Window model of the destuffer over (bit, active, reset) triples: returns
/// per bit (stuff_bit, stuff_error, next_is_stuff after it, stuff_level after it).
fn destuffer_model(seq: &[(bool, bool, bool)]) -> Vec<(bool, bool, bool, bool)> {
    let mut hist: Vec<bool> = vec![];
    let mut res = vec![];
    for &(bit, active, reset) in seq {
        let n = hist.len();
        let five = n >= 5 && hist[n - 5..].iter().all(|&b| b == hist[n - 1]);
        let (sb, se) = if active && five { (bit != hist[n - 1], bit == hist[n - 1]) } else { (false, false) };
        if reset || !active {
            hist.clear();
        } else {
            hist.push(bit);
        }
        let m = hist.len();
        let nis = m >= 5 && hist[m - 5..].iter().all(|&b| b == hist[m - 1]);
        let lvl = if m > 0 { !hist[m - 1] } else { false };
        res.push((sb, se, nis, lvl));
    }
    res
}

/// Feed (bit, active, reset) triples to a BitDestuffer with random idle
/// cycles between strobes; return per strobe (stuff_bit, stuff_error,
/// next_is_stuff after, stuff_level after).
fn run_destuffer(u: &mut BitDestuffer, seq: &[(bool, bool, bool)], rng: &mut ChaCha8Rng) -> Vec<(bool, bool, bool, bool)> {
    let mut res = vec![];
    for &(bit, active, reset) in seq {
        while rng.gen_bool(0.3) {
            u.en.next = false;
            u.din.next = rng.gen();
            u.active.next = rng.gen();
            u.reset.next = false;
            drive::settle(u);
            assert!(!u.stuff_bit.val() && !u.stuff_error.val(), "flags only at en");
            let before = (u.next_is_stuff.val(), u.stuff_level.val());
            drive::cycle(u);
            assert_eq!((u.next_is_stuff.val(), u.stuff_level.val()), before, "state held without en");
        }
        u.en.next = true;
        u.din.next = bit;
        u.active.next = active;
        u.reset.next = reset;
        drive::settle(u);
        let (sb, se) = (u.stuff_bit.val(), u.stuff_error.val());
        drive::cycle(u);
        res.push((sb, se, u.next_is_stuff.val(), u.stuff_level.val()));
    }
    u.en.next = false;
    u.reset.next = false;
    res
}

#[test]
fn stuffer_output_matches_software_and_destuffs_back() {
    let mut rng = flow::rng(41);
    let mut s = BitStuffer::default();
    let mut d = BitDestuffer::default();
    drive::init(&mut s);
    drive::init(&mut d);
    let mut total_stuff = 0;
    for _ in 0..300 {
        let n = rng.gen_range(0..120);
        let data = runs(&mut rng, n, 8);
        let segs = [Segment { active: true, bits: data.clone() }, Segment { active: false, bits: vec![true; 3] }];
        let sent = run_stuffer(&mut s, &segs, &mut rng);
        let stream: Vec<bool> = sent.iter().filter(|x| x.1).map(|x| x.0).collect();
        assert_eq!(stream, stuff_bits(&data), "stuffer against software stuffing");
        assert!(max_run(&stream) <= 5, "no 6 equal bits");
        // The inactive tail is sent unchanged.
        assert!(sent.iter().filter(|x| !x.1).all(|x| x.0));
        // Destuff in RTL.
        let seq: Vec<(bool, bool, bool)> = sent.iter().map(|&(b, a)| (b, a, false)).collect();
        let flags = run_destuffer(&mut d, &seq, &mut rng);
        let mut back = vec![];
        for (k, (&(b, a, _), f)) in seq.iter().zip(flags.iter()).enumerate() {
            assert!(!f.1, "no stuff error at bit {k}");
            if k > 0 && flags[k - 1].2 && a {
                assert!(f.0, "next_is_stuff predicted a stuff bit at {k}");
                assert_eq!(b, flags[k - 1].3, "stuff_level predicted its level");
            }
            if a && !f.0 {
                back.push(b);
            }
            total_stuff += f.0 as usize;
        }
        assert_eq!(back, data, "destuffed stream is the original");
    }
    assert!(total_stuff > 1000, "stuffing was exercised ({total_stuff})");
}

#[test]
fn destuffer_flags_an_injected_sixth_bit_exactly() {
    let mut rng = flow::rng(42);
    let mut d = BitDestuffer::default();
    drive::init(&mut d);
    let mut injected = 0;
    for _ in 0..300 {
        let data = runs(&mut rng, 80, 8);
        let mut stream = stuff_bits(&data);
        let (_, stuffs) = destuff_sw(&stream).unwrap();
        if stuffs.is_empty() {
            continue;
        }
        let p = stuffs[rng.gen_range(0..stuffs.len())];
        stream[p] = !stream[p]; // the stuff bit becomes a 6th equal bit
        injected += 1;
        // Inactive idle bits before and after, then a reset for the next round.
        let mut seq = vec![(true, false, false); 4];
        seq.extend(stream.iter().map(|&b| (b, true, false)));
        seq.push((true, false, true));
        let flags = run_destuffer(&mut d, &seq, &mut rng);
        for (k, f) in flags.iter().enumerate() {
            let in_stream = k.checked_sub(4).filter(|&i| i < stream.len());
            match in_stream {
                Some(i) if i == p => assert!(f.1 && !f.0, "stuff error at the injected bit"),
                Some(i) if i < p => {
                    assert!(!f.1, "no stuff error before the injected bit");
                    assert_eq!(f.0, stuffs.contains(&i), "stuff bits before the error at {i}");
                }
                _ if in_stream.is_none() => assert!(!f.0 && !f.1, "inactive bits are never flagged"),
                _ => {}
            }
        }
    }
    assert!(injected > 250);
}

#[test]
fn destuffer_matches_window_model_on_raw_streams() {
    // Unstuffed raw streams with runs up to 8, inactive stretches and resets:
    // stuff bits, stuff errors and the registered prediction all match.
    let mut rng = flow::rng(43);
    let mut d = BitDestuffer::default();
    drive::init(&mut d);
    let bits = runs(&mut rng, 20_000, 8);
    let mut active = true;
    let seq: Vec<(bool, bool, bool)> = bits
        .iter()
        .map(|&b| {
            if rng.gen_bool(0.02) {
                active = !active;
            }
            (b, active, rng.gen_bool(0.005))
        })
        .collect();
    let got = run_destuffer(&mut d, &seq, &mut rng);
    let want = destuffer_model(&seq);
    for (k, (g, w)) in got.iter().zip(want.iter()).enumerate() {
        assert_eq!((g.0, g.1, g.2), (w.0, w.1, w.2), "bit {k}: (stuff_bit, stuff_error, next_is_stuff)");
        if w.2 {
            assert_eq!(g.3, w.3, "bit {k}: stuff_level");
        }
    }
    let errors = got.iter().filter(|g| g.1).count();
    let stuffs = got.iter().filter(|g| g.0).count();
    assert!(errors > 100 && stuffs > 100, "errors {errors}, stuff bits {stuffs}");
}

#[test]
fn destuffer_after_error_is_deterministic() {
    // Documented behaviour: the run stays at 5, further equal bits are errors.
    let mut rng = flow::rng(44);
    let mut d = BitDestuffer::default();
    drive::init(&mut d);
    let seq: Vec<(bool, bool, bool)> = [false, false, false, false, false, false, false, true, true].iter().map(|&b| (b, true, false)).collect();
    let flags = run_destuffer(&mut d, &seq, &mut rng);
    let errs: Vec<bool> = flags.iter().map(|f| f.1).collect();
    let stf: Vec<bool> = flags.iter().map(|f| f.0).collect();
    assert_eq!(errs, vec![false, false, false, false, false, true, true, false, false]);
    assert_eq!(stf, vec![false, false, false, false, false, false, false, true, false]);
}

#[test]
fn active_low_disables_stuffing() {
    let mut rng = flow::rng(45);
    let mut s = BitStuffer::default();
    drive::init(&mut s);
    // Ten equal bits while inactive: sent unchanged.
    let sent = run_stuffer(&mut s, &[Segment { active: false, bits: vec![false; 10] }], &mut rng);
    assert_eq!(sent.iter().map(|x| x.0).collect::<Vec<_>>(), vec![false; 10]);
    // The inactive bits do not count: 4 active equal bits after them are not stuffed.
    let sent = run_stuffer(&mut s, &[Segment { active: true, bits: vec![false; 4] }], &mut rng);
    assert_eq!(sent.len(), 4);
    // Five active bits: the emulator sends the trailing stuff bit.
    let sent = run_stuffer(&mut s, &[Segment { active: true, bits: vec![true; 5] }], &mut rng);
    assert_eq!(sent.iter().map(|x| x.0).collect::<Vec<_>>(), vec![true, true, true, true, true, false]);
    // Five active bits, then `active` low: no stuff bit, the run is cleared.
    s.active.next = true;
    s.data.next = true;
    s.en.next = true;
    for _ in 0..5 {
        drive::cycle(&mut s);
    }
    assert!(s.stuff_pending.val());
    drive::settle(&mut s);
    assert!(s.is_stuff.val() && !s.out.val(), "active: stuff bit due");
    s.active.next = false;
    drive::settle(&mut s);
    assert!(!s.is_stuff.val() && s.out.val(), "inactive: data passes");
    drive::cycle(&mut s);
    assert!(!s.stuff_pending.val(), "run cleared by an inactive bit");
    s.en.next = false;

    let mut d = BitDestuffer::default();
    drive::init(&mut d);
    let seq: Vec<(bool, bool, bool)> = (0..12).map(|_| (true, false, false)).chain((0..5).map(|_| (true, true, false))).collect();
    let flags = run_destuffer(&mut d, &seq, &mut rng);
    assert!(flags[..12].iter().all(|f| !f.0 && !f.1 && !f.2), "inactive bits never flag nor count");
    assert!(flags[..16].iter().all(|f| !f.2));
    assert!(flags[16].2 && !flags[16].3, "the 5th active bit arms the stuff prediction");
}


// ---------------------------------------------------------------- Verilog flow

/// Per-cycle stimulus for the destuffer co-simulation: stuffed frames (with
/// occasional corrupted bits), inactive idle stretches, strobes at random
/// intervals, occasional resets.
fn destuffer_stimulus(seed: u64, cycles: usize) -> Vec<(bool, bool, bool, bool)> {
    let mut rng = flow::rng(seed);
    let mut v = Vec::with_capacity(cycles);
    while v.len() < cycles {
        let mut frame: Vec<(bool, bool)> = (0..rng.gen_range(0..12)).map(|_| (true, false)).collect();
        let n = rng.gen_range(1..120);
        let mut stuffed = stuff_bits(&runs(&mut rng, n, 8));
        if rng.gen_bool(0.3) {
            let p = rng.gen_range(0..stuffed.len());
            stuffed[p] = !stuffed[p];
        }
        frame.extend(stuffed.into_iter().map(|b| (b, true)));
        for (b, a) in frame {
            let gap = rng.gen_range(0..6);
            for _ in 0..gap {
                v.push((false, rng.gen(), rng.gen(), rng.gen_bool(0.0005)));
            }
            v.push((true, b, a, rng.gen_bool(0.001)));
        }
    }
    v.truncate(cycles);
    v
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn bit_destuffer_verilog_flow() {
    let stim = destuffer_stimulus(105, FLOW_CYCLES);
    let (errors, stuffs) = {
        // The stimulus must reach the interesting states.
        let mut d = BitDestuffer::default();
        drive::init(&mut d);
        let (mut e, mut s) = (0, 0);
        for &(en, bit, active, reset) in &stim {
            d.en.next = en;
            d.din.next = bit;
            d.active.next = active;
            d.reset.next = reset;
            drive::settle(&mut d);
            e += d.stuff_error.val() as usize;
            s += d.stuff_bit.val() as usize;
            drive::cycle(&mut d);
        }
        (e, s)
    };
    assert!(errors > 50 && stuffs > 1000, "stimulus: {errors} stuff errors, {stuffs} stuff bits");
    let mut u = BitDestuffer::default();
    let (synth, cs) = flow::full_check(&mut u, "bit_destuffer", FLOW_CYCLES, 105, |u, _, i| {
        let (en, bit, active, reset) = stim[i];
        u.en.next = en;
        u.din.next = bit;
        u.active.next = active;
        u.reset.next = reset;
    })
    .expect("flow");
    assert_eq!(cs.cycles, FLOW_CYCLES);
    assert!(synth.cells > 0);
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn bit_stuffer_verilog_flow() {
    // A frame-logic emulator inside the stimulus: data holds the next bit of
    // the current segment, is consumed at an `en` unless `is_stuff`; active
    // segments alternate with inactive ones; strobes at random intervals.
    let mut seg_rng = flow::rng(1106);
    let mut seg = Segment { active: false, bits: vec![] };
    let mut pos = 0usize;
    let mut stuffs = 0usize;
    let mut u = BitStuffer::default();
    let (synth, cs) = flow::full_check(&mut u, "bit_stuffer", FLOW_CYCLES, 106, |u, rng, _| {
        u.reset.next = rng.gen_bool(0.0005);
        if pos >= seg.bits.len() && !(seg.active && u.stuff_pending.val()) {
            let active = !seg.active;
            let n = if active { seg_rng.gen_range(1..120) } else { seg_rng.gen_range(1..15) };
            seg = Segment { active, bits: runs(&mut seg_rng, n, 8) };
            pos = 0;
        }
        let en = rng.gen_bool(0.3);
        u.en.next = en;
        u.active.next = seg.active;
        u.data.next = if pos < seg.bits.len() { seg.bits[pos] } else { rng.gen() };
        drive::settle(u);
        if en && !u.is_stuff.val() {
            pos += 1;
        }
        stuffs += (en && u.is_stuff.val()) as usize;
    })
    .expect("flow");
    assert!(stuffs > 500, "stuffing exercised: {stuffs}");
    assert_eq!(cs.cycles, FLOW_CYCLES);
    assert!(synth.cells > 0);
}
