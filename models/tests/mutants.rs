//! The equivalence checks catch a wrong model: each committed mutant (a model
//! generated with one operator swapped by the compiler's debug hook, see
//! `registry::MUTANTS`) runs against its rust-hdl design on the same seeded random
//! stimulus as the real model, and a mismatch must be reported.

/// The committed mutant models (`tests/mutants/`, written by `registry::mutant_files`).
mod mutants {
    pub mod bit_stuffer_m2;
    pub mod bit_timing_m30;
    pub mod bit_timing_m7;
    pub mod crc15_m0;
    pub mod crc15_m2;
}
use mutants::*;

use canstar_hdl::{btl, crc15, drive::Clocked, stuff};
use canstar_models::lockstep::{Lockstep, RandomInputs};
use canstar_rtlc::rt::{Block, Model};

/// Cycles until the first mismatch (`None`: none within `cycles`).
fn first_mismatch<H: Clocked, M: Model>(
    hdl: H,
    make: fn(&dyn Block) -> Result<M, canstar_rtlc::Error>,
    set: fn(&mut H, &[u128]),
    get: fn(&H, &mut [u128]),
    cycles: u64,
) -> Option<String> {
    let mut l = match Lockstep::new(hdl, make, set, get) {
        Ok(l) => l,
        Err(m) => return Some(m.to_string()),
    };
    let mut stim = RandomInputs::new(&l.model, 99, |n| if n == "reset" || n == "clear" { 0.001 } else { 0.2 });
    for _ in 0..cycles {
        if let Err(m) = l.step(stim.draw()) {
            return Some(m.to_string());
        }
    }
    l.compare_all().err().map(|m| m.to_string())
}

#[test]
fn every_mutant_is_caught() {
    let mut caught = vec![];
    let btl = || {
        let mut b = btl::BitTiming::default();
        b.set_config(&btl::BtlConfig::from_fields(1, 1, 3, 3, 2, false));
        b
    };
    caught.push(first_mismatch(crc15::Crc15::default(), crc15_m0::Crc15M0::from_instance, crc15_m0::hdl_set_inputs, crc15_m0::hdl_outputs, 100_000));
    caught.push(first_mismatch(crc15::Crc15::default(), crc15_m2::Crc15M2::from_instance, crc15_m2::hdl_set_inputs, crc15_m2::hdl_outputs, 100_000));
    caught.push(first_mismatch(stuff::BitStuffer::default(), bit_stuffer_m2::BitStufferM2::from_instance, bit_stuffer_m2::hdl_set_inputs, bit_stuffer_m2::hdl_outputs, 100_000));
    caught.push(first_mismatch(btl(), bit_timing_m7::BitTimingM7::from_instance, bit_timing_m7::hdl_set_inputs, bit_timing_m7::hdl_outputs, 100_000));
    caught.push(first_mismatch(btl(), bit_timing_m30::BitTimingM30::from_instance, bit_timing_m30::hdl_set_inputs, bit_timing_m30::hdl_outputs, 100_000));
    for (i, c) in caught.iter().enumerate() {
        eprintln!("mutant {:?}: {}", canstar_models::registry::MUTANTS[i], c.as_deref().unwrap_or("NOT CAUGHT"));
    }
    assert!(caught.iter().all(|c| c.is_some()), "a wrong model passed the equivalence check");
}

/// The same stimulus finds no difference with the real models (so the mutants are
/// caught for their mutation, not for the harness).
#[test]
fn real_models_pass_the_same_check() {
    use canstar_models::generated as g;
    assert_eq!(first_mismatch(crc15::Crc15::default(), g::crc15::Crc15::from_instance, g::crc15::hdl_set_inputs, g::crc15::hdl_outputs, 100_000), None);
    assert_eq!(first_mismatch(stuff::BitStuffer::default(), g::bit_stuffer::BitStuffer::from_instance, g::bit_stuffer::hdl_set_inputs, g::bit_stuffer::hdl_outputs, 100_000), None);
    let mut b = btl::BitTiming::default();
    b.set_config(&btl::BtlConfig::from_fields(1, 1, 3, 3, 2, false));
    assert_eq!(first_mismatch(b, g::bit_timing::BitTiming::from_instance, g::bit_timing::hdl_set_inputs, g::bit_timing::hdl_outputs, 100_000), None);
}

/// The atom comparison sees internal state the outputs do not show yet: a register of
/// the model changed behind its back is reported by name.
#[test]
fn atom_comparison_catches_a_wrong_register() {
    use canstar_models::generated as g;
    let mut l = Lockstep::new(canstar_controller::core::CanCore::new(), g::can_core::CanCore::from_instance, g::can_core::hdl_set_inputs, g::can_core::hdl_outputs).unwrap();
    let mut stim = RandomInputs::new(&l.model, 5, |n| if n == "reset" { 0.0 } else { 0.05 });
    for _ in 0..2000 {
        l.step(stim.draw()).unwrap();
    }
    l.compare_all().unwrap();
    let info = l.model.info();
    let a = (0..info.atoms.len()).find(|&a| info.atoms[a].name == "q" && info.atoms[a].width > 4).expect("a register");
    let v = l.model.atom(a);
    assert!(l.model.set_atom(a, v ^ 1));
    let e = l.compare_all().expect_err("a changed register must be reported").to_string();
    assert!(e.contains(".q`"), "{e}");
}
