//! The ISO 16845-1 cases implemented on the lower tester (`canstar_verify::iso::cases`),
//! run through `run_iso` as `canstar conformance --suite iso` will.

//! Clause 7 (IUT as receiver) and the suite as a whole; clause 8 is in
//! `iso_cases_tx.rs`.

mod iso_util;
use canstar_verify::iso::run_iso;
use iso_util::{case, failures};


#[test]
fn iso_7_1_1_identifier_and_dlc() {
    let runs = run_iso(Some("7.1.1"));
    assert_eq!(runs.len(), 1);
    let (name, r) = &runs[0];
    assert_eq!(name, "iso_7_1_1_identifier_and_dlc");
    assert_eq!(r.len(), 8 * 9, "8 identifiers x DLC 0..8");
    assert!(r.iter().any(|s| s.name == "iso_7_1_1_id7ff_dlc8"));
    let f = failures(r);
    assert!(f.is_empty(), "{} failed:\n{}", f.len(), f.join("\n"));
}

#[test]
fn iso_7_2_2_stuff_error() {
    let runs = run_iso(Some("iso_7_2_2_stuff_error"));
    assert_eq!(runs.len(), 1);
    let r = &runs[0].1;
    assert!(r.len() >= 30, "{} elementary tests", r.len());
    for field in ["_id_", "_dlc_", "_data_", "_crc_"] {
        assert!(r.iter().any(|s| s.name.contains(field)), "no elementary test in {field}");
    }
    let f = failures(r);
    assert!(f.is_empty(), "{} of {} failed:\n{}", f.len(), r.len(), f.join("\n"));
}


#[test]
fn iso_7_1_2_extended_identifier_and_dlc() {
    let r = case("7.1.2", "iso_7_1_2_extended_identifier_and_dlc", 5 * 9);
    assert!(r.iter().any(|s| s.name == "iso_7_1_2_id1fffffff_dlc8"));
}

#[test]
fn iso_7_1_3_arbitration_lost_reception() {
    case("7.1.3", "iso_7_1_3_arbitration_lost_reception", 6);
}

#[test]
fn iso_7_1_4_base_reserved_bit() {
    case("7.1.4", "iso_7_1_4_base_reserved_bit", 4);
}

#[test]
fn iso_7_1_5_extended_srr_and_reserved_bits() {
    case("7.1.5", "iso_7_1_5_extended_srr_and_reserved_bits", 8);
}

#[test]
fn iso_7_1_8_dlc_above_8() {
    case("7.1.8", "iso_7_1_8_dlc_above_8", 7);
}

#[test]
fn iso_7_1_9_frames_without_bus_idle() {
    case("7.1.9", "iso_7_1_9_frames_without_bus_idle", 2);
}

#[test]
fn iso_7_1_10_base_stuffing_profiles() {
    case("7.1.10", "iso_7_1_10_base_stuffing_profiles", 10);
}

#[test]
fn iso_7_1_11_extended_stuffing_profiles() {
    case("7.1.11", "iso_7_1_11_extended_stuffing_profiles", 7);
}

#[test]
fn iso_7_1_12_eof7_valid_frame() {
    case("7.1.12", "iso_7_1_12_eof7_valid_frame", 1);
}

#[test]
fn iso_7_2_1_ack_bit_error() {
    case("7.2.1", "iso_7_2_1_ack_bit_error", 1);
}

#[test]
fn iso_7_2_3_extended_stuff_error() {
    let r = case("7.2.3", "iso_7_2_3_extended_stuff_error", run_iso(Some("7.2.3"))[0].1.len());
    assert!(r.len() >= 30, "{} elementary tests", r.len());
    for field in ["_id_", "_exid_", "_dlc_", "_data_", "_crc_"] {
        assert!(r.iter().any(|s| s.name.contains(field)), "no elementary test in {field}");
    }
}

#[test]
fn iso_7_2_5_crc_error() {
    case("7.2.5", "iso_7_2_5_crc_error", 3);
}

#[test]
fn iso_7_2_6_crc_and_crc_delimiter_errors() {
    case("7.2.6", "iso_7_2_6_crc_and_crc_delimiter_errors", 1);
}

#[test]
fn iso_7_2_7_crc_delimiter_form_error() {
    case("7.2.7", "iso_7_2_7_crc_delimiter_form_error", 1);
}

#[test]
fn iso_7_2_9_ack_delimiter_form_error() {
    case("7.2.9", "iso_7_2_9_ack_delimiter_form_error", 1);
}

#[test]
fn iso_7_2_10_eof_form_error() {
    case("7.2.10", "iso_7_2_10_eof_form_error", 5);
}

#[test]
fn iso_7_2_11_eof6_form_error() {
    case("7.2.11", "iso_7_2_11_eof6_form_error", 1);
}

#[test]
fn iso_7_3_1_error_flag_lengthened() {
    case("7.3.1", "iso_7_3_1_error_flag_lengthened", 3);
}

#[test]
fn iso_7_3_2_frame_after_error_frame() {
    case("7.3.2", "iso_7_3_2_frame_after_error_frame", 1);
}

#[test]
fn iso_7_3_3_error_flag_bit_error() {
    case("7.3.3", "iso_7_3_3_error_flag_bit_error", 3);
}

#[test]
fn iso_7_3_4_error_delimiter_form_error() {
    case("7.3.4", "iso_7_3_4_error_delimiter_form_error", 3);
}

#[test]
fn iso_7_4_1_intermission_overload() {
    case("7.4.1", "iso_7_4_1_intermission_overload", 2);
}

#[test]
fn iso_7_4_2_eof7_overload() {
    case("7.4.2", "iso_7_4_2_eof7_overload", 1);
}

#[test]
fn iso_7_4_3_delimiter_bit8_overload() {
    case("7.4.3", "iso_7_4_3_delimiter_bit8_overload", 2);
}

#[test]
fn iso_7_4_4_overload_flag_bit_error() {
    case("7.4.4", "iso_7_4_4_overload_flag_bit_error", 3);
}

#[test]
fn iso_7_4_5_overload_delimiter_form_error() {
    case("7.4.5", "iso_7_4_5_overload_delimiter_form_error", 3);
}

#[test]
fn iso_7_4_6_intermission_after_error_frame_overload() {
    case("7.4.6", "iso_7_4_6_intermission_after_error_frame_overload", 2);
}

#[test]
fn iso_7_4_7_intermission_after_overload_frame_overload() {
    case("7.4.7", "iso_7_4_7_intermission_after_overload_frame_overload", 2);
}

#[test]
fn iso_7_6_1_error_flag_bit_error_rec() {
    case("7.6.1", "iso_7_6_1_error_flag_bit_error_rec", 3);
}

#[test]
fn iso_7_6_2_overload_flag_bit_error_rec() {
    case("7.6.2", "iso_7_6_2_overload_flag_bit_error_rec", 3);
}

#[test]
fn iso_7_6_3_dominant_after_error_flag_rec() {
    case("7.6.3", "iso_7_6_3_dominant_after_error_flag_rec", 1);
}

#[test]
fn iso_7_6_4_dominant_after_overload_flag_rec() {
    case("7.6.4", "iso_7_6_4_dominant_after_overload_flag_rec", 1);
}

#[test]
fn iso_7_6_5_ack_bit_error_rec() {
    case("7.6.5", "iso_7_6_5_ack_bit_error_rec", 1);
}

#[test]
fn iso_7_6_6_crc_delimiter_rec() {
    case("7.6.6", "iso_7_6_6_crc_delimiter_rec", 1);
}

#[test]
fn iso_7_6_9_stuff_error_rec() {
    case("7.6.9", "iso_7_6_9_stuff_error_rec", 8);
}

#[test]
fn iso_7_6_10_crc_error_rec() {
    case("7.6.10", "iso_7_6_10_crc_error_rec", 1);
}

#[test]
fn iso_7_6_11_first_dominant_after_flag_rec() {
    case("7.6.11", "iso_7_6_11_first_dominant_after_flag_rec", 1);
}

#[test]
fn iso_7_6_12_error_delimiter_form_error_rec() {
    case("7.6.12", "iso_7_6_12_error_delimiter_form_error_rec", 2);
}

#[test]
fn iso_7_6_13_overload_delimiter_form_error_rec() {
    case("7.6.13", "iso_7_6_13_overload_delimiter_form_error_rec", 2);
}

#[test]
fn iso_7_6_14_valid_frame_rec() {
    case("7.6.14", "iso_7_6_14_valid_frame_rec", 1);
}

#[test]
fn iso_7_6_15_passive_valid_frame_rec() {
    case("7.6.15", "iso_7_6_15_passive_valid_frame_rec", 2);
}

#[test]
fn iso_7_6_16_eof7_rec() {
    case("7.6.16", "iso_7_6_16_eof7_rec", 2);
}

#[test]
fn iso_7_6_17_long_overload_flag_rec() {
    case("7.6.17", "iso_7_6_17_long_overload_flag_rec", 1);
}

#[test]
fn iso_7_6_18_long_error_flag_rec() {
    case("7.6.18", "iso_7_6_18_long_error_flag_rec", 1);
}

#[test]
fn iso_7_6_19_error_delimiter_bit8_rec() {
    case("7.6.19", "iso_7_6_19_error_delimiter_bit8_rec", 1);
}

#[test]
fn iso_7_6_20_overload_delimiter_bit8_rec() {
    case("7.6.20", "iso_7_6_20_overload_delimiter_bit8_rec", 1);
}

#[test]
fn iso_7_6_21_own_frame_rec() {
    case("7.6.21", "iso_7_6_21_own_frame_rec", 1);
}

#[test]
fn iso_7_7_3_late_edge_within_sjw() {
    case("7.7.3", "iso_7_7_3_late_edge_within_sjw", 2);
}

#[test]
fn iso_7_7_4_late_edge_beyond_sjw() {
    case("7.7.4", "iso_7_7_4_late_edge_beyond_sjw", 3);
}

#[test]
fn iso_7_7_5_early_edge_within_sjw() {
    case("7.7.5", "iso_7_7_5_early_edge_within_sjw", 2);
}

#[test]
fn iso_7_7_6_early_edge_beyond_sjw() {
    case("7.7.6", "iso_7_7_6_early_edge_beyond_sjw", 2);
}

#[test]
fn iso_7_7_1_sample_point() {
    // one per timing of c7_7_1::timings
    case("7.7.1", "iso_7_7_1_sample_point", 7);
}

#[test]
fn iso_7_7_2_hard_sync_early_sof() {
    // e = 1..NTQ for each timing: 10 + 10 + 10 + 10 + 8 + 25 + 10
    let r = case("7.7.2", "iso_7_7_2_hard_sync_early_sof", 83);
    assert!(r.iter().any(|s| s.name == "iso_7_7_2_t25_sp17_sjw1_e25"));
}

#[test]
fn iso_7_7_7_two_edges_before_sample_point() {
    // the timings with SP >= 4
    case("7.7.7", "iso_7_7_7_two_edges_before_sample_point", 6);
}

#[test]
fn iso_7_7_8_early_edge_then_second_edge() {
    case("7.7.8", "iso_7_7_8_early_edge_then_second_edge", 6);
}

#[test]
fn iso_7_7_9_1_idle_glitch_no_sof() {
    case("7.7.9.1", "iso_7_7_9_1_idle_glitch_no_sof", 7);
}

#[test]
fn iso_7_7_9_2_idle_glitch_group_no_resync() {
    // the timings with SP >= 4, BRP doubled where the glitches need it
    let r = case("7.7.9.2", "iso_7_7_9_2_idle_glitch_group_no_resync", 6);
    assert!(r.iter().any(|s| s.name == "iso_7_7_9_2_t10_sp6_sjw2_brp2"));
}

#[test]
fn iso_7_7_10_no_resync_after_dominant_sample() {
    // the timings with PH2 >= 3
    case("7.7.10", "iso_7_7_10_no_resync_after_dominant_sample", 4);
}

#[test]
fn iso_7_7_11_early_edge_at_ack() {
    // e = 1..min(SJW, PH2) for each timing: 2 + 1 + 1 + 4 + 1 + 1 + 1
    case("7.7.11", "iso_7_7_11_early_edge_at_ack", 11);
}

#[test]
fn iso_7_5_1_passive_flag_superimposed() {
    case("7.5.1", "iso_7_5_1_passive_flag_superimposed", 3);
}

#[test]
fn iso_7_5_2_passive_frame_after_error_frame() {
    case("7.5.2", "iso_7_5_2_passive_frame_after_error_frame", 1);
}

#[test]
fn iso_7_5_3_passive_dominant_after_flag() {
    case("7.5.3", "iso_7_5_3_passive_dominant_after_flag", 3);
}

#[test]
fn iso_7_5_5_passive_flag_restart() {
    case("7.5.5", "iso_7_5_5_passive_flag_restart", 3);
}

#[test]
fn iso_7_5_7_active_to_passive() {
    case("7.5.7", "iso_7_5_7_active_to_passive", 1);
}

#[test]
fn iso_7_5_4_passive_stays_passive() {
    case("7.5.4", "iso_7_5_4_passive_stays_passive", 1);
}

#[test]
fn iso_7_5_6_passive_error_delimiter_form_error() {
    case("7.5.6", "iso_7_5_6_passive_error_delimiter_form_error", 3);
}

#[test]
fn iso_7_6_7_ack_delimiter_rec_under_both_rules() {
    // D2: REC 9 -> 9 with the ISO rule (-1 at the ACK slot, +1 at the form error),
    // 9 -> 10 with the 1999 rule (no decrement before a recessive EOF bit 7)
    let r = case("7.6.7", "iso_7_6_7_ack_delimiter_rec", 2);
    assert!(r.iter().any(|s| s.name.ends_with("_bosch1999_rule")));
}

#[test]
fn iso_7_6_8_eof_form_error_rec_under_both_rules() {
    let r = case("7.6.8", "iso_7_6_8_eof_form_error_rec", 6);
    assert_eq!(r.iter().filter(|s| s.name.ends_with("_iso_rule")).count(), 3);
}

#[test]
fn only_known_failures_fail_and_the_cli_marks_them() {
    let mut out = vec![];
    let (pass, fail) = canstar_verify::iso::run_iso_cli(None, &mut out).unwrap();
    let out = String::from_utf8(out).unwrap();
    assert!(pass > 400, "{out}");
    let known = out.lines().filter(|l| l.starts_with("  FAIL (known: ")).count();
    assert_eq!(fail, known, "{out}");
    let last = out.lines().last().unwrap();
    if fail == 0 {
        assert_eq!(last, format!("{pass} passed, 0 failed"), "{out}");
    } else {
        assert!(last.ends_with(&format!("passed, {fail} failed ({fail} of them known failures)")), "{out}");
    }
}

#[test]
fn filters_select_by_clause_prefix_and_name() {
    assert!(run_iso(Some("9.9")).is_empty());
    let names: Vec<&str> = canstar_verify::iso::cases().iter().map(|c| c.name).collect();
    assert!(names.starts_with(&["iso_7_1_1_identifier_and_dlc", "iso_7_1_2_extended_identifier_and_dlc"]), "{names:?}");
    let clauses: Vec<Vec<u32>> = canstar_verify::iso::cases().iter().map(|c| c.clause.split('.').map(|x| x.parse().unwrap()).collect()).collect();
    assert!(clauses.windows(2).all(|w| w[0] < w[1]), "cases in clause order, one per clause: {names:?}");
    assert!(names.contains(&"iso_7_2_2_stuff_error") && names.contains(&"iso_8_1_1_identifier_and_dlc"));
    assert!(run_iso(Some("8.1.1")).len() == 1 && run_iso(Some("7.1.1")).len() == 1, "7.1.1 must not select 7.1.10..7.1.12");
    assert_eq!(run_iso(Some("iso_7_2_2_stuff_error")).len(), 1);
    assert!(run_iso(Some("7.1")).iter().all(|(n, _)| n.starts_with("iso_7_1_")));
    // "7.1" must not select 7.10 .. 7.19 by accident
    assert!(!run_iso(Some("7.1")).iter().any(|(n, _)| n.starts_with("iso_7_2")));
}


