//! Campaign machinery: shard partition, merge = unsharded, JSON round trip, SVG plot,
//! and a small fixed-seed campaign whose class outcomes are asserted (run by CI).

use canstar_recan::campaign::report::CampaignReport;
use canstar_recan::campaign::{self, plot, system, Settings, Shard};
use std::collections::HashSet;

fn settings(seed: u64, reps: u32) -> Settings {
    Settings { seed, reps, ..Settings::default() }
}

#[test]
fn shards_cover_every_run_exactly_once() {
    let classes = campaign::select("*").unwrap();
    let s = settings(7, 5);
    let all = campaign::plan(&classes, &s, None);
    assert_eq!(all.len(), classes.len() * 5);
    let key = |p: &campaign::RunPlan| (p.class.name.clone(), p.rep, p.seed);
    let full: HashSet<_> = all.iter().map(key).collect();
    assert_eq!(full.len(), all.len(), "every (class, rep) once in the unsharded plan");
    for n in 1..=7u32 {
        let mut seen = HashSet::new();
        let mut count = 0;
        for i in 1..=n {
            for p in campaign::plan(&classes, &s, Some(Shard { index: i, count: n })) {
                assert!(seen.insert(key(&p)), "{:?} in two shards of {n}", key(&p));
                count += 1;
            }
        }
        assert_eq!(count, all.len());
        assert_eq!(seen, full, "shards of {n} cover the plan");
    }
    // a run's seed does not depend on the selection
    let one = campaign::plan(&campaign::select("pub05").unwrap(), &s, None);
    assert!(one.iter().all(|p| full.contains(&key(p))));
}

#[test]
fn filters_and_bad_inputs() {
    assert_eq!(campaign::select("pub*").unwrap().len(), 21);
    let v = campaign::select("pub02, pub01,pub0?").unwrap();
    assert_eq!(v.len(), 9);
    assert_eq!(v[0].name, "pub01", "catalogue order, each once");
    assert!(campaign::select("pub22").is_err());
    assert!(campaign::select("pub01,nope*").is_err());
    assert!(campaign::select("").is_err());
    assert!(campaign::class("pub*").is_err(), "--class takes an exact name");
    assert!(Shard::parse("3/2").is_err());
}

/// A mock outcome, to test the bookkeeping without simulating.
fn fake(p: &campaign::RunPlan) -> campaign::RunOutcome {
    let pass = !p.seed.is_multiple_of(5);
    campaign::RunOutcome {
        class: p.class.name.clone(),
        rep: p.rep,
        seed: p.seed,
        pass,
        failures: if pass { vec![] } else { vec!["mock failure".into()] },
        worst_healthy: (p.seed % 97) as u32,
        worst_healthy_tec: (p.seed % 50) as u32,
        worst_healthy_rec: (p.seed % 60) as u32,
        isolation_latency_bits: (!p.seed.is_multiple_of(3)).then_some((p.seed % 40) as u32),
        isolations: vec![format!("hub 0 port {}@1", p.rep)],
        duplicates: (p.seed % 2) as u32,
        ..Default::default()
    }
}

#[test]
fn executor_is_deterministic_and_ordered() {
    let classes = campaign::select("pub0*,crash-*").unwrap();
    let s = settings(3, 4);
    let plans = campaign::plan(&classes, &s, None);
    let mut n = 0;
    let a = campaign::execute(&plans, 3, fake, |_| n += 1);
    assert_eq!(n, plans.len());
    let b = campaign::execute(&plans, 1, fake, |_| {});
    assert_eq!(a, b);
    for (o, p) in a.iter().zip(&plans) {
        assert_eq!((o.class.as_str(), o.rep), (p.class.name.as_str(), p.rep));
    }
    // aggregation: a mock report's summaries match a direct count
    let r = CampaignReport::new(s.clone(), &classes, None, a.clone());
    for c in r.summaries() {
        let runs: Vec<_> = a.iter().filter(|o| o.class == c.class).collect();
        assert_eq!(c.runs as usize, runs.len());
        assert_eq!(c.passes as usize, runs.iter().filter(|o| o.pass).count());
        assert_eq!(c.failing.len(), runs.iter().filter(|o| !o.pass).count());
        let mut lat: Vec<u32> = runs.iter().filter_map(|o| o.isolation_latency_bits).collect();
        lat.sort();
        if let Some((lo, med, hi)) = c.isolation_bits {
            assert_eq!((lo, med, hi), (lat[0], lat[(lat.len() - 1) / 2], *lat.last().unwrap()));
        } else {
            assert!(lat.is_empty());
        }
    }
    let t = r.table();
    for f in a.iter().filter(|o| !o.pass) {
        assert!(t.contains(&format!("{} rep {} seed {}", f.class, f.rep, f.seed)), "failing seed printed");
    }
}

#[test]
fn merge_and_json_bookkeeping() {
    let classes = campaign::select("pub1*,eof-*").unwrap();
    let s = settings(11, 3);
    let full = CampaignReport::new(s.clone(), &classes, None, campaign::execute(&campaign::plan(&classes, &s, None), 2, fake, |_| {}));
    let shards: Vec<CampaignReport> = (1..=3)
        .map(|i| {
            let sh = Shard { index: i, count: 3 };
            let o = campaign::execute(&campaign::plan(&classes, &s, Some(sh)), 2, fake, |_| {});
            let r = CampaignReport::new(s.clone(), &classes, Some(sh), o);
            // every shard survives a JSON round trip
            let back = CampaignReport::from_json(&r.to_json(), "shard").unwrap();
            assert_eq!(back, r);
            back
        })
        .collect();
    let m = CampaignReport::merge(&[shards[2].clone(), shards[0].clone(), shards[1].clone()]).unwrap();
    assert_eq!(m, full);
    assert_eq!(m.table(), full.table());
    // overlapping shards, other campaigns and malformed files are refused
    assert!(CampaignReport::merge(&[shards[0].clone(), shards[0].clone()]).is_err());
    let mut other = shards[1].clone();
    other.settings.seed = 12;
    assert!(CampaignReport::merge(&[shards[0].clone(), other]).is_err());
    // a campaign with another hub configuration is another campaign; it survives the JSON
    let mut other = shards[1].clone();
    other.settings.hub = Some(canstar_hub::config::HubConfig { sub_bic_decay: 3, ..Default::default() });
    assert_eq!(CampaignReport::from_json(&other.to_json(), "h").unwrap(), other);
    assert!(CampaignReport::merge(&[shards[0].clone(), other]).is_err());
    assert!(CampaignReport::from_json("{", "x").is_err());
    assert!(CampaignReport::from_json("[]", "x").is_err());
    let bad = full.to_json().replacen("\"pub10\"", "\"pub99\"", 1);
    assert!(CampaignReport::from_json(&bad, "x").is_err());
    // a partial merge says which shards it holds
    let part = CampaignReport::merge(&shards[..2]).unwrap();
    assert_eq!(part.shards.len(), 2);
    assert!(part.runs.len() < part.expected_runs());
}

#[test]
fn merge_joins_campaigns_over_different_classes() {
    // three campaigns over disjoint parts of one class selection, one of them sharded,
    // join into the campaign over the whole selection (catalogue order, plan order)
    let s = settings(13, 2);
    let report = |filter: &str, shard: Option<Shard>| {
        let classes = campaign::select(filter).unwrap();
        let r = CampaignReport::new(s.clone(), &classes, shard, campaign::execute(&campaign::plan(&classes, &s, shard), 2, fake, |_| {}));
        CampaignReport::from_json(&r.to_json(), filter).unwrap()
    };
    let full = report("pub0*,eof-*,hub-*", None);
    let pubs = report("pub0*", None);
    let eof = report("eof-*", None);
    let hub1 = report("hub-*", Some(Shard { index: 1, count: 2 }));
    let hub2 = report("hub-*", Some(Shard { index: 2, count: 2 }));
    let m = CampaignReport::merge(&[hub2.clone(), eof.clone(), hub1.clone(), pubs.clone()]).unwrap();
    assert_eq!(m, full);
    assert_eq!(m.table(), full.table());
    // a join with a shard missing is partial and says so
    let part = CampaignReport::merge(&[eof.clone(), hub1.clone(), pubs.clone()]).unwrap();
    assert_eq!(part.classes, full.classes);
    assert!(part.runs.len() < part.expected_runs());
    assert_eq!(part.shards, vec![Shard { index: 1, count: 2 }]);
    // overlapping class lists join only when no run is in both
    let overlap = report("eof-*,hub-*", None);
    let e = CampaignReport::merge(&[eof.clone(), overlap]).unwrap_err().to_string();
    assert!(e.contains("appears twice"), "{e}");
    // other settings are another campaign
    let mut other = eof.clone();
    other.settings.reps = 3;
    assert!(CampaignReport::merge(&[pubs.clone(), other]).is_err());
    // a class the catalogue does not have is refused by both, named
    let mut unknown = eof.clone();
    unknown.classes.push("no-such-class".into());
    let e = CampaignReport::merge(&[pubs, unknown.clone()]).unwrap_err().to_string();
    assert!(e.contains("report 2: unknown class `no-such-class`"), "{e}");
    let e = CampaignReport::from_json(&unknown.to_json(), "x.json").unwrap_err().to_string();
    assert!(e.contains("x.json: unknown class `no-such-class`"), "{e}");
}

/// Minimal XML well-formedness check: balanced tags, quoted attributes, known entities.
fn check_xml(s: &str) -> Result<usize, String> {
    let b = s.as_bytes();
    let mut i = 0;
    let mut stack: Vec<String> = vec![];
    let mut elements = 0;
    let mut roots = 0;
    while i < b.len() {
        if b[i] == b'<' {
            let end = s[i..].find('>').ok_or("unterminated tag")? + i;
            let tag = &s[i + 1..end];
            if tag.starts_with('?') {
                if !tag.ends_with('?') {
                    return Err("bad declaration".into());
                }
            } else if let Some(name) = tag.strip_prefix('/') {
                let open = stack.pop().ok_or(format!("close </{name}> without open"))?;
                if open != name.trim() {
                    return Err(format!("<{open}> closed by </{name}>"));
                }
            } else {
                let self_close = tag.ends_with('/');
                let body = tag.trim_end_matches('/');
                let name: String = body.chars().take_while(|c| !c.is_whitespace()).collect();
                if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == ':' || c == '_') {
                    return Err(format!("bad element name in <{tag}>"));
                }
                // attributes: name="value" pairs
                let mut rest = body[name.len()..].trim();
                while !rest.is_empty() {
                    let eq = rest.find('=').ok_or(format!("attribute without value in <{tag}>"))?;
                    let an = rest[..eq].trim();
                    if an.is_empty() || an.contains(char::is_whitespace) {
                        return Err(format!("bad attribute name in <{tag}>"));
                    }
                    let v = &rest[eq + 1..];
                    if !v.starts_with('"') {
                        return Err(format!("unquoted attribute in <{tag}>"));
                    }
                    let close = v[1..].find('"').ok_or("unterminated attribute")? + 1;
                    if v[1..close].contains('<') {
                        return Err("< in attribute".into());
                    }
                    rest = v[close + 1..].trim();
                }
                elements += 1;
                if stack.is_empty() {
                    roots += 1;
                }
                if !self_close {
                    stack.push(name);
                }
            }
            i = end + 1;
        } else {
            if b[i] == b'&' {
                let semi = s[i..].find(';').ok_or("bare &")? + i;
                let ent = &s[i + 1..semi];
                if !["amp", "lt", "gt", "quot", "apos"].contains(&ent) {
                    return Err(format!("unknown entity &{ent};"));
                }
            } else if stack.is_empty() && !b[i].is_ascii_whitespace() {
                return Err("text outside the root element".into());
            }
            i += 1;
        }
    }
    if !stack.is_empty() {
        return Err(format!("unclosed <{}>", stack.last().unwrap()));
    }
    if roots != 1 {
        return Err(format!("{roots} root elements"));
    }
    Ok(elements)
}

#[test]
fn xml_checker_rejects_broken_documents() {
    assert!(check_xml(r#"<svg a="1"><g><line/></g></svg>"#).is_ok());
    for bad in [r#"<svg><g></svg>"#, r#"<svg a=1/>"#, "<svg>a & b</svg>", "<svg/><svg/>", r#"<svg><text>x<y</text></svg>"#] {
        assert!(check_xml(bad).is_err(), "{bad}");
    }
}

#[test]
fn plot_of_synthetic_data_is_valid_svg_with_markers() {
    let d = plot::PlotData {
        title: "t <&> \"q\"".into(),
        end_ps: 10_000_000,
        series: vec![
            plot::Series { label: "a & b".into(), points: vec![(0, 0, 0), (1_000_000, 8, 1), (5_000_000, 96, 2)] },
            plot::Series { label: "c".into(), points: vec![(0, 0, 0)] },
        ],
        markers: vec![
            plot::Marker { t_ps: 2_000_000, kind: plot::MarkerKind::Isolation, label: "isolated hub 0 port 1".into() },
            plot::Marker { t_ps: 5_000_000, kind: plot::MarkerKind::Quarantine, label: "quarantined <x>".into() },
        ],
    };
    let s = plot::svg(&d);
    check_xml(&s).unwrap();
    assert_eq!(s.matches("<polyline").count(), 4);
    assert!(s.contains(r#"class="marker isolation""#) && s.contains(r#"class="marker quarantine""#));
    assert!(s.contains("quarantined &lt;x&gt;"));
}

// ---------------------------------------------------------------- real runs

/// The CI campaign: a few classes × 2 repetitions with a fixed seed. Every class
/// must pass, and each shows the outcome that characterises it.
#[test]
fn small_fixed_seed_campaign() {
    let classes = campaign::select(
        "pub12,pub18,pub20,flip-receiver-nontx-down-r10,sublink-sad,hub-sad,crash-blinker-tx,double-two-nodes,eof-last-tx,eof-penult-rx2-crash",
    )
    .unwrap();
    let s = settings(2024, 2);
    let plans = campaign::plan(&classes, &s, None);
    let out = campaign::execute(&plans, 2, |p| system::run_plan(p, &s), |_| {});
    let r = CampaignReport::new(s.clone(), &classes, None, out);
    println!("{}", r.table());
    let by = |c: &'static str| r.runs.iter().filter(move |o| o.class == c);
    for o in &r.runs {
        assert!(o.pass, "{} seed {} failed: {:?}", o.class, o.seed, o.failures);
        assert!(o.delivered >= 5, "{} delivered {}", o.class, o.delivered);
        assert!(o.worst_healthy < 96);
    }
    // pub18: Receiver tx uplink SAD: the hub isolates it, nobody is quarantined
    for o in by("pub18") {
        assert_eq!(o.isolations.len(), 1, "{o:?}");
        assert!(o.isolations[0].ends_with("(dominant run 13/13)"), "isolated by the DBC rule: {o:?}");
        assert!(o.quarantined.is_empty(), "{o:?}");
    }
    // pub12: no isolation, quarantine, maxI retransmissions
    for o in by("pub12") {
        assert!(o.isolations.is_empty());
        assert_eq!(o.quarantined.len(), 1);
        assert_eq!(o.max_retransmissions, 3);
    }
    // pub20 and sublink-sad: isolated quickly
    for o in by("pub20").chain(by("sublink-sad")) {
        assert!(o.isolation_latency_bits.is_some_and(|l| l < 40), "{o:?}");
    }
    // hub-sad: the healthy hub cuts both sublinks of the faulty one
    let th = canstar_recan::NetworkSpec::default().hub.sub_dbc_threshold;
    let by_run = format!("(dominant run {th}/{th})");
    for o in by("hub-sad") {
        assert!(o.isolations.iter().filter(|i| i.contains("sublink") && i.ends_with(&by_run)).count() >= 2, "{o:?}");
    }
    // crash of the Blinker's tx controller: caught by the timer, quarantined
    for o in by("crash-blinker-tx") {
        assert_eq!(o.quarantined.len(), 1, "{o:?}");
        assert!(o.quarantined[0].contains("timer"), "{o:?}");
    }
    // eof-last-tx: the transmitter alone sees the last-bit error and sends again:
    // the others already accepted the frame, a duplicate (allowed)
    for o in by("eof-last-tx") {
        assert!(o.duplicates >= 1, "{o:?}");
    }
    // the report is reproducible from the printed seeds
    let again = system::run_plan(&plans[0], &s);
    assert_eq!(again, r.runs[0]);
}

#[test]
fn merge_of_real_shards_equals_unsharded() {
    let classes = campaign::select("pub09,crash-receiver-nontx").unwrap();
    let s = settings(5, 2);
    let run = |sh| {
        let plans = campaign::plan(&classes, &s, sh);
        CampaignReport::new(s.clone(), &classes, sh, campaign::execute(&plans, 2, |p| system::run_plan(p, &s), |_| {}))
    };
    let full = run(None);
    let a = run(Some(Shard { index: 1, count: 2 }));
    let b = run(Some(Shard { index: 2, count: 2 }));
    let a = CampaignReport::from_json(&a.to_json(), "a").unwrap();
    let b = CampaignReport::from_json(&b.to_json(), "b").unwrap();
    let m = CampaignReport::merge(&[b, a]).unwrap();
    assert_eq!(m, full);
    assert_eq!(m.table(), full.table());
}

#[test]
fn plot_of_a_real_run_marks_isolation_and_quarantine() {
    let c = campaign::class("pub20").unwrap();
    let d = system::run_detailed(&c, 0, 77, &Settings::default(), None, false);
    let s = plot::svg(&d.plot);
    check_xml(&s).unwrap();
    assert!(s.contains(r#"class="marker isolation""#), "isolation marked");
    assert!(s.contains(r#"class="marker quarantine""#), "quarantine marked");
    assert!(s.contains(r#"class="marker fault""#));
    assert_eq!(s.matches(r#"<polyline class="tec""#).count(), 6, "six controllers");
    assert_eq!(s.matches(r#"<polyline class="rec""#).count(), 6);
}
