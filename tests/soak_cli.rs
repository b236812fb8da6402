//! End-to-end tests of `canstar soak`: bad input fails cleanly and writes nothing;
//! shards written as JSON merge into the unsharded summary; `--network` soaks a
//! network file (the hub clocked at 29.48 MHz on the chunk where the reference hub
//! blamed a fast receiver's early ACK before the early-ACK rule, README "No false blame"),
//! and the network with interlinks of unequal length keeps both sublinks (hub.md §5.18).
mod common;
use common::{canstar, entries, example};

/// Replay one soak chunk (`canstar soak ARGS`) in a fresh folder; (exit ok, stdout, stderr).
fn soak_chunk(args: &[&str]) -> (bool, String, String) {
    let d = tempfile::tempdir().unwrap();
    let args: Vec<&str> = ["soak"].iter().chain(args).copied().collect();
    canstar(&args, d.path())
}

#[test]
fn soak_bad_input_fails_cleanly_and_writes_nothing() {
    let d = tempfile::tempdir().unwrap();
    let net = std::fs::read_to_string(example("recancentrate.toml")).unwrap();
    std::fs::write(
        d.path().join("bad-key.toml"),
        net.replace("k_bits = 4.0", "k_bitz = 4.0"),
    )
    .unwrap();
    std::fs::write(d.path().join("bad.json"), "{ not json").unwrap();
    let before = entries(d.path());
    let cases: &[(&[&str], &str)] = &[
        (
            &[
                "soak",
                "--frames",
                "100",
                "--network",
                "bad-key.toml",
                "--json",
                "o.json",
            ],
            "bad-key.toml",
        ),
        (
            &[
                "soak",
                "--frames",
                "100",
                "--network",
                "bad-key.toml",
                "--json",
                "o.json",
            ],
            "k_bitz",
        ),
        (
            &[
                "soak",
                "--frames",
                "100",
                "--network",
                "missing.toml",
                "--json",
                "o.json",
            ],
            "missing.toml",
        ),
        (&["soak", "--frames", "0", "--json", "o.json"], "--frames"),
        (
            &[
                "soak", "--frames", "100", "--shard", "3/2", "--json", "o.json",
            ],
            "malformed shard",
        ),
        (
            &["soak", "--merge", "bad.json", "--json", "o.json"],
            "bad.json",
        ),
        (
            &["soak", "--frames", "100", "--json", "no/such/dir/o.json"],
            "does not exist",
        ),
    ];
    for (args, msg) in cases {
        let (ok, _, err) = canstar(args, d.path());
        assert!(!ok, "{args:?} should fail");
        assert!(
            err.contains(msg),
            "{args:?}: stderr {err:?} should mention {msg:?}"
        );
        assert_eq!(entries(d.path()), before, "{args:?} wrote something");
    }
    // --fast only applies to the reference network
    let (ok, _, _) = canstar(
        &[
            "soak",
            "--fast",
            "--network",
            &example("recancentrate.toml"),
        ],
        d.path(),
    );
    assert!(!ok);
    assert_eq!(entries(d.path()), before);
}

#[test]
fn soak_shards_merge_into_the_unsharded_summary() {
    let d = tempfile::tempdir().unwrap();
    let common = [
        "soak",
        "--frames",
        "300",
        "--chunk-frames",
        "100",
        "--fast",
        "--jobs",
        "1",
    ];
    let run = |extra: &[&str]| {
        let args: Vec<&str> = common.iter().chain(extra).copied().collect();
        let (ok, out, err) = canstar(&args, d.path());
        assert!(ok, "{args:?}: {err}");
        out
    };
    let whole = run(&["--json", "all.json"]);
    assert!(
        whole.starts_with("frames 300  chunks 3  blames 0  isolations 0"),
        "{whole}"
    );
    run(&["--shard", "1/2", "--json", "s1.json"]);
    run(&["--shard", "2/2", "--json", "s2.json"]);
    let (ok, merged, err) = canstar(&["soak", "--merge", "s1.json", "s2.json"], d.path());
    assert!(ok, "{err}");
    assert_eq!(merged, whole);
    let json = std::fs::read_to_string(d.path().join("all.json")).unwrap();
    assert!(json.contains("\"chunks\""));
}

#[test]
fn soak_of_a_network_file_uses_that_network() {
    let d = tempfile::tempdir().unwrap();
    // Chunk 16 of the default soak puts hub 1 at +6250 ppm and some receivers at
    // -6250 ppm; the reference hub (14.74 MHz) blamed a fast receiver's early ACK in
    // its CRC delimiter there before the early-ACK rule (README "No false blame"). With
    // the hubs at 29.48 MHz it is clean too.
    let hub29 = example("recancentrate-hub-29mhz.toml");
    let (ok, out, err) = canstar(
        &[
            "soak",
            "--network",
            &hub29,
            "--chunk",
            "16",
            "--json",
            "c.json",
        ],
        d.path(),
    );
    assert!(ok, "{out}{err}");
    assert!(out.contains("controllers (A, B)"), "{out}");
    assert!(
        out.contains("blames 0  isolations 0  worst TEC 0 REC 0  controller errors 0"),
        "{out}"
    );
    // the settings recorded in the JSON carry the network (its name)
    let json = std::fs::read_to_string(d.path().join("c.json")).unwrap();
    assert!(
        json.contains("recancentrate-hub-29mhz"),
        "the report should carry the soaked network"
    );
}

/// The replica skew filter (hub.md §5.18) at system level: with interlink 0 at 10 ns and
/// interlink 1 at 150 ns the peer's edges reach the two replicas about two hub clocks
/// apart. Without the filter hub 1 cut off its healthy sublink 1 in this fault-free
/// chunk (`replica 2/2`, the §5.18 rules before `replica_skew`); now it is clean.
#[test]
fn unequal_interlink_soak_chunk_keeps_both_sublinks() {
    let net = example("recancentrate-unequal-interlinks.toml");
    let (ok, out, err) = soak_chunk(&["--network", &net, "--events", "--chunk", "1"]);
    assert!(ok, "{out}{err}");
    assert!(out.contains("hubs [6250.0, 6250.0] ppm"), "the chunk's oscillators changed: {out}");
    assert!(out.contains("blames 0  isolations 0"), "{out}");
}

/// The early-ACK rule at system level: chunk 2 of the default soak (hub 0 slow, the
/// acknowledging B controllers fast) had hub 0 blame both sublinks at its CRC delimiter
/// before the rule (README "No false blame"); now it is clean.
#[test]
fn reference_soak_chunk_with_an_early_ack_is_clean() {
    let (ok, out, err) = soak_chunk(&["--chunk", "2"]);
    assert!(ok, "{out}{err}");
    assert!(out.contains("hubs [6250.0, -6250.0] ppm"), "the chunk's oscillators changed: {out}");
    assert!(out.contains("blames 0  isolations 0  worst TEC 0 REC 0  controller errors 0"), "{out}");
}

/// The first-flagger rule (hub.md §5.12) at a dominant stuff bit: in chunk 25 of the
/// event soak node 1 is switched off in the middle of its own frame (bit 35100); nodes
/// that saw one more recessive bit than hub 1's monitor start their error flags at the
/// stuff bit the monitor still expects, the monitor finds the stuff error five bits later
/// with the sublinks dominant, and without the dominant-stuff-bit exception hub 1 charged
/// both sublinks (2 blames at CRC bit 12). Now clean.
#[test]
fn event_soak_chunk_with_a_transmitter_switched_off_is_clean() {
    let (ok, out, err) = soak_chunk(&["--events", "--chunk", "25"]);
    assert!(ok, "{out}{err}");
    assert!(out.contains("node 1 off at bit 35100"), "the chunk's events changed: {out}");
    assert!(out.contains("blames 0  isolations 0"), "{out}");
}

#[test]
fn soak_chunk_vcd_covers_only_its_window() {
    let d = tempfile::tempdir().unwrap();
    let (ok, out, err) =
        canstar(&["soak", "--chunk", "0", "--frames", "200", "--chunk-frames", "200", "--vcd", "w.vcd", "--vcd-from", "100", "--vcd-bits", "20"], d.path());
    assert!(ok, "{out}{err}");
    let vcd = std::fs::read_to_string(d.path().join("w.vcd")).unwrap();
    let body = &vcd[vcd.find("$enddefinitions").expect("a VCD header")..];
    assert!(vcd.contains("$scope module hub0") && vcd.contains("$scope module hub1"));
    let times: Vec<u64> = body.lines().filter_map(|l| l.strip_prefix('#')).map(|t| t.parse().unwrap()).collect();
    // the reference network's bit time is 8 TQ of 2 clocks at 14.74 MHz: 1085.5 ns
    let bit_ps = 1_085_487u64;
    assert!(times.len() > 100, "{} timestamps", times.len());
    assert!(times[0] >= 100 * bit_ps - bit_ps / 100, "starts at {}", times[0]);
    assert!(*times.last().unwrap() <= 121 * bit_ps, "ends at {}", times.last().unwrap());
    assert_eq!(entries(d.path()), vec!["w.vcd"]);
    // only with --chunk
    let (ok, _, err) = canstar(&["soak", "--frames", "200", "--vcd", "x.vcd"], d.path());
    assert!(!ok && err.contains("--chunk"), "{err}");
    assert_eq!(entries(d.path()), vec!["w.vcd"]);
}

/// The propagation budget (docs/recancentrate.md §1.1) against the simulated system: a
/// network over budget has controller errors in fault-free traffic and is warned about;
/// one with a margin of a few tens of ns is clean on the same chunk and warned about as
/// tight; the reference network (211 ns) is not warned about. The chunks are ones that
/// showed errors over budget (chunk 1 with both interlinks at 120 ns, chunk 3 with every
/// node link at 65 ns).
#[test]
fn budget_predicts_the_first_errors() {
    let d = tempfile::tempdir().unwrap();
    let reference = std::fs::read_to_string(example("recancentrate.toml")).unwrap();
    let variant = |name: &str, interlink_ns: u64, link_ns: u64| {
        let text = reference
            .replace("up_ps = 10000 ", &format!("up_ps = {link_ns}000 "))
            .replace("down_ps = 10000 ", &format!("down_ps = {link_ns}000 "))
            .replace("h0_to_h1_ps = 10000", &format!("h0_to_h1_ps = {interlink_ns}000"))
            .replace("h1_to_h0_ps = 10000", &format!("h1_to_h0_ps = {interlink_ns}000"));
        let path = d.path().join(name);
        std::fs::write(&path, text).unwrap();
        path.display().to_string()
    };
    for (name, interlink_ns, link_ns, chunk, margin, warning) in [
        ("il100.toml", 100, 10, "1", "margin 31.", Some("leaves only 31.")),
        ("il120.toml", 120, 10, "1", "margin -8.", Some("longer than the sample point")),
        ("nl50.toml", 10, 50, "3", "margin 51.", Some("leaves only 51.")),
        ("nl65.toml", 10, 65, "3", "margin -8.", Some("longer than the sample point")),
        ("ref.toml", 10, 10, "1", "margin 211.", None),
    ] {
        let net = variant(name, interlink_ns, link_ns);
        let (ok, out, err) = soak_chunk(&["--network", &net, "--chunk", chunk]);
        assert!(out.contains(margin), "{name}: {out}");
        match warning {
            Some(w) => assert!(err.contains(&format!("warning: {net}: the loop through the hubs")) && err.contains(w), "{name}: {err}"),
            None => assert!(!err.contains("warning"), "{name}: {err}"),
        }
        let over = margin.contains('-');
        assert_eq!(ok, !over, "{name}: {out}{err}");
        if over {
            assert!(!out.contains("controller errors 0 "), "{name}: {out}");
        } else {
            assert!(out.contains("blames 0  isolations 0  worst TEC 0 REC 0  controller errors 0 "), "{name}: {out}");
        }
    }
}
