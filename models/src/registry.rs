//! The designs canstar generates, and the shapes of them this crate carries a
//! compiled model for (one file per shape under `src/generated/`).
//!
//! A shape is everything structural (hub ports N, sublinks M, debug outputs...);
//! constant values (thresholds, timing, synchroniser depth, fault-injection codes,
//! reintegration) are runtime data of a model. `current` regenerates every file in
//! memory and compares; `CANSTAR_BLESS=1 cargo test -p canstar-models --test current`
//! rewrites them.

use std::path::{Path, PathBuf};

use canstar_hub::config::HubConfig;
use canstar_hub::{hub::HubCore, top::Hub};
use canstar_rtlc::rt::Block;

/// One committed model.
pub struct Entry {
    /// File (module) name under `src/generated/`.
    pub module: &'static str,
    /// Model struct name.
    pub name: &'static str,
    /// Rust path of the rust-hdl type.
    pub hdl_type: &'static str,
    pub description: String,
    /// Builds the instance the model is generated from.
    pub build: Box<dyn Fn() -> Box<dyn Block>>,
    /// Internal signals evaluated every clock because a reader uses them
    /// (`canstar_rtlc::Options::keep`).
    pub keep: Vec<String>,
}

fn entry(module: &'static str, name: &'static str, hdl_type: &'static str, description: &str, build: impl Fn() -> Box<dyn Block> + 'static) -> Entry {
    Entry { module, name, hdl_type, description: description.to_string(), build: Box::new(build), keep: vec![] }
}

/// Hub configurations with a committed model: (module suffix, struct suffix, ports, sublinks).
/// N = 3 with M = 2 is the reference ReCANcentrate hub, M = 0 CANcentrate; the hub
/// tests use M = 1 too. Debug outputs on (the default).
pub const HUB_SHAPES: [(&str, &str, usize, usize); 3] = [("n3_m2", "N3M2", 3, 2), ("n3_m0", "N3M0", 3, 0), ("n3_m1", "N3M1", 3, 1)];

fn hub_cfg(n: usize, m: usize) -> HubConfig {
    HubConfig { ports: n, sublinks: m, ..HubConfig::default() }
}

/// Every committed model, in file order.
pub fn entries() -> Vec<Entry> {
    use canstar_hdl::{btl, crc15, stuff, sync};
    let mut v = vec![
        entry("synchroniser", "Synchroniser", "canstar_hdl::sync::Synchroniser", "input synchroniser (`canstar_hdl::sync::Synchroniser`, depth 1 or 2)", || {
            Box::new(sync::Synchroniser::new(2))
        }),
        entry("edge_detector", "EdgeDetector", "canstar_hdl::sync::EdgeDetector", "edge detector (`canstar_hdl::sync::EdgeDetector`)", || {
            Box::new(sync::EdgeDetector::default())
        }),
        entry("crc15", "Crc15", "canstar_hdl::crc15::Crc15", "CAN CRC-15 (`canstar_hdl::crc15::Crc15`)", || Box::new(crc15::Crc15::default())),
        entry("bit_stuffer", "BitStuffer", "canstar_hdl::stuff::BitStuffer", "bit stuffer (`canstar_hdl::stuff::BitStuffer`)", || {
            Box::new(stuff::BitStuffer::default())
        }),
        entry("bit_destuffer", "BitDestuffer", "canstar_hdl::stuff::BitDestuffer", "bit destuffer (`canstar_hdl::stuff::BitDestuffer`)", || {
            Box::new(stuff::BitDestuffer::default())
        }),
        entry("bit_timing", "BitTiming", "canstar_hdl::btl::BitTiming", "bit timing logic (`canstar_hdl::btl::BitTiming`)", || {
            Box::new(btl::BitTiming::default())
        }),
        entry("semantics", "Ops", "crate::semantics::Ops", "operator semantics test design (`canstar_models::semantics::Ops`)", || {
            Box::new(crate::semantics::Ops::default())
        }),
        entry(
            "can_core",
            "CanCore",
            "canstar_controller::core::CanCore",
            "CAN controller core (`canstar_controller::core::CanCore`, any synchroniser depth)",
            || Box::new(canstar_controller::core::CanCore::new()),
        ),
        entry(
            "sja1000",
            "Sja1000",
            "canstar_controller::sja1000::Sja1000",
            "SJA1000 (PeliCAN) controller on Wishbone (`canstar_controller::sja1000::Sja1000`, any power-up bit timing)",
            || Box::new(canstar_controller::sja1000::Sja1000::new()),
        ),
    ];
    for (suffix, name_suffix, n, m) in HUB_SHAPES {
        let module: &'static str = Box::leak(format!("hub_core_{suffix}").into_boxed_str());
        let name: &'static str = Box::leak(format!("HubCore{name_suffix}").into_boxed_str());
        let mut e = entry(module, name, "canstar_hub::hub::HubCore", &format!("hub core (`canstar_hub::hub::HubCore`), N = {n} ports, M = {m} sublinks, debug outputs"), move || {
            Box::new(HubCore::new(&hub_cfg(n, m)))
        });
        e.keep = crate::hub_sim::core_reader_signals(n, m);
        v.push(e);
        let module: &'static str = Box::leak(format!("hub_{suffix}").into_boxed_str());
        let name: &'static str = Box::leak(format!("Hub{name_suffix}").into_boxed_str());
        let mut e = entry(module, name, "canstar_hub::top::Hub", &format!("complete hub with frame monitor (`canstar_hub::top::Hub`), N = {n} ports, M = {m} sublinks, debug outputs"), move || {
            Box::new(Hub::new(&hub_cfg(n, m)))
        });
        e.keep = crate::hub_sim::core_reader_signals(n, m).into_iter().map(|p| format!("core.{p}")).collect();
        v.push(e);
    }
    v
}

/// Options for compiling an entry.
pub fn options(e: &Entry) -> canstar_rtlc::Options {
    canstar_rtlc::Options { name: e.name.into(), description: e.description.clone(), hdl_type: Some(e.hdl_type.into()), mutate: None, keep: e.keep.clone() }
}

/// The `generated/mod.rs` listing.
pub fn mod_rs(entries: &[Entry]) -> String {
    let mut s = String::from("//! Generated by canstar-rtlc (see `crate::registry`); do not edit.\n\n");
    for e in entries {
        s.push_str(&format!("pub mod {};\n", e.module));
    }
    s.push_str("\n/// A fresh model of every committed shape.\npub fn all() -> Vec<Box<dyn canstar_rtlc::rt::Model>> {\n    vec![\n");
    for e in entries {
        s.push_str(&format!("        Box::new({}::{}::new()),\n", e.module, e.name));
    }
    s.push_str("    ]\n}\n");
    s
}

/// The directory the generated sources live in.
pub fn generated_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src").join("generated")
}

/// Deliberately wrong models for the test that shows the equivalence checks catch
/// them: (entry module, operator number swapped by the compiler's debug hook).
pub const MUTANTS: [(&str, usize); 5] = [("crc15", 0), ("crc15", 2), ("bit_stuffer", 2), ("bit_timing", 7), ("bit_timing", 30)];

/// The directory the mutant models live in (`tests/mutants`).
pub fn mutants_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests").join("mutants")
}

/// Every mutant file: (file name, contents, what was changed).
pub fn mutant_files() -> Result<Vec<(String, String, String)>, canstar_rtlc::Error> {
    let entries = entries();
    let mut out = vec![];
    for (module, k) in MUTANTS {
        let e = entries.iter().find(|e| e.module == module).expect("registered entry");
        let mut o = options(e);
        o.name = format!("{}M{k}", e.name);
        o.description = format!("MUTANT (operator {k} swapped) of the {}", e.description);
        o.mutate = Some(k);
        let b = (e.build)();
        let c = canstar_rtlc::compile(b.as_ref(), &o)?;
        out.push((format!("{module}_m{k}.rs"), c.source, c.mutation.unwrap_or_default()));
    }
    Ok(out)
}

/// Every generated file: (path relative to the crate's `src/generated`, contents).
pub fn files() -> Result<Vec<(String, String)>, canstar_rtlc::Error> {
    let entries = entries();
    let mut out = vec![];
    for e in &entries {
        let b = (e.build)();
        let c = canstar_rtlc::compile(b.as_ref(), &options(e))?;
        out.push((format!("{}.rs", e.module), c.source));
    }
    out.push(("mod.rs".into(), mod_rs(&entries)));
    Ok(out)
}

/// Files that differ from what the compiler generates now.
#[derive(Debug, Default)]
pub struct Stale {
    /// Generated files whose committed contents differ (or are missing).
    pub changed: Vec<PathBuf>,
    /// Files in the generated directories that no registry entry writes.
    pub unregistered: Vec<PathBuf>,
}

impl Stale {
    pub fn is_empty(&self) -> bool {
        self.changed.is_empty() && self.unregistered.is_empty()
    }
}

/// Compare every committed model and mutant with what the compiler generates from
/// the current designs; with `bless`, rewrite the stale ones and remove unregistered
/// files (what `CANSTAR_BLESS=1 cargo test -p canstar-models --test current` does,
/// and what `canstar generate --check` can call).
pub fn check(bless: bool) -> Result<Stale, Box<dyn std::error::Error>> {
    check_dirs(&generated_dir(), &mutants_dir(), bless)
}

/// [`check`] on other directories.
pub fn check_dirs(generated: &Path, mutants: &Path, bless: bool) -> Result<Stale, Box<dyn std::error::Error>> {
    let mut stale = Stale::default();
    let mut sync = |dir: PathBuf, files: Vec<(String, String)>, sweep: bool| -> std::io::Result<()> {
        if bless {
            std::fs::create_dir_all(&dir)?;
        }
        for (f, text) in &files {
            let p = dir.join(f);
            if std::fs::read_to_string(&p).ok().as_deref() != Some(text.as_str()) {
                if bless {
                    std::fs::write(&p, text)?;
                }
                stale.changed.push(p);
            }
        }
        if sweep && dir.exists() {
            for e in std::fs::read_dir(&dir)? {
                let name = e?.file_name().to_string_lossy().into_owned();
                if !files.iter().any(|(f, _)| *f == name) {
                    if bless {
                        std::fs::remove_file(dir.join(&name))?;
                    }
                    stale.unregistered.push(dir.join(name));
                }
            }
        }
        Ok(())
    };
    sync(generated.to_path_buf(), files()?, true)?;
    sync(mutants.to_path_buf(), mutant_files()?.into_iter().map(|(f, t, _)| (f, t)).collect(), true)?;
    Ok(stale)
}
