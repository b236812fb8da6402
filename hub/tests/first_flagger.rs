//! The first-flagger rule at hub level with two sublinks (hub.md §5.12, §5.15): the
//! transmitter sits behind the peer hub, so the sublinks are the dominant contenders when
//! its error flag starts an episode that the frame monitor alone detects. A glitch that
//! every replica shows (the peer's contribution) does not excuse the replicas from each
//! other; a glitch of one replica alone excuses the other one. A SOF whose edge came through
//! the sublinks alone well before its bit start makes no first flagger of the overload flags
//! that answer it (§5.26). A sublink charged as the only dominant contender while its
//! replica was recessive also gets a replica charge (§5.27).
mod common;
use canstar_hub::config::HubConfig;
use canstar_hub::frame_state::Field;
use canstar_hub::hub::HubCore;
use common::*;

/// One bit as the frame monitor reports it; the ports are recessive, sublink j is
/// recessive at clock k iff `sub(j, k)`; `error`: the monitor detects an error at the sample.
fn bit(h: &mut HubCore, field: Field, pos: usize, error: bool, sub: &dyn Fn(usize, usize) -> bool) {
    monitor_bit(h, field, pos, error, &|_, _| true, sub);
}

/// A hub (3 ports, 2 sublinks) after reset and 12 idle bits.
fn idle_hub(cfg: &HubConfig) -> HubCore {
    let mut h = HubCore::new(cfg);
    for i in 0..3 {
        h.set_rx(i, true);
    }
    for j in 0..2 {
        h.set_reh_rx(j, true);
    }
    reset_hub(&mut h);
    for _ in 0..12 {
        bit(&mut h, Field::Idle, 0, false, &|_, _| true);
    }
    h
}

/// A frame from behind the peer: SOF and identifier bits on both sublinks, a 2-clock
/// dominant pulse at the start of identifier bit 2 on the sublinks in `glitching`, then the
/// transmitter's error flag (six dominant bits, the monitor's stuff error at the sixth).
/// Returns the ports' and the sublinks' `bic`.
fn flag_after_glitch(glitching: &[usize]) -> (Vec<u64>, Vec<u64>) {
    let mut h = idle_hub(&HubConfig::default());
    let (rec, dom) = (|_: usize, _: usize| true, |_: usize, _: usize| false);
    bit(&mut h, Field::Sof, 0, false, &dom);
    bit(&mut h, Field::Id, 0, false, &rec);
    bit(&mut h, Field::Id, 1, false, &dom);
    bit(&mut h, Field::Id, 2, false, &|j, k| !(glitching.contains(&j) && (2..4).contains(&k)));
    for p in 3..7 {
        bit(&mut h, Field::Id, p, false, if p % 2 == 0 { &dom } else { &rec });
    }
    for p in 7..13 {
        bit(&mut h, Field::Id, p, p == 12, &dom);
    }
    bit(&mut h, Field::ErrorFlag, 0, false, &dom);
    (h.bic(), h.sub_bic())
}

#[test]
fn a_common_glitch_does_not_excuse_the_replicas() {
    assert_eq!(flag_after_glitch(&[]), (vec![0; 3], vec![8, 8]), "no glitch: both contenders charged");
    assert_eq!(flag_after_glitch(&[0, 1]), (vec![0; 3], vec![8, 8]), "common glitch (the peer's): both still charged");
    assert_eq!(flag_after_glitch(&[0]), (vec![0; 3], vec![8, 0]), "sublink 0 alone glitched: it excuses sublink 1, not itself");
}

/// hub.md §5.26: a pulse reaches this hub at clock `edge` of Intermission bit 2 (through
/// both sublinks, or with `port_led` through port 2), at or after this hub's sample (clock
/// 12), and the monitor takes the next bit for a SOF. Port 0's node samples later and
/// answers with an overload flag (six dominant bits from the SOF's bit start), and so does
/// a node behind the peer (the sublinks stay dominant); the monitor finds the stuff error
/// at the sixth dominant bit. Returns the ports' and the sublinks' `bic`.
fn overload_flags_after_early_sof(edge: usize, port_led: bool, early_sof_clocks: u64) -> (Vec<u64>, Vec<u64>) {
    let mut h = idle_hub(&HubConfig { early_sof_clocks, ..HubConfig::default() });
    let (rec, dom) = (|_: usize, _: usize| true, |_: usize, _: usize| false);
    monitor_bit(&mut h, Field::Intermission, 0, false, &|_, _| true, &rec);
    let pulse = |k: usize| k < edge;
    if port_led {
        monitor_bit(&mut h, Field::Intermission, 1, false, &|i, k| i != 2 || pulse(k), &rec);
    } else {
        monitor_bit(&mut h, Field::Intermission, 1, false, &|_, _| true, &|_, k| pulse(k));
    }
    // port 0's overload flag; port 2 stays dominant when it led
    let flag = |i: usize, _: usize| i == 1 || (i == 2 && !port_led);
    monitor_bit(&mut h, Field::Sof, 0, false, &flag, &dom);
    for p in 0..5 {
        monitor_bit(&mut h, Field::Id, p, p == 4, &flag, &dom);
    }
    monitor_bit(&mut h, Field::ErrorFlag, 0, false, &flag, &dom);
    (h.bic(), h.sub_bic())
}

#[test]
fn overload_flags_after_an_early_sof_from_the_peer_are_not_first_flags() {
    let f = overload_flags_after_early_sof;
    let (charged, nobody) = ((vec![8, 0, 0], vec![8, 8]), (vec![0; 3], vec![0, 0]));
    assert_eq!(f(12, false, 3), nobody, "BT dominant 3 clocks before the bit start, from the sublinks: nobody charged");
    assert_eq!(f(12, false, 0), charged, "rule off: the dominant contenders are charged");
    assert_eq!(f(13, false, 3), charged, "2 clocks early (as a SOF from the peer's bit start can be): charged");
    assert_eq!(f(13, false, 2), nobody, "the same with early_sof_clocks 2");
    assert_eq!(f(12, true, 3), (vec![8, 0, 8], vec![8, 8]), "a port led the edge (this hub's node): charged");
}

/// hub.md §5.27: a frame from behind the peer; in identifier bit 6 (recessive) sublink 0
/// alone is dominant (`pulse`: for the whole bit; otherwise both sublinks carry the
/// transmitter's dominant bit), and the monitor alone detects an error at that sample.
/// Returns the sublinks' `bic` and replica counts.
fn monitor_error_under(pulse: bool, ff_replica_charge: bool) -> (Vec<u64>, Vec<u64>) {
    let mut h = idle_hub(&HubConfig { ff_replica_charge, ..HubConfig::default() });
    let (rec, dom) = (|_: usize, _: usize| true, |_: usize, _: usize| false);
    bit(&mut h, Field::Sof, 0, false, &dom);
    for p in 0..6 {
        bit(&mut h, Field::Id, p, false, if p % 2 == 0 { &rec } else { &dom });
    }
    bit(&mut h, Field::Id, 6, true, if pulse { &|j, _| j != 0 } else { &dom });
    bit(&mut h, Field::ErrorFlag, 0, false, &dom);
    (h.sub_bic(), h.sub_rep())
}

#[test]
fn the_only_dominant_contender_against_its_replica_gets_a_replica_charge() {
    let f = monitor_error_under;
    assert_eq!(f(true, true), (vec![8, 0], vec![1, 0]), "sublink 0 alone dominant: first flagger and replica charge");
    assert_eq!(f(true, false), (vec![8, 0], vec![0, 0]), "rule off: first-flagger charge only");
    assert_eq!(f(false, true), (vec![8, 8], vec![0, 0]), "both replicas dominant: no minority, no replica charge");
}
