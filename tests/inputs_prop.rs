//! Property tests of issue #15 over every file format (configuration, board,
//! scenario, network) and every command line: random and mutated inputs never
//! panic and never leave a stray file; each either runs or stops with a
//! message that names the file and the key.
//!
//! A mutation takes a shipped file, parses it as TOML and changes one thing:
//! a value replaced by a hostile one (NaN, infinities, 0, -1, the integer
//! limits, a value near the old one, a string with spaces or slashes, a value
//! of another type), a key removed, an unknown key added, or the text cut or
//! spoiled by one character. The in-process properties run many cases of the
//! parsers (and the simulations of accepted files, briefly); the command-line
//! properties run fewer cases of the `canstar` binary in a scratch folder.
//! The cases are the same on every run; `PROPTEST_RNG_SEED=<n> cargo test
//! --release --test inputs_prop` explores others (a loop over seeds found the
//! bugs of the test itself that the fixed seed did not).
use canstar::boards::pinfile::pin_file;
use canstar::boards::{Board, DesignPins, Pinout};
use proptest::prelude::*;
use proptest::test_runner::{Config as PtConfig, TestRunner};
use std::path::{Path, PathBuf};
use std::process::Command;
use toml::Value;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn read(p: &str) -> String {
    std::fs::read_to_string(root().join(p)).unwrap()
}

/// The shipped files of each format.
fn bases(format: &str) -> Vec<String> {
    match format {
        "config" => vec![read("configs/default.toml")],
        "board" => vec![
            read("boards/xsa-3s1000.toml"),
            read("boards/ice40-hx8k.toml"),
            read("boards/alchitry-cu.toml"),
            read("boards/ulx3s.toml"),
            read("boards/arty-a7.toml"),
        ],
        "scenario" => vec![read("examples/arbitration.toml"), read("examples/disturbance.toml")],
        "network" => vec![read("examples/recancentrate.toml")],
        _ => unreachable!(),
    }
}

/// A key path: table keys and array indices.
#[derive(Clone, Debug)]
enum Seg {
    Key(String),
    Index(usize),
}

fn paths(v: &Value, prefix: &mut Vec<Seg>, out: &mut Vec<Vec<Seg>>) {
    match v {
        Value::Table(t) => {
            for (k, x) in t {
                prefix.push(Seg::Key(k.clone()));
                out.push(prefix.clone());
                paths(x, prefix, out);
                prefix.pop();
            }
        }
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                prefix.push(Seg::Index(i));
                if x.is_table() {
                    paths(x, prefix, out);
                } else {
                    out.push(prefix.clone());
                }
                prefix.pop();
            }
        }
        _ => {}
    }
}

fn get_mut<'a>(v: &'a mut Value, path: &[Seg]) -> Option<&'a mut Value> {
    let mut cur = v;
    for s in path {
        cur = match s {
            Seg::Key(k) => cur.as_table_mut()?.get_mut(k)?,
            Seg::Index(i) => cur.as_array_mut()?.get_mut(*i)?,
        };
    }
    Some(cur)
}

/// The names a message may use for the key at `path`: its own name and the
/// names of the tables holding it.
fn key_names(path: &[Seg]) -> Vec<String> {
    path.iter()
        .filter_map(|s| match s {
            Seg::Key(k) => Some(k.clone()),
            Seg::Index(_) => None,
        })
        .collect()
}

fn hostile_value(old: &Value, pick: u64, r: u64) -> Value {
    let near = |x: i64| -> Vec<i64> { vec![x + 1, x - 1, x.saturating_mul(2), x / 2, x.saturating_mul(1000), -x] };
    let mut ints: Vec<i64> = vec![0, -1, 1, 2, 3, 7, 8, 16, 255, 256, 65_535, 1_000_000_000, i64::MAX, i64::MIN, r as i64];
    let mut floats: Vec<f64> = vec![f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 0.0, -0.0, 1e300, -1e300, 1e-300, 0.5, -0.5, f64::from_bits(r)];
    match old {
        Value::Integer(x) => ints.extend(near(*x)),
        Value::Float(x) => floats.extend([x + 1.0, x - 1.0, x * 2.0, x * 1e6, -x]),
        _ => {}
    }
    let strings = ["", " ", "a b", "../x", "/", "x\ny", "\"", "é", "name", "Data_Field", "counter", "H15"];
    let all: Vec<Value> = ints
        .into_iter()
        .map(Value::Integer)
        .chain(floats.into_iter().map(Value::Float))
        .chain(strings.iter().map(|s| Value::String(s.to_string())))
        .chain([Value::Boolean(true), Value::Boolean(false), Value::Array(vec![]), Value::Table(Default::default())])
        .collect();
    // Mostly a value of the old type (the ones that pass the parser).
    let same: Vec<&Value> = all.iter().filter(|v| std::mem::discriminant(*v) == std::mem::discriminant(old)).collect();
    if pick % 4 != 0 && !same.is_empty() {
        same[(pick / 4) as usize % same.len()].clone()
    } else {
        all[(pick / 4) as usize % all.len()].clone()
    }
}

/// One mutation of a base file: the new text and the key it touched (None for
/// a change of the raw text).
#[derive(Clone, Debug)]
struct Mutated {
    text: String,
    key: Option<Vec<Seg>>,
}

fn mutate(base: &str, kind: u8, which: u64, pick: u64, r: u64) -> Mutated {
    let mut doc: Value = Value::Table(base.parse::<toml::Table>().unwrap());
    let mut all = vec![];
    paths(&doc, &mut vec![], &mut all);
    let path = all[which as usize % all.len()].clone();
    match kind % 8 {
        // remove a key
        0 => {
            let (last, parent) = path.split_last().unwrap();
            if let Some(p) = get_mut(&mut doc, parent) {
                match (p, last) {
                    (Value::Table(t), Seg::Key(k)) => {
                        t.remove(k);
                    }
                    (Value::Array(a), Seg::Index(i)) => {
                        a.remove(*i);
                    }
                    _ => {}
                }
            }
            to_text(&doc, base, path)
        }
        // add an unknown key beside it
        1 => {
            let (_, parent) = path.split_last().unwrap();
            let mut key = parent.to_vec();
            key.push(Seg::Key("wibble".into()));
            match get_mut(&mut doc, parent) {
                Some(Value::Table(t)) => {
                    t.insert("wibble".into(), Value::Integer(1));
                    to_text(&doc, base, key)
                }
                _ => Mutated { text: base.to_string(), key: None },
            }
        }
        // cut the text, or spoil one character
        2 => {
            let mut cut = (r as usize) % (base.len() + 1);
            while !base.is_char_boundary(cut) {
                cut -= 1;
            }
            if pick % 2 == 0 {
                Mutated { text: base[..cut].to_string(), key: None }
            } else {
                let c = ['"', '[', ']', '=', '\n', '\u{0}', 'x', '#', '\u{fffd}'][(pick / 2) as usize % 9];
                let mut t = base.to_string();
                t.insert(cut, c);
                Mutated { text: t, key: None }
            }
        }
        // replace a value
        _ => {
            if let Some(v) = get_mut(&mut doc, &path) {
                let new = hostile_value(v, pick, r);
                *v = new;
            }
            to_text(&doc, base, path)
        }
    }
}

/// The mutated document as text (TOML cannot write every document, e.g. an
/// array of tables and numbers: then the base file, unchanged).
fn to_text(doc: &Value, base: &str, key: Vec<Seg>) -> Mutated {
    match toml::to_string(doc) {
        Ok(text) => Mutated { text, key: Some(key) },
        Err(_) => Mutated { text: base.to_string(), key: None },
    }
}

fn mutation() -> impl Strategy<Value = (usize, u8, u64, u64, u64)> {
    (0usize..8, any::<u8>(), any::<u64>(), any::<u64>(), any::<u64>())
}

/// The message of a rejected file must name one of the keys on the mutated path.
fn names_the_key(msg: &str, m: &Mutated) -> Result<(), TestCaseError> {
    if let Some(k) = &m.key {
        let names = key_names(k);
        prop_assert!(
            names.is_empty() || names.iter().any(|n| msg.contains(n.as_str())),
            "message does not name any of {names:?}:\n{msg}\n--- file:\n{}",
            m.text
        );
    }
    Ok(())
}

/// A runner with a fixed seed, so that the suite is the same on every run;
/// `PROPTEST_RNG_SEED=<n>` explores other cases.
fn runner(cases: u32) -> TestRunner {
    let mut c = PtConfig { cases, failure_persistence: None, ..PtConfig::default() };
    if std::env::var_os("PROPTEST_RNG_SEED").is_none() {
        c.rng_seed = proptest::test_runner::RngSeed::Fixed(15);
    }
    TestRunner::new(c)
}

// ---------------------------------------------------------------- in process

#[test]
fn configuration_files_never_panic_and_name_the_key() {
    let bases = bases("config");
    let d = tempfile::tempdir().unwrap();
    let file = d.path().join("c.toml");
    runner(256)
        .run(&mutation(), |(b, kind, which, pick, r)| {
            let m = mutate(&bases[b % bases.len()], kind, which, pick, r);
            std::fs::write(&file, &m.text).unwrap();
            match canstar::config::Config::load(&file) {
                Ok(c) => {
                    // accepted: the generator renders it
                    canstar::generate::render(canstar::generate::Target::Blocks, &c, None).map_err(|e| TestCaseError::fail(format!("{e:#}")))?;
                }
                Err(e) => {
                    let msg = format!("{e:#}");
                    prop_assert!(msg.starts_with(&file.display().to_string()), "{msg}");
                    names_the_key(&msg, &m)?;
                }
            }
            Ok(())
        })
        .unwrap();
}

#[test]
fn board_files_never_panic_never_escape_and_name_the_key() {
    let bases = bases("board");
    let d = tempfile::tempdir().unwrap();
    let file = d.path().join("b.toml");
    let hub = DesignPins { functional: canstar::designs::hub_functional_roles(3, 2), debug: DesignPins::port_roles("dbg", 70) };
    runner(256)
        .run(&mutation(), |(b, kind, which, pick, r)| {
            let m = mutate(&bases[b % bases.len()], kind, which, pick, r);
            std::fs::write(&file, &m.text).unwrap();
            match Board::lookup(&file.display().to_string()) {
                Ok(board) => {
                    // accepted: its name is one plain folder name
                    let p = Path::new(&board.name);
                    prop_assert!(p.components().count() == 1 && !board.name.starts_with('.'), "{:?}", board.name);
                    let _ = pin_file(&board, Pinout::Hub, "hub", &hub);
                    let _ = pin_file(&board, Pinout::Controller, "ctrl", &DesignPins { functional: vec!["rx".into()], debug: vec![] });
                    let _ = pin_file(&board, Pinout::Slcan, "slcan", &DesignPins { functional: vec!["uart_rx".into()], debug: vec![] });
                    // what `canstar build` derives from a board before running a tool
                    let _ = canstar::build::tools::device_args(&board);
                    if let Ok(s) = canstar::build::pll::choose(board.clock.hz, 14_740_000, 2000.0, &board.label()) {
                        prop_assert!(s.in_range() && s.error_ppm(14_740_000).abs() <= 2000.0, "{s:?}");
                    }
                }
                Err(e) => {
                    let msg = format!("{e:#}");
                    prop_assert!(msg.starts_with(&file.display().to_string()), "{msg}");
                    names_the_key(&msg, &m)?;
                }
            }
            Ok(())
        })
        .unwrap();
}

#[test]
fn scenario_files_never_panic_and_name_the_key() {
    use canstar_verify::scenario::{run, RunOptions, Scenario};
    let bases = bases("scenario");
    runner(256)
        .run(&mutation(), |(b, kind, which, pick, r)| {
            let m = mutate(&bases[b % bases.len()], kind, which, pick, r);
            match Scenario::from_toml(&m.text) {
                Ok(s) => {
                    // accepted: it runs (20 us of it)
                    let _ = run(&s, &RunOptions { until_ps: Some(20_000_000), ..Default::default() });
                }
                Err(e) => names_the_key(&e, &m)?,
            }
            Ok(())
        })
        .unwrap();
}

#[test]
fn network_files_never_panic_and_name_the_key() {
    use canstar_recan::{run, NetworkSpec, RunSpec};
    let bases = bases("network");
    runner(128)
        .run(&mutation(), |(b, kind, which, pick, r)| {
            let m = mutate(&bases[b % bases.len()], kind, which, pick, r);
            match NetworkSpec::from_toml(&m.text) {
                Ok(net) => {
                    // accepted: it builds and runs (3 us of it)
                    let mut spec = RunSpec::new(net, r, 0);
                    spec.max_time_ps = Some(3_000_000);
                    let res = run(&spec);
                    prop_assert!(!res.failures.iter().any(|f| f.contains("invalid network")), "{:?}", res.failures);
                }
                Err(e) => names_the_key(&e, &m)?,
            }
            Ok(())
        })
        .unwrap();
}

// ---------------------------------------------------------------- the binary

/// Every file and folder under `d`, relative, sorted.
fn tree(d: &Path) -> Vec<String> {
    fn walk(d: &Path, base: &Path, v: &mut Vec<String>) {
        for e in std::fs::read_dir(d).unwrap().flatten() {
            let p = e.path();
            v.push(p.strip_prefix(base).unwrap().display().to_string());
            if p.is_dir() && !p.is_symlink() {
                walk(&p, base, v);
            }
        }
    }
    let mut v = vec![];
    walk(d, d, &mut v);
    v.sort();
    v
}

struct Outcome {
    ok: bool,
    err: String,
}

/// Run `canstar args` in `d`; check: no panic; a failure says `error: ` and
/// writes nothing; a success writes nothing but what is under `outputs`; no
/// temporary is left.
fn run_checked(args: &[String], d: &Path, outputs: &[String]) -> Result<Outcome, TestCaseError> {
    let before = tree(d);
    let o = Command::new(env!("CARGO_BIN_EXE_canstar")).args(args).current_dir(d).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    prop_assert!(!err.contains("panicked") && o.status.code() != Some(101), "{args:?} panicked:\n{err}");
    let after = tree(d);
    prop_assert!(!after.iter().any(|p| p.contains("canstar-tmp") || p.contains("canstar-old")), "{args:?} left temporaries: {after:?}");
    let new: Vec<&String> = after.iter().filter(|p| !before.contains(p)).collect();
    if o.status.success() {
        // an output, a file inside an output folder, or a folder created to hold one
        let declared = |p: &str| outputs.iter().any(|o| p == o || Path::new(p).starts_with(o) || Path::new(o).starts_with(p));
        prop_assert!(new.iter().all(|p| declared(p)), "{args:?} wrote undeclared files: {new:?}");
    } else {
        prop_assert!(new.is_empty(), "{args:?} failed and wrote {new:?}:\n{err}");
        // clap's usage errors start with `error:` too
        prop_assert!(err.starts_with("error: ") || err.contains("\nerror: ") || err.is_empty() && o.status.code() == Some(141), "{args:?}: {err}");
    }
    // Outputs of this case do not stay for the next one.
    for p in &new {
        let p = d.join(p);
        if p.is_dir() {
            let _ = std::fs::remove_dir_all(&p);
        } else {
            let _ = std::fs::remove_file(&p);
        }
    }
    Ok(Outcome { ok: o.status.success(), err })
}

fn scratch() -> tempfile::TempDir {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("afile"), "x").unwrap();
    std::fs::create_dir(d.path().join("adir")).unwrap();
    d
}

fn s(v: &[&str]) -> Vec<String> {
    v.iter().map(|x| x.to_string()).collect()
}

#[test]
fn mutated_files_through_the_command_line_run_or_name_file_and_key() {
    let d = scratch();
    let formats = ["config", "board", "scenario", "network"];
    let bases: Vec<Vec<String>> = formats.iter().map(|f| bases(f)).collect();
    runner(48)
        .run(&(0usize..4, mutation()), |(f, (b, kind, which, pick, r))| {
            let m = mutate(&bases[f][b % bases[f].len()], kind, which, pick, r);
            let file = format!("in-{}.toml", formats[f]);
            std::fs::write(d.path().join(&file), &m.text).unwrap();
            let (args, outputs) = match formats[f] {
                "config" => (s(&["generate", "blocks", "--config", &file, "--out", "v", "--constraints", "c"]), s(&["v", "c"])),
                "board" => (s(&["generate", "hub", "--board", &file, "--out", "v", "--constraints", "c"]), s(&["v", "c"])),
                _ => (s(&["sim", &file, "--ms", "0.003", "--vcd", "o.vcd", "--trace", "o.trace"]), s(&["o.vcd", "o.trace"])),
            };
            let o = run_checked(&args, d.path(), &outputs)?;
            if !o.ok && !o.err.contains("check(s) failed") {
                prop_assert!(o.err.contains(&file), "the message names the file: {}", o.err);
                names_the_key(&o.err, &m)?;
            }
            std::fs::remove_file(d.path().join(&file)).unwrap();
            Ok(())
        })
        .unwrap();
}

/// Values for a numeric option: hostile ones and a few small valid ones.
fn number(pick: u8) -> String {
    ["0", "-1", "1", "2", "nan", "inf", "-inf", "1e300", "-0", "0.001", "0.004", "18446744073709551616", "x", "", "3", "1.5"][pick as usize % 16].to_string()
}

/// Values for an output path: writable, in a missing folder, a folder, below a
/// file, empty, under /proc, and two spellings of one place.
fn out_path(pick: u8, ext: &str) -> String {
    let v = [format!("o.{ext}"), format!("no/such/o.{ext}"), "adir".into(), format!("afile/o.{ext}"), String::new(), format!("/proc/o.{ext}"), format!("adir/../o2.{ext}"), format!("adir/o.{ext}")];
    v[pick as usize % v.len()].clone()
}

fn input_path(pick: u8, valid: &str) -> String {
    let v = [valid.to_string(), valid.to_string(), "missing.toml".into(), "adir".into(), "afile".into(), String::new(), "/dev/null".into()];
    v[pick as usize % v.len()].clone()
}

/// A random command line of `canstar` with small workloads (every option
/// that sets the amount of work is either invalid or small).
fn command_line(cmd: u8, p: &[u8]) -> (Vec<String>, Vec<String>) {
    let ex = |n: &str| root().join("examples").join(n).display().to_string();
    let mut a: Vec<String> = vec![];
    let mut outs: Vec<String> = vec![];
    let opt = |a: &mut Vec<String>, flag: &str, v: String, k: u8| {
        if k % 3 != 0 {
            if k % 5 == 0 {
                a.push(format!("{flag}={v}"));
            } else {
                a.push(flag.into());
                a.push(v);
            }
        }
    };
    match cmd % 6 {
        0 => {
            a.push("sim".into());
            let file = if p[0] % 2 == 0 { ex("arbitration.toml") } else { ex("recancentrate.toml") };
            a.push(input_path(p[1], &file));
            a.push("--ms".into());
            a.push(["0", "-1", "nan", "inf", "-inf", "1e300", "-0", "0.001", "0.003", "x", "", "1e-9"][p[2] as usize % 12].into());
            for (flag, ext, k) in [("--vcd", "vcd", p[3]), ("--trace", "trace", p[4]), ("--log", "log", p[5])] {
                let o = out_path(p[6].wrapping_add(k), ext);
                outs.push(o.clone());
                opt(&mut a, flag, o, k);
            }
            opt(&mut a, "--seed", number(p[7]), p[8]);
        }
        1 => {
            a.push("generate".into());
            a.push(["blocks", "controller", "hub", "bogus"][p[0] as usize % 4].into());
            opt(&mut a, "--config", input_path(p[1], &root().join("configs/default.toml").display().to_string()), p[2]);
            opt(&mut a, "--board", ["xsa-3s1000", "ice40-hx8k", "nosuch", "adir", "missing.toml", ""][p[3] as usize % 6].into(), p[4]);
            let (o, c) = (out_path(p[5], "d"), out_path(p[6], "c"));
            outs.extend([o.clone(), c.clone(), "verilog-out".into(), "constraints".into()]);
            opt(&mut a, "--out", o, p[7]);
            opt(&mut a, "--constraints", c, p[8]);
            if p[9] % 4 == 0 {
                a.push("--check".into());
            }
        }
        2 => {
            a.push("campaign".into());
            // a run of a class takes a second or two: rarely a valid one
            let class = ["pub01", "nosuch", "pub0*", ""][p[0] as usize % 4];
            if p[1] % 2 == 0 {
                a.extend(s(&["--classes", class, "--reps"]));
                a.push(if p[2] % 4 == 0 { "1".into() } else { number(p[2]).replace('1', "0") });
                opt(&mut a, "--jobs", number(p[3]), p[4]);
                opt(&mut a, "--shard", ["1/2", "3/2", "x", "0/0"][p[5] as usize % 4].into(), p[6]);
            } else {
                a.extend(s(&["--class", class]));
                opt(&mut a, "--run-seed", number(p[2]), p[3]);
                if p[4] % 3 == 0 {
                    a.push("--classes".into());
                    a.push("pub01".into());
                }
            }
            for (flag, ext, k) in [("--json", "json", p[7]), ("--vcd", "vcd", p[8]), ("--plot", "svg", p[9])] {
                let o = out_path(p[10].wrapping_add(k), ext);
                outs.push(o.clone());
                opt(&mut a, flag, o, k);
            }
            if p[11] % 5 == 0 {
                a.push("--merge".into());
                a.push(input_path(p[12], "missing.json"));
            }
            // keep the valid runs rare: every valid campaign gets one more invalid option
            if p[13] % 3 != 0 {
                a.push("--reps".into());
                a.push("0".into());
            }
        }
        3 => {
            a.push("conformance".into());
            opt(&mut a, "--program", ["idle", "nosuch", "", "IDLE"][p[0] as usize % 4].into(), 1);
            let o = out_path(p[1], "d");
            outs.push(o.clone());
            opt(&mut a, "--vcd", o, p[2]);
        }
        4 => {
            a.push("fuzz".into());
            a.push("--frames".into());
            a.push(number(p[0]).replace("1e300", "1").replace("3", "2"));
            opt(&mut a, "--per-run", number(p[1]).replace("1e300", "2"), p[2]);
            opt(&mut a, "--jobs", number(p[3]).replace("1e300", "1"), p[4]);
            opt(&mut a, "--run-seed", number(p[5]), p[6]);
            let o = out_path(p[7], "d");
            outs.push(o.clone());
            opt(&mut a, "--vcd-dir", o, p[8]);
            opt(&mut a, "--max-failures", number(p[9]), p[10]);
        }
        _ => {
            a.push("bench".into());
            a.push("--cycles".into());
            a.push(["100", "0", "-1", "nan", "1000", "x"][p[0] as usize % 6].into());
            opt(&mut a, "--nodes", ["2", "0", "1,2", "5000", "", "-1"][p[1] as usize % 6].into(), p[2]);
            let o = out_path(p[3], "vcd");
            outs.push(o.clone());
            opt(&mut a, "--vcd", o, p[4]);
            opt(&mut a, "--signals", ["btl0.sample", "nosuch", "", "*"][p[5] as usize % 4].into(), p[6]);
        }
    }
    // `adir/../o2.x` is `o2.x` once written
    let outs = outs.into_iter().flat_map(|o| [o.clone(), o.replace("adir/../", "")]).filter(|o| !o.is_empty()).collect();
    (a, outs)
}

#[test]
fn random_command_lines_run_or_stop_cleanly() {
    let d = scratch();
    runner(40)
        .run(&(any::<u8>(), proptest::collection::vec(any::<u8>(), 14)), |(cmd, p)| {
            let (args, outs) = command_line(cmd, &p);
            run_checked(&args, d.path(), &outs)?;
            // the scratch folder's fixtures stay as they were
            prop_assert_eq!(std::fs::read_to_string(d.path().join("afile")).unwrap(), "x");
            prop_assert!(PathBuf::from(d.path().join("adir")).is_dir());
            Ok(())
        })
        .unwrap();
}
