//! Shapes and runtime constants: one model serves every value of the constants
//! (thresholds, timing, synchroniser depth, fault-injection codes, reintegration),
//! instances of another shape are refused with a clear error, and the registry
//! finds the committed model of an instance.

use canstar_controller::core::CanCore;
use canstar_controller::sja1000::Sja1000;
use canstar_hub::config::{FaultInjection, FaultPoint, HubConfig, InjectionKind};
use canstar_hub::top::Hub;
use canstar_models::generated as g;
use canstar_rtlc::{fingerprint, Error};

fn fp(b: &dyn canstar_rtlc::rt::Block) -> u64 {
    fingerprint(b).unwrap()
}

#[test]
fn constants_do_not_change_the_shape() {
    assert_eq!(fp(&CanCore::with_sync_depth(1)), fp(&CanCore::with_sync_depth(2)));
    assert_eq!(fp(&CanCore::new()), g::can_core::CanCore::FINGERPRINT);
    assert_eq!(fp(&Sja1000::with_reset_timing(0x40, 0x25)), g::sja1000::Sja1000::FINGERPRINT);
    let variants = [
        HubConfig::default(),
        HubConfig { sync_depth: 2, ..HubConfig::default() },
        HubConfig { reintegration: Some(7), bic_threshold: 3, life_threshold: 100, nack_threshold: 2, ..HubConfig::default() },
        HubConfig { fault_injection: Some(FaultInjection { point: FaultPoint::Sublink(1), kind: InjectionKind::StuckRecessive, start_field: 2 }), ..HubConfig::default() },
        HubConfig { timing: canstar_hdl::timing::BtlConfig::from_fields(3, 4, 3, 3, 2, false), ..HubConfig::default() },
    ];
    for cfg in &variants {
        assert_eq!(fp(&Hub::new(cfg)), g::hub_n3_m2::HubN3M2::FINGERPRINT, "{cfg:?}");
    }
}

#[test]
fn structure_changes_the_shape() {
    let base = fp(&Hub::new(&HubConfig::default()));
    for cfg in [HubConfig { sublinks: 1, ..HubConfig::default() }, HubConfig { ports: 4, ..HubConfig::default() }, HubConfig { debug: false, ..HubConfig::default() }] {
        assert_ne!(fp(&Hub::new(&cfg)), base, "{cfg:?}");
    }
}

#[test]
fn another_shape_is_refused_with_a_clear_error() {
    let h = Hub::new(&HubConfig { sublinks: 0, ..HubConfig::default() });
    match g::hub_n3_m2::HubN3M2::from_instance(&h) {
        Err(Error::ShapeMismatch { expected, found, .. }) => {
            assert_eq!(expected, g::hub_n3_m2::HubN3M2::FINGERPRINT);
            assert_eq!(found, g::hub_n3_m0::HubN3M0::FINGERPRINT);
        }
        Err(e) => panic!("wrong error {e}"),
        Ok(_) => panic!("a model of another shape was accepted"),
    }
    let five = Hub::new(&HubConfig { ports: 5, ..HubConfig::default() });
    let e = canstar_models::model_for(&five).err().expect("no committed model for N = 5");
    assert!(e.to_string().contains("no compiled model for this design shape"), "{e}");
}

#[test]
fn registry_finds_the_model_and_loads_the_constants() {
    let cfg = HubConfig { sublinks: 1, bic_threshold: 5, ..HubConfig::default() };
    let h = Hub::new(&cfg);
    let m = canstar_models::model_for(&h).unwrap();
    assert_eq!(m.info().name, "HubN3M1");
    // the constant `bic_limit` of port judge 0 is 8 * 5 in the loaded model
    let mut rec = canstar_models::lockstep::AtomRecorder::default();
    m.accept("top", &mut rec);
    let (_, v) = rec.atoms.iter().find(|(p, _)| p.ends_with("pj$0.bic_limit")).expect("bic_limit atom");
    let bits: Vec<u8> = match v {
        rust_hdl::core::prelude::VCDValue::Vector(b) => b.iter().map(|x| (*x == vcd::Value::V1) as u8).collect(),
        other => panic!("{other:?}"),
    };
    let value = bits.iter().fold(0u32, |a, &b| (a << 1) | b as u32);
    assert_eq!(value, 40);
}

/// Any configuration can be compiled on request (a library call writing the source).
#[test]
fn any_configuration_compiles_on_request() {
    let h = Hub::new(&HubConfig { ports: 5, sublinks: 3, debug: false, ..HubConfig::default() });
    let dir = std::env::temp_dir().join(format!("rtlc-shape-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("hub_n5_m3.rs");
    let opts = canstar_rtlc::Options { name: "HubN5M3".into(), description: "hub N = 5, M = 3".into(), hdl_type: Some("canstar_hub::top::Hub".into()), mutate: None, keep: vec![] };
    let c = canstar_rtlc::generate(&h, &opts, &path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("pub struct HubN5M3") && text.contains(&format!("{:#018x}", c.fingerprint)));
    assert!(text.contains("rx_4") && text.contains("hub_tx_2"));
    std::fs::remove_dir_all(&dir).unwrap();
}
