//! End-to-end tests of `canstar campaign`: bad input fails cleanly and writes
//! nothing; shards written as JSON merge into the unsharded table; one run's VCD and
//! SVG plot.
mod common;
use common::{canstar, entries};

#[test]
fn campaign_bad_input_fails_cleanly_and_writes_nothing() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("bad.json"), "{ not json").unwrap();
    std::fs::write(d.path().join("empty.json"), "").unwrap();
    std::fs::write(d.path().join("h4.toml"), "[hub]\nports = 4\n").unwrap();
    std::fs::write(d.path().join("hkey.toml"), "[hub]\nsub_bic_decay = 9\n").unwrap();
    std::fs::write(d.path().join("hunk.toml"), "[hub]\nbic_decays = 2\n").unwrap();
    let before = entries(d.path());
    let cases: &[(&[&str], &str)] = &[
        (&["campaign", "--classes", "pub99", "--json", "out.json"], "unknown scenario class `pub99`"),
        (&["campaign", "--classes", "pub01,zzz*", "--json", "out.json"], "unknown scenario class `zzz*`"),
        (&["campaign", "--classes", "pub01", "--shard", "3/2", "--json", "out.json"], "malformed shard `3/2`"),
        (&["campaign", "--classes", "pub01", "--shard", "0/2", "--json", "out.json"], "malformed shard"),
        (&["campaign", "--classes", "pub01", "--shard", "x", "--json", "out.json"], "malformed shard"),
        (&["campaign", "--merge", "bad.json", "--json", "out.json"], "bad.json: not a campaign report"),
        (&["campaign", "--merge", "empty.json"], "empty.json: not a campaign report"),
        (&["campaign", "--merge", "missing.json", "--json", "out.json"], "missing.json: cannot read"),
        (&["campaign", "--class", "nope", "--plot", "p.svg", "--vcd", "v.vcd"], "unknown scenario class `nope`"),
        (&["campaign", "--class", "pub01", "--plot", "no/such/dir/p.svg"], "does not exist"),
        (&["campaign", "--classes", "pub01", "--json", "no/such/dir/o.json"], "does not exist"),
        (&["campaign", "--classes", "pub01", "--reps", "0", "--json", "out.json"], "--reps"),
        (&["campaign", "--classes", "pub01", "--hub-config", "h4.toml", "--json", "out.json"], "h4.toml: hub.ports = 4"),
        (&["campaign", "--classes", "pub01", "--hub-config", "hkey.toml", "--json", "out.json"], "sub_bic_decay must be in 1..=7"),
        (&["campaign", "--classes", "pub01", "--hub-config", "hunk.toml", "--json", "out.json"], "hunk.toml"),
        (&["campaign", "--class", "pub01", "--hub-config", "none.toml"], "none.toml"),
    ];
    for (args, msg) in cases {
        let (ok, _, err) = canstar(args, d.path());
        assert!(!ok, "{args:?} should fail");
        assert!(err.contains(msg), "{args:?}: stderr {err:?} should mention {msg:?}");
        assert_eq!(entries(d.path()), before, "{args:?} wrote something");
    }
    // --plot without --class is a usage error
    let (ok, _, _) = canstar(&["campaign", "--plot", "p.svg"], d.path());
    assert!(!ok);
    let (ok, _, _) = canstar(&["campaign", "--trace", "t.log"], d.path());
    assert!(!ok);
    assert_eq!(entries(d.path()), before);
}

/// `--hub-config` reaches both hubs: the healthy hub cuts a stuck-dominant hub off by
/// the sublink dominant-run limit of the file (20) instead of the reference 28.
#[test]
fn campaign_hub_config_sets_both_hubs() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("h.toml"), "[hub]\nsub_dbc_threshold = 20\n").unwrap();
    let (ok, out, err) = canstar(&["campaign", "--class", "hub-sad", "--hub-config", "h.toml"], d.path());
    assert!(ok, "{err}");
    assert!(out.contains("(dominant run 20/20)") && !out.contains("28/28"), "{out}");
}

#[test]
fn campaign_list_names_every_class() {
    let d = tempfile::tempdir().unwrap();
    let (ok, out, _) = canstar(&["campaign", "--list"], d.path());
    assert!(ok);
    let names: Vec<&str> = out.lines().collect();
    assert!(names.contains(&"pub01") && names.contains(&"pub21") && names.contains(&"hub-sad") && names.contains(&"eof-last-rx1"));
    assert_eq!(names.iter().filter(|n| n.starts_with("pub")).count(), 21);
}

#[test]
fn campaign_shards_merge_into_the_unsharded_table() {
    let d = tempfile::tempdir().unwrap();
    let common = ["campaign", "--classes", "crash-counter-nontx", "--reps", "2", "--seed", "9", "--jobs", "2"];
    let run = |extra: &[&str]| {
        let mut a: Vec<&str> = common.to_vec();
        a.extend_from_slice(extra);
        canstar(&a, d.path())
    };
    let (ok_full, full, _) = run(&["--json", "full.json", "--junit", "full.xml"]);
    let (ok1, _, e1) = run(&["--shard", "1/2", "--json", "s1.json"]);
    let (ok2, _, e2) = run(&["--shard", "2/2", "--json", "s2.json"]);
    assert!(e1.contains("shard 1/2") && e2.contains("shard 2/2"));
    let (ok_m, merged, _) = canstar(&["campaign", "--merge", "s2.json", "s1.json", "--json", "merged.json", "--junit", "merged.xml"], d.path());
    assert_eq!(merged, full, "merged shards print the unsharded table");
    assert_eq!(ok_m, ok_full);
    assert_eq!(ok1 && ok2, ok_full);
    assert!(full.contains("crash-counter-nontx") && full.contains("total:"));
    let a = std::fs::read_to_string(d.path().join("full.json")).unwrap();
    let b = std::fs::read_to_string(d.path().join("merged.json")).unwrap();
    assert_eq!(a, b, "merged JSON equals the unsharded JSON");
    // the JUnit report: one case for the class, from a run and from merged shards alike
    let x = std::fs::read_to_string(d.path().join("full.xml")).unwrap();
    assert!(x.contains(r#"<testcase name="crash-counter-nontx" classname="campaign""#), "{x}");
    assert_eq!(x.contains("<failure"), !ok_full, "{x}");
    assert_eq!(x, std::fs::read_to_string(d.path().join("merged.xml")).unwrap(), "merged JUnit equals the unsharded one");
    // the same shard twice is refused
    let (ok, _, err) = canstar(&["campaign", "--merge", "s1.json", "s1.json"], d.path());
    assert!(!ok && err.contains("appears twice"), "{err}");
}

#[test]
fn campaign_one_run_writes_vcd_and_plot() {
    let d = tempfile::tempdir().unwrap();
    let (_, out, err) = canstar(&["campaign", "--class", "pub18", "--run-seed", "3", "--vcd", "r.vcd", "--plot", "r.svg", "--trace", "r.trace"], d.path());
    assert!(out.contains("pub18 seed 3:"), "{out}{err}");
    let svg = std::fs::read_to_string(d.path().join("r.svg")).unwrap();
    assert!(svg.starts_with("<?xml") && svg.trim_end().ends_with("</svg>"));
    assert_eq!(svg.matches("<polyline class=\"tec\"").count(), 6);
    let vcd = std::fs::read_to_string(d.path().join("r.vcd")).unwrap();
    assert!(vcd.contains("$enddefinitions") && vcd.contains("$var"));
    // the drivers' routine log: every node's first request, and tx routines
    let tr = std::fs::read_to_string(d.path().join("r.trace")).unwrap();
    for k in 0..2 {
        assert!(tr.contains(&format!("node {k}: tx request")), "{tr}");
    }
    assert!(tr.contains("tx routine"), "{tr}");
}
