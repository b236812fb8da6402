//! The committed models (and mutants) are what the compiler generates from the
//! current designs. `CANSTAR_BLESS=1 cargo test -p canstar-models --test current`
//! rewrites them.

use canstar_models::registry;

#[test]
fn committed_models_are_current() {
    let bless = std::env::var("CANSTAR_BLESS").is_ok_and(|v| v == "1");
    let stale = registry::check(bless).expect("every registered design compiles");
    if bless {
        if !stale.is_empty() {
            eprintln!("rewrote {:?}, removed {:?}", stale.changed, stale.unregistered);
        }
    } else {
        assert!(
            stale.is_empty(),
            "stale generated models {:?}, unregistered files {:?}: regenerate with CANSTAR_BLESS=1 cargo test -p canstar-models --test current",
            stale.changed,
            stale.unregistered
        );
    }
}

/// A changed and an unregistered file are reported, and blessing fixes both.
#[test]
fn stale_and_unregistered_files_are_found_and_blessed() {
    let tmp = std::env::temp_dir().join(format!("canstar-models-current-{}", std::process::id()));
    let (gen, mutants) = (tmp.join("generated"), tmp.join("mutants"));
    for (from, to) in [(registry::generated_dir(), &gen), (registry::mutants_dir(), &mutants)] {
        std::fs::create_dir_all(to).unwrap();
        for e in std::fs::read_dir(from).unwrap() {
            let e = e.unwrap();
            std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
        }
    }
    assert!(registry::check_dirs(&gen, &mutants, false).unwrap().is_empty());
    let crc = gen.join("crc15.rs");
    let text = std::fs::read_to_string(&crc).unwrap().replacen("wrapping_", "wrapping_ ", 1);
    std::fs::write(&crc, text).unwrap();
    std::fs::write(gen.join("old_model.rs"), "// gone").unwrap();
    let s = registry::check_dirs(&gen, &mutants, false).unwrap();
    assert_eq!(s.changed, vec![crc.clone()]);
    assert_eq!(s.unregistered, vec![gen.join("old_model.rs")]);
    registry::check_dirs(&gen, &mutants, true).unwrap();
    assert!(registry::check_dirs(&gen, &mutants, false).unwrap().is_empty());
    std::fs::remove_dir_all(&tmp).unwrap();
}

/// Figures of every compilation (diagnostic).
#[test]
#[ignore]
fn diag_compile_stats() {
    for e in registry::entries() {
        let b = (e.build)();
        let t = std::time::Instant::now();
        let c = canstar_rtlc::compile(b.as_ref(), &registry::options(&e)).unwrap();
        println!("{:<16} {:?} fingerprint {:#018x} in {:.2} s", e.name, c.stats, c.fingerprint, t.elapsed().as_secs_f64());
        for w in &c.warnings {
            println!("    warning: {w}");
        }
    }
}
