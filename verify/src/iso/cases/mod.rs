//! The ISO 16845-1 cases implemented on the lower tester, one file per case
//! (see each file's documentation for the clause and what it checks). A case
//! is a function returning one [`crate::conformance::StepResult`] per
//! elementary test; [`all`] lists them for [`super::run_iso`].
//!
//! # Writing a case
//!
//! - File `c<clause>.rs` (`c7_2_2.rs`), a doc comment naming the clause and
//!   saying in our own words what the case checks, an entry in [`all`] with
//!   the clause and the name `iso_<clause>_<topic>`, and a test in
//!   `verify/tests/iso_cases.rs` (clause 7) or `iso_cases_tx.rs` (clause 8) running it
//!   through `run_iso`.
//! - One [`super::LtBench`] per case (or per group of elementary tests that
//!   need another configuration), one step per elementary test:
//!   `begin_step`, `preset` of the counters the case starts from, then
//!   - IUT as receiver (7.x): `Plan::frame` of the LT's frame, changed with
//!     `find`/`set_level`/`lengthen`/`shorten`/`glitch`/`disturb`, cut after
//!     the faulty bit (`truncate` + `push_recessive`) when the IUT is to flag,
//!     `expect` for the IUT's answer (flag bits, ACK), `play_and_run`;
//!   - IUT as transmitter (8.x): `request` a frame on node 0, `wait` for
//!     `Trigger::at(Field::Sof, 1)`, play `Plan::answer` (ACK and every bit of
//!     the IUT's frame expected), or wait for the bit to disturb and play a
//!     short plan there;
//!   - `end_step`, then assert on the record (`check_expects`, `iut_events`,
//!     the bit records) and on the counters, with `ensure!`.
//! - Name elementary tests `iso_<clause>_<what varies>` so a failure names
//!   the situation (`iso_7_2_2_f0_id_8_D`).
//! - Shared steps live in [`common`]: `receive_frame`/`receive_plan` (a frame
//!   acknowledged and delivered), `transmit_frame` (a frame sent and checked
//!   bit by bit), `receive_error` and `transmit_error` (an error at a given
//!   plan bit, its flag, the counters, the retransmission), `flag_scenario`
//!   and `tx_flag_scenario` (what the LT does from the IUT's first error or
//!   overload flag bit on).
//! - Where canstar's documented behaviour differs from the ISO expectation,
//!   keep the ISO check, list the elementary tests in [`KNOWN_FAILURES`] with
//!   the reason, and add the disagreement to README's list.

use super::IsoCase;

/// Elementary tests expected to fail, with the reason: (name prefix,
/// reason). They keep their ISO check and stay failures in the output of
/// `canstar conformance --suite iso`, marked as known.
pub const KNOWN_FAILURES: &[(&str, &str)] = &[];

/// The reason elementary test `name` is a known failure, if it is one.
pub fn known_failure(name: &str) -> Option<&'static str> {
    KNOWN_FAILURES.iter().find(|(p, _)| name.starts_with(p)).map(|(_, r)| *r)
}

pub mod common;
pub mod c7_1_1;
pub mod c7_1_2;
pub mod c7_1_3;
pub mod c7_1_4;
pub mod c7_1_5;
pub mod c7_1_8;
pub mod c7_1_9;
pub mod c7_1_10;
pub mod c7_1_11;
pub mod c7_1_12;
pub mod c7_2_1;
pub mod c7_2_2;
pub mod c7_2_3;
pub mod c7_2_5;
pub mod c7_2_6;
pub mod c7_2_7;
pub mod c7_2_9;
pub mod c7_2_10;
pub mod c7_2_11;
pub mod c7_3_1;
pub mod c7_3_2;
pub mod c7_3_3;
pub mod c7_3_4;
pub mod c7_4_1;
pub mod c7_4_2;
pub mod c7_4_3;
pub mod c7_4_4;
pub mod c7_4_5;
pub mod c7_4_6;
pub mod c7_4_7;
pub mod c7_5_1;
pub mod c7_5_2;
pub mod c7_5_3;
pub mod c7_5_4;
pub mod c7_5_5;
pub mod c7_5_6;
pub mod c7_5_7;
pub mod c7_6_1;
pub mod c7_6_2;
pub mod c7_6_3;
pub mod c7_6_4;
pub mod c7_6_5;
pub mod c7_6_6;
pub mod c7_6_7;
pub mod c7_6_8;
pub mod c7_6_9;
pub mod c7_6_10;
pub mod c7_6_11;
pub mod c7_6_12;
pub mod c7_6_13;
pub mod c7_6_14;
pub mod c7_6_15;
pub mod c7_6_16;
pub mod c7_6_17;
pub mod c7_6_18;
pub mod c7_6_19;
pub mod c7_6_20;
pub mod c7_6_21;
pub mod c7_7_1;
pub mod c7_7_2;
pub mod c7_7_3;
pub mod c7_7_4;
pub mod c7_7_5;
pub mod c7_7_6;
pub mod c7_7_7;
pub mod c7_7_8;
pub mod c7_7_9_1;
pub mod c7_7_9_2;
pub mod c7_7_10;
pub mod c7_7_11;
pub mod c8_1_1;
pub mod c8_1_2;
pub mod c8_1_3;
pub mod c8_1_4;
pub mod c8_1_5;
pub mod c8_1_6;
pub mod c8_1_7;
pub mod c8_1_8;
pub mod c8_2_1;
pub mod c8_2_2;
pub mod c8_2_3;
pub mod c8_2_4;
pub mod c8_2_5;
pub mod c8_2_6;
pub mod c8_3_1;
pub mod c8_3_2;
pub mod c8_3_3;
pub mod c8_3_4;
pub mod c8_4_1;
pub mod c8_4_2;
pub mod c8_4_3;
pub mod c8_4_4;
pub mod c8_4_5;
pub mod c8_5_1;
pub mod c8_5_2;
pub mod c8_5_3;
pub mod c8_5_4;
pub mod c8_5_5;
pub mod c8_5_6;
pub mod c8_5_7;
pub mod c8_5_8;
pub mod c8_5_9;
pub mod c8_5_10;
pub mod c8_5_11;
pub mod c8_5_12;
pub mod c8_5_13;
pub mod c8_5_14;
pub mod c8_5_15;
pub mod c8_6_3;
pub mod c8_6_4;
pub mod c8_6_5;
pub mod c8_6_13;
pub mod c8_6_14;
pub mod c8_6_15;
pub mod c8_6_16;
pub mod c8_6_8;
pub mod c8_6_11;
pub mod c8_6_12;
pub mod c8_6_17;
pub mod c8_6_18;
pub mod c8_6_20;
pub mod c8_6_21;
pub mod c8_7_1;
pub mod c8_7_2;
pub mod c8_7_3;
pub mod c8_7_4;
pub mod c8_7_5;
pub mod c8_7_6;
pub mod c8_7_7;
pub mod c8_7_8;
pub mod c8_7_9;

/// The cases in clause order (7.2.10 after 7.2.9).
pub fn all() -> Vec<IsoCase> {
    let mut v = vec![
        IsoCase { clause: "7.1.1", name: "iso_7_1_1_identifier_and_dlc", run: c7_1_1::run },
        IsoCase { clause: "7.1.2", name: "iso_7_1_2_extended_identifier_and_dlc", run: c7_1_2::run },
        IsoCase { clause: "7.1.3", name: "iso_7_1_3_arbitration_lost_reception", run: c7_1_3::run },
        IsoCase { clause: "7.1.4", name: "iso_7_1_4_base_reserved_bit", run: c7_1_4::run },
        IsoCase { clause: "7.1.5", name: "iso_7_1_5_extended_srr_and_reserved_bits", run: c7_1_5::run },
        IsoCase { clause: "7.1.8", name: "iso_7_1_8_dlc_above_8", run: c7_1_8::run },
        IsoCase { clause: "7.1.9", name: "iso_7_1_9_frames_without_bus_idle", run: c7_1_9::run },
        IsoCase { clause: "7.1.10", name: "iso_7_1_10_base_stuffing_profiles", run: c7_1_10::run },
        IsoCase { clause: "7.1.11", name: "iso_7_1_11_extended_stuffing_profiles", run: c7_1_11::run },
        IsoCase { clause: "7.1.12", name: "iso_7_1_12_eof7_valid_frame", run: c7_1_12::run },
        IsoCase { clause: "7.2.1", name: "iso_7_2_1_ack_bit_error", run: c7_2_1::run },
        IsoCase { clause: "7.2.2", name: "iso_7_2_2_stuff_error", run: c7_2_2::run },
        IsoCase { clause: "7.2.3", name: "iso_7_2_3_extended_stuff_error", run: c7_2_3::run },
        IsoCase { clause: "7.2.5", name: "iso_7_2_5_crc_error", run: c7_2_5::run },
        IsoCase { clause: "7.2.6", name: "iso_7_2_6_crc_and_crc_delimiter_errors", run: c7_2_6::run },
        IsoCase { clause: "7.2.7", name: "iso_7_2_7_crc_delimiter_form_error", run: c7_2_7::run },
        IsoCase { clause: "7.2.9", name: "iso_7_2_9_ack_delimiter_form_error", run: c7_2_9::run },
        IsoCase { clause: "7.2.10", name: "iso_7_2_10_eof_form_error", run: c7_2_10::run },
        IsoCase { clause: "7.2.11", name: "iso_7_2_11_eof6_form_error", run: c7_2_11::run },
        IsoCase { clause: "7.3.1", name: "iso_7_3_1_error_flag_lengthened", run: c7_3_1::run },
        IsoCase { clause: "7.3.2", name: "iso_7_3_2_frame_after_error_frame", run: c7_3_2::run },
        IsoCase { clause: "7.3.3", name: "iso_7_3_3_error_flag_bit_error", run: c7_3_3::run },
        IsoCase { clause: "7.3.4", name: "iso_7_3_4_error_delimiter_form_error", run: c7_3_4::run },
        IsoCase { clause: "7.4.1", name: "iso_7_4_1_intermission_overload", run: c7_4_1::run },
        IsoCase { clause: "7.4.2", name: "iso_7_4_2_eof7_overload", run: c7_4_2::run },
        IsoCase { clause: "7.4.3", name: "iso_7_4_3_delimiter_bit8_overload", run: c7_4_3::run },
        IsoCase { clause: "7.4.4", name: "iso_7_4_4_overload_flag_bit_error", run: c7_4_4::run },
        IsoCase { clause: "7.4.5", name: "iso_7_4_5_overload_delimiter_form_error", run: c7_4_5::run },
        IsoCase { clause: "7.4.6", name: "iso_7_4_6_intermission_after_error_frame_overload", run: c7_4_6::run },
        IsoCase { clause: "7.4.7", name: "iso_7_4_7_intermission_after_overload_frame_overload", run: c7_4_7::run },
        IsoCase { clause: "7.5.1", name: "iso_7_5_1_passive_flag_superimposed", run: c7_5_1::run },
        IsoCase { clause: "7.5.2", name: "iso_7_5_2_passive_frame_after_error_frame", run: c7_5_2::run },
        IsoCase { clause: "7.5.3", name: "iso_7_5_3_passive_dominant_after_flag", run: c7_5_3::run },
        IsoCase { clause: "7.5.5", name: "iso_7_5_5_passive_flag_restart", run: c7_5_5::run },
        IsoCase { clause: "7.5.4", name: "iso_7_5_4_passive_stays_passive", run: c7_5_4::run },
        IsoCase { clause: "7.5.6", name: "iso_7_5_6_passive_error_delimiter_form_error", run: c7_5_6::run },
        IsoCase { clause: "7.5.7", name: "iso_7_5_7_active_to_passive", run: c7_5_7::run },
        IsoCase { clause: "7.6.1", name: "iso_7_6_1_error_flag_bit_error_rec", run: c7_6_1::run },
        IsoCase { clause: "7.6.2", name: "iso_7_6_2_overload_flag_bit_error_rec", run: c7_6_2::run },
        IsoCase { clause: "7.6.3", name: "iso_7_6_3_dominant_after_error_flag_rec", run: c7_6_3::run },
        IsoCase { clause: "7.6.4", name: "iso_7_6_4_dominant_after_overload_flag_rec", run: c7_6_4::run },
        IsoCase { clause: "7.6.5", name: "iso_7_6_5_ack_bit_error_rec", run: c7_6_5::run },
        IsoCase { clause: "7.6.6", name: "iso_7_6_6_crc_delimiter_rec", run: c7_6_6::run },
        IsoCase { clause: "7.6.7", name: "iso_7_6_7_ack_delimiter_rec", run: c7_6_7::run },
        IsoCase { clause: "7.6.8", name: "iso_7_6_8_eof_form_error_rec", run: c7_6_8::run },
        IsoCase { clause: "7.6.9", name: "iso_7_6_9_stuff_error_rec", run: c7_6_9::run },
        IsoCase { clause: "7.6.10", name: "iso_7_6_10_crc_error_rec", run: c7_6_10::run },
        IsoCase { clause: "7.6.11", name: "iso_7_6_11_first_dominant_after_flag_rec", run: c7_6_11::run },
        IsoCase { clause: "7.6.12", name: "iso_7_6_12_error_delimiter_form_error_rec", run: c7_6_12::run },
        IsoCase { clause: "7.6.13", name: "iso_7_6_13_overload_delimiter_form_error_rec", run: c7_6_13::run },
        IsoCase { clause: "7.6.14", name: "iso_7_6_14_valid_frame_rec", run: c7_6_14::run },
        IsoCase { clause: "7.6.15", name: "iso_7_6_15_passive_valid_frame_rec", run: c7_6_15::run },
        IsoCase { clause: "7.6.16", name: "iso_7_6_16_eof7_rec", run: c7_6_16::run },
        IsoCase { clause: "7.6.17", name: "iso_7_6_17_long_overload_flag_rec", run: c7_6_17::run },
        IsoCase { clause: "7.6.18", name: "iso_7_6_18_long_error_flag_rec", run: c7_6_18::run },
        IsoCase { clause: "7.6.19", name: "iso_7_6_19_error_delimiter_bit8_rec", run: c7_6_19::run },
        IsoCase { clause: "7.6.20", name: "iso_7_6_20_overload_delimiter_bit8_rec", run: c7_6_20::run },
        IsoCase { clause: "7.6.21", name: "iso_7_6_21_own_frame_rec", run: c7_6_21::run },
        IsoCase { clause: "7.7.1", name: "iso_7_7_1_sample_point", run: c7_7_1::run },
        IsoCase { clause: "7.7.2", name: "iso_7_7_2_hard_sync_early_sof", run: c7_7_2::run },
        IsoCase { clause: "7.7.3", name: "iso_7_7_3_late_edge_within_sjw", run: c7_7_3::run },
        IsoCase { clause: "7.7.4", name: "iso_7_7_4_late_edge_beyond_sjw", run: c7_7_4::run },
        IsoCase { clause: "7.7.5", name: "iso_7_7_5_early_edge_within_sjw", run: c7_7_5::run },
        IsoCase { clause: "7.7.6", name: "iso_7_7_6_early_edge_beyond_sjw", run: c7_7_6::run },
        IsoCase { clause: "7.7.7", name: "iso_7_7_7_two_edges_before_sample_point", run: c7_7_7::run },
        IsoCase { clause: "7.7.8", name: "iso_7_7_8_early_edge_then_second_edge", run: c7_7_8::run },
        IsoCase { clause: "7.7.9.1", name: "iso_7_7_9_1_idle_glitch_no_sof", run: c7_7_9_1::run },
        IsoCase { clause: "7.7.9.2", name: "iso_7_7_9_2_idle_glitch_group_no_resync", run: c7_7_9_2::run },
        IsoCase { clause: "7.7.10", name: "iso_7_7_10_no_resync_after_dominant_sample", run: c7_7_10::run },
        IsoCase { clause: "7.7.11", name: "iso_7_7_11_early_edge_at_ack", run: c7_7_11::run },
        IsoCase { clause: "8.1.1", name: "iso_8_1_1_identifier_and_dlc", run: c8_1_1::run },
        IsoCase { clause: "8.1.2", name: "iso_8_1_2_extended_identifier_and_dlc", run: c8_1_2::run },
        IsoCase { clause: "8.1.3", name: "iso_8_1_3_arbitration_lost_base", run: c8_1_3::run },
        IsoCase { clause: "8.1.5", name: "iso_8_1_5_intermission1_overload", run: c8_1_5::run },
        IsoCase { clause: "8.1.6", name: "iso_8_1_6_base_stuffing", run: c8_1_6::run },
        IsoCase { clause: "8.1.7", name: "iso_8_1_7_extended_stuffing", run: c8_1_7::run },
        IsoCase { clause: "8.1.8", name: "iso_8_1_8_sof_at_intermission_3", run: c8_1_8::run },
        IsoCase { clause: "8.2.1", name: "iso_8_2_1_base_bit_error", run: c8_2_1::run },
        IsoCase { clause: "8.2.2", name: "iso_8_2_2_extended_bit_error", run: c8_2_2::run },
        IsoCase { clause: "8.2.3", name: "iso_8_2_3_base_stuff_error", run: c8_2_3::run },
        IsoCase { clause: "8.2.4", name: "iso_8_2_4_extended_stuff_error", run: c8_2_4::run },
        IsoCase { clause: "8.2.5", name: "iso_8_2_5_form_error", run: c8_2_5::run },
        IsoCase { clause: "8.2.6", name: "iso_8_2_6_ack_error", run: c8_2_6::run },
        IsoCase { clause: "8.3.1", name: "iso_8_3_1_error_flag_lengthened", run: c8_3_1::run },
        IsoCase { clause: "8.3.3", name: "iso_8_3_3_error_flag_bit_error", run: c8_3_3::run },
        IsoCase { clause: "8.3.4", name: "iso_8_3_4_error_delimiter_form_error", run: c8_3_4::run },
        IsoCase { clause: "8.4.1", name: "iso_8_4_1_passive_intermission_overload", run: c8_4_1::run },
        IsoCase { clause: "8.4.4", name: "iso_8_4_4_overload_flag_bit_error", run: c8_4_4::run },
        IsoCase { clause: "8.4.5", name: "iso_8_4_5_overload_delimiter_form_error", run: c8_4_5::run },
        IsoCase { clause: "8.6.3", name: "iso_8_6_3_dominant_after_error_flag_tec", run: c8_6_3::run },
        IsoCase { clause: "8.6.4", name: "iso_8_6_4_dominant_after_passive_flag_tec", run: c8_6_4::run },
        IsoCase { clause: "8.6.5", name: "iso_8_6_5_dominant_after_overload_flag_tec", run: c8_6_5::run },
        IsoCase { clause: "8.6.13", name: "iso_8_6_13_long_overload_flag_tec", run: c8_6_13::run },
        IsoCase { clause: "8.6.14", name: "iso_8_6_14_long_error_flag_tec", run: c8_6_14::run },
        IsoCase { clause: "8.6.15", name: "iso_8_6_15_overload_delimiter_bit8_tec", run: c8_6_15::run },
        IsoCase { clause: "8.6.16", name: "iso_8_6_16_error_delimiter_bit8_tec", run: c8_6_16::run },
        IsoCase { clause: "8.6.8", name: "iso_8_6_8_ack_error_tec", run: c8_6_8::run },
        IsoCase { clause: "8.6.11", name: "iso_8_6_11_success_tec", run: c8_6_11::run },
        IsoCase { clause: "8.6.12", name: "iso_8_6_12_passive_success_tec", run: c8_6_12::run },
        IsoCase { clause: "8.6.17", name: "iso_8_6_17_passive_ack_error_tec", run: c8_6_17::run },
        IsoCase { clause: "8.6.18", name: "iso_8_6_18_passive_ack_error_dominant_flag_tec", run: c8_6_18::run },
        IsoCase { clause: "8.6.20", name: "iso_8_6_20_reception_tec", run: c8_6_20::run },
        IsoCase { clause: "8.6.21", name: "iso_8_6_21_arbitration_lost_error_tec", run: c8_6_21::run },
        IsoCase { clause: "8.7.1", name: "iso_8_7_1_sample_point", run: c8_7_1::run },
        IsoCase { clause: "8.7.2", name: "iso_8_7_2_hard_sync_before_intermission3_sample_point", run: c8_7_2::run },
        IsoCase { clause: "8.7.3", name: "iso_8_7_3_hard_sync_after_intermission3_sample_point", run: c8_7_3::run },
        IsoCase { clause: "8.7.4", name: "iso_8_7_4_early_edge_within_sjw", run: c8_7_4::run },
        IsoCase { clause: "8.7.5", name: "iso_8_7_5_early_edge_beyond_sjw", run: c8_7_5::run },
        IsoCase { clause: "8.7.6", name: "iso_8_7_6_one_sync_between_sample_points", run: c8_7_6::run },
        IsoCase { clause: "8.7.7", name: "iso_8_7_7_no_resync_on_late_edge_while_dominant", run: c8_7_7::run },
        IsoCase { clause: "8.7.8", name: "iso_8_7_8_edge_right_after_sample_point", run: c8_7_8::run },
        IsoCase { clause: "8.7.9", name: "iso_8_7_9_resync_after_disturbed_dominant_bit", run: c8_7_9::run },
        IsoCase { clause: "8.1.4", name: "iso_8_1_4_arbitration_lost_extended", run: c8_1_4::run },
        IsoCase { clause: "8.5.1", name: "iso_8_5_1_passive_flag_overlapped", run: c8_5_1::run },
        IsoCase { clause: "8.5.7", name: "iso_8_5_7_passive_suspend_after_frame", run: c8_5_7::run },
        IsoCase { clause: "8.5.2", name: "iso_8_5_2_passive_frame_at_intermission_3", run: c8_5_2::run },
        IsoCase { clause: "8.5.3", name: "iso_8_5_3_passive_dominant_after_flag", run: c8_5_3::run },
        IsoCase { clause: "8.5.5", name: "iso_8_5_5_passive_suspend_after_error", run: c8_5_5::run },
        IsoCase { clause: "8.5.9", name: "iso_8_5_9_passive_frame_during_suspend", run: c8_5_9::run },
        IsoCase { clause: "8.5.15", name: "iso_8_5_15_active_to_passive_tx", run: c8_5_15::run },
        IsoCase { clause: "8.4.2", name: "iso_8_4_2_passive_delimiter_bit8_overload", run: c8_4_2::run },
        IsoCase { clause: "8.4.3", name: "iso_8_4_3_sof_at_intermission_3_after_overload", run: c8_4_3::run },
        IsoCase { clause: "8.5.4", name: "iso_8_5_4_passive_frame_during_suspend", run: c8_5_4::run },
        IsoCase { clause: "8.5.6", name: "iso_8_5_6_passive_suspend_after_overload", run: c8_5_6::run },
        IsoCase { clause: "8.5.8", name: "iso_8_5_8_passive_arbitration_lost_no_suspend", run: c8_5_8::run },
        IsoCase { clause: "8.5.12", name: "iso_8_5_12_passive_flag_six_equal_bits", run: c8_5_12::run },
        IsoCase { clause: "8.5.13", name: "iso_8_5_13_passive_error_delimiter_form_error", run: c8_5_13::run },
        IsoCase { clause: "8.5.11", name: "iso_8_5_11_bus_off_recovery", run: c8_5_11::run },
        IsoCase { clause: "8.5.10", name: "iso_8_5_10_passive_to_bus_off", run: c8_5_10::run },
        IsoCase { clause: "8.5.14", name: "iso_8_5_14_passive_recovery_time", run: c8_5_14::run },
        IsoCase { clause: "8.3.2", name: "iso_8_3_2_sof_at_intermission_3_after_error", run: c8_3_2::run },
    ];
    v.sort_by_key(|c| c.clause.split('.').map(|x| x.parse::<u32>().unwrap_or(0)).collect::<Vec<_>>());
    v
}
