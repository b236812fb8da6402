//! The error-delimiter rule at hub level (hub.md §5.2, §5.14): error and overload delimiter
//! bits 2..7 must be recessive, except the bit right after a sample that started or renewed
//! an error episode, which carries the nodes' reactions to that error.
mod common;
use canstar_hub::config::HubConfig;
use canstar_hub::frame_state::Field;
use canstar_hub::hub::HubCore;
use common::*;

/// One error-delimiter bit at position `pos` as the frame monitor reports it; `dom(i, k)`:
/// port i's uplink is dominant at clock k of the bit.
fn delimiter_bit(h: &mut HubCore, pos: usize, dom: &dyn Fn(usize, usize) -> bool) {
    monitor_bit(h, Field::ErrorDelim, pos, false, &|i, k| !dom(i, k), &|_, _| true);
}

/// With `pulse`, port 0 is dominant from clock 13 of delimiter bit 1 to clock 8 of bit 2
/// (12 clocks, no glitch): recessive at both samples but in bit 2's window, so it is
/// blamed there and the hub starts an error flag. With `reaction`, port 1 is dominant for
/// the whole bit 3, as a node that sampled port 0's level would be. Returns the ports' `bic`.
fn delimiter_with(pulse: bool, reaction: bool) -> Vec<u64> {
    let mut h = HubCore::new(&HubConfig { sublinks: 0, ..Default::default() });
    for i in 0..3 {
        h.set_rx(i, true);
    }
    reset_hub(&mut h);
    delimiter_bit(&mut h, 0, &|_, _| false);
    delimiter_bit(&mut h, 1, &|i, k| pulse && i == 0 && k >= 13);
    delimiter_bit(&mut h, 2, &|i, k| pulse && i == 0 && k <= 8);
    delimiter_bit(&mut h, 3, &|i, _| reaction && i == 1);
    h.bic()
}

#[test]
fn reaction_right_after_a_blame_in_the_delimiter_is_not_blamed() {
    // a charged delimiter bit counts `delim_blames` blames (§5.17; no other port leads here)
    let d = 8 * HubConfig::default().delim_blames;
    assert_eq!(delimiter_with(false, true), [0, d, 0], "a dominant delimiter bit is blamed");
    assert_eq!(delimiter_with(true, false), [d, 0, 0], "port 0 blamed by the window rule");
    assert_eq!(delimiter_with(true, true), [d, 0, 0], "port 1's reaction in the next bit: not blamed");
}
