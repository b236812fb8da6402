//! The ISO 16845-1 clause 8 cases (IUT as transmitter) implemented on the lower
//! tester, run through `run_iso` as `canstar conformance --suite iso` will.

mod iso_util;
use canstar_verify::iso::run_iso;
use iso_util::{case, failures};

#[test]
fn iso_8_1_1_identifier_and_dlc() {
    let runs = run_iso(Some("8.1.1"));
    assert_eq!(runs.len(), 1);
    let r = &runs[0].1;
    assert_eq!(r.len(), 8 * 9, "8 identifiers x DLC 0..8");
    let f = failures(r);
    assert!(f.is_empty(), "{} failed:\n{}", f.len(), f.join("\n"));
}

#[test]
fn iso_8_1_2_extended_identifier_and_dlc() {
    case("8.1.2", "iso_8_1_2_extended_identifier_and_dlc", 5 * 9);
}

#[test]
fn iso_8_1_3_arbitration_lost_base() {
    case("8.1.3", "iso_8_1_3_arbitration_lost_base", 11);
}

#[test]
fn iso_8_1_5_intermission1_overload() {
    case("8.1.5", "iso_8_1_5_intermission1_overload", 1);
}

#[test]
fn iso_8_1_6_base_stuffing() {
    case("8.1.6", "iso_8_1_6_base_stuffing", 6);
}

#[test]
fn iso_8_1_7_extended_stuffing() {
    case("8.1.7", "iso_8_1_7_extended_stuffing", 3);
}

#[test]
fn iso_8_1_8_sof_at_intermission_3() {
    case("8.1.8", "iso_8_1_8_sof_at_intermission_3", 2);
}

#[test]
fn iso_8_2_1_base_bit_error() {
    case("8.2.1", "iso_8_2_1_base_bit_error", 11);
}

#[test]
fn iso_8_2_2_extended_bit_error() {
    case("8.2.2", "iso_8_2_2_extended_bit_error", 11);
}

#[test]
fn iso_8_2_3_base_stuff_error() {
    case("8.2.3", "iso_8_2_3_base_stuff_error", 35); // the standard counts 35 for its six frames
}

#[test]
fn iso_8_2_4_extended_stuff_error() {
    case("8.2.4", "iso_8_2_4_extended_stuff_error", 34);
}

#[test]
fn iso_8_2_5_form_error() {
    case("8.2.5", "iso_8_2_5_form_error", 5);
}

#[test]
fn iso_8_2_6_ack_error() {
    case("8.2.6", "iso_8_2_6_ack_error", 1);
}

#[test]
fn iso_8_6_8_ack_error_tec() {
    case("8.6.8", "iso_8_6_8_ack_error_tec", 1);
}

#[test]
fn iso_8_6_11_success_tec() {
    case("8.6.11", "iso_8_6_11_success_tec", 1);
}

#[test]
fn iso_8_6_17_passive_ack_error_tec() {
    case("8.6.17", "iso_8_6_17_passive_ack_error_tec", 1);
}

#[test]
fn iso_8_6_20_reception_tec() {
    case("8.6.20", "iso_8_6_20_reception_tec", 1);
}

#[test]
fn iso_8_6_4_dominant_after_passive_flag_tec() {
    case("8.6.4", "iso_8_6_4_dominant_after_passive_flag_tec", 5);
}

#[test]
fn iso_8_6_12_passive_success_tec() {
    case("8.6.12", "iso_8_6_12_passive_success_tec", 1);
}

#[test]
fn iso_8_6_18_passive_ack_error_dominant_flag_tec() {
    case("8.6.18", "iso_8_6_18_passive_ack_error_dominant_flag_tec", 1);
}

#[test]
fn iso_8_6_21_arbitration_lost_error_tec() {
    case("8.6.21", "iso_8_6_21_arbitration_lost_error_tec", 1);
}

#[test]
fn iso_8_7_1_sample_point() {
    case("8.7.1", "iso_8_7_1_sample_point", 7);
}

#[test]
fn iso_8_7_2_hard_sync_before_intermission3_sample_point() {
    case("8.7.2", "iso_8_7_2_hard_sync_before_intermission3_sample_point", 7);
}

#[test]
fn iso_8_7_3_hard_sync_after_intermission3_sample_point() {
    case("8.7.3", "iso_8_7_3_hard_sync_after_intermission3_sample_point", 5);
}

#[test]
fn iso_8_7_4_early_edge_within_sjw() {
    case("8.7.4", "iso_8_7_4_early_edge_within_sjw", 2);
}

#[test]
fn iso_8_7_5_early_edge_beyond_sjw() {
    case("8.7.5", "iso_8_7_5_early_edge_beyond_sjw", 2);
}

#[test]
fn iso_8_7_6_one_sync_between_sample_points() {
    case("8.7.6", "iso_8_7_6_one_sync_between_sample_points", 7);
}

#[test]
fn iso_8_7_7_no_resync_on_late_edge_while_dominant() {
    case("8.7.7", "iso_8_7_7_no_resync_on_late_edge_while_dominant", 7);
}

#[test]
fn iso_8_7_8_edge_right_after_sample_point() {
    case("8.7.8", "iso_8_7_8_edge_right_after_sample_point", 7);
}

#[test]
fn iso_8_7_9_resync_after_disturbed_dominant_bit() {
    case("8.7.9", "iso_8_7_9_resync_after_disturbed_dominant_bit", 6);
}

#[test]
fn iso_8_3_1_error_flag_lengthened() {
    case("8.3.1", "iso_8_3_1_error_flag_lengthened", 3);
}

#[test]
fn iso_8_3_3_error_flag_bit_error() {
    case("8.3.3", "iso_8_3_3_error_flag_bit_error", 3);
}

#[test]
fn iso_8_3_4_error_delimiter_form_error() {
    case("8.3.4", "iso_8_3_4_error_delimiter_form_error", 3);
}

#[test]
fn iso_8_4_1_passive_intermission_overload() {
    case("8.4.1", "iso_8_4_1_passive_intermission_overload", 2);
}

#[test]
fn iso_8_4_4_overload_flag_bit_error() {
    case("8.4.4", "iso_8_4_4_overload_flag_bit_error", 3);
}

#[test]
fn iso_8_4_5_overload_delimiter_form_error() {
    case("8.4.5", "iso_8_4_5_overload_delimiter_form_error", 3);
}

#[test]
fn iso_8_6_3_dominant_after_error_flag_tec() {
    case("8.6.3", "iso_8_6_3_dominant_after_error_flag_tec", 1);
}

#[test]
fn iso_8_6_5_dominant_after_overload_flag_tec() {
    case("8.6.5", "iso_8_6_5_dominant_after_overload_flag_tec", 1);
}

#[test]
fn iso_8_6_13_long_overload_flag_tec() {
    case("8.6.13", "iso_8_6_13_long_overload_flag_tec", 1);
}

#[test]
fn iso_8_6_14_long_error_flag_tec() {
    case("8.6.14", "iso_8_6_14_long_error_flag_tec", 1);
}

#[test]
fn iso_8_6_15_overload_delimiter_bit8_tec() {
    case("8.6.15", "iso_8_6_15_overload_delimiter_bit8_tec", 1);
}

#[test]
fn iso_8_6_16_error_delimiter_bit8_tec() {
    case("8.6.16", "iso_8_6_16_error_delimiter_bit8_tec", 1);
}

#[test]
fn iso_8_1_4_arbitration_lost_extended() {
    case("8.1.4", "iso_8_1_4_arbitration_lost_extended", 31);
}

#[test]
fn iso_8_5_1_passive_flag_overlapped() {
    case("8.5.1", "iso_8_5_1_passive_flag_overlapped", 3);
}

#[test]
fn iso_8_5_7_passive_suspend_after_frame() {
    case("8.5.7", "iso_8_5_7_passive_suspend_after_frame", 1);
}

#[test]
fn iso_8_5_14_passive_recovery_time() {
    case("8.5.14", "iso_8_5_14_passive_recovery_time", 1);
}

#[test]
fn iso_8_3_2_sof_at_intermission_3_after_error() {
    case("8.3.2", "iso_8_3_2_sof_at_intermission_3_after_error", 2);
}

#[test]
fn iso_8_4_2_passive_delimiter_bit8_overload() {
    case("8.4.2", "iso_8_4_2_passive_delimiter_bit8_overload", 2);
}

#[test]
fn iso_8_4_3_sof_at_intermission_3_after_overload() {
    case("8.4.3", "iso_8_4_3_sof_at_intermission_3_after_overload", 2);
}

#[test]
fn iso_8_5_2_passive_frame_at_intermission_3() {
    case("8.5.2", "iso_8_5_2_passive_frame_at_intermission_3", 1);
}

#[test]
fn iso_8_5_3_passive_dominant_after_flag() {
    case("8.5.3", "iso_8_5_3_passive_dominant_after_flag", 3);
}

#[test]
fn iso_8_5_4_passive_frame_during_suspend() {
    case("8.5.4", "iso_8_5_4_passive_frame_during_suspend", 3);
}

#[test]
fn iso_8_5_5_passive_suspend_after_error() {
    case("8.5.5", "iso_8_5_5_passive_suspend_after_error", 1);
}

#[test]
fn iso_8_5_6_passive_suspend_after_overload() {
    case("8.5.6", "iso_8_5_6_passive_suspend_after_overload", 1);
}

#[test]
fn iso_8_5_8_passive_arbitration_lost_no_suspend() {
    case("8.5.8", "iso_8_5_8_passive_arbitration_lost_no_suspend", 1);
}

#[test]
fn iso_8_5_9_passive_frame_during_suspend() {
    case("8.5.9", "iso_8_5_9_passive_frame_during_suspend", 3);
}

#[test]
fn iso_8_5_10_passive_to_bus_off() {
    case("8.5.10", "iso_8_5_10_passive_to_bus_off", 1);
}

#[test]
fn iso_8_5_11_bus_off_recovery() {
    case("8.5.11", "iso_8_5_11_bus_off_recovery", 2);
}

#[test]
fn iso_8_5_12_passive_flag_six_equal_bits() {
    case("8.5.12", "iso_8_5_12_passive_flag_six_equal_bits", 1);
}

#[test]
fn iso_8_5_13_passive_error_delimiter_form_error() {
    case("8.5.13", "iso_8_5_13_passive_error_delimiter_form_error", 3);
}

#[test]
fn iso_8_5_15_active_to_passive_tx() {
    case("8.5.15", "iso_8_5_15_active_to_passive_tx", 1);
}
