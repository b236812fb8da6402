//! Tests of the CRC-15 block (`canstar_hdl::crc15`): software check value, RTL against
//! software, and (ignored without the tools) the Verilog flow.

mod util;
use util::*;

// ---------------------------------------------------------------- CRC-15

const CHECK: &[u8] = b"123456789";

#[test]
fn crc15_check_value_software() {
    assert_eq!(crc15_bytes(CHECK), 0x059E);
    assert_eq!(crc15_bits(&bytes_to_bits(CHECK)), 0x059E);
    assert_eq!(crc15_bits(&[]), 0);
    assert_eq!(crc15_bytes(&[]), 0);
}

/// Shift `bits` into a Crc15 block with random idle cycles between the
/// strobes; check `crc` after every bit against the software CRC.
fn run_crc_block(u: &mut Crc15, bits: &[bool], rng: &mut ChaCha8Rng) -> u16 {
    u.clear.next = true;
    u.en.next = rng.gen();
    u.din.next = rng.gen();
    drive::cycle(u);
    u.clear.next = false;
    assert_eq!(u.crc.val().index() as u16, 0, "clear");
    for (i, &b) in bits.iter().enumerate() {
        while rng.gen_bool(0.4) {
            u.en.next = false;
            u.din.next = rng.gen();
            let before = u.crc.val();
            drive::cycle(u);
            assert_eq!(u.crc.val(), before, "no change without en");
        }
        u.en.next = true;
        u.din.next = b;
        drive::settle(u);
        let expect = crc15_bits(&bits[..=i]) as u64;
        assert_eq!(u.crc_next.val().index() as u64, expect, "crc_next at bit {i}");
        drive::cycle(u);
        assert_eq!(u.crc.val().index() as u64, expect, "crc at bit {i}");
    }
    u.en.next = false;
    u.crc.val().index() as u16
}

#[test]
fn crc15_check_value_rtl() {
    let mut u = Crc15::default();
    drive::init(&mut u);
    assert_eq!(u.crc.val().index(), 0, "power-up value 0");
    let mut rng = flow::rng(31);
    assert_eq!(run_crc_block(&mut u, &bytes_to_bits(CHECK), &mut rng), 0x059E);
}

#[test]
fn crc15_rtl_matches_software_on_random_bit_strings() {
    let mut u = Crc15::default();
    drive::init(&mut u);
    let mut rng = flow::rng(32);
    for _ in 0..200 {
        let n = rng.gen_range(0..=140);
        let bits: Vec<bool> = (0..n).map(|_| rng.gen()).collect();
        let c = run_crc_block(&mut u, &bits, &mut rng);
        assert_eq!(c, crc15_bits(&bits));
    }
}

#[test]
fn crc15_reset_and_clear_win_over_en() {
    let mut u = Crc15::default();
    drive::init(&mut u);
    let mut rng = flow::rng(33);
    run_crc_block(&mut u, &bytes_to_bits(b"ab"), &mut rng);
    assert_ne!(u.crc.val().index(), 0);
    u.en.next = true;
    u.din.next = true;
    u.reset.next = true;
    drive::cycle(&mut u);
    assert_eq!(u.crc.val().index(), 0, "reset");
    u.reset.next = false;
    drive::cycle(&mut u);
    assert_eq!(u.crc.val().index() as u16, crc15_bits(&[true]));
    u.clear.next = true;
    drive::cycle(&mut u);
    assert_eq!(u.crc.val().index(), 0, "clear");
}

proptest! {
    #[test]
    fn crc15_bytes_matches_crc_crate(bytes in proptest::collection::vec(any::<u8>(), 0..64)) {
        let reference = crc::Crc::<u16>::new(&crc::CRC_15_CAN).checksum(&bytes);
        prop_assert_eq!(crc15_bytes(&bytes), reference);
        prop_assert_eq!(crc15_bits(&bytes_to_bits(&bytes)), reference);
    }

    #[test]
    fn crc15_of_message_plus_crc_is_zero(bits in proptest::collection::vec(any::<bool>(), 0..200)) {
        // Appending the CRC (MSB first) gives a zero remainder.
        let c = crc15_bits(&bits);
        let mut all = bits.clone();
        all.extend((0..15).rev().map(|i| (c >> i) & 1 == 1));
        prop_assert_eq!(crc15_bits(&all), 0);
    }
}


// ---------------------------------------------------------------- Verilog flow

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn crc15_verilog_flow() {
    let mut u = Crc15::default();
    let (synth, cs) = flow::full_check(&mut u, "crc15", FLOW_CYCLES, 104, |u, rng, _| {
        u.en.next = rng.gen_bool(0.3);
        u.din.next = rng.gen();
        u.clear.next = rng.gen_bool(0.005);
        u.reset.next = rng.gen_bool(0.0005);
    })
    .expect("flow");
    assert_eq!(cs.cycles, FLOW_CYCLES);
    assert!(synth.cells > 0);
}
