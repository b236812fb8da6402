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
//!   `verify/tests/iso_cases.rs` running it through `run_iso`.
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

use super::IsoCase;

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
pub mod c7_2_7;
pub mod c7_2_9;
pub mod c7_2_10;
pub mod c7_2_11;
pub mod c8_1_1;
pub mod c8_1_2;
pub mod c8_1_3;
pub mod c8_1_5;
pub mod c8_1_6;
pub mod c8_1_7;
pub mod c8_1_8;

pub fn all() -> Vec<IsoCase> {
    vec![
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
        IsoCase { clause: "7.2.7", name: "iso_7_2_7_crc_delimiter_form_error", run: c7_2_7::run },
        IsoCase { clause: "7.2.9", name: "iso_7_2_9_ack_delimiter_form_error", run: c7_2_9::run },
        IsoCase { clause: "7.2.10", name: "iso_7_2_10_eof_form_error", run: c7_2_10::run },
        IsoCase { clause: "7.2.11", name: "iso_7_2_11_eof6_form_error", run: c7_2_11::run },
        IsoCase { clause: "8.1.1", name: "iso_8_1_1_identifier_and_dlc", run: c8_1_1::run },
        IsoCase { clause: "8.1.2", name: "iso_8_1_2_extended_identifier_and_dlc", run: c8_1_2::run },
        IsoCase { clause: "8.1.3", name: "iso_8_1_3_arbitration_lost_base", run: c8_1_3::run },
        IsoCase { clause: "8.1.5", name: "iso_8_1_5_intermission1_overload", run: c8_1_5::run },
        IsoCase { clause: "8.1.6", name: "iso_8_1_6_base_stuffing", run: c8_1_6::run },
        IsoCase { clause: "8.1.7", name: "iso_8_1_7_extended_stuffing", run: c8_1_7::run },
        IsoCase { clause: "8.1.8", name: "iso_8_1_8_sof_at_intermission_3", run: c8_1_8::run },
    ]
}
