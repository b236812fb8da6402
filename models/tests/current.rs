//! The committed models are what the compiler generates from the current designs.
//! `CANSTAR_BLESS=1 cargo test -p canstar-models --test current` rewrites them.

use canstar_models::registry;

#[test]
fn committed_models_are_current() {
    let files = registry::files().expect("every registered design compiles");
    let dir = registry::generated_dir();
    let bless = std::env::var("CANSTAR_BLESS").is_ok_and(|v| v == "1");
    let mut stale = vec![];
    for (f, text) in &files {
        let p = dir.join(f);
        if std::fs::read_to_string(&p).ok().as_deref() != Some(text.as_str()) {
            if bless {
                std::fs::write(&p, text).unwrap();
            }
            stale.push(f.clone());
        }
    }
    let mut extra = vec![];
    for e in std::fs::read_dir(&dir).unwrap() {
        let name = e.unwrap().file_name().to_string_lossy().into_owned();
        if !files.iter().any(|(f, _)| *f == name) {
            if bless {
                std::fs::remove_file(dir.join(&name)).unwrap();
            }
            extra.push(name);
        }
    }
    if !bless {
        assert!(
            stale.is_empty() && extra.is_empty(),
            "stale generated models {stale:?}, unregistered files {extra:?}: regenerate with CANSTAR_BLESS=1 cargo test -p canstar-models --test current"
        );
    } else if !stale.is_empty() || !extra.is_empty() {
        eprintln!("rewrote {stale:?}, removed {extra:?}");
    }
}

/// The committed mutants (see `tests/mutants.rs`) are current too.
#[test]
fn committed_mutants_are_current() {
    let dir = registry::mutants_dir();
    let bless = std::env::var("CANSTAR_BLESS").is_ok_and(|v| v == "1");
    if bless {
        std::fs::create_dir_all(&dir).unwrap();
    }
    let mut stale = vec![];
    for (f, text, what) in registry::mutant_files().expect("mutants compile") {
        assert!(!what.is_empty());
        let p = dir.join(&f);
        if std::fs::read_to_string(&p).ok().as_deref() != Some(text.as_str()) {
            if bless {
                std::fs::write(&p, &text).unwrap();
                eprintln!("mutant {f}: {what}");
            }
            stale.push(f);
        }
    }
    assert!(bless || stale.is_empty(), "stale mutants {stale:?}: regenerate with CANSTAR_BLESS=1 cargo test -p canstar-models --test current");
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
