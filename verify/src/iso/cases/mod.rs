//! The ISO 16845-1 cases implemented on the lower tester, one file per case
//! (see each file's documentation for the clause and what it checks). A case
//! is a function returning one [`crate::conformance::StepResult`] per
//! elementary test; [`all`] lists them for [`super::run_iso`].

use super::IsoCase;

pub mod c7_1_1;
pub mod c7_2_2;

pub fn all() -> Vec<IsoCase> {
    vec![
        IsoCase { clause: "7.1.1", name: "iso_7_1_1_identifier_and_dlc", run: c7_1_1::run },
        IsoCase { clause: "7.2.2", name: "iso_7_2_2_stuff_error", run: c7_2_2::run },
    ]
}
