//! Network files: the shipped reference file equals `NetworkSpec::default()`;
//! malformed files are rejected with a message naming the problem.
use canstar_recan::NetworkSpec;

#[test]
fn shipped_reference_file_is_the_default_network() {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/recancentrate.toml")).unwrap();
    assert!(NetworkSpec::is_network_file(&text));
    let s = NetworkSpec::from_toml(&text).unwrap();
    assert_eq!(s, NetworkSpec::default());
    // and the default round-trips through TOML
    assert_eq!(NetworkSpec::from_toml(&NetworkSpec::default().to_toml()).unwrap(), NetworkSpec::default());
    assert!(NetworkSpec::fast().validate().is_ok());
}

#[test]
fn bus_scenarios_are_not_network_files() {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/arbitration.toml")).unwrap();
    assert!(!NetworkSpec::is_network_file(&text));
}

fn err(edit: impl FnOnce(&mut NetworkSpec)) -> String {
    let mut s = NetworkSpec::default();
    edit(&mut s);
    s.validate().unwrap_err()
}

#[test]
fn invalid_networks_are_rejected_with_a_reason() {
    let minimal = "[network]\n[[nodes]]\nname = \"x\"\napp = \"counter\"\nid = 1\nbogus = 3\n";
    assert!(NetworkSpec::from_toml(minimal).unwrap_err().contains("bogus"));
    let minimal = "[network]\n[[nodes]]\nname = \"x\"\napp = \"counter\"\nid = 1\n";
    assert_eq!(NetworkSpec::from_toml(minimal).unwrap().nodes.len(), 1);
    assert!(err(|s| { s.hubs.pop(); }).contains("hubs"));
    assert!(err(|s| { s.interlinks.pop(); }).contains("interlinks"));
    assert!(err(|s| s.nodes[1].id = 0x0A0).contains("used by another sender"));
    assert!(err(|s| s.nodes[0].id = 0x800).contains("11 bits"));
    assert!(err(|s| s.nodes[2].b.timing.brp = 5).contains("bit time"));
    assert!(err(|s| s.nodes[2].a.timing.sjw = 3).contains("sjw"));
    assert!(err(|s| s.nodes[0].b.up_ps = 400_000).contains("half a bit"));
    assert!(err(|s| s.nodes[0].initial_tx = 2).contains("initial_tx"));
    assert!(err(|s| s.hub.ports = 2).contains("hub.ports"));
    assert!(err(|s| s.hub.dbc_threshold = 0).contains("hub"));
}
