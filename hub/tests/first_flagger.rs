//! The first-flagger rule at hub level with two sublinks (hub.md §5.12, §5.15): the
//! transmitter sits behind the peer hub, so the sublinks are the dominant contenders when
//! its error flag starts an episode that the frame monitor alone detects. A glitch that
//! every replica shows (the peer's contribution) does not excuse the replicas from each
//! other; a glitch of one replica alone excuses the other one.
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

/// A frame from behind the peer: SOF and identifier bits on both sublinks, a 2-clock
/// dominant pulse at the start of identifier bit 2 on the sublinks in `glitching`, then the
/// transmitter's error flag (six dominant bits, the monitor's stuff error at the sixth).
/// Returns the ports' and the sublinks' `bic`.
fn flag_after_glitch(glitching: &[usize]) -> (Vec<u64>, Vec<u64>) {
    let mut h = HubCore::new(&HubConfig::default());
    for i in 0..3 {
        h.set_rx(i, true);
    }
    for j in 0..2 {
        h.set_reh_rx(j, true);
    }
    reset_hub(&mut h);
    let (rec, dom) = (|_: usize, _: usize| true, |_: usize, _: usize| false);
    for _ in 0..12 {
        bit(&mut h, Field::Idle, 0, false, &rec);
    }
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
    (h.bic.iter().map(|s| s.val().index() as u64).collect(), h.sub_bic.iter().map(|s| s.val().index() as u64).collect())
}

#[test]
fn a_common_glitch_does_not_excuse_the_replicas() {
    assert_eq!(flag_after_glitch(&[]), (vec![0; 3], vec![8, 8]), "no glitch: both contenders charged");
    assert_eq!(flag_after_glitch(&[0, 1]), (vec![0; 3], vec![8, 8]), "common glitch (the peer's): both still charged");
    assert_eq!(flag_after_glitch(&[0]), (vec![0; 3], vec![8, 0]), "sublink 0 alone glitched: it excuses sublink 1, not itself");
}
